// SPDX-License-Identifier: MIT
// average_geodesic_distance: the AGD function, its local maxima and their persistence: the feature points of
// blended intrinsic maps.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"
#include "shapestruct/geometry/detail/eigen_forward.hpp"
#include "shapestruct/geometry/detail/geometry_common.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"

namespace shapestruct {

/// Options of average_geodesic_distance.
///
/// | field | default | meaning |
/// |---|---|---|
/// | num_sources | 64 | geodesic FPS samples the integral is estimated from (all vertices if >= #V: exact) |
/// | first | 0 | first FPS sample (the result barely depends on it) |
/// | threads | 0 | std::threads for the Dijkstra runs, 0 = all cores; the result does not depend on it |
struct agd_options {
  index_t num_sources = 64;
  index_t first = 0;
  int threads = 0;
};

/// Average geodesic distance of every vertex, AGD(p) = (1 / area) * integral over the surface of d_g(p, p') dA(p')
/// (dissertation ch. 3, Kim et al. 2011: multiply by total_area for the unnormalised integral; the maxima are the
/// same). d_g is the edge-graph (Dijkstra) distance. The integral is estimated from `num_sources` geodesic
/// farthest-point samples s_k: AGD(p) ~ sum_k w_k d_g(p, s_k) / sum_k w_k, where w_k is the area (barycentric
/// vertex areas) of s_k's geodesic Voronoi cell - every vertex's area goes to its nearest sample - so unevenly
/// sampled regions are weighted by the surface they stand for. Because d_g is symmetric the table d_g(., s_k) is
/// one Dijkstra run per sample, run in parallel. On several components, samples in another component (distance
/// +inf) are left out of a vertex's average; a vertex reached by no sample gets +inf.
/// \param V (#V x 3) vertex positions  \param F (#F x 3) triangles  \param options see agd_options
/// \returns (#V) AGD values in distance units.
/// \throws invalid_input (empty, non_finite, bad_face) from validate_mesh; (bad_parameter) for num_sources < 1,
/// a bad first vertex or threads < 0. Complexity O(num_sources * E log V) work.
template <class Scalar>
[[nodiscard]] vector_x<Scalar> average_geodesic_distance(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                         const Eigen::Ref<const face_matrix>& F,
                                                         const agd_options& options = {}) {
  validate_mesh(V, F, "average_geodesic_distance");
  if (options.num_sources < 1)
    throw invalid_input(input_error::bad_parameter, no_index,
                        "average_geodesic_distance: options.num_sources must be >= 1, got " +
                            std::to_string(options.num_sources));
  detail::geometry_check_vertex(options.first, V.rows(), "average_geodesic_distance", "options.first");
  const unsigned workers = detail::resolve_threads(options.threads, "average_geodesic_distance");
  const index_t n = V.rows();
  const dijkstra_geodesics<Scalar> geo(V, F, validation_level::trust);
  std::vector<index_t> sources;
  if (options.num_sources >= n) {
    sources.resize(static_cast<std::size_t>(n));
    std::iota(sources.begin(), sources.end(), index_t{0});
  } else {
    sources = geodesic_farthest_point_sampling(geo, options.num_sources, options.first).indices;
  }
  const matrix_x<Scalar> D = geo.distance_table(sources, static_cast<int>(workers));
  const vector_x<Scalar> area = vertex_areas<Scalar>(V, F, validation_level::trust);
  // Geodesic Voronoi cell areas of the samples (nearest sample, ties to the first column).
  std::vector<double> w(sources.size(), 0.0);
  for (index_t v = 0; v < n; ++v) {
    index_t best = -1;
    Scalar bd = std::numeric_limits<Scalar>::infinity();
    for (index_t k = 0; k < D.cols(); ++k)
      if (D(v, k) < bd) bd = D(v, k), best = k;
    if (best >= 0) w[static_cast<std::size_t>(best)] += double(area[v]);
  }
  vector_x<Scalar> agd(n);
  for (index_t v = 0; v < n; ++v) {
    double num = 0, den = 0;
    for (index_t k = 0; k < D.cols(); ++k) {
      const Scalar d = D(v, k);
      if (d == std::numeric_limits<Scalar>::infinity()) continue;
      num += w[static_cast<std::size_t>(k)] * double(d);
      den += w[static_cast<std::size_t>(k)];
    }
    agd[v] = den > 0 ? static_cast<Scalar>(num / den) : std::numeric_limits<Scalar>::infinity();
  }
  return agd;
}

/// Local maxima of a per-vertex function (normally the AGD): vertices v with f(v) > f(u) for every other vertex
/// u within geodesic (edge-graph) distance `radius` (ties broken towards the smaller index, so a plateau yields
/// one maximum). These are the feature points of blended intrinsic maps (dissertation ch. 3: "points at maxima
/// of the Average Geodesic Distance function": tips of extremities and top of the head on articulated figures;
/// usually <= 10 of them). The radius sets the scale: bumps narrower than it are not features. Measured on
/// SCAPE with the defaults: 5 maxima on mesh000 and mesh050 (hands, feet, head), 7 on mesh010 (a flexed foot
/// adds toe and heel), the same body points in every pose (tests/geometry/data_test_agd_features.cpp).
/// \param V (#V x 3)  \param F (#F x 3)  \param agd (#V) values (non-finite entries are never maxima)
/// \param radius geodesic suppression radius; 0 (default) = 0.1 * sqrt(total area)
/// \returns the maxima sorted by agd descending (ties by index).
/// \throws invalid_input (empty, non_finite, bad_face) from validate_mesh; (size_mismatch) if agd.size() != #V;
/// (bad_parameter) for a negative or NaN radius.
/// Complexity O(V + F) plus one bounded Dijkstra (the radius ball) per one-ring maximum.
template <class Scalar>
[[nodiscard]] std::vector<index_t> agd_local_maxima(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                    const Eigen::Ref<const face_matrix>& F,
                                                    const Eigen::Ref<const vector_x<Scalar>>& agd, double radius = 0) {
  validate_mesh(V, F, "agd_local_maxima");
  if (agd.size() != V.rows())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "agd_local_maxima: agd has " + std::to_string(agd.size()) + " entries, the mesh has " +
                            std::to_string(V.rows()) + " vertices");
  if (!(radius >= 0) || !std::isfinite(radius))
    throw invalid_input(input_error::bad_parameter, no_index,
                        "agd_local_maxima: radius must be finite and >= 0 (0 = default), got " + std::to_string(radius));
  // 0.1 sqrt(area): on a human body a little less than a hand's length, so the five extremity tips
  // and the head survive while the bumps of a single finger or a nose do not.
  const double r = radius > 0 ? radius : 0.1 * std::sqrt(double(total_area<Scalar>(V, F, validation_level::trust)));
  const dijkstra_geodesics<Scalar> geo(V, F, validation_level::trust);
  const auto& g = geo.graph();
  const index_t n = V.rows();
  // (value, -index) order: higher value wins, then smaller index.
  auto above = [&](index_t u, index_t v) {  // u ranks above v
    return agd[u] > agd[v] || (agd[u] == agd[v] && u < v);
  };
  std::vector<index_t> maxima;
  typename dijkstra_geodesics<Scalar>::workspace ws;
  for (index_t v = 0; v < n; ++v) {
    if (!std::isfinite(double(agd[v])) || g.degree(v) == 0) continue;
    bool ring_max = true;  // cheap filter: a maximum in the ball is a maximum in the one-ring
    for (index_t k = g.offsets[static_cast<std::size_t>(v)]; k < g.offsets[static_cast<std::size_t>(v + 1)]; ++k) {
      const index_t u = g.neighbours[static_cast<std::size_t>(k)];
      if (std::isfinite(double(agd[u])) && above(u, v)) {
        ring_max = false;
        break;
      }
    }
    if (!ring_max) continue;
    bool is_max = true;
    geo.visit_within(
        v, static_cast<Scalar>(r),
        [&](std::int32_t u, Scalar) {
          if (u != v && std::isfinite(double(agd[u])) && above(u, v)) is_max = false;
          return is_max;
        },
        ws);
    if (is_max) maxima.push_back(v);
  }
  std::sort(maxima.begin(), maxima.end(), above);
  return maxima;
}

