// SPDX-License-Identifier: MIT
// extrinsic_alignment: similarity alignment of two shape records (upright, or any rotation when the models share no
// up direction; principal-axis starts refined by ICP) and the alignment scores a = L_a * B_a it leaves on an edge of
// the alignment graph (dissertation 4.3.3).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <Eigen/SparseCore>

#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "shapestruct/geometry/principal_frame.hpp"
#include "shapestruct/knn/knn_index.hpp"

namespace shapestruct {

/// extrinsic_alignment_options::up_axis for a collection whose models share no up direction.
inline constexpr int no_up_axis = -1;

/// Options of align_extrinsic (the dissertation's defaults where it gives them).
struct extrinsic_alignment_options {
  /// The axis every model is upright along (0 = x, 1 = y, 2 = z); alignments rotate about it only. +y is up, as
  /// in the project's generator and most 3D Warehouse / COSEG models. no_up_axis (-1): the models are not
  /// consistently oriented (PSB's four-legged animals lie along x, y or z); the starts are then the four proper
  /// alignments of the 3-D principal axes and ICP fits any rotation (docs/fuzzy.md measures both on PSB).
  int up_axis = 1;
  /// sigma(S) = sigma_fraction * Diam(S): the ambiguity of a pairwise alignment (4.3.3 uses Diam(S) / 5), > 0.
  /// It trades precision for robustness (docs/fuzzy.md): Diam / 10 keeps landmarks sharper on clean collections
  /// (generated chairs: 0.914 within 0.10 against 0.717), Diam / 5 transfers part labels better on real ones
  /// (COSEG and PSB chairs, tables, four-legged animals).
  double sigma_fraction = 0.2;
  /// ICP iterations per start (>= 0; 0 keeps the principal-axis starts as they are).
  int icp_iterations = 30;
  /// ICP stops once an iteration changes the transform by less than this: relative scale change + rotation
  /// change in radians + translation change over Diam(source). >= 0.
  double icp_tolerance = 1e-6;
  /// Fit a uniform scale (4.3.3: "a 2D rotation and a scale"); false keeps the scale at 1.
  bool allow_scale = true;
  /// After the similarity ICP, refine once more with a scale per axis of the source's frame (x -> S R x + t, S
  /// diagonal, each scale within a factor 2 of the uniform one): shapes that differ in proportions (a wider seat,
  /// longer legs) then fit closely. Upright alignments only; needs allow_scale. Off in the chapter's matcher.
  bool axis_scales = false;
  /// Entries of a row of a(p_i, .) below keep_fraction * the row's largest are dropped; in [0, 1].
  float keep_fraction = 1e-3f;
  /// At most this many entries per row are kept (the largest), >= 1.
  index_t max_entries_per_row = 16;
};

namespace detail {

/// x -> scale * R(angle about the up axis) * x + translation: the transforms extrinsic alignment searches.
struct upright_similarity {
  double scale = 1;
  double angle = 0;  ///< radians, counter-clockwise seen from +up (right-handed about the up axis)
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

inline Eigen::Matrix3d upright_rotation(int up, double angle) {
  return Eigen::AngleAxisd(angle, Eigen::Vector3d::Unit(up)).toRotationMatrix();
}

/// A transform as the matrix A and translation t of x -> A x + t, with A^-1 for the reverse direction.
struct affine_pair {
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d A_inverse = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

inline affine_pair to_affine_pair(const upright_similarity& T, int up) {
  const Eigen::Matrix3d R = upright_rotation(up, T.angle);
  return {T.scale * R, R.transpose() / T.scale, T.translation};
}

/// x -> scale * rotation * x + translation, any rotation: what extrinsic alignment searches without an up axis.
struct free_similarity {
  double scale = 1;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

inline affine_pair to_affine_pair(const free_similarity& T, int /*up*/) {
  return {T.scale * T.rotation, T.rotation.transpose() / T.scale, T.translation};
}

/// x -> S R(angle about the up axis) x + translation with S = diag(scales) in the source's axes: an upright
/// similarity that also stretches each axis (options.axis_scales).
struct upright_stretch {
  Eigen::Vector3d scales = Eigen::Vector3d::Ones();
  double base_scale = 1;  ///< the uniform scale it started from: each of `scales` stays within a factor 2 of it
  double angle = 0;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

inline affine_pair to_affine_pair(const upright_stretch& T, int up) {
  const Eigen::Matrix3d R = upright_rotation(up, T.angle);
  return {T.scales.asDiagonal() * R, R.transpose() * T.scales.cwiseInverse().asDiagonal(), T.translation};
}

/// The size factor of a transform: what turns a distance in the target's frame into one in the source's.
inline double size_factor(const upright_similarity& T) { return T.scale; }
inline double size_factor(const free_similarity& T) { return T.scale; }
inline double size_factor(const upright_stretch& T) { return std::cbrt(T.scales.prod()); }

/// Centroid, angle of the first horizontal principal axis and RMS radius of a point set: what the principal-axis
/// starts need.
struct horizontal_frame {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  /// Angle of the major axis of the points projected onto the plane orthogonal to up, measured in the (a, b)
  /// coordinates a = (up + 1) % 3, b = (up + 2) % 3 (so that a rotation by phi about up adds phi to it).
  double major_angle = 0;
  double rms_radius = 0;  ///< sqrt(mean |p - centroid|^2), in 3-D
};

inline horizontal_frame horizontal_frame_of(const Eigen::Matrix<double, Eigen::Dynamic, 3>& P, int up) {
  horizontal_frame f;
  const int a = (up + 1) % 3, b = (up + 2) % 3;
  const double n = double(P.rows());
  f.centroid = P.colwise().sum().transpose() / n;
  double caa = 0, cbb = 0, cab = 0, r2 = 0;
  for (index_t i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d d = P.row(i).transpose() - f.centroid;
    caa += d[a] * d[a];
    cbb += d[b] * d[b];
    cab += d[a] * d[b];
    r2 += d.squaredNorm();
  }
  // Closed form of the 2 x 2 eigenproblem: deterministic, and a round horizontal section (caa = cbb, cab = 0)
  // gives angle 0 rather than whatever an iterative solver returns.
  f.major_angle = 0.5 * std::atan2(2 * cab, caa - cbb);
  f.rms_radius = std::sqrt(r2 / n);
  return f;
}

/// The means of two equally long point lists.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> means_of(const std::vector<Eigen::Vector3d>& p,
                                                            const std::vector<Eigen::Vector3d>& x) {
  Eigen::Vector3d p_mean = Eigen::Vector3d::Zero(), x_mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    p_mean += p[i];
    x_mean += x[i];
  }
  return {p_mean / double(p.size()), x_mean / double(p.size())};
}

/// Horn's symmetric scale sqrt(x_norm2 / p_norm2) (see fit_upright_similarity), `previous` where it is not a
/// positive finite number, 1 without allow_scale.
inline double symmetric_scale(double x_norm2, double p_norm2, bool allow_scale, double previous) {
  if (!allow_scale) return 1;
  const double scale = std::sqrt(x_norm2 / p_norm2);
  return scale > 0 && std::isfinite(scale) ? scale : previous;
}

/// The upright similarity best taking the p_i onto the x_i, in closed form. The rotation about `up` is the 2-D
/// Procrustes solution in the horizontal plane (the angle of sum z(x_i) conj(z(p_i)) for centred points written as
/// complex numbers z = v_a + i v_b); the up components need no rotation. The scale is Horn's symmetric one,
/// sqrt(sum |x_i'|^2 / sum |p_i'|^2) over the centred points, which minimises sum |x_i' / sqrt(s) - sqrt(s) R p_i'|^2
/// rather than the one-sided sum |s R p_i' - x_i'|^2: the one-sided (Umeyama) scale is a regression of x on p,
/// shrunk by the nearest-point noise of the pairs whose p is the nearest point (the reverse ones) and by poorly
/// correlated pairs far from the optimum, which can collapse the scale; the symmetric one is neither. The
/// translation then matches the centroids. Degenerate sums keep `previous`'s angle or scale.
inline upright_similarity fit_upright_similarity(const std::vector<Eigen::Vector3d>& p,
                                                 const std::vector<Eigen::Vector3d>& x, int up, bool allow_scale,
                                                 const upright_similarity& previous) {
  const int a = (up + 1) % 3, b = (up + 2) % 3;
  const auto [p_mean, x_mean] = means_of(p, x);
  double re = 0, im = 0, p_norm2 = 0, x_norm2 = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3d dp = p[i] - p_mean, dx = x[i] - x_mean;
    re += dx[a] * dp[a] + dx[b] * dp[b];
    im += dx[b] * dp[a] - dx[a] * dp[b];
    p_norm2 += dp.squaredNorm();
    x_norm2 += dx.squaredNorm();
  }
  upright_similarity T = previous;
  if (re != 0 || im != 0) T.angle = std::atan2(im, re);
  T.scale = symmetric_scale(x_norm2, p_norm2, allow_scale, T.scale);
  T.translation = x_mean - T.scale * upright_rotation(up, T.angle) * p_mean;
  return T;
}

/// The similarity with any rotation best taking the p_i onto the x_i, in closed form: the rotation is the 3-D
/// Procrustes solution (Kabsch: from the SVD of sum x_i' p_i'^T, a reflection turned into the nearest rotation),
/// the scale and translation as fit_upright_similarity's (Horn's symmetric scale, for the reasons given there).
/// Degenerate sums keep `previous`'s rotation or scale.
inline free_similarity fit_free_similarity(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& x,
                                           bool allow_scale, const free_similarity& previous) {
  const auto [p_mean, x_mean] = means_of(p, x);
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  double p_norm2 = 0, x_norm2 = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3d dp = p[i] - p_mean, dx = x[i] - x_mean;
    H += dx * dp.transpose();
    p_norm2 += dp.squaredNorm();
    x_norm2 += dx.squaredNorm();
  }
  free_similarity T = previous;
  if (H.squaredNorm() > 0) {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
    D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
    T.rotation = svd.matrixU() * D * svd.matrixV().transpose();
  }
  T.scale = symmetric_scale(x_norm2, p_norm2, allow_scale, T.scale);
  T.translation = x_mean - T.scale * T.rotation * p_mean;
  return T;
}

/// The upright stretch best taking the p_i onto the x_i, one alternation of closed forms from `previous`: the angle
/// by 2-D Procrustes between the p_i' and the x_i' with previous's stretch undone, then each axis's scale by least
/// squares on that axis, then the translation matching the centroids (primes: centred). Least squares, not the
/// symmetric scale of the similarities: that one is a ratio of the two point sets' spreads, which differ along a
/// stretched axis when the ICP's query points are not corresponding points. Each scale stays within a factor 2 of
/// `base_scale` (a thin axis holds too little spread to fit its own).
inline upright_stretch fit_upright_stretch(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& x,
                                           int up, const upright_stretch& previous) {
  const int a = (up + 1) % 3, b = (up + 2) % 3;
  const auto [p_mean, x_mean] = means_of(p, x);
  const Eigen::Vector3d unstretch = previous.scales.cwiseInverse();
  double re = 0, im = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3d dp = p[i] - p_mean, y = unstretch.cwiseProduct(x[i] - x_mean);
    re += y[a] * dp[a] + y[b] * dp[b];
    im += y[b] * dp[a] - y[a] * dp[b];
  }
  upright_stretch T = previous;
  if (re != 0 || im != 0) T.angle = std::atan2(im, re);
  const Eigen::Matrix3d R = upright_rotation(up, T.angle);
  Eigen::Vector3d qq = Eigen::Vector3d::Zero(), xq = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3d q = R * (p[i] - p_mean), dx = x[i] - x_mean;
    qq += q.cwiseAbs2();
    xq += dx.cwiseProduct(q);
  }
  for (int k = 0; k < 3; ++k) {
    const double scale = xq[k] / qq[k];
    if (scale > 0 && std::isfinite(scale))
      T.scales[k] = std::clamp(scale, 0.5 * previous.base_scale, 2 * previous.base_scale);
  }
  T.translation = x_mean - T.scales.asDiagonal() * (R * p_mean);
  return T;
}

