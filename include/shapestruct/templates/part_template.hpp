// SPDX-License-Identifier: MIT
// part_template: a deformable part-based template (dissertation 5.3.1): oriented boxes with Gaussians, as JSON.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SVD>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/io/json_file.hpp"

namespace shapestruct {

/// One part of a template: an oriented box whose centre and anisotropic size are Gaussian random variables
/// (independent per box axis, since the fitter solves each axis separately, eq. 5.6 and 5.3.2 step iii), plus a
/// Gaussian over the per-point local shape features of the points it explains.
/// All positions are in the template's canonical frame: shapes are centred on their bounding-box centre and
/// scaled to unit bounding-box diagonal before fitting (template_fitter), so templates are scale-free.
struct part_box {
  std::string name;                             ///< free text ("seat", "leg 1")
  index_t label = 0;                            ///< output label; boxes may share one (four legs, one label)
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< mean centre mu^p (canonical frame)
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< rows: the box's orthonormal axes (not deformed)
  Eigen::Vector3d size = Eigen::Vector3d::Constant(0.1);     ///< mean side lengths mu^s along the axes
  Eigen::Vector3d sigma_center = Eigen::Vector3d::Constant(0.05);  ///< sigma^p per box axis
  Eigen::Vector3d sigma_size = Eigen::Vector3d::Constant(0.05);    ///< sigma^s per box axis
  Eigen::VectorXd feature_mean;                 ///< mu^f, one entry per feature (empty: features not used)
  Eigen::VectorXd feature_sigma;                ///< sigma^f, same length
  bool must_exist = false;                      ///< a fit that leaves this part empty is rejected (5.3.2)
};

/// A template: boxes plus the collection's up axis (rotations are searched about it). `id` names the template
/// in outputs and clusters.
struct part_template {
  std::string id = "template";
  int up_axis = 1;  ///< 0 = x, 1 = y, 2 = z of the input shapes
  std::vector<part_box> parts;

