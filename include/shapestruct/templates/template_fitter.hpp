// SPDX-License-Identifier: MIT
// fit_template: fits a part-based template to one sampled shape (dissertation 5.3.2, eq. 5.1-5.7).
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "shapestruct/core/status.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/templates/alpha_expansion.hpp"
#include "shapestruct/templates/energy_sum.hpp"
#include "shapestruct/templates/fit_energy_terms.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/pivot_start.hpp"
#include "shapestruct/templates/shape_samples.hpp"

namespace shapestruct {

/// Options of fit_template, with the chapter's values where it gives them.
struct template_fit_options {
  int rotations = 4;              ///< candidate rotations about the up axis, multiples of 2 pi / rotations (5.3.2)
  int max_iterations = 100;       ///< label / correspondence / regression rounds per rotation (5.3.2)
  int samples_per_part = 96;      ///< template points per box for the t -> s term (area-weighted on the mean box)
  double distance_unit = 0.05;    ///< distances in units of this fraction of the canonical diagonal (see docs)
  double effective_points = 500;  ///< N_eff: per-point terms are means times N_eff (fit_state::point_weight)
  double deformation_tolerance = 1e-3;  ///< converged when no part centre or size moves more than this
  int rotation_probe_rounds = 3;  ///< rounds every rotation gets before only the best continues
  int graph_cut_sweeps = 1;       ///< alpha-expansion sweeps per round (warm-started from the last labeling)
  bool deform = true;             ///< false: keep the mean template (the chapter's "init" results)
  /// Heights tried per pivot by the extra start (best_pivot_start; 0: only the mean template starts)
  int pivot_start_heights = 12;
  std::uint64_t seed = 1;         ///< seeds the template-sample positions (deterministic results)
};

/// Result of fitting one template to one shape. The rigid part maps shape canonical points q to the template
/// frame as p = rotation * q; input coordinates x map to q = (x - samples.center) / samples.scale.
struct template_fit {
  /// e of eq. 5.1 divided by N_eff: the chapter's per-point means plus alpha E_deform / N_eff (docs)
  double energy = std::numeric_limits<double>::infinity();
  std::vector<double> terms;                                 ///< each energy term's value, in energy order
  int rotation_index = 0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  std::vector<Eigen::Vector3d> centers;  ///< per part: deformed centre (template frame)
  std::vector<Eigen::Vector3d> sizes;    ///< per part: deformed side lengths
  std::vector<index_t> parts;            ///< per sample: part index, or -1 for the null label
  std::vector<index_t> labels;           ///< per sample: the part's output label (part_box::label), or -1
  std::vector<box_point> correspondence; ///< per sample: (part, unit-box coordinate) on the template
  int iterations = 0;
  status info = status::ok;  ///< not_converged if a rotation hit max_iterations; numerical_issue if no valid fit
};

namespace detail {

/// Area-weighted, seeded samples of the unit-box surface, scaled by the mean box's side lengths.
inline std::vector<box_point> template_box_samples(const part_template& t, int per_part, std::uint64_t seed) {
  std::vector<box_point> out;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(-0.5, 0.5);
  for (index_t b = 0; b < t.num_parts(); ++b) {
    const Eigen::Vector3d& s = t.parts[static_cast<std::size_t>(b)].size;
    const std::array<double, 3> area{s[1] * s[2], s[0] * s[2], s[0] * s[1]};  // face pair normal to axis k
    const double total = area[0] + area[1] + area[2];
    for (int j = 0; j < per_part; ++j) {
      double r = (j + 0.5) / per_part * total;  // stratified choice of the face pair keeps counts exact
      int k = 0;
      while (k < 2 && r > area[static_cast<std::size_t>(k)]) r -= area[static_cast<std::size_t>(k++)];
      Eigen::Vector3d u(u01(rng), u01(rng), u01(rng));
      u[k] = (j % 2 == 0) ? 0.5 : -0.5;
      out.push_back({b, u});
    }
  }
  return out;
}

inline Eigen::Matrix3d rotation_about_axis(int axis, double angle) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  const double c = std::cos(angle), s = std::sin(angle);
  R(a, a) = c;
  R(a, b) = -s;
  R(b, a) = s;
  R(b, b) = c;
  return R;
}

/// Correspondences for the current labels and deformation: s -> t closest box point; t -> s nearest shape point
/// carrying the same part label (brute force per part: parts hold |P| / K points, cheaper than a tree rebuild).
inline void update_correspondences(fit_state& x) {
  const index_t n = x.p.rows(), K = x.num_parts();
  x.s2t.assign(static_cast<std::size_t>(n), box_point{});
  std::vector<std::vector<index_t>> members(static_cast<std::size_t>(K));
  for (index_t i = 0; i < n; ++i) {
    const index_t b = x.labels[static_cast<std::size_t>(i)];
    if (b >= K) continue;
    x.s2t[static_cast<std::size_t>(i)] = {b, x.closest_on_box(b, x.p.row(i).transpose()).first};
    members[static_cast<std::size_t>(b)].push_back(i);
  }
  x.t2s.assign(x.t_samples.size(), no_index);
  for (std::size_t j = 0; j < x.t_samples.size(); ++j) {
    const auto& m = members[static_cast<std::size_t>(x.t_samples[j].part)];
    if (m.empty()) continue;
    const Eigen::Vector3d y = x.deformed_point(x.t_samples[j].part, x.t_samples[j].u);
    double best = std::numeric_limits<double>::infinity();
    for (const index_t i : m) {
      const double d = (x.p.row(i).transpose() - y).squaredNorm();
      if (d < best) {
        best = d;
        x.t2s[j] = i;
      }
    }
  }
}

/// Closed-form deformation update (5.3.2 step iii): one 2x2 solve per part and box axis.
template <class Energy>
void regress_deformation(fit_state& x, const Energy& energy) {
  std::vector<std::array<part_axis_system, 3>> sys(static_cast<std::size_t>(x.num_parts()));
  energy.accumulate_regression(x, sys);
  for (index_t b = 0; b < x.num_parts(); ++b) {
    const auto& box = x.tpl->parts[static_cast<std::size_t>(b)];
    Eigen::Vector3d c_local = box.axes * x.centers[static_cast<std::size_t>(b)];
    Eigen::Vector3d& s = x.sizes[static_cast<std::size_t>(b)];
    for (int k = 0; k < 3; ++k) {
      const auto& S = sys[static_cast<std::size_t>(b)][static_cast<std::size_t>(k)];
      if (std::abs(S.A.determinant()) < 1e-300) continue;  // no data and no prior: keep the current value
      const Eigen::Vector2d sol = S.A.partialPivLu().solve(S.b);
      if (!sol.allFinite()) continue;
      c_local[k] = sol[0];
      // A box may flatten (a seat is nearly planar) but never invert: keep 1% of the mean size.
      s[k] = std::max(sol[1], 0.01 * box.size[k]);
    }
    x.centers[static_cast<std::size_t>(b)] = box.axes.transpose() * c_local;
  }
}

}  // namespace detail

