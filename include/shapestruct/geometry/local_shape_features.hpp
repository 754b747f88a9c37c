// SPDX-License-Identifier: MIT
// local_shape_features: per-point covariance (PCA) features of a neighbourhood, as in dissertation section 5.3.2.
#pragma once

#include <algorithm>
#include <array>
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
#include <Eigen/Eigenvalues>

#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/detail/eigen_forward.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/knn/detail/morton_order.hpp"
#include "shapestruct/knn/knn_index.hpp"

namespace shapestruct {

/// Number of columns of local_shape_features_result::features.
inline constexpr int local_shape_feature_count = 6;

/// Options of local_shape_features. Defaults are the dissertation's (section 5.3.2).
struct local_shape_features_options {
  /// Neighbourhood radius as a fraction of the shape diameter R ("the furthest distance between any pair of
  /// points in a shape"): tau_Nhd = 0.15 R in the dissertation. Used when radius == 0 and k == 0. Must be > 0.
  double radius_fraction = 0.15;
  /// Absolute neighbourhood radius; > 0 overrides radius_fraction.
  double radius = 0;
  /// > 0: use the k nearest points (the point itself included) instead of a radius neighbourhood.
  index_t k = 0;
  /// Shape diameter R; 0 = estimate it from the points (see estimate_diameter), > 0 = use this value (e.g. to
  /// give every shape of a collection the same neighbourhood size).
  double shape_diameter = 0;
  /// The collection's up direction a_up and second reference axis a_2 of the angle features (normalised on
  /// entry). The dissertation assumes repositories have a default up direction; +Y is the convention of the
  /// OFF/OBJ data sets we read (COSEG, PSB, Warehouse exports), and a_2 = +X is the horizontal axis.
  std::array<double, 3> up_axis = {0, 1, 0};
  std::array<double, 3> second_axis = {1, 0, 0};
  /// Worker threads, 0 = all cores; results do not depend on it.
  int threads = 0;
  validation_level validation = validation_level::full;
};

/// Per-point local shape features of a point set (row i describes point i).
///   features        (#P x 6)  the dissertation's feature vector f, in [0, 1]:
///                     [lambda2/lambda1, lambda3/lambda1, acos|v1.a_up|/pi, acos|v1.a_2|/pi,
///                      acos|v2.a_up|/pi, acos|v2.a_2|/pi]
///                     Eigenvectors are defined only up to sign, so the literal acos(v . a) / pi would jump
///                     between theta/pi and 1 - theta/pi with the solver's sign choice; the angle between the
///                     axis LINES, acos|v . a| / pi in [0, 1/2], is the sign-free reading.
///   eigenvalues     (#P x 3)  lambda1 >= lambda2 >= lambda3 of the neighbourhood covariance divided by the squared
///                     neighbourhood radius (the radius, or the distance to the k-th neighbour in k mode): scale
///                     free, e.g. 1/4, 1/4, 0 for a uniformly sampled flat disc.
///   principal_axes  (#P x 3)  v1, the direction of largest spread
///   normals         (#P x 3)  v3, the direction of least spread (surface normal estimate), oriented away from the
///                     centroid of all points (outward on closed, roughly star-shaped shapes)
///   linearity, planarity, scattering (#P)  (l1 - l2)/l1, (l2 - l3)/l1, l3/l1 (they sum to 1)
///   neighbor_counts (#P)      neighbourhood sizes, the point itself included
/// Points whose neighbourhood has no spread (fewer than 2 distinct points) get eigenvalues 0, ratios 0, angle
/// features 1/4 (the middle of their range), zero axes, and are counted in `degenerate`.
template <class Scalar = double>
struct local_shape_features_result {
  matrix_x<Scalar> features;
  matrix_x3<Scalar> eigenvalues;
  matrix_x3<Scalar> principal_axes;
  matrix_x3<Scalar> normals;
  vector_x<Scalar> linearity;
  vector_x<Scalar> planarity;
  vector_x<Scalar> scattering;
  Eigen::Matrix<index_t, Eigen::Dynamic, 1> neighbor_counts;
  Scalar radius = 0;          ///< the neighbourhood radius used (0 in k-nearest mode)
  Scalar shape_diameter = 0;  ///< R, given or estimated
  index_t degenerate = 0;     ///< points whose neighbourhood has no spread
};

/// Diameter of a point set (largest pairwise distance), estimated from the points that are extreme along 256
/// fixed directions (a Fibonacci hemisphere): the exact maximum over those candidates. The diameter pair is
/// extreme along its own direction, which lies within ~0.1 rad of a sampled one, so the estimate is a lower
/// bound within 0.5% of the diameter (and exact whenever the pair is among the candidates). O(256 P).
/// \param P (#P x 3) points. \returns 0 for fewer than 2 distinct points.
/// \throws invalid_input empty, non_finite (validate_points).
template <class Scalar>
[[nodiscard]] Scalar estimate_diameter(const Eigen::Ref<const matrix_x3<Scalar>>& P,
                                       validation_level level = validation_level::full) {
  validate_points(P, "estimate_diameter", level);
  constexpr int directions = 256;
  std::vector<index_t> candidates;
  candidates.reserve(2 * directions);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int d = 0; d < directions; ++d) {
    const double z = 1.0 - (double(d) + 0.5) / double(directions);  // hemisphere z in (0, 1)
    const double rho = std::sqrt(1.0 - z * z), phi = golden * double(d);
    const vec3<Scalar> u(Scalar(rho * std::cos(phi)), Scalar(rho * std::sin(phi)), Scalar(z));
    index_t lo = 0, hi = 0;
    Scalar vlo = std::numeric_limits<Scalar>::infinity(), vhi = -vlo;
    for (index_t i = 0; i < P.rows(); ++i) {
      const Scalar v = P.row(i).dot(u.transpose());
      if (v < vlo) vlo = v, lo = i;
      if (v > vhi) vhi = v, hi = i;
    }
    candidates.push_back(lo);
    candidates.push_back(hi);
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  Scalar best = 0;
  for (std::size_t a = 0; a < candidates.size(); ++a)
    for (std::size_t b = a + 1; b < candidates.size(); ++b)
      best = std::max(best, (P.row(candidates[a]) - P.row(candidates[b])).squaredNorm());
  return std::sqrt(best);
}

namespace detail {

inline Eigen::Vector3d feature_axis(const std::array<double, 3>& a, const char* name) {
  const Eigen::Vector3d v(a[0], a[1], a[2]);
  const double n = v.norm();
  if (!std::isfinite(n) || !(n > 0))
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string("local_shape_features: ") + name + " must be a finite non-zero vector");
  return v / n;
}

/// Flips v so that its largest-magnitude component is positive: a deterministic sign for eigenvectors.
inline Eigen::Vector3d canonical_sign(const Eigen::Vector3d& v) {
  Eigen::Index i = 0;
  v.cwiseAbs().maxCoeff(&i);
  return v[i] < 0 ? Eigen::Vector3d(-v) : v;
}

}  // namespace detail

