// SPDX-License-Identifier: MIT
// fit_state and the four EnergyTerm policies of the fitting energy (dissertation eq. 5.1-5.7): distance,
// feature, deformation and smoothness. energy_sum (energy_sum.hpp) composes them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/types.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/shape_samples.hpp"

namespace shapestruct {

/// Per-part, per-box-axis normal equations of the closed-form deformation update (5.3.2, step iii): unknowns are
/// the part centre along the axis (in box coordinates) and the side length. Terms ADD to A and b.
struct part_axis_system {
  Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};

/// A point of a deformed box: the part and its coordinate on the unit box ([-1/2, 1/2]^3, on the surface).
struct box_point {
  index_t part = no_index;
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
};

/// Everything the energy terms read: the template, the shape, the current rigid rotation (shape points are
/// rotated into the template frame: p = R^T q), deformation, labels and correspondences.
/// Labels: part index in [0, K) or K for the null label ("outlier", 5.3.2).
struct fit_state {
  const part_template* tpl = nullptr;
  const shape_samples* shape = nullptr;
  Eigen::Matrix<double, Eigen::Dynamic, 3> p;  ///< shape points in the template frame (#P x 3)
  std::vector<Eigen::Vector3d> centers;        ///< deformed part centres (template frame)
  std::vector<Eigen::Vector3d> sizes;          ///< deformed side lengths along the box axes
  std::vector<index_t> labels;                 ///< per shape point
  std::vector<box_point> s2t;                  ///< per shape point: closest point on its part's box
  /// template -> shape correspondences: template sample (part, u) -> shape point index (no_index: part empty)
  std::vector<box_point> t_samples;
  std::vector<index_t> t2s;
  double distance_unit = 0.05;  ///< distances are divided by this (fraction of the canonical diagonal)
  /// Per-point weight N_eff / |P_s| of the per-point terms: the chapter's means (eq. 5.3-5.5) times N_eff, so
  /// that the data outweigh the deformation prior as they would for N_eff points, whatever the sample count.
  double point_weight = 1;
  double effective_points = 500;  ///< N_eff (the t -> s mean is scaled by it too)

  [[nodiscard]] index_t num_parts() const noexcept { return static_cast<index_t>(centers.size()); }
  [[nodiscard]] index_t null_label() const noexcept { return num_parts(); }

  /// Position of unit-box coordinate u of part b under the current deformation.
  [[nodiscard]] Eigen::Vector3d deformed_point(index_t b, const Eigen::Vector3d& u) const {
    const auto& box = tpl->parts[static_cast<std::size_t>(b)];
    return centers[static_cast<std::size_t>(b)] +
           box.axes.transpose() * (sizes[static_cast<std::size_t>(b)].cwiseProduct(u));
  }
  /// Position of unit-box coordinate u of part b on the MEAN template (the canonical space of 5.4.4).
  [[nodiscard]] Eigen::Vector3d mean_point(index_t b, const Eigen::Vector3d& u) const {
    const auto& box = tpl->parts[static_cast<std::size_t>(b)];
    return box.center + box.axes.transpose() * box.size.cwiseProduct(u);
  }
  /// Closest point on the surface of deformed box b to x: its unit coordinate, and the squared distance.
  [[nodiscard]] std::pair<Eigen::Vector3d, double> closest_on_box(index_t b, const Eigen::Vector3d& x) const {
    return detail::closest_on_box_surface(tpl->parts[static_cast<std::size_t>(b)].axes,
                                          centers[static_cast<std::size_t>(b)], sizes[static_cast<std::size_t>(b)], x);
  }
};

/// E_{s->t} + E_{t->s} (eq. 5.3, 5.4): mean squared distance between shape points and their corresponding
/// template points, both directions, in units of fit_state::distance_unit. In labeling it contributes the
/// s->t part as unary costs (the chapter drops t->s there because m^{-1} needs a labeling); in the regression
/// both directions contribute data rows.
struct distance_term {
  using scalar_type = double;
  double weight = 1;
  /// Distance (canonical units) charged to a null-labeled point. The chapter charges 0 and relies on the
  /// feature penalty; with learned (tight) feature Gaussians that made the null label win for most points, so
  /// a point is only an outlier when it is farther than this from every part (or its features are very off).
  double null_distance = 0.1;