/// Keeps the pairs whose squared distance is within the `keep` quantile of d2 (ties at the cut all stay).
inline void trim_pairs(std::vector<Eigen::Vector3d>& p, std::vector<Eigen::Vector3d>& x, std::vector<double>& d2,
                       std::size_t begin, double keep, std::vector<double>& scratch) {
  const std::size_t n = d2.size() - begin;
  if (n == 0) return;
  scratch.assign(d2.begin() + std::ptrdiff_t(begin), d2.end());
  const std::size_t k = std::min(n - 1, static_cast<std::size_t>(keep * double(n)));
  std::nth_element(scratch.begin(), scratch.begin() + std::ptrdiff_t(k), scratch.end());
  const double cut = scratch[k];
  std::size_t w = begin;
  for (std::size_t r = begin; r < d2.size(); ++r)
    if (d2[r] <= cut) {
      p[w] = p[r];
      x[w] = x[r];
      d2[w] = d2[r];
      ++w;
    }
  p.resize(w);
  x.resize(w);
  d2.resize(w);
}

inline double wrapped_angle_difference(double u, double v) {
  return std::abs(std::remainder(u - v, 2 * std::numbers::pi));
}

/// Up to `count` evenly spread rows of P (Euclidean farthest points from row 0): the ICP query points.
inline Eigen::Matrix<double, Eigen::Dynamic, 3> spread_subset(const Eigen::Matrix<double, Eigen::Dynamic, 3>& P,
                                                              index_t count) {
  if (P.rows() <= count) return P;
  const auto picks = farthest_point_sampling(P, count);
  Eigen::Matrix<double, Eigen::Dynamic, 3> out(count, 3);
  for (index_t i = 0; i < count; ++i) out.row(i) = P.row(picks.indices[std::size_t(i)]);
  return out;
}