/// Persistence of local maxima of a per-vertex function over the edge graph: how far the function must fall
/// from a maximum before its region meets higher ground. Sweeping a level down from the top, every maximum starts a
/// region of the superlevel set; where two regions meet (at a vertex v), the one whose maximum ranks lower ends,
/// and its maximum's persistence is f(max) - f(v). The highest maximum of a connected component never ends: it
/// gets f(max) - min f over the component. On the AGD, an extremity's tip is separated from the body by a deep dip
/// (0.10-0.65 in units of sqrt(area) on the TOSCA meshes), while bumps on an extremity, such as a dog's eyes and mouth
/// on its head, rise little above their surroundings (at most 0.07) even when they lie farther apart than any
/// suppression radius that keeps the paws apart.
/// \param graph the mesh's edge graph  \param values (#V) the function (non-finite entries are never part of a region)
/// \param maxima the vertices to report, normally agd_local_maxima's; a vertex that is not a one-ring maximum gets 0
/// \returns the persistence of each vertex of `maxima`, in order; 0 for a vertex with a non-finite value.
/// \throws invalid_input (size_mismatch) if values.size() != #V; (bad_parameter) for a vertex out of range.
/// Complexity O(V log V + E alpha(V)).
template <class Scalar>
[[nodiscard]] std::vector<Scalar> maximum_persistence(const edge_graph<Scalar>& graph,
                                                      const Eigen::Ref<const vector_x<Scalar>>& values,
                                                      std::span<const index_t> maxima) {
  const index_t n = graph.num_vertices();
  if (values.size() != n)
    throw invalid_input(input_error::size_mismatch, no_index,
                        "maximum_persistence: values has " + std::to_string(values.size()) +
                            " entries, the graph has " + std::to_string(n) + " vertices");
  for (const index_t m : maxima)
    if (m < 0 || m >= n)
      throw invalid_input(input_error::bad_parameter, m,
                          "maximum_persistence: vertex " + std::to_string(m) + " is out of range (the graph has " +
                              std::to_string(n) + " vertices)");
  auto finite = [&](index_t v) { return std::isfinite(double(values[v])); };
  auto above = [&](index_t u, index_t v) { return values[u] > values[v] || (values[u] == values[v] && u < v); };
  std::vector<index_t> order;
  order.reserve(static_cast<std::size_t>(n));
  for (index_t v = 0; v < n; ++v)
    if (finite(v)) order.push_back(v);
  std::sort(order.begin(), order.end(), above);
  constexpr Scalar unset = -1;
  std::vector<Scalar> persistence(static_cast<std::size_t>(n), unset);
  std::vector<index_t> peak(static_cast<std::size_t>(n), no_index);  // a region's maximum, kept at its root
  std::vector<char> swept(static_cast<std::size_t>(n), 0);
  detail::disjoint_sets regions(n);
  for (const index_t v : order) {
    swept[static_cast<std::size_t>(v)] = 1;
    peak[static_cast<std::size_t>(v)] = v;
    const auto first = graph.neighbours.begin() + graph.offsets[static_cast<std::size_t>(v)];
    const auto last = graph.neighbours.begin() + graph.offsets[static_cast<std::size_t>(v + 1)];
    for (auto it = first; it != last; ++it) {
      const index_t u = *it;
      if (!swept[static_cast<std::size_t>(u)]) continue;
      const index_t ru = regions.find(u), rv = regions.find(v);
      if (ru == rv) continue;
      const index_t pu = peak[static_cast<std::size_t>(ru)], pv = peak[static_cast<std::size_t>(rv)];
      const index_t higher = above(pu, pv) ? pu : pv, lower = higher == pu ? pv : pu;
      persistence[static_cast<std::size_t>(lower)] = values[lower] - values[v];
      regions.unite(ru, rv);
      peak[static_cast<std::size_t>(regions.find(v))] = higher;
    }
  }
  // Peaks that never ended: the depth of their whole component (its lowest vertex was swept last).
  std::vector<Scalar> lowest(static_cast<std::size_t>(n), std::numeric_limits<Scalar>::infinity());
  for (const index_t v : order) {
    auto& low = lowest[static_cast<std::size_t>(regions.find(v))];
    low = std::min(low, values[v]);
  }
  std::vector<Scalar> result;
  result.reserve(maxima.size());
  for (const index_t m : maxima) {
    if (!finite(m)) {
      result.push_back(Scalar(0));
      continue;
    }
    const Scalar p = persistence[static_cast<std::size_t>(m)];
    result.push_back(p != unset ? p : values[m] - lowest[static_cast<std::size_t>(regions.find(m))]);
  }
  return result;
}

