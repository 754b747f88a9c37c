// SPDX-License-Identifier: MIT
// make_shape_record: samples a shape once (ch. 4.3.1) and keeps the small record the collection stages need.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/concepts/shape_descriptor.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/geometry/mesh_repair.hpp"
#include "shapestruct/geometry/surface_sampling.hpp"
#include "shapestruct/knn/knn_index.hpp"

namespace shapestruct {

/// How the K samples are spread (ch. 4.3.1: farthest-point sampling).
enum class sample_metric {
  automatic,  ///< geodesic on closed genus-0 manifolds, Euclidean otherwise
  geodesic,   ///< edge-graph geodesic farthest points among the vertices (needs one connected surface)
  euclidean,  ///< Euclidean farthest points among evenly spread surface points (soups, scans)
};

/// Options of make_shape_record (the chapter's defaults).
struct shape_record_options {
  index_t samples = 128;          ///< K, the samples per shape (ch. 4.4.9)
  index_t surface_points = 1024;  ///< M, evenly spread points for extrinsic alignment and the descriptor
  sample_metric metric = sample_metric::automatic;
  std::uint64_t seed = 1;  ///< seeds the surface sampling; the first farthest-point pick is vertex / point 0
};

namespace detail {

/// Diam(S) of ch. 4.3.3: mean Euclidean distance over all ordered pairs of samples (K^2 terms, as written).
inline double mean_pairwise_distance(const Eigen::Matrix<double, Eigen::Dynamic, 3>& P) {
  const index_t K = P.rows();
  if (K == 0) return 0;
  double sum = 0;
  for (index_t i = 0; i < K; ++i)
    for (index_t j = i + 1; j < K; ++j) sum += 2.0 * (P.row(i) - P.row(j)).norm();
  return sum / double(K * K);
}

inline void check_record_options(const shape_record_options& o, const char* who) {
  if (o.samples < 1)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": samples must be >= 1, got " + std::to_string(o.samples));
  if (o.surface_points < o.samples)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": surface_points (" + std::to_string(o.surface_points) +
                            ") must be at least samples (" + std::to_string(o.samples) + ")");
}

/// Nearest row of `samples` for every row of `points` (Euclidean).
inline std::vector<std::int32_t> nearest_sample_of(const Eigen::Matrix<double, Eigen::Dynamic, 3>& points,
                                                   const Eigen::Matrix<double, Eigen::Dynamic, 3>& samples) {
  knn_index<double, 3> index(samples);
  std::vector<std::int32_t> out(static_cast<std::size_t>(points.rows()));
  for (index_t v = 0; v < points.rows(); ++v)
    out[static_cast<std::size_t>(v)] = static_cast<std::int32_t>(index.nearest(points.row(v).transpose()).index);
  return out;
}

}  // namespace detail

/// The record of one surface: K farthest-point samples (geodesic among the vertices of a closed genus-0
/// manifold, else Euclidean among M evenly spread surface points), the nearest sample of every vertex, the
/// K x K sample geodesics (manifolds), M surface points, the descriptor of those points, Diam(S) and the area.
/// \param name the shape's name in the collection  \param describe the ShapeDescriptor policy
/// \throws invalid_input (empty, non_finite, bad_face) for an unusable mesh, (empty) when it has fewer
///         vertices than samples on the geodesic path or no face of positive area, (unsupported_topology) when
///         metric = geodesic on a shape that is not one closed genus-0 surface, (bad_parameter) for options.
/// Complexity O(K (V + E) log V) geodesic, O(M K + M log M) Euclidean.
template <SurfaceMesh Mesh, ShapeDescriptor Descriptor>
[[nodiscard]] shape_record make_shape_record(const Mesh& mesh, std::string name, const Descriptor& describe,
                                             const shape_record_options& options = {}) {
  const char* who = "make_shape_record";
  detail::check_record_options(options, who);
  const triangle_mesh<double> m = to_triangle_mesh<double>(mesh);
  validate_mesh(m.V, m.F, who);
  shape_record r;
  r.name = std::move(name);
  r.vertex_count = m.V.rows();
  r.area = total_area<double>(m.V, m.F);
  if (!(r.area > 0) || !std::isfinite(r.area))
    throw invalid_input(input_error::empty, no_index,
                        std::string(who) + ": shape '" + r.name + "' has no face of positive finite area");
  const mesh_report report = check_mesh(m);
  r.closed_genus0 = report.is_closed_genus0_manifold();
  // A sphere pinched at a few vertices (SCAPE's template at vertex 419) is still a sphere to the blended matcher
  // (mid_edge_flattening accepts pinched vertices): it is one once those vertices are split.
  if (!r.closed_genus0 && report.is_valid() && report.is_closed() && report.num_non_manifold_edges == 0 &&
      report.num_non_manifold_vertices > 0)
    r.closed_genus0 = check_mesh(split_non_manifold_vertices(m).mesh).is_closed_genus0_manifold();
  const bool geodesic = options.metric == sample_metric::geodesic ||
                        (options.metric == sample_metric::automatic && r.closed_genus0);
  if (geodesic && !r.closed_genus0)
    throw invalid_input(input_error::unsupported_topology, no_index,
                        std::string(who) + ": shape '" + r.name +
                            "' is not one closed genus-0 surface; use sample_metric::euclidean (or automatic)");

  surface_sampling_options so;
  so.seed = options.seed;
  so.threads = 1;  // records are made in parallel over shapes
  so.validation = validation_level::trust;
  r.surface_points = sample_surface_even<double>(m.V, m.F, options.surface_points, so).points;

  if (geodesic) {
    if (m.V.rows() < options.samples)
      throw invalid_input(input_error::empty, no_index,
                          std::string(who) + ": shape '" + r.name + "' has " + std::to_string(m.V.rows()) +
                              " vertices, fewer than the " + std::to_string(options.samples) +
                              " samples asked for; lower --samples or refine the mesh");
    const dijkstra_geodesics<double> geo(m.V, m.F, validation_level::trust);
    const auto fps = geodesic_farthest_point_sampling(geo, options.samples, 0);
    r.sample_vertex = fps.indices;
    const matrix_x<double> D = geo.distance_table(std::span<const index_t>(r.sample_vertex), 1);
    const index_t K = options.samples;
    r.samples.resize(K, 3);
    r.sample_geodesics.resize(K, K);
    for (index_t i = 0; i < K; ++i) {
      r.samples.row(i) = m.V.row(r.sample_vertex[static_cast<std::size_t>(i)]);
      for (index_t j = 0; j < K; ++j)
        r.sample_geodesics(i, j) = static_cast<float>(D(r.sample_vertex[static_cast<std::size_t>(j)], i));
    }
    r.vertex_sample.resize(static_cast<std::size_t>(m.V.rows()));
    for (index_t v = 0; v < m.V.rows(); ++v) {
      index_t best = 0;
      D.row(v).minCoeff(&best);
      r.vertex_sample[static_cast<std::size_t>(v)] = static_cast<std::int32_t>(best);
    }
  } else {
    const auto fps = farthest_point_sampling<double>(r.surface_points, options.samples, 0);
    r.samples.resize(options.samples, 3);
    for (index_t i = 0; i < options.samples; ++i) r.samples.row(i) = r.surface_points.row(fps.indices[static_cast<std::size_t>(i)]);
    r.sample_vertex.assign(static_cast<std::size_t>(options.samples), no_index);
    r.vertex_sample = detail::nearest_sample_of(m.V, r.samples);
  }
  r.diameter = detail::mean_pairwise_distance(r.samples);
  r.descriptor = describe(r.surface_points);
  return r;
}

}  // namespace shapestruct