/// Fits template t to shape s: from each of the `rotations` candidate rotations about the up axis (and one extra
/// start, see template_fit_options::pivot_start_heights), alternates
/// (i) labeling by alpha-expansion on the unary and pairwise costs of `energy` (null label included),
/// (ii) closest-point correspondences within each part in both directions, (iii) closed-form per-part centre and
/// size regression with the deformation prior, until the labeling stops changing; returns the rotation with
/// the lowest energy.
/// \param t      a template (validated here)
/// \param s      the shape's samples (validated here), see make_shape_samples
/// \param energy any energy_sum over fit_state terms; make_chapter5_energy() is the chapter's
/// \throws invalid_input from validate_template / validate_samples (bad template or samples), bad_parameter for
///         options out of range, size_mismatch when the template's feature dimension exceeds the samples'.
/// \returns the best fit; info = numerical_issue when every rotation violated a must-exist part (energy inf).
/// Complexity: (rotations + 1) x iterations x (P K box distances + sweeps K max-flows on P nodes + P K_samples),
/// plus the pivot search (best_pivot_start: rotations x pivots x heights x (P / 4 x K + 14 K log P)).
template <class Energy = chapter5_energy>
[[nodiscard]] template_fit fit_template(const part_template& t, const shape_samples& s,
                                        const template_fit_options& opt = {},
                                        const Energy& energy = make_chapter5_energy()) {
  validate_template(t, "fit_template");
  validate_samples(s, "fit_template");
  if (opt.rotations < 1 || opt.max_iterations < 1 || opt.samples_per_part < 1 || !(opt.distance_unit > 0) ||
      opt.graph_cut_sweeps < 1 || !(opt.effective_points > 0) || opt.rotation_probe_rounds < 1 ||
      opt.pivot_start_heights < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        "fit_template: rotations, max_iterations, samples_per_part, graph_cut_sweeps must be >= 1, "
                        "pivot_start_heights >= 0 and distance_unit > 0");
  if (t.parts.front().feature_mean.size() > s.features.cols())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "fit_template: template '" + t.id + "' has " +
                            std::to_string(t.parts.front().feature_mean.size()) +
                            " features per part but the shape samples have " + std::to_string(s.features.cols()));
  const index_t K = t.num_parts();
  fit_state x;
  x.tpl = &t;
  x.shape = &s;
  x.distance_unit = opt.distance_unit;
  x.effective_points = opt.effective_points;
  x.point_weight = opt.effective_points / static_cast<double>(s.size());
  x.t_samples = detail::template_box_samples(t, opt.samples_per_part, opt.seed);
  x.t2s.assign(x.t_samples.size(), no_index);
  std::vector<potts_edge> edges;
  energy.accumulate_pairwise(x, edges);

  // One round = labeling, correspondences, regression. Returns true when converged.
  auto round = [&](fit_state& y) {
    Eigen::MatrixXd U = Eigen::MatrixXd::Zero(s.size(), K + 1);
    energy.accumulate_unary(y, U);
    auto ae = alpha_expansion(U, edges, y.labels, {.max_sweeps = opt.graph_cut_sweeps});
    const bool changed = ae.labels != y.labels;
    y.labels = std::move(ae.labels);
    detail::update_correspondences(y);
    // Stop when the labeling is stable (5.3.2) AND the deformation has settled: closest-point correspondences
    // are ICP-like and need several rounds to converge even when no label moves.
    double moved = 0;
    if (opt.deform) {
      const auto c0 = y.centers;
      const auto s0 = y.sizes;
      detail::regress_deformation(y, energy);
      detail::update_correspondences(y);
      for (index_t b = 0; b < K; ++b)
        moved = std::max({moved, (y.centers[static_cast<std::size_t>(b)] - c0[static_cast<std::size_t>(b)]).norm(),
                          (y.sizes[static_cast<std::size_t>(b)] - s0[static_cast<std::size_t>(b)]).norm()});
    }
    return !changed && moved < opt.deformation_tolerance;
  };
  // Starts: the mean template under each rotation (the chapter's four) plus, unless disabled, the best
  // piecewise-linear arrangement of best_pivot_start (for shapes whose proportions differ from the template's).
  // Phase 1: every start runs `rotation_probe_rounds` rounds; phase 2: the lowest-energy one runs to convergence.
  // (The chapter converges all four; after a few rounds the order of the energies is settled in practice, and
  // this cuts the cost by about 3x.)
  struct candidate {
    fit_state y;
    Eigen::Matrix3d R;
    int rotation_index = 0;
    int rounds = 0;
    bool converged = false;
    double e = std::numeric_limits<double>::infinity();
  };
  std::vector<candidate> cands(static_cast<std::size_t>(opt.rotations));
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<Eigen::MatrixXd> rotated;
  for (int r = 0; r < opt.rotations; ++r) {
    rotations.push_back(detail::rotation_about_axis(t.up_axis, 2 * std::numbers::pi * r / opt.rotations));
    rotated.push_back(s.points * rotations.back().transpose());
  }
  pivot_start_result pivot;
  if (opt.pivot_start_heights > 0) {
    const knn_index<double, 3> index(s.points);
    pivot = best_pivot_start(t, rotated, index, rotations, opt.pivot_start_heights, detail::box_corners_and_faces());
    if (std::isfinite(pivot.score)) cands.emplace_back();
  }
  for (std::size_t ci = 0; ci < cands.size(); ++ci) {
    const bool is_pivot = ci == static_cast<std::size_t>(opt.rotations);
    const auto r = static_cast<std::size_t>(is_pivot ? pivot.rotation : static_cast<int>(ci));
    auto& c = cands[ci];
    c.R = rotations[r];
    c.y = x;
    c.y.p = rotated[r];
    c.rotation_index = static_cast<int>(r);
    if (is_pivot) {
      c.y.centers = pivot.centers;
      c.y.sizes = pivot.sizes;
    } else {
      for (const auto& b : t.parts) {
        c.y.centers.push_back(b.center);
        c.y.sizes.push_back(b.size);
      }
    }
    c.y.t2s.assign(x.t_samples.size(), no_index);
    const int probe = cands.size() > 1 ? std::min(opt.rotation_probe_rounds, opt.max_iterations) : opt.max_iterations;
    while (!c.converged && c.rounds < probe) {
      c.converged = round(c.y);
      ++c.rounds;
    }
    c.e = energy.value(c.y);
  }
  std::size_t r_best = 0;
  for (std::size_t r = 1; r < cands.size(); ++r)
    if (cands[r].e < cands[r_best].e) r_best = r;
  auto& c = cands[r_best];
  while (!c.converged && c.rounds < opt.max_iterations) {
    c.converged = round(c.y);
    ++c.rounds;
  }
  template_fit best;
  const fit_state& y = c.y;
  best.energy = energy.value(y) / opt.effective_points;
  const auto v = energy.values(y);
  best.terms.assign(v.begin(), v.end());
  for (auto& term : best.terms) term /= opt.effective_points;
  best.rotation_index = c.rotation_index;
  best.rotation = c.R;
  best.centers = y.centers;
  best.sizes = y.sizes;
  best.parts.resize(y.labels.size());
  best.labels.resize(y.labels.size());
  for (std::size_t i = 0; i < y.labels.size(); ++i) {
    const bool null = y.labels[i] >= K;
    best.parts[i] = null ? -1 : y.labels[i];
    best.labels[i] = null ? -1 : t.parts[static_cast<std::size_t>(y.labels[i])].label;
  }
  best.correspondence = y.s2t;
  best.iterations = c.rounds;
  const bool any_unconverged = !c.converged;
  best.info = !std::isfinite(best.energy) ? status::numerical_issue
                                          : (any_unconverged ? status::not_converged : status::ok);
  return best;
}

}  // namespace shapestruct