/// Local shape features of every point of P over its neighbourhood in P (see local_shape_features_result for
/// the columns): the covariance of the neighbourhood (all points within tau = radius_fraction * R, or the k
/// nearest) about its centroid, its eigen-decomposition, and the dissertation's six features (eigenvalue ratios
/// and the angles of v1, v2 to a_up and a_2). Parallel over points; deterministic for any thread count.
/// O(P (log P + m)) for neighbourhoods of m points, plus O(P log P) for the kd-tree.
/// \param P (#P x 3) points, e.g. uniform surface samples (sample_surface_even)
/// \throws invalid_input empty, non_finite (point index); bad_parameter for radius_fraction <= 0, negative
///         radius / shape_diameter / k / threads, zero or parallel reference axes, or a zero-diameter point set
///         in radius mode (all points coincide, so no radius can be derived).
template <class Scalar>
[[nodiscard]] local_shape_features_result<Scalar> local_shape_features(const Eigen::Ref<const matrix_x3<Scalar>>& P,
                                                                       const local_shape_features_options& options = {}) {
  const char* who = "local_shape_features";
  validate_points(P, who, options.validation);
  const unsigned workers = detail::resolve_threads(options.threads, who);
  auto bad = [&](const std::string& what) { throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": " + what); };
  if (options.k < 0) bad("k must be >= 0, got " + std::to_string(options.k));
  if (!(options.radius >= 0) || !std::isfinite(options.radius)) bad("radius must be finite and >= 0");
  if (!(options.shape_diameter >= 0) || !std::isfinite(options.shape_diameter)) bad("shape_diameter must be finite and >= 0");
  if (!(options.radius_fraction > 0) || !std::isfinite(options.radius_fraction)) bad("radius_fraction must be finite and > 0");
  const Eigen::Vector3d up = detail::feature_axis(options.up_axis, "up_axis");
  const Eigen::Vector3d second = detail::feature_axis(options.second_axis, "second_axis");
  if (up.cross(second).norm() < 1e-6) bad("up_axis and second_axis must not be parallel");

  local_shape_features_result<Scalar> out;
  const index_t n = P.rows();
  out.shape_diameter = options.shape_diameter > 0 ? Scalar(options.shape_diameter)
                                                  : estimate_diameter<Scalar>(P, validation_level::trust);
  const bool use_k = options.k > 0;
  if (!use_k) {
    out.radius = options.radius > 0 ? Scalar(options.radius) : Scalar(options.radius_fraction) * out.shape_diameter;
    if (!(out.radius > 0))
      bad("all points coincide (diameter 0), so the neighbourhood radius radius_fraction * R is 0; pass radius or k");
  }
  out.features.resize(n, local_shape_feature_count);
  out.eigenvalues.resize(n, 3);
  out.principal_axes.resize(n, 3);
  out.normals.resize(n, 3);
  out.linearity.resize(n);
  out.planarity.resize(n);
  out.scattering.resize(n);
  out.neighbor_counts.resize(n);

  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (index_t i = 0; i < n; ++i) centroid += P.row(i).transpose().template cast<double>();
  centroid /= double(n);

  const knn_index<Scalar, 3> index(P);
  std::vector<char> degenerate(static_cast<std::size_t>(n), 0);
  // Points in Morton order: consecutive neighbourhoods overlap, so their points stay in cache. Each point
  // writes only its own rows, so the order does not change the result.
  const std::vector<std::uint32_t> order = detail::morton_order<3>(
      static_cast<std::size_t>(n), [&](std::size_t i, int d) { return P(static_cast<index_t>(i), d); });
  detail::parallel_for(n, workers, [&](index_t j) {
    const index_t i = static_cast<index_t>(order[static_cast<std::size_t>(j)]);
    std::vector<std::pair<std::uint32_t, Scalar>> hits;
    double scale2 = double(out.radius) * double(out.radius);
    if (use_k) {
      const auto r = index.knn(P.row(i), options.k);
      hits.reserve(r.indices.size());
      for (std::size_t j = 0; j < r.indices.size(); ++j)
        hits.emplace_back(static_cast<std::uint32_t>(r.indices[j]), r.sq_distances[j]);
      scale2 = hits.empty() ? 0.0 : double(hits.back().second);
    } else {
      index.radius_into(P.row(i), out.radius, hits);
    }
    out.neighbor_counts[i] = static_cast<index_t>(hits.size());
    // Covariance in double about the neighbourhood centroid; coordinates are shifted by the query point first
    // so that far-from-origin shapes do not lose digits to cancellation.
    const Eigen::Vector3d origin = P.row(i).transpose().template cast<double>();
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& h : hits) mean += P.row(h.first).transpose().template cast<double>() - origin;
    mean /= double(std::max<std::size_t>(1, hits.size()));
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for (const auto& h : hits) {
      const Eigen::Vector3d d = P.row(h.first).transpose().template cast<double>() - origin - mean;
      C.noalias() += d * d.transpose();
    }
    C /= double(std::max<std::size_t>(1, hits.size()));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
    // Ascending order from Eigen: lambda1 is the last.
    const double l1 = std::max(0.0, eig.eigenvalues()[2]), l2 = std::max(0.0, eig.eigenvalues()[1]),
                 l3 = std::max(0.0, eig.eigenvalues()[0]);
    // "No spread": the largest variance is rounding noise relative to the neighbourhood size.
    if (!(l1 > 1e-24 * std::max(scale2, 1e-300)) || scale2 <= 0) {
      degenerate[static_cast<std::size_t>(i)] = 1;
      out.eigenvalues.row(i).setZero();
      out.principal_axes.row(i).setZero();
      out.normals.row(i).setZero();
      out.features.row(i) << 0, 0, 0.25, 0.25, 0.25, 0.25;
      out.linearity[i] = out.planarity[i] = out.scattering[i] = 0;
      return;
    }
    const Eigen::Vector3d v1 = detail::canonical_sign(eig.eigenvectors().col(2));
    const Eigen::Vector3d v2 = detail::canonical_sign(eig.eigenvectors().col(1));
    Eigen::Vector3d v3 = eig.eigenvectors().col(0);
    const double outward = v3.dot(origin - centroid);
    v3 = outward < 0 ? Eigen::Vector3d(-v3) : (outward > 0 ? v3 : detail::canonical_sign(v3));
    auto angle = [](const Eigen::Vector3d& v, const Eigen::Vector3d& a) {
      return std::acos(std::min(1.0, std::abs(v.dot(a)))) / std::numbers::pi;
    };
    out.features.row(i) << Scalar(l2 / l1), Scalar(l3 / l1), Scalar(angle(v1, up)), Scalar(angle(v1, second)),
        Scalar(angle(v2, up)), Scalar(angle(v2, second));
    out.eigenvalues.row(i) << Scalar(l1 / scale2), Scalar(l2 / scale2), Scalar(l3 / scale2);
    out.principal_axes.row(i) = v1.cast<Scalar>().transpose();
    out.normals.row(i) = v3.cast<Scalar>().transpose();
    out.linearity[i] = Scalar((l1 - l2) / l1);
    out.planarity[i] = Scalar((l2 - l3) / l1);
    out.scattering[i] = Scalar(l3 / l1);
  });
  for (char d : degenerate) out.degenerate += d;
  return out;
}