// What the ICP below needs of each kind of transform: the closed-form fit and the size of a step.
inline upright_similarity fit_like(const upright_similarity& previous, const std::vector<Eigen::Vector3d>& p,
                                   const std::vector<Eigen::Vector3d>& x, const extrinsic_alignment_options& o) {
  return fit_upright_similarity(p, x, o.up_axis, o.allow_scale, previous);
}
inline free_similarity fit_like(const free_similarity& previous, const std::vector<Eigen::Vector3d>& p,
                                const std::vector<Eigen::Vector3d>& x, const extrinsic_alignment_options& o) {
  return fit_free_similarity(p, x, o.allow_scale, previous);
}
inline upright_stretch fit_like(const upright_stretch& previous, const std::vector<Eigen::Vector3d>& p,
                                const std::vector<Eigen::Vector3d>& x, const extrinsic_alignment_options& o) {
  return fit_upright_stretch(p, x, o.up_axis, previous);
}
/// Relative scale change + rotation change in radians + translation change over `length`.
inline double transform_change(const upright_similarity& next, const upright_similarity& T, double length) {
  return std::abs(next.scale - T.scale) / T.scale + wrapped_angle_difference(next.angle, T.angle) +
         (next.translation - T.translation).norm() / length;
}
inline double transform_change(const upright_stretch& next, const upright_stretch& T, double length) {
  return (next.scales - T.scales).cwiseQuotient(T.scales).cwiseAbs().sum() +
         wrapped_angle_difference(next.angle, T.angle) + (next.translation - T.translation).norm() / length;
}
inline double transform_change(const free_similarity& next, const free_similarity& T, double length) {
  const double cosine = std::clamp(((next.rotation * T.rotation.transpose()).trace() - 1) / 2, -1.0, 1.0);
  return std::abs(next.scale - T.scale) / T.scale + std::acos(cosine) +
         (next.translation - T.translation).norm() / length;
}