  [[nodiscard]] double value(const fit_state& x) const {
    const double u2 = x.distance_unit * x.distance_unit;
    double s2t = 0, t2s = 0;
    index_t ns = 0, nt = 0;
    for (std::size_t i = 0; i < x.labels.size(); ++i) {
      if (x.labels[i] >= x.num_parts()) {
        s2t += null_distance * null_distance;
        continue;
      }
      s2t += x.closest_on_box(x.labels[i], x.p.row(static_cast<index_t>(i)).transpose()).second;
      ++ns;
    }
    for (std::size_t j = 0; j < x.t_samples.size(); ++j) {
      if (x.t2s[j] == no_index) continue;
      t2s += (x.deformed_point(x.t_samples[j].part, x.t_samples[j].u) - x.p.row(x.t2s[j]).transpose()).squaredNorm();
      ++nt;
    }
    (void)ns;
    const double b = nt == 0 ? 0.0 : x.effective_points * t2s / static_cast<double>(nt);
    return weight * (x.point_weight * s2t + b) / u2;
  }
  /// Adds per-point costs (#P x (K+1)), times the point weight.
  void accumulate_unary(const fit_state& x, Eigen::MatrixXd& U) const {
    const double inv = x.point_weight * weight / (x.distance_unit * x.distance_unit);
    for (index_t i = 0; i < U.rows(); ++i) {
      for (index_t b = 0; b < x.num_parts(); ++b) U(i, b) += inv * x.closest_on_box(b, x.p.row(i).transpose()).second;
      U(i, x.null_label()) += inv * null_distance * null_distance;
    }
  }
  /// Adds data rows (weight w, unit coordinate u, observed box-frame coordinate o) to every part-axis system.
  void accumulate_regression(const fit_state& x, std::vector<std::array<part_axis_system, 3>>& sys) const {
    const double u2 = x.distance_unit * x.distance_unit;
    const double ws = x.point_weight * weight / u2;
    index_t nt = 0;
    for (const auto t : x.t2s) nt += t != no_index ? 1 : 0;
    const double wt = nt == 0 ? 0.0 : x.effective_points * weight / (u2 * static_cast<double>(nt));
    auto add = [&](index_t b, const Eigen::Vector3d& u, const Eigen::Vector3d& q, double w) {
      const Eigen::Vector3d o = x.tpl->parts[static_cast<std::size_t>(b)].axes * q;
      for (int k = 0; k < 3; ++k) {
        auto& s = sys[static_cast<std::size_t>(b)][static_cast<std::size_t>(k)];
        s.A(0, 0) += w;
        s.A(0, 1) += w * u[k];
        s.A(1, 0) += w * u[k];
        s.A(1, 1) += w * u[k] * u[k];
        s.b[0] += w * o[k];
        s.b[1] += w * o[k] * u[k];
      }
    };
    for (std::size_t i = 0; i < x.labels.size(); ++i)
      if (x.labels[i] < x.num_parts()) add(x.s2t[i].part, x.s2t[i].u, x.p.row(static_cast<index_t>(i)).transpose(), ws);
    for (std::size_t j = 0; j < x.t_samples.size(); ++j)
      if (x.t2s[j] != no_index) add(x.t_samples[j].part, x.t_samples[j].u, x.p.row(x.t2s[j]).transpose(), wt);
  }
};

/// gamma E_feat (eq. 5.5): dissimilarity of a point's local shape features to its part's feature Gaussian.
/// E_featdist = 1 - exp(-mean_d (f_d - mu_d)^2 / (2 sigma_d^2)), in [0, 1), so that the chapter's null-label
/// penalty of 1 is the largest possible dissimilarity (with a raw squared z-score the null label would win for
/// any point more than one sigma away, which is most points). Parts without features cost 0.
struct feature_term {
  using scalar_type = double;
  double weight = 2;        ///< gamma
  double null_penalty = 1;  ///< E_featdist(p, null)