/// local_shape_features of any dense Eigen `#P x 3` matrix (Scalar = its scalar type).
/// \throws invalid_input size_mismatch if P does not have 3 columns; otherwise as the kernel.
template <detail::geometry_dense_real D>
[[nodiscard]] auto local_shape_features(const Eigen::MatrixBase<D>& P, const local_shape_features_options& options = {}) {
  using Scalar = typename D::Scalar;
  if (P.cols() != 3)
    throw invalid_input(input_error::size_mismatch, no_index,
                        "local_shape_features: points must be #P x 3, got " + std::to_string(P.cols()) + " columns");
  const matrix_x3<Scalar> points = P;
  return local_shape_features<Scalar>(points, options);
}

/// local_shape_features of any 3-D PointSet (gathered into an `#P x 3` matrix of its scalar type, O(P)).
template <PointSet Points>
  requires(!detail::geometry_dense<std::remove_cvref_t<Points>> && point_set_traits_t<Points>::dimension == 3)
[[nodiscard]] auto local_shape_features(const Points& points, const local_shape_features_options& options = {}) {
  using traits = point_set_traits_t<Points>;
  using Scalar = typename traits::scalar_type;
  const index_t n = static_cast<index_t>(traits::num_points(points));
  matrix_x3<Scalar> P(n, 3);
  for (index_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) P(i, d) = static_cast<Scalar>(traits::coord(points, i, d));
  return local_shape_features<Scalar>(P, options);
}

}  // namespace shapestruct