/// Symmetric trimmed point-to-point ICP over similarities (upright_similarity or free_similarity) taking the
/// target onto the source: each iteration pairs every transformed target query point (Ql) with its nearest source
/// surface point (tree_k) and every source query point (Qk) with the nearest target surface point (tree_l) of its
/// pre-image, drops the farthest pairs of each direction and refits. `length` scales the translation in the
/// stopping test.
template <class Similarity>
Similarity refine_similarity_icp(const Eigen::Matrix<double, Eigen::Dynamic, 3>& Qk, const knn_index<double, 3>& tree_k,
                                 const Eigen::Matrix<double, Eigen::Dynamic, 3>& Ql, const knn_index<double, 3>& tree_l,
                                 Similarity T, double length, const extrinsic_alignment_options& o) {
  // Trimmed ICP (Chetverikov et al. 2002) with a fixed 90 % overlap: parts present in only one of the two
  // shapes (the missing / extraneous parts 4.3 warns about) would otherwise pull the least-squares fit, and a hard
  // trim keeps the closed-form update. Both directions are used, so neither shape's extra parts can be ignored
  // wholesale (one-sided ICP happily shrinks the target into a sub-part of the source).
  constexpr double keep = 0.9;
  const int up = o.up_axis;
  std::vector<Eigen::Vector3d> p, x;
  std::vector<double> d2, scratch;
  p.reserve(std::size_t(Qk.rows() + Ql.rows()));
  x.reserve(p.capacity());
  d2.reserve(p.capacity());
  for (int it = 0; it < o.icp_iterations; ++it) {
    const affine_pair M = to_affine_pair(T, up);
    p.clear();
    x.clear();
    d2.clear();
    for (index_t j = 0; j < Ql.rows(); ++j) {
      const Eigen::Vector3d q = Ql.row(j).transpose();
      const auto nn = tree_k.nearest(Eigen::Vector3d(M.A * q + M.t));
      p.push_back(q);
      x.push_back(tree_k.point(nn.index));
      d2.push_back(nn.sq_distance);
    }
    trim_pairs(p, x, d2, 0, keep, scratch);
    const std::size_t reverse_begin = d2.size();
    // Distances measured in the target frame, reported in the source's.
    const double s2 = size_factor(T) * size_factor(T);
    for (index_t i = 0; i < Qk.rows(); ++i) {
      const Eigen::Vector3d v = Qk.row(i).transpose();
      const auto nn = tree_l.nearest(Eigen::Vector3d(M.A_inverse * (v - M.t)));
      p.push_back(tree_l.point(nn.index));
      x.push_back(v);
      d2.push_back(s2 * nn.sq_distance);
    }
    trim_pairs(p, x, d2, reverse_begin, keep, scratch);
    const Similarity next = fit_like(T, p, x, o);
    const double change = transform_change(next, T, length);
    T = next;
    if (change < o.icp_tolerance) break;
  }
  return T;
}