  [[nodiscard]] index_t num_parts() const noexcept { return static_cast<index_t>(parts.size()); }
  /// Number of distinct output labels (max label + 1).
  [[nodiscard]] index_t num_labels() const noexcept {
    index_t l = 0;
    for (const auto& p : parts) l = std::max(l, p.label + 1);
    return l;
  }
};

namespace detail {

/// Closest point on the SURFACE of a box (rows of `axes` its axes, centre c, side lengths s) to x: its unit-box
/// coordinate (in [-0.5, 0.5]^3) and the squared distance. A point inside is pushed to the nearest face: a
/// template box stands for a surface, not a solid. Shared by the fitter and its start search.
inline std::pair<Eigen::Vector3d, double> closest_on_box_surface(const Eigen::Matrix3d& axes, const Eigen::Vector3d& c,
                                                                 const Eigen::Vector3d& s, const Eigen::Vector3d& x) {
  const Eigen::Vector3d l = axes * (x - c);
  const Eigen::Vector3d h = 0.5 * s;
  Eigen::Vector3d q = l.cwiseMax(-h).cwiseMin(h);
  if (q == l) {
    int k = 0;
    double best = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
      if (h[a] - std::abs(l[a]) < best) {
        best = h[a] - std::abs(l[a]);
        k = a;
      }
    q[k] = l[k] >= 0 ? h[k] : -h[k];
  }
  return {q.cwiseQuotient(s), (l - q).squaredNorm()};
}

}  // namespace detail

/// Checks a template's invariants: at least one part; finite numbers; positive sizes and sigmas; orthonormal
/// axes; every part with the same feature dimension (or all without features); non-negative labels; up axis in
/// {0, 1, 2}. `who` names the caller (or the file) in the message.
/// \throws invalid_input empty (no parts), non_finite / bad_parameter (part index), size_mismatch (part index,
/// inconsistent feature dimensions). O(parts x features).
inline void validate_template(const part_template& t, const std::string& who = "validate_template") {
  if (t.parts.empty())
    throw invalid_input(input_error::empty, no_index, who + ": template '" + t.id + "' has no parts");
  if (t.up_axis < 0 || t.up_axis > 2)
    throw invalid_input(input_error::bad_parameter, no_index,
                        who + ": template '" + t.id + "' has up_axis " + std::to_string(t.up_axis) +
                            ", expected 0, 1 or 2");
  const auto dim = t.parts.front().feature_mean.size();
  for (std::size_t i = 0; i < t.parts.size(); ++i) {
    const part_box& b = t.parts[i];
    const index_t pi = static_cast<index_t>(i);
    const std::string where = who + ": template '" + t.id + "' part " + std::to_string(i) + " ('" + b.name + "')";
    if (!b.center.allFinite() || !b.axes.allFinite() || !b.size.allFinite() || !b.sigma_center.allFinite() ||
        !b.sigma_size.allFinite() || !b.feature_mean.allFinite() || !b.feature_sigma.allFinite())
      throw invalid_input(input_error::non_finite, pi, where + " has a non-finite number");
    if ((b.size.array() <= 0).any()) throw invalid_input(input_error::bad_parameter, pi, where + " has a size <= 0");
    if ((b.sigma_center.array() <= 0).any() || (b.sigma_size.array() <= 0).any())
      throw invalid_input(input_error::bad_parameter, pi, where + " has a standard deviation <= 0");
    if (!(b.axes * b.axes.transpose()).isIdentity(1e-6))
      throw invalid_input(input_error::bad_parameter, pi, where + " has axes that are not orthonormal");
    if (b.label < 0) throw invalid_input(input_error::bad_parameter, pi, where + " has a negative label");
    if (b.feature_mean.size() != dim || b.feature_sigma.size() != dim)
      throw invalid_input(input_error::size_mismatch, pi,
                          where + " has " + std::to_string(b.feature_mean.size()) + " feature means and " +
                              std::to_string(b.feature_sigma.size()) + " feature sigmas; part 0 has " +
                              std::to_string(dim));
    if ((b.feature_sigma.array() <= 0).any())
      throw invalid_input(input_error::bad_parameter, pi, where + " has a feature sigma <= 0");
  }
}

namespace detail {

inline nlohmann::ordered_json json_vec(const Eigen::VectorXd& v) {
  auto a = nlohmann::ordered_json::array();
  for (index_t i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

inline Eigen::VectorXd json_to_vec(const nlohmann::ordered_json& a, const std::string& what, index_t expected,
                                   const std::string& path) {
  if (!a.is_array()) throw io_error(file_error::bad_value, path, 0, 0, what + " must be an array of numbers");
  if (expected >= 0 && static_cast<index_t>(a.size()) != expected)
    throw io_error(file_error::bad_value, path, 0, 0,
                   what + " must have " + std::to_string(expected) + " numbers, found " + std::to_string(a.size()));
  Eigen::VectorXd out(static_cast<index_t>(a.size()));
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_number()) throw io_error(file_error::bad_value, path, 0, 0, what + " must contain only numbers");
    out[static_cast<index_t>(i)] = a[i].get<double>();
  }
  return out;
}

}  // namespace detail

/// The template as a JSON object (see docs/part_templates.md for the schema). O(parts x features).
inline nlohmann::ordered_json template_to_json(const part_template& t) {
  nlohmann::ordered_json o;  // ordered: keys are written in this order
  o["id"] = t.id;
  o["up_axis"] = t.up_axis;
  auto parts = nlohmann::ordered_json::array();
  for (const auto& b : t.parts) {
    nlohmann::ordered_json p;
    p["name"] = b.name;
    p["label"] = static_cast<long long>(b.label);
    p["center"] = detail::json_vec(b.center);
    auto axes = nlohmann::ordered_json::array();
    for (int r = 0; r < 3; ++r) axes.push_back(detail::json_vec(b.axes.row(r).transpose()));
    p["axes"] = std::move(axes);
    p["size"] = detail::json_vec(b.size);
    p["sigma_center"] = detail::json_vec(b.sigma_center);
    p["sigma_size"] = detail::json_vec(b.sigma_size);
    p["feature_mean"] = detail::json_vec(b.feature_mean);
    p["feature_sigma"] = detail::json_vec(b.feature_sigma);
    p["must_exist"] = b.must_exist;
    parts.push_back(std::move(p));
  }
  o["parts"] = std::move(parts);
  return o;
}

/// Builds a template from its JSON object. Optional keys take part_box's defaults ("axes" identity, sigmas 0.05,
/// no features, "label" = part index, "must_exist" false); "center" and "size" are required. "axes" rows within
/// 1e-3 of orthonormal (a few written decimals) are snapped to the nearest orthonormal matrix. The result is
/// validated (validate_template), so a template with no parts or inconsistent dimensions is rejected.
/// \throws io_error bad_value naming `path` and the offending key; invalid_input from validate_template.
inline part_template template_from_json(const nlohmann::ordered_json& v, const std::string& path = {}) {
  if (!v.is_object()) throw io_error(file_error::bad_value, path, 0, 0, "a template must be a JSON object");
  part_template t;
  if (const auto* id = json_member(v, "id")) {
    if (!id->is_string()) throw io_error(file_error::bad_value, path, 0, 0, "\"id\" must be a string");
    t.id = id->get<std::string>();
  }
  if (const auto* up = json_member(v, "up_axis")) {
    if (!up->is_number() || std::floor(up->get<double>()) != up->get<double>())
      throw io_error(file_error::bad_value, path, 0, 0, "\"up_axis\" must be an integer");
    t.up_axis = static_cast<int>(up->get<double>());
  }
  const auto* parts = json_member(v, "parts");
  if (parts == nullptr || !parts->is_array())
    throw io_error(file_error::bad_value, path, 0, 0, "template '" + t.id + "' needs a \"parts\" array");
  const auto& arr = *parts;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const nlohmann::ordered_json& p = arr[i];
    const std::string where = "part " + std::to_string(i);
    if (!p.is_object()) throw io_error(file_error::bad_value, path, 0, 0, where + " must be an object");
    part_box b;
    b.label = static_cast<index_t>(i);
    if (const auto* n = json_member(p, "name")) {
      if (!n->is_string()) throw io_error(file_error::bad_value, path, 0, 0, where + ": \"name\" must be a string");
      b.name = n->get<std::string>();
    }
    if (const auto* l = json_member(p, "label")) {
      if (!l->is_number() || std::floor(l->get<double>()) != l->get<double>())
        throw io_error(file_error::bad_value, path, 0, 0, where + ": \"label\" must be an integer");
      b.label = static_cast<index_t>(l->get<double>());
    }
    const auto* c = json_member(p, "center");
    const auto* s = json_member(p, "size");
    if (c == nullptr || s == nullptr)
      throw io_error(file_error::bad_value, path, 0, 0, where + " needs \"center\" and \"size\"");
    b.center = detail::json_to_vec(*c, where + ": \"center\"", 3, path);
    b.size = detail::json_to_vec(*s, where + ": \"size\"", 3, path);
    if (const auto* a = json_member(p, "axes")) {
      if (!a->is_array() || a->size() != 3)
        throw io_error(file_error::bad_value, path, 0, 0, where + ": \"axes\" must be 3 rows of 3 numbers");
      for (int r = 0; r < 3; ++r)
        b.axes.row(r) = detail::json_to_vec((*a)[static_cast<std::size_t>(r)], where + ": \"axes\" row", 3,
                                            path)
                            .transpose();
      // Hand-written axes carry a few decimals ([0.7071, 0, 0.7071]): snap rows within 1e-3 of orthonormal to
      // the nearest orthonormal matrix (polar factor U V^T); anything further off is left for validate_template
      // to reject. Axes that are orthonormal to rounding are kept bit for bit, so write/read round-trips exactly.
      const Eigen::Matrix3d gram = b.axes * b.axes.transpose();
      if (gram.isIdentity(1e-3) && !gram.isIdentity(1e-12)) {
        const Eigen::JacobiSVD<Eigen::Matrix3d> svd(b.axes, Eigen::ComputeFullU | Eigen::ComputeFullV);
        b.axes = svd.matrixU() * svd.matrixV().transpose();
      }
    }
    if (const auto* x = json_member(p, "sigma_center")) b.sigma_center = detail::json_to_vec(*x, where + ": \"sigma_center\"", 3, path);
    if (const auto* x = json_member(p, "sigma_size")) b.sigma_size = detail::json_to_vec(*x, where + ": \"sigma_size\"", 3, path);
    if (const auto* x = json_member(p, "feature_mean")) b.feature_mean = detail::json_to_vec(*x, where + ": \"feature_mean\"", -1, path);
    if (const auto* x = json_member(p, "feature_sigma")) b.feature_sigma = detail::json_to_vec(*x, where + ": \"feature_sigma\"", -1, path);
    if (const auto* x = json_member(p, "must_exist")) {
      if (!x->is_boolean()) throw io_error(file_error::bad_value, path, 0, 0, where + ": \"must_exist\" must be true or false");
      b.must_exist = x->get<bool>();
    }
    t.parts.push_back(std::move(b));
  }
  validate_template(t, path.empty() ? std::string("template_from_json") : path);
  return t;
}

/// Reads a template file: either one template object or {"templates": [ ... ]} (a template set).
/// \throws io_error (cannot_open, syntax with line:column, bad_value naming the key) and invalid_input
/// (validate_template, the message names the file). O(file size).
inline std::vector<part_template> read_templates(const std::string& path) {
  const nlohmann::ordered_json doc = read_json_file(path);
  std::vector<part_template> out;
  if (const auto* arr = json_member(doc, "templates")) {
    if (!arr->is_array()) throw io_error(file_error::bad_value, path, 0, 0, "\"templates\" must be an array");
    for (const auto& t : *arr) out.push_back(template_from_json(t, path));
    if (out.empty()) throw io_error(file_error::bad_value, path, 0, 0, "\"templates\" is empty");
  } else {
    out.push_back(template_from_json(doc, path));
  }
  return out;
}

/// Writes a template set as {"templates": [...]}. \throws io_error cannot_open / write_failed.
inline void write_templates(const std::string& path, const std::vector<part_template>& ts) {
  auto arr = nlohmann::ordered_json::array();
  for (const auto& t : ts) arr.push_back(template_to_json(t));
  nlohmann::ordered_json o;
  o["templates"] = std::move(arr);
  write_json_file(path, o);
}

}  // namespace shapestruct
