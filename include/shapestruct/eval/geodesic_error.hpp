// SPDX-License-Identifier: MIT
// geodesic_error: the BIM benchmark's correspondence error, geodesic distance / sqrt(area of the target)
// (benchmark_geodesic_errors), and its summary (curves: eval/error_curve.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"

namespace shapestruct {

/// Per-point errors d_g(predicted[k], truth[k]) / normalization on the target surface (Dijkstra distances from
/// each distinct true vertex). For the BIM benchmark's error use benchmark_geodesic_errors, which fixes the
/// normalization to sqrt(area of the target).
/// \param geo Dijkstra geodesics of the target  \param predicted, truth equal-length target vertex lists
/// \returns (#points) errors; a predicted no_index counts as +infinity.
/// \throws invalid_input (size_mismatch; bad_parameter for a non-positive normalization or a bad vertex).
/// Complexity O(#distinct truths * E log V / threads).
template <class Scalar>
[[nodiscard]] std::vector<Scalar> geodesic_errors(const dijkstra_geodesics<Scalar>& geo, std::span<const index_t> predicted,
                                                  std::span<const index_t> truth, Scalar normalization, int threads = 0) {
  if (predicted.size() != truth.size())
    throw invalid_input(input_error::size_mismatch, no_index, "geodesic_errors: predicted and truth differ in length");
  if (!(normalization > 0))
    throw invalid_input(input_error::bad_parameter, no_index, "geodesic_errors: normalization must be > 0");
  std::vector<index_t> uniq(truth.begin(), truth.end());
  std::sort(uniq.begin(), uniq.end());
  uniq.erase(std::unique(uniq.begin(), uniq.end()), uniq.end());
  std::vector<Scalar> out(truth.size(), std::numeric_limits<Scalar>::infinity());
  if (uniq.empty()) return out;
  const matrix_x<Scalar> table = geo.distance_table(std::span<const index_t>(uniq), threads);
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const index_t col = std::lower_bound(uniq.begin(), uniq.end(), truth[k]) - uniq.begin();
    const index_t p = predicted[k];
    if (p < 0 || p >= table.rows()) continue;
    out[k] = table(p, col) / normalization;
  }
  return out;
}

/// The BIM benchmark's correspondence error (Kim, Lipman & Funkhouser 2011; dissertation ch. 3.5): per point,
/// the geodesic distance on the target between the predicted and the true image, divided by sqrt(area of the
/// target), err = d_g(predicted[k], truth[k]) / sqrt(area(V, F)). The stored results of the original program
/// are on this scale (see the data README; an earlier reading, d / (2 sqrt(area)), made every figure half the
/// benchmark's). The area is computed here from the target mesh, so no caller picks the normalisation; on a
/// unit-area mesh (blended_shape::mesh()) the errors are the Dijkstra distances themselves.
/// \param V, F the target mesh the geodesics were built on  \param geo its Dijkstra geodesics
/// \param predicted, truth equal-length target vertex lists (a predicted no_index counts as +infinity)
/// 	hrows invalid_input (size_mismatch if geo and V differ in vertex count or the lists in length;
///         degenerate_face for zero or non-finite total area; as face_areas and geodesic_errors).
/// Complexity O(F + #distinct truths * E log V / threads). Pinned by tests/eval/test_benchmark_error_scale.cpp.
template <class Scalar>
[[nodiscard]] std::vector<Scalar> benchmark_geodesic_errors(
    const Eigen::Ref<const matrix_x3<std::type_identity_t<Scalar>>>& V, const Eigen::Ref<const face_matrix>& F,
    const dijkstra_geodesics<Scalar>& geo, std::span<const index_t> predicted, std::span<const index_t> truth,
    int threads = 0) {
  if (geo.num_vertices() != V.rows())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "benchmark_geodesic_errors: the geodesics and the target mesh differ in vertex count");
  const Scalar area = total_area<Scalar>(V, F);
  if (!(area > 0) || !std::isfinite(static_cast<double>(area)))
    throw invalid_input(input_error::degenerate_face, no_index, "benchmark_geodesic_errors: the target has zero area");
  return geodesic_errors(geo, predicted, truth, static_cast<Scalar>(std::sqrt(area)), threads);
}

/// For every query vertex q, the vertex s(q) that is its image under an intrinsic symmetry known only at
/// feature points: features[k] <-> features[perm[k]]. s(q) minimises sum_k (d(s, f_k) - d(q, f_perm(k)))^2
/// (the geodesic-descriptor interpolation the dissertation uses to make sparse correspondences dense).
/// \throws invalid_input (size_mismatch if perm and features differ in length; empty for no features).
/// Complexity O(#features E log V / threads + #queries V #features).
template <class Scalar>
[[nodiscard]] std::vector<index_t> symmetric_vertices(const dijkstra_geodesics<Scalar>& geo,
                                                      std::span<const index_t> features, std::span<const index_t> perm,
                                                      std::span<const index_t> queries, int threads = 0) {
  if (features.empty()) throw invalid_input(input_error::empty, no_index, "symmetric_vertices: no feature points");
  if (perm.size() != features.size())
    throw invalid_input(input_error::size_mismatch, no_index, "symmetric_vertices: perm and features differ in length");
  const matrix_x<Scalar> D = geo.distance_table(features, threads);
  const index_t nv = D.rows(), nf = D.cols();
  std::vector<index_t> out(queries.size(), no_index);
  for (index_t qi = 0; qi < static_cast<index_t>(queries.size()); ++qi) {
    const index_t q = queries[static_cast<std::size_t>(qi)];
    Eigen::Matrix<Scalar, 1, Eigen::Dynamic> want(nf);
    for (index_t k = 0; k < nf; ++k) want[k] = D(q, perm[static_cast<std::size_t>(k)]);
    Scalar best = std::numeric_limits<Scalar>::infinity();
    index_t arg = q;
    for (index_t v = 0; v < nv; ++v) {
      const Scalar e = (D.row(v) - want).squaredNorm();
      if (e < best) {
        best = e;
        arg = v;
      }
    }
    out[static_cast<std::size_t>(qi)] = arg;
  }
  return out;
}

/// Summary of a set of errors: mean and the fractions within the benchmark's thresholds.
struct geodesic_error_summary {
  double mean = 0;
  double within_005 = 0, within_010 = 0, within_025 = 0;
  std::size_t count = 0;
};

/// Mean and fractions within 0.05 / 0.10 / 0.25 (infinite errors count as misses and are left out of the mean
/// only if all are infinite). O(n).
template <class Scalar>
[[nodiscard]] geodesic_error_summary summarize_errors(std::span<const Scalar> errors) {
  geodesic_error_summary s;
  s.count = errors.size();
  if (errors.empty()) return s;
  double sum = 0;
  std::size_t finite = 0;
  for (Scalar e : errors) {
    if (std::isfinite(static_cast<double>(e))) {
      sum += static_cast<double>(e);
      ++finite;
    }
    s.within_005 += e <= Scalar(0.05);
    s.within_010 += e <= Scalar(0.10);
    s.within_025 += e <= Scalar(0.25);
  }
  const double n = static_cast<double>(errors.size());
  s.mean = finite ? sum / static_cast<double>(finite) : std::numeric_limits<double>::infinity();
  s.within_005 /= n;
  s.within_010 /= n;
  s.within_025 /= n;
  return s;
}

}  // namespace shapestruct