/// The scores of one transform x -> A x + t (target frame to source frame), eq. 4.1-4.3. Every distance is
/// measured in the frame of the shape it is measured to and compared with that shape's own sigma: the source
/// sample p_i is taken back into the target frame for L_a (|A^-1 (p_i - t) - p_j| against sigma(S_l), which for a
/// similarity is |p_i - T(p_j)| against the sigma of T(S_l)) and for the first factor of B_a, the target samples
/// are taken into the source frame for the second. With scale 1 this is eq. 4.2-4.3 as printed; with a scale it
/// keeps the scores independent of the units each model was modelled in.
inline alignment_alternative score_affine_pair(const shape_record& source, const shape_record& target,
                                               const knn_index<double, 3>& tree_k,
                                               const knn_index<double, 3>& tree_l, const affine_pair& M,
                                               const extrinsic_alignment_options& o) {
  const double sigma_k = o.sigma_fraction * source.diameter, sigma_l = o.sigma_fraction * target.diameter;
  const index_t Kk = source.samples.rows(), Kl = target.samples.rows();
  // Source samples in the target frame, reused by B_a's first factor and by L_a.
  Eigen::Matrix<double, Eigen::Dynamic, 3> back(Kk, 3);
  for (index_t i = 0; i < Kk; ++i) back.row(i) = (M.A_inverse * (source.samples.row(i).transpose() - M.t)).transpose();

  // B_a (eq. 4.3): the fraction of each shape's samples within about sigma / 2 of the other's surface, the
  // surface being approximated by its evenly spread surface_points (their spacing is far below sigma / 2).
  const double tight_k = 1.0 / ((0.5 * sigma_k) * (0.5 * sigma_k)), tight_l = 1.0 / ((0.5 * sigma_l) * (0.5 * sigma_l));
  double to_target = 0, to_source = 0;
  for (index_t i = 0; i < Kk; ++i) to_target += std::exp(-tree_l.nearest(back.row(i)).sq_distance * tight_l);
  for (index_t j = 0; j < Kl; ++j)
    to_source += std::exp(-tree_k.nearest(Eigen::Vector3d(M.A * target.samples.row(j).transpose() + M.t)).sq_distance * tight_k);
  alignment_alternative alt;
  alt.global_score = (to_target / double(Kk)) * (to_source / double(Kl));

  // L_a (eq. 4.2) row by row. a(p_i, p_j) >= keep_fraction * max_j a(p_i, p_j) is exactly
  // d2_j <= min d2 + sigma^2 ln(1 / keep_fraction), so entries are chosen on squared distances and only the kept
  // ones are exponentiated: no underflow can hide a row's largest entry.
  const double inv_sigma2 = 1.0 / (sigma_l * sigma_l);
  const double slack = o.keep_fraction > 0 ? -std::log(double(o.keep_fraction)) * sigma_l * sigma_l
                                           : std::numeric_limits<double>::infinity();
  std::vector<Eigen::Triplet<float, std::int32_t>> entries;
  entries.reserve(std::size_t(Kk * std::min(Kl, o.max_entries_per_row)));
  std::vector<std::pair<double, index_t>> row(static_cast<std::size_t>(Kl));
  for (index_t i = 0; i < Kk; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    for (index_t j = 0; j < Kl; ++j) {
      const double d2 = (back.row(i) - target.samples.row(j)).squaredNorm();
      row[std::size_t(j)] = {d2, j};
      nearest = std::min(nearest, d2);
    }
    const double cut = nearest + slack;
    const auto kept_end = std::partition(row.begin(), row.end(), [&](const auto& e) { return e.first <= cut; });
    const auto count = std::min<std::ptrdiff_t>(kept_end - row.begin(), std::ptrdiff_t(o.max_entries_per_row));
    // (d2, j) order: the largest scores first, ties to the lower sample, so the choice is deterministic.
    std::partial_sort(row.begin(), row.begin() + count, kept_end);
    for (std::ptrdiff_t e = 0; e < count; ++e) {
      const auto [d2, j] = row[std::size_t(e)];
      // A far-off alignment can underflow float; the smallest normal float keeps the entry (and every row) present
      // and positive, so a later row normalisation never divides by zero.
      const float value = std::max(static_cast<float>(alt.global_score * std::exp(-d2 * inv_sigma2)),
                                   std::numeric_limits<float>::min());
      entries.emplace_back(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j), value);
    }
  }
  alt.scores.resize(Kk, Kl);
  alt.scores.setFromTriplets(entries.begin(), entries.end());
  alt.scores.makeCompressed();

  Eigen::Matrix<double, 3, 4> affine;
  affine.leftCols<3>() = M.A;
  affine.col(3) = M.t;
  alt.parameters.assign(affine.data(), affine.data() + 12);
  return alt;
}

/// What ICP and the scores of one pair need, built once per pair: both shapes' surface-point trees and their ICP
/// query points. ICP pairs only an evenly spread subset of each shape's surface points with the nearest of ALL the
/// other's: the fit keeps the full surface's accuracy, while 4 starts x 30 iterations x 2 x 1,024 nearest-point
/// queries (~150 ms per call, measured) shrink to 2 x 128 per iteration (~10 ms per call). 128 per shape leaves
/// ~115 pairs per direction after trimming for the five parameters, at about the spacing of K = 128 samples.
struct extrinsic_pair_geometry {
  static constexpr index_t icp_queries = 128;
  const shape_record* source;
  const shape_record* target;
  knn_index<double, 3> tree_k, tree_l;
  Eigen::Matrix<double, Eigen::Dynamic, 3> query_k, query_l;