/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto average_geodesic_distance(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F,
                                             const agd_options& options = {}) {
  return average_geodesic_distance<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>(), options);
}
/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF, detail::geometry_dense DA>
[[nodiscard]] auto agd_local_maxima(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F,
                                    const Eigen::MatrixBase<DA>& agd, double radius = 0) {
  using S = typename DV::Scalar;
  return agd_local_maxima<S>(V.derived(), F.derived().template cast<index_t>(), agd.derived().template cast<S>(),
                             radius);
}

/// AGD of any SurfaceMesh (Scalar = the mesh's scalar type).
template <SurfaceMesh Mesh>
[[nodiscard]] vector_x<mesh_scalar_t<Mesh>> average_geodesic_distance(const Mesh& mesh, const agd_options& options = {}) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return average_geodesic_distance<mesh_scalar_t<Mesh>>(m.V, m.F, options);
}
/// AGD local maxima on any SurfaceMesh.
template <SurfaceMesh Mesh>
[[nodiscard]] std::vector<index_t> agd_local_maxima(const Mesh& mesh, const vector_x<mesh_scalar_t<Mesh>>& agd,
                                                    double radius = 0) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return agd_local_maxima<mesh_scalar_t<Mesh>>(m.V, m.F, agd, radius);
}

}  // namespace shapestruct
