// SPDX-License-Identifier: MIT
// shape_samples: a shape as the fitter sees it (dissertation 5.3.1): points in a canonical frame, normals,
// local shape features and a neighbourhood graph.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/templates/alpha_expansion.hpp"

namespace shapestruct {

/// A shape sampled for template fitting. Points live in the canonical frame: input coordinates minus `center`
/// (the bounding-box centre), divided by `scale` (the bounding-box diagonal), so the shape radius R of the
/// chapter (largest distance between two points) is close to 1 and templates are scale-free.
///   points    (#P x 3) canonical positions
///   normals   (#P x 3) unit normals (orientation irrelevant: soups have no consistent orientation)
///   features  (#P x D) local shape features (D = 0 allowed: the feature term is then constant)
///   faces     (#P)     source face of each sample (no_index for point clouds) for projecting labels to faces
///   edges     neighbourhood graph (kNN, symmetric, each pair once) with the smoothness weight of eq. 5.7
struct shape_samples {
  Eigen::Matrix<double, Eigen::Dynamic, 3> points;
  Eigen::Matrix<double, Eigen::Dynamic, 3> normals;
  Eigen::MatrixXd features;
  std::vector<index_t> faces;
  std::vector<potts_edge> edges;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double scale = 1;

  [[nodiscard]] index_t size() const noexcept { return points.rows(); }
};

/// Smoothness weight of a neighbourhood edge (eq. 5.7, as intended): high between nearby points with similar
/// normals, low across creases. The printed formula, -log(1 - theta/pi) exp(d / tau^2), is zero for parallel
/// normals and grows with distance, the opposite of the text's stated intent ("penalizes segmentations in which
/// nearby points with similar surface normals are assigned to different parts"); we use
/// -log(max(theta/pi, 0.01)) / -log(0.01) * exp(-d^2 / tau^2), in (0, 1], with theta the angle between the
/// unoriented normals (soups have no consistent orientation).
inline double smoothness_weight(const Eigen::Vector3d& n1, const Eigen::Vector3d& n2, double dist, double tau) {
  const double c = std::min(1.0, std::abs(n1.dot(n2)) / std::max(1e-300, n1.norm() * n2.norm()));
  const double theta = std::acos(c);
  constexpr double floor_ratio = 0.01;  // caps the weight of exactly parallel normals at 1
  const double w = -std::log(std::max(theta / 3.14159265358979323846, floor_ratio)) / -std::log(floor_ratio);
  return w * std::exp(-(dist * dist) / (tau * tau));
}

/// Checks the invariants of shape_samples (sizes agree, finite values, edges in range, scale > 0).
/// \throws invalid_input empty, size_mismatch, non_finite (point index), bad_face (edge index), bad_parameter.
inline void validate_samples(const shape_samples& s, const std::string& who) {
  const index_t n = s.points.rows();
  if (n == 0) throw invalid_input(input_error::empty, no_index, who + ": the shape has no sample points");
  if (s.normals.rows() != n || (s.features.size() > 0 && s.features.rows() != n) ||
      (!s.faces.empty() && static_cast<index_t>(s.faces.size()) != n))
    throw invalid_input(input_error::size_mismatch, no_index,
                        who + ": points, normals, features and faces of the samples differ in length");
  for (index_t i = 0; i < n; ++i)
    if (!s.points.row(i).allFinite() || !s.normals.row(i).allFinite() ||
        (s.features.size() > 0 && !s.features.row(i).allFinite()))
      throw invalid_input(input_error::non_finite, i, who + ": sample " + std::to_string(i) + " is not finite");
  for (std::size_t k = 0; k < s.edges.size(); ++k)
    if (s.edges[k].a < 0 || s.edges[k].b < 0 || s.edges[k].a >= n || s.edges[k].b >= n ||
        !(s.edges[k].weight >= 0) || !std::isfinite(s.edges[k].weight))
      throw invalid_input(input_error::bad_face, static_cast<index_t>(k),
                          who + ": neighbourhood edge " + std::to_string(k) + " is out of range or badly weighted");
  if (!(s.scale > 0) || !std::isfinite(s.scale) || !s.center.allFinite())
    throw invalid_input(input_error::bad_parameter, no_index, who + ": the canonical-frame scale must be > 0");
}

}  // namespace shapestruct