  extrinsic_pair_geometry(const shape_record& s, const shape_record& t)
      : source(&s), target(&t), tree_k(s.surface_points), tree_l(t.surface_points),
        query_k(spread_subset(s.surface_points, icp_queries)), query_l(spread_subset(t.surface_points, icp_queries)) {}

  /// ICP from `start` (an upright_similarity or a free_similarity), then the scores of the refined transform.
  /// With o.axis_scales an upright similarity is refined once more as an upright_stretch.
  template <class Similarity>
  [[nodiscard]] alignment_alternative refine_and_score(const Similarity& start,
                                                       const extrinsic_alignment_options& o) const {
    const Similarity T = refine_similarity_icp(query_k, tree_k, query_l, tree_l, start, source->diameter, o);
    if constexpr (std::is_same_v<Similarity, upright_similarity>) {
      if (o.axis_scales) {
        upright_stretch S;
        S.scales.setConstant(T.scale);
        S.base_scale = T.scale;
        S.angle = T.angle;
        S.translation = T.translation;
        S = refine_similarity_icp(query_k, tree_k, query_l, tree_l, S, source->diameter, o);
        return score_affine_pair(*source, *target, tree_k, tree_l, to_affine_pair(S, o.up_axis), o);
      }
    }
    return score_affine_pair(*source, *target, tree_k, tree_l, to_affine_pair(T, o.up_axis), o);
  }
};

inline void check_extrinsic_options(const extrinsic_alignment_options& o, const char* who) {
  auto fail = [&](const std::string& what) {
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": " + what);
  };
  if (o.up_axis < no_up_axis || o.up_axis > 2)
    fail("options.up_axis must be 0 (x), 1 (y), 2 (z) or no_up_axis (-1), got " + std::to_string(o.up_axis));
  if (!(o.sigma_fraction > 0) || !std::isfinite(o.sigma_fraction))
    fail("options.sigma_fraction must be positive and finite, got " + std::to_string(o.sigma_fraction));
  if (o.icp_iterations < 0) fail("options.icp_iterations must be >= 0, got " + std::to_string(o.icp_iterations));
  if (!(o.icp_tolerance >= 0) || !std::isfinite(o.icp_tolerance))
    fail("options.icp_tolerance must be finite and >= 0, got " + std::to_string(o.icp_tolerance));
  if (!(o.keep_fraction >= 0 && o.keep_fraction <= 1))
    fail("options.keep_fraction must be in [0, 1], got " + std::to_string(o.keep_fraction));
  if (o.max_entries_per_row < 1)
    fail("options.max_entries_per_row must be >= 1, got " + std::to_string(o.max_entries_per_row));
  if (o.axis_scales && (o.up_axis == no_up_axis || !o.allow_scale))
    fail("options.axis_scales needs an up axis and allow_scale (it stretches an upright similarity)");
}

inline void check_extrinsic_record(const shape_record& r, const char* role, const char* who) {
  const std::string name = std::string(who) + ": " + role;
  const std::string shape = r.name.empty() ? std::string() : " (shape '" + r.name + "')";
  if (r.samples.rows() == 0)
    throw invalid_input(input_error::empty, no_index,
                        name + ".samples is empty" + shape + "; the scores need the shape's K samples");
  if (r.surface_points.rows() == 0)
    throw invalid_input(input_error::empty, no_index,
                        name + ".surface_points is empty" + shape + "; ICP and B_a need the shape's surface points");
  if (!r.samples.allFinite())
    throw invalid_input(input_error::non_finite, no_index, name + ".samples has a non-finite coordinate" + shape);
  if (!r.surface_points.allFinite())
    throw invalid_input(input_error::non_finite, no_index,
                        name + ".surface_points has a non-finite coordinate" + shape);
  if (!(r.diameter > 0) || !std::isfinite(r.diameter))
    throw invalid_input(input_error::bad_parameter, no_index,
                        name + ".diameter must be positive and finite" + shape + ", got " + std::to_string(r.diameter) +
                            "; it is Diam(S), the mean distance between the samples");
}

/// The principal frame of all of P (its surface points).
inline principal_frame principal_frame_of_all(const Eigen::Matrix<double, Eigen::Dynamic, 3>& P) {
  std::vector<index_t> all(static_cast<std::size_t>(P.rows()));
  for (index_t i = 0; i < P.rows(); ++i) all[std::size_t(i)] = i;
  return principal_frame_of(P, all);
}

