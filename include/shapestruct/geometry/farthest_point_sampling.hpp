// SPDX-License-Identifier: MIT
// farthest_point_sampling: evenly spread samples by greedy max-min selection, Euclidean or geodesic.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/detail/eigen_forward.hpp"
#include "shapestruct/geometry/detail/geometry_common.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"

namespace shapestruct {

/// Result of farthest-point sampling.
template <class Scalar>
struct farthest_point_result {
  std::vector<index_t> indices;  ///< the chosen points / vertices, in the order picked (indices[0] = first)
  /// radii[k] = covering radius after k + 1 picks: the largest distance from any point to its nearest pick.
  /// Non-increasing. +inf while some point cannot be reached (geodesic version, several components).
  std::vector<Scalar> radii;
};

namespace detail {
inline void fps_check(index_t n, index_t count, index_t first, const char* who) {
  if (count < 0 || count > n)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": count must be in [0, " + std::to_string(n) + "], got " +
                            std::to_string(count));
  geometry_check_vertex(first, n, who, "first");
}
/// Index of the largest entry; ties go to the smallest index, so the result is deterministic.
template <class Scalar>
index_t fps_argmax(const vector_x<Scalar>& d) {
  index_t best = 0;
  for (index_t i = 1; i < d.size(); ++i)
    if (d[i] > d[best]) best = i;
  return best;
}
}  // namespace detail

/// Euclidean farthest-point sampling: starts at `first`, then repeatedly picks the point farthest from all
/// picks so far (ties to the smallest index). The picks are a 2-approximation of the optimal k-center cover.
/// \param P (#P x 3) points  \param count number of picks, in [0, #P]  \param first the first pick
/// \returns indices and covering radii (see farthest_point_result).
/// \throws invalid_input (empty, non_finite) from validate_points; (bad_parameter) for count or first out of range.
/// Complexity O(#P * count).
template <class Scalar>
[[nodiscard]] farthest_point_result<Scalar> farthest_point_sampling(const Eigen::Ref<const matrix_x3<Scalar>>& P,
                                                                    index_t count, index_t first = 0) {
  validate_points(P, "farthest_point_sampling");
  detail::fps_check(P.rows(), count, first, "farthest_point_sampling");
  farthest_point_result<Scalar> out;
  if (count == 0) return out;
  // Squared distances over contiguous coordinate columns (a loop the compiler vectorises): the same picks, as the
  // square is monotonic, several times faster than norms of strided rows.
  const index_t n = P.rows();
  const vector_x<Scalar> x = P.col(0), y = P.col(1), z = P.col(2);
  vector_x<Scalar> d = vector_x<Scalar>::Constant(n, std::numeric_limits<Scalar>::infinity());
  Scalar* dd = d.data();
  const Scalar *xs = x.data(), *ys = y.data(), *zs = z.data();
  index_t pick = first;
  for (index_t k = 0; k < count; ++k) {
    out.indices.push_back(pick);
    const Scalar px = xs[pick], py = ys[pick], pz = zs[pick];
    for (index_t i = 0; i < n; ++i) {
      const Scalar dx = xs[i] - px, dy = ys[i] - py, dz = zs[i] - pz;
      dd[i] = std::min(dd[i], dx * dx + dy * dy + dz * dz);
    }
    pick = detail::fps_argmax(d);
    out.radii.push_back(std::sqrt(d[pick]));
  }
  return out;
}

/// Geodesic farthest-point sampling on the edge graph: like farthest_point_sampling with edge-graph
/// (Dijkstra) distances. Each pick updates the distance field incrementally (only the region now closer to the
/// new pick is re-explored), so the total cost is far below count full Dijkstra runs.
/// \param geo a dijkstra_geodesics built on the mesh  \param count in [0, #V]  \param first the first pick
/// \throws invalid_input (bad_parameter) for count or first out of range.
/// Complexity O(count * region * log V), at most O(count * E log V).
template <class Scalar>
[[nodiscard]] farthest_point_result<Scalar> geodesic_farthest_point_sampling(const dijkstra_geodesics<Scalar>& geo,
                                                                             index_t count, index_t first = 0) {
  detail::fps_check(geo.num_vertices(), count, first, "geodesic_farthest_point_sampling");
  farthest_point_result<Scalar> out;
  if (count == 0) return out;
  vector_x<Scalar> d = vector_x<Scalar>::Constant(geo.num_vertices(), std::numeric_limits<Scalar>::infinity());
  typename dijkstra_geodesics<Scalar>::workspace ws;
  index_t pick = first;
  for (index_t k = 0; k < count; ++k) {
    out.indices.push_back(pick);
    geo.update_distances(pick, d, ws);
    pick = detail::fps_argmax(d);
    out.radii.push_back(d[pick]);
  }
  return out;
}

/// Geodesic farthest-point sampling on (V, F). \param V (#V x 3) \param F (#F x 3)
/// \throws invalid_input (empty, non_finite, bad_face) from validate_mesh, (bad_parameter) as above.
template <class Scalar>
[[nodiscard]] farthest_point_result<Scalar> geodesic_farthest_point_sampling(
    const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F, index_t count,
    index_t first = 0) {
  const dijkstra_geodesics<Scalar> geo(V, F);
  return geodesic_farthest_point_sampling(geo, count, first);
}

/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DP>
[[nodiscard]] auto farthest_point_sampling(const Eigen::MatrixBase<DP>& P, index_t count, index_t first = 0) {
  return farthest_point_sampling<typename DP::Scalar>(P.derived(), count, first);
}
/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto geodesic_farthest_point_sampling(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F,
                                                    index_t count, index_t first = 0) {
  return geodesic_farthest_point_sampling<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>(),
                                                               count, first);
}

/// Euclidean farthest-point sampling of any 3-D PointSet (gathered into an #P x 3 matrix).
template <PointSet Points>
  requires(point_set_traits_t<Points>::dimension == 3)
[[nodiscard]] farthest_point_result<point_scalar_t<Points>> farthest_point_sampling(const Points& points,
                                                                                     index_t count, index_t first = 0) {
  using S = point_scalar_t<Points>;
  using T = point_set_traits_t<Points>;
  matrix_x3<S> P(static_cast<index_t>(T::num_points(points)), 3);
  for (index_t i = 0; i < P.rows(); ++i)
    for (int c = 0; c < 3; ++c) P(i, c) = static_cast<S>(T::coord(points, i, c));
  return farthest_point_sampling<S>(P, count, first);
}

/// Geodesic farthest-point sampling on any SurfaceMesh.
template <SurfaceMesh Mesh>
[[nodiscard]] farthest_point_result<mesh_scalar_t<Mesh>> geodesic_farthest_point_sampling(const Mesh& mesh,
                                                                                          index_t count,
                                                                                          index_t first = 0) {
  const dijkstra_geodesics<mesh_scalar_t<Mesh>> geo(mesh);
  return geodesic_farthest_point_sampling(geo, count, first);
}

}  // namespace shapestruct