  [[nodiscard]] static double dissimilarity(const fit_state& x, index_t i, index_t b) {
    const auto& box = x.tpl->parts[static_cast<std::size_t>(b)];
    const index_t D = std::min<index_t>(box.feature_mean.size(), x.shape->features.cols());
    if (D == 0) return 0.0;
    double z = 0;
    for (index_t d = 0; d < D; ++d) {
      const double t = (x.shape->features(i, d) - box.feature_mean[d]) / box.feature_sigma[d];
      z += t * t;
    }
    return 1.0 - std::exp(-0.5 * z / static_cast<double>(D));
  }
  [[nodiscard]] double value(const fit_state& x) const {
    double e = 0;
    for (std::size_t i = 0; i < x.labels.size(); ++i)
      e += x.labels[i] >= x.num_parts() ? null_penalty : dissimilarity(x, static_cast<index_t>(i), x.labels[i]);
    return x.point_weight * weight * e;
  }
  void accumulate_unary(const fit_state& x, Eigen::MatrixXd& U) const {
    const double w = x.point_weight * weight;
    for (index_t i = 0; i < U.rows(); ++i) {
      for (index_t b = 0; b < x.num_parts(); ++b) U(i, b) += w * dissimilarity(x, i, b);
      U(i, x.null_label()) += w * null_penalty;
    }
  }
};

/// alpha E_deform (eq. 5.6): squared z-scores of the part centres and sizes under the template's Gaussians,
/// per box axis. A must-exist part with no points makes the energy infinite (E_exist penalty).
struct deformation_term {
  using scalar_type = double;
  double weight = 0.5;  ///< alpha

  [[nodiscard]] double value(const fit_state& x) const {
    double e = 0;
    std::vector<char> used(static_cast<std::size_t>(x.num_parts()), 0);
    for (const auto l : x.labels)
      if (l < x.num_parts()) used[static_cast<std::size_t>(l)] = 1;
    for (index_t b = 0; b < x.num_parts(); ++b) {
      const auto& box = x.tpl->parts[static_cast<std::size_t>(b)];
      if (box.must_exist && !x.labels.empty() && !used[static_cast<std::size_t>(b)])
        return std::numeric_limits<double>::infinity();
      const Eigen::Vector3d dc = box.axes * (x.centers[static_cast<std::size_t>(b)] - box.center);
      const Eigen::Vector3d ds = x.sizes[static_cast<std::size_t>(b)] - box.size;
      e += dc.cwiseQuotient(box.sigma_center).squaredNorm() + ds.cwiseQuotient(box.sigma_size).squaredNorm();
    }
    return weight * e;
  }
  void accumulate_regression(const fit_state& x, std::vector<std::array<part_axis_system, 3>>& sys) const {
    for (index_t b = 0; b < x.num_parts(); ++b) {
      const auto& box = x.tpl->parts[static_cast<std::size_t>(b)];
      const Eigen::Vector3d mc = box.axes * box.center;
      for (int k = 0; k < 3; ++k) {
        auto& s = sys[static_cast<std::size_t>(b)][static_cast<std::size_t>(k)];
        const double wc = weight / (box.sigma_center[k] * box.sigma_center[k]);
        const double ws = weight / (box.sigma_size[k] * box.sigma_size[k]);
        s.A(0, 0) += wc;
        s.b[0] += wc * mc[k];
        s.A(1, 1) += ws;
        s.b[1] += ws * box.size[k];
      }
    }
  }
};

/// beta E_smooth (eq. 5.7): the weights of cut neighbourhood edges, times the point weight. The
/// edge weights are computed once per shape (make_shape_samples) from normal angles and distances.
struct smoothness_term {
  using scalar_type = double;
  double weight = 2;  ///< beta

  [[nodiscard]] double value(const fit_state& x) const {
    double e = 0;
    for (const auto& ed : x.shape->edges)
      if (x.labels[static_cast<std::size_t>(ed.a)] != x.labels[static_cast<std::size_t>(ed.b)]) e += ed.weight;
    return x.point_weight * weight * e;
  }
  void accumulate_pairwise(const fit_state& x, std::vector<potts_edge>& edges) const {
    for (const auto& ed : x.shape->edges) edges.push_back({ed.a, ed.b, x.point_weight * weight * ed.weight});
  }
};

}  // namespace shapestruct