/// The 24 starts without an up axis: the rotations taking the target's principal axes onto the source's, in any
/// order and with either sign, the mirrors left out (both frames are right-handed). Any order, not only largest
/// onto largest: measured on PSB (docs/fuzzy.md), airplanes (span close to length) and tables (square tops) need
/// the other orders. The scale starts at the ratio of the RMS radii, the translation maps mean onto mean.
inline std::vector<free_similarity> free_starts(const principal_frame& fk, const principal_frame& fl,
                                                bool allow_scale) {
  const double rk = std::sqrt(fk.variances.sum()), rl = std::sqrt(fl.variances.sum());
  const double scale = allow_scale && rk > 0 && rl > 0 ? rk / rl : 1;
  constexpr std::array<std::array<int, 3>, 6> orders = {
      {{0, 1, 2}, {1, 0, 2}, {0, 2, 1}, {2, 1, 0}, {1, 2, 0}, {2, 0, 1}}};
  std::vector<free_similarity> out;
  for (const auto& order : orders)
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d P = Eigen::Matrix3d::Zero();  // target axis j -> +-source axis order[j]
      for (std::size_t j = 0; j < 3; ++j) P(order[j], Eigen::Index(j)) = (signs >> j & 1) ? -1 : 1;
      if (P.determinant() < 0) continue;
      free_similarity T;
      T.scale = scale;
      T.rotation = fk.axes.transpose() * P * fl.axes;  // axes are rows
      T.translation = fk.mean - scale * T.rotation * fl.mean;
      out.push_back(T);
    }
  return out;
}

}  // namespace detail

/// The 3 x 4 affine [s R | t] of an extrinsic alternative (its `parameters`, column-major): it takes target points
/// into the source's frame, x_source = M.leftCols<3>() * x_target + M.col(3).
/// \throws invalid_input (size_mismatch) unless the alternative has exactly 12 parameters.
[[nodiscard]] inline Eigen::Matrix<double, 3, 4> extrinsic_transform(const alignment_alternative& alternative) {
  if (alternative.parameters.size() != 12)
    throw invalid_input(input_error::size_mismatch, no_index,
                        "extrinsic_transform: alternative.parameters must hold the 12 entries of a 3 x 4 affine "
                        "transform, got " + std::to_string(alternative.parameters.size()));
  return Eigen::Map<const Eigen::Matrix<double, 3, 4>>(alternative.parameters.data());
}

/// Scores one given transform (target frame to source frame, x -> M.leftCols<3>() x + M.col(3), any invertible
/// linear part) as align_extrinsic scores its refined alternatives: B_a (eq. 4.3) as global_score, a = L_a * B_a
/// (eq. 4.1-4.2) as sparse scores, M as parameters. For re-scoring a transform during the graph optimisation.
/// \throws invalid_input as align_extrinsic; (bad_parameter) for a non-finite or singular transform.
/// Complexity O(K_k K_l + (K_k + K_l) log M).
[[nodiscard]] inline alignment_alternative score_extrinsic_alignment(const shape_record& source,
                                                                     const shape_record& target,
                                                                     const Eigen::Matrix<double, 3, 4>& transform,
                                                                     const extrinsic_alignment_options& options = {}) {
  const char* who = "score_extrinsic_alignment";
  detail::check_extrinsic_options(options, who);
  detail::check_extrinsic_record(source, "source", who);
  detail::check_extrinsic_record(target, "target", who);
  detail::affine_pair M;
  M.A = transform.leftCols<3>();
  M.t = transform.col(3);
  const double det = M.A.determinant();
  if (!transform.allFinite() || !(std::abs(det) > 0) || !std::isfinite(det))
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": transform must be finite with an invertible 3 x 3 part");
  M.A_inverse = M.A.inverse();
  const knn_index<double, 3> tree_k(source.surface_points), tree_l(target.surface_points);
  return detail::score_affine_pair(source, target, tree_k, tree_l, M, options);
}

