// SPDX-License-Identifier: MIT
// surface_sampling: area-weighted random and even (Poisson-disk sample elimination) point samples of a mesh.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <queue>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/surface_point.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/knn/knn_index.hpp"

namespace shapestruct {

/// Points sampled on a triangle mesh; row i describes sample i.
///   points   (#S x 3) positions
///   faces    (#S)     face each sample lies on
///   bary     (#S x 3) barycentric weights in that face (rows sum to 1)
///   normals  (#S x 3) unit normal of that face (corner order, counter-clockwise seen from outside)
template <class Scalar = double>
struct surface_samples {
  matrix_x3<Scalar> points;
  Eigen::Matrix<index_t, Eigen::Dynamic, 1> faces;
  matrix_x3<Scalar> bary;
  matrix_x3<Scalar> normals;

  [[nodiscard]] index_t size() const noexcept { return points.rows(); }
  /// Sample i as a surface_point.
  [[nodiscard]] surface_point<Scalar> location(index_t i) const {
    return surface_point<Scalar>{faces[i], bary.row(i).transpose()};
  }
};

/// Options of sample_surface_random and sample_surface_even.
struct surface_sampling_options {
  /// Seed of the std::mt19937_64 engine; the same seed gives the same samples on every platform (uniform
  /// numbers are built from the raw 64-bit output, not from implementation-defined std distributions).
  std::uint64_t seed = 0;
  /// Even sampling only: random candidates drawn per requested sample before elimination. Yuksel (2015)
  /// reports that 3-5 candidates per output sample already give near-maximal Poisson-disk spacing; more cost
  /// time with little gain. Must be finite and >= 1 (1 = plain random sampling).
  double oversampling = 4.0;
  /// Even sampling only: threads for the neighbour search (0 = all cores); the result does not depend on it.
  int threads = 0;
  /// validation_level::trust skips validate_mesh for callers that already checked the mesh.
  validation_level validation = validation_level::full;
};

namespace detail {

/// Uniform double in [0, 1) from the top 53 bits of one engine draw: portable across standard libraries.
inline double sampling_uniform01(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

/// Per-face sampling weights: the area, or 0 for a numerically degenerate face (twice its area below 64
/// machine epsilons of its longest squared edge, i.e. the cross product is rounding noise and its normal has
/// no meaning). Throws if no face has positive weight.
template <class Scalar>
std::vector<double> sampling_weights(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                     const Eigen::Ref<const face_matrix>& F, const vector_x<Scalar>& areas,
                                     const char* who) {
  std::vector<double> w(static_cast<std::size_t>(F.rows()), 0.0);
  bool any = false;
  for (index_t f = 0; f < F.rows(); ++f) {
    Scalar longest = 0;
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (V.row(F(f, k)) - V.row(F(f, (k + 1) % 3))).squaredNorm());
    if (Scalar(2) * areas[f] > Scalar(64) * std::numeric_limits<Scalar>::epsilon() * longest) {
      w[static_cast<std::size_t>(f)] = double(areas[f]);
      any = true;
    }
  }
  if (!any)
    throw invalid_input(input_error::degenerate_face, 0,
                        std::string(who) + ": every face is degenerate (zero area), so there is no surface to sample");
  return w;
}

template <class Scalar>
void check_sampling_arguments(index_t count, const surface_sampling_options& options, const char* who) {
  if (count < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": count must be >= 0, got " + std::to_string(count));
  if (!std::isfinite(options.oversampling) || options.oversampling < 1.0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": oversampling must be finite and >= 1, got " +
                            std::to_string(options.oversampling));
}

template <class Scalar>
surface_samples<Scalar> random_samples_unchecked(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                 const Eigen::Ref<const face_matrix>& F, index_t count,
                                                 std::uint64_t seed, const char* who) {
  const vector_x<Scalar> areas = face_areas<Scalar>(V, F, validation_level::trust);
  const matrix_x3<Scalar> normals = face_normals<Scalar>(V, F, validation_level::trust);
  const std::vector<double> w = sampling_weights<Scalar>(V, F, areas, who);
  // Cumulative weights in double: with 1e6 faces a float prefix sum would lose the smallest faces.
  std::vector<double> cdf(w.size());
  double total = 0;
  index_t last_positive = 0;
  for (std::size_t f = 0; f < w.size(); ++f) {
    total += w[f];
    cdf[f] = total;
    if (w[f] > 0) last_positive = static_cast<index_t>(f);
  }
  surface_samples<Scalar> out;
  out.points.resize(count, 3);
  out.faces.resize(count);
  out.bary.resize(count, 3);
  out.normals.resize(count, 3);
  std::mt19937_64 rng(seed);
  for (index_t i = 0; i < count; ++i) {
    // First face whose cumulative weight exceeds u: zero-weight faces have empty intervals, never chosen.
    const double u = sampling_uniform01(rng) * total;
    auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    const index_t f = it == cdf.end() ? last_positive : static_cast<index_t>(it - cdf.begin());
    // Uniform point in a triangle (Osada et al. 2002): sqrt warps r1 so area, not height, is uniform.
    const double s = std::sqrt(sampling_uniform01(rng)), r2 = sampling_uniform01(rng);
    const vec3<Scalar> b(Scalar(1 - s), Scalar(s * (1 - r2)), Scalar(s * r2));
    out.faces[i] = f;
    out.bary.row(i) = b.transpose();
    out.points.row(i) = b[0] * V.row(F(f, 0)) + b[1] * V.row(F(f, 1)) + b[2] * V.row(F(f, 2));
    out.normals.row(i) = normals.row(f);
  }
  return out;
}

}  // namespace detail

/// Area-weighted random sampling: `count` independent points, each on face f with probability area(f) / total
/// area and uniform within the face. Works on meshes and polygon soups alike (faces need not share vertices).
/// Degenerate (zero-area) faces get probability 0. O(F + count log F).
/// \param V (#V x 3) vertex positions
/// \param F (#F x 3) triangles
/// \param count number of samples, >= 0 (exactly this many are returned)
/// \returns surface_samples with `count` rows; deterministic for a given options.seed.
/// \throws invalid_input empty, non_finite, bad_face (validate_mesh); degenerate_face if every face has zero
///         area; bad_parameter if count < 0.
template <class Scalar>
[[nodiscard]] surface_samples<Scalar> sample_surface_random(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                            const Eigen::Ref<const face_matrix>& F, index_t count,
                                                            const surface_sampling_options& options = {}) {
  const char* who = "sample_surface_random";
  detail::check_sampling_arguments<Scalar>(count, options, who);
  validate_mesh(V, F, who, options.validation);
  return detail::random_samples_unchecked<Scalar>(V, F, count, options.seed, who);
}

/// Even (blue-noise) sampling with exactly `count` points: draws ceil(oversampling * count) area-weighted
/// random candidates, then removes candidates one at a time by weighted sample elimination (Yuksel, "Sample
/// Elimination for Generating Poisson Disk Sample Sets", 2015): each candidate's weight sums
/// (1 - d / (2 r_max))^8 over the candidates within 2 r_max, where r_max = sqrt(A / (2 sqrt(3) count)) is the
/// spacing of a hexagonal packing of `count` points on area A, and d is clamped below at 2 r_min with
/// r_min = 0.65 r_max (1 - (count / candidates)^1.5) so near-coincident pairs do not dominate; the heaviest
/// (most crowded) candidate goes first, ties to the higher candidate index. Distances are Euclidean, which
/// matches geodesic ones at the sample spacing on any surface whose features are larger than r_max.
/// Survivors keep their candidate order. Deterministic for a given seed, whatever options.threads.
/// O(N log N) time for N candidates (kd-tree neighbour search plus a heap); memory O(N): each candidate stores
/// its neighbours within 2 r_max, on average 4 pi oversampling / (2 sqrt 3) ~ 14.5 at the default oversampling.
/// \returns surface_samples with exactly `count` rows.
/// \throws as sample_surface_random; bad_parameter if oversampling < 1 or threads < 0.
template <class Scalar>
[[nodiscard]] surface_samples<Scalar> sample_surface_even(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                          const Eigen::Ref<const face_matrix>& F, index_t count,
                                                          const surface_sampling_options& options = {}) {
  const char* who = "sample_surface_even";
  detail::check_sampling_arguments<Scalar>(count, options, who);
  const unsigned workers = detail::resolve_threads(options.threads, who);
  validate_mesh(V, F, who, options.validation);
  const index_t n = std::max<index_t>(count, static_cast<index_t>(std::ceil(options.oversampling * double(count))));
  surface_samples<Scalar> cand = detail::random_samples_unchecked<Scalar>(V, F, n, options.seed, who);
  if (n == count) return cand;

  double area = 0;
  {
    const vector_x<Scalar> areas = face_areas<Scalar>(V, F, validation_level::trust);
    const std::vector<double> w = detail::sampling_weights<Scalar>(V, F, areas, who);
    for (double a : w) area += a;
  }
  const double r_max = std::sqrt(area / (2.0 * std::numbers::sqrt3 * double(count)));
  const double r_min = 0.65 * r_max * (1.0 - std::pow(double(count) / double(n), 1.5));
  const double reach = 2.0 * r_max;
  auto weight = [&](double d) {
    const double x = 1.0 - std::max(d, 2.0 * r_min) / reach;
    const double x2 = x * x, x4 = x2 * x2;
    return x4 * x4;  // alpha = 8, Yuksel's recommendation for 2-D domains
  };

  // Neighbour lists (CSR), built in parallel: each list depends only on the candidate set.
  const knn_index<Scalar, 3> index(cand.points);
  std::vector<std::vector<std::pair<index_t, double>>> nbrs(static_cast<std::size_t>(n));
  detail::parallel_for(n, workers, [&](index_t i) {
    std::vector<std::pair<std::uint32_t, Scalar>> hits;
    index.radius_into(cand.points.row(i), static_cast<Scalar>(reach), hits);
    auto& list = nbrs[static_cast<std::size_t>(i)];
    list.reserve(hits.size());
    for (const auto& [j, d2] : hits)
      if (static_cast<index_t>(j) != i) list.emplace_back(static_cast<index_t>(j), weight(std::sqrt(double(d2))));
  });

  std::vector<double> W(static_cast<std::size_t>(n), 0.0);
  for (index_t i = 0; i < n; ++i)
    for (const auto& [j, w] : nbrs[static_cast<std::size_t>(i)]) W[static_cast<std::size_t>(i)] += w;
  // Lazy max-heap: stale entries (weight changed since the push) are skipped when popped.
  std::priority_queue<std::pair<double, index_t>> heap;
  for (index_t i = 0; i < n; ++i) heap.emplace(W[static_cast<std::size_t>(i)], i);
  std::vector<char> removed(static_cast<std::size_t>(n), 0);
  index_t remaining = n;
  while (remaining > count) {
    const auto [wi, i] = heap.top();
    heap.pop();
    const auto si = static_cast<std::size_t>(i);
    if (removed[si] || wi != W[si]) continue;
    removed[si] = 1;
    --remaining;
    for (const auto& [j, w] : nbrs[si]) {
      const auto sj = static_cast<std::size_t>(j);
      if (removed[sj]) continue;
      W[sj] -= w;
      heap.emplace(W[sj], j);
    }
  }

  surface_samples<Scalar> out;
  out.points.resize(count, 3);
  out.faces.resize(count);
  out.bary.resize(count, 3);
  out.normals.resize(count, 3);
  index_t k = 0;
  for (index_t i = 0; i < n; ++i) {
    if (removed[static_cast<std::size_t>(i)]) continue;
    out.points.row(k) = cand.points.row(i);
    out.faces[k] = cand.faces[i];
    out.bary.row(k) = cand.bary.row(i);
    out.normals.row(k) = cand.normals.row(i);
    ++k;
  }
  return out;
}

/// sample_surface_random on any SurfaceMesh, gathered into triangle_mesh<Scalar> first (O(V + F)).
template <class Scalar = double, SurfaceMesh Mesh>
[[nodiscard]] surface_samples<Scalar> sample_surface_random(const Mesh& mesh, index_t count,
                                                            const surface_sampling_options& options = {}) {
  const auto m = to_triangle_mesh<Scalar>(mesh);
  return sample_surface_random<Scalar>(m.V, m.F, count, options);
}

/// sample_surface_even on any SurfaceMesh, gathered into triangle_mesh<Scalar> first (O(V + F)).
template <class Scalar = double, SurfaceMesh Mesh>
[[nodiscard]] surface_samples<Scalar> sample_surface_even(const Mesh& mesh, index_t count,
                                                          const surface_sampling_options& options = {}) {
  const auto m = to_triangle_mesh<Scalar>(mesh);
  return sample_surface_even<Scalar>(m.V, m.F, count, options);
}

}  // namespace shapestruct