/// Extrinsic pairwise alignment of ch. 4.3.3: finds transforms T = translation * uniform scale * rotation about the
/// up axis taking the target S_l into the source S_k's frame, and scores each with a(p_i, p_j) = L_a(p_i, p_j) B_a
/// (eq. 4.1-4.3) for p_i in source.samples, p_j in target.samples.
///
/// Starts: the four alignments of the shapes' first horizontal principal axes (PCA of the surface_points projected
/// onto the plane orthogonal to up, after centring). Matching the axes with their two signs and two orders gives
/// eight maps of the plane, four of them mirrors; upright models never need a mirror, so the four starts are the
/// proper rotations among them: theta0 (major axis onto major axis), theta0 + pi (the same axis, reversed), and
/// theta0 +- pi/2 (major axis onto the other's minor axis, for shapes whose proportions swap which horizontal
/// axis dominates). theta0 is the angle between the two major axes; the scale starts at the ratio of the RMS radii
/// about the centroids (1 with allow_scale = false) and the translation maps centroid onto centroid. Each start is
/// refined by symmetric trimmed ICP (closed-form upright Procrustes per iteration, up to icp_iterations): 128
/// evenly spread surface_points of each shape (farthest points) are paired with the nearest of all the other's
/// surface_points. With options.axis_scales each refined start is refined once more with a scale per axis of the
/// source's frame (detail::upright_stretch), the same ICP.
///
/// With options.up_axis = no_up_axis the rotation is free: 24 starts take the target's 3-D principal axes (PCA of
/// its surface_points) onto the source's in every order and with every sign change that keeps a rotation, and ICP
/// fits any rotation per iteration (Kabsch). Six times the work of the upright alignment.
///
/// All refined alternatives (4, or 24 without an up axis) are returned, in the start order above, with `initial`
/// the one of largest B_a: the graph optimisation (4.3.7) may pick another. Each alternative's parameters are the
/// 3 x 4 [s R | t] (S R with axis_scales) read back by extrinsic_transform; B_a uses sigma(S) =
/// options.sigma_fraction * diameter.
/// Distances to a surface are distances to the nearest of its surface_points. Rows of the scores keep the entries of at least
/// keep_fraction * the row's largest, at most max_entries_per_row of them (the largest), never fewer than one.
/// `seconds` is the wall time of the call.
///
/// Deterministic and free of shared state: safe to call concurrently for different (or the same) pairs.
/// \throws invalid_input (empty) for a record without samples or surface points, (non_finite) for a NaN/Inf
///         coordinate, (bad_parameter) for a non-positive diameter or an option out of range.
/// Complexity O(M (log M + 128) + icp_iterations 128 log M + K_k K_l) time, O(M + K_k max_entries_per_row)
/// memory; about 10 ms for K = 128, M = 1,024 on one core.
[[nodiscard]] inline pair_alignment align_extrinsic(const shape_record& source, const shape_record& target,
                                                    const extrinsic_alignment_options& options = {}) {
  const char* who = "align_extrinsic";
  const auto start_time = std::chrono::steady_clock::now();
  detail::check_extrinsic_options(options, who);
  detail::check_extrinsic_record(source, "source", who);
  detail::check_extrinsic_record(target, "target", who);
  const int up = options.up_axis;
  const detail::extrinsic_pair_geometry geometry(source, target);
  pair_alignment out;
  if (up == no_up_axis) {
    const principal_frame fk = detail::principal_frame_of_all(source.surface_points);
    const principal_frame fl = detail::principal_frame_of_all(target.surface_points);
    for (const auto& start : detail::free_starts(fk, fl, options.allow_scale))
      out.alternatives.push_back(geometry.refine_and_score(start, options));
    out.initial = best_global_alternative(out.alternatives);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    return out;
  }
  const detail::horizontal_frame fk = detail::horizontal_frame_of(source.surface_points, up);
  const detail::horizontal_frame fl = detail::horizontal_frame_of(target.surface_points, up);
  double scale = 1;
  if (options.allow_scale && fl.rms_radius > 0 && fk.rms_radius > 0) scale = fk.rms_radius / fl.rms_radius;

  constexpr double pi = std::numbers::pi;
  const double theta0 = fk.major_angle - fl.major_angle;
  const std::array<double, 4> starts = {theta0, theta0 + pi, theta0 + pi / 2, theta0 - pi / 2};
  out.alternatives.reserve(starts.size());
  for (const double angle : starts) {
    detail::upright_similarity T;
    T.scale = scale;
    T.angle = std::remainder(angle, 2 * pi);
    T.translation = fk.centroid - scale * detail::upright_rotation(up, T.angle) * fl.centroid;
    out.alternatives.push_back(geometry.refine_and_score(T, options));
  }
  out.initial = best_global_alternative(out.alternatives);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return out;
}

/// ShapeAligner over a collection's records by extrinsic alignment. Holds a reference to the records (the
/// collection owns them and must outlive the aligner) and the options; align is const and thread-safe.
class extrinsic_aligner {
 public:
  /// \throws invalid_input (bad_parameter) for options out of range.
  explicit extrinsic_aligner(const std::vector<shape_record>& records, const extrinsic_alignment_options& options = {})
      : records_(&records), options_(options) {
    detail::check_extrinsic_options(options_, "extrinsic_aligner");
  }
  /// The aligner would dangle on a temporary collection.
  extrinsic_aligner(std::vector<shape_record>&&, const extrinsic_alignment_options& = {}) = delete;

  /// align_extrinsic(records[source], records[target]) with `source` and `target` filled in.
  /// \throws invalid_input (bad_parameter) for an index out of range or source == target; as align_extrinsic.
  [[nodiscard]] pair_alignment align(index_t source, index_t target) const {
    const index_t n = static_cast<index_t>(records_->size());
    if (source < 0 || source >= n || target < 0 || target >= n || source == target)
      throw invalid_input(input_error::bad_parameter, no_index,
                          "extrinsic_aligner::align: source and target must be two different shapes in [0, " +
                              std::to_string(n) + "), got " + std::to_string(source) + " and " + std::to_string(target));
    pair_alignment out = align_extrinsic((*records_)[std::size_t(source)], (*records_)[std::size_t(target)], options_);
    out.source = source;
    out.target = target;
    return out;
  }

  [[nodiscard]] const extrinsic_alignment_options& options() const noexcept { return options_; }
  [[nodiscard]] const std::vector<shape_record>& records() const noexcept { return *records_; }

 private:
  const std::vector<shape_record>* records_;
  extrinsic_alignment_options options_;
};

}  // namespace shapestruct
