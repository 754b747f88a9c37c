// SPDX-License-Identifier: MIT
// make_shape_samples: turns a mesh, polygon soup or point cloud into the fitter's shape_samples.
#pragma once

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/local_shape_features.hpp"
#include "shapestruct/geometry/surface_sampling.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/templates/shape_samples.hpp"

namespace shapestruct {

/// Options of make_shape_samples.
struct shape_sampling_options {
  index_t points = 1500;       ///< samples per shape (the fitter is linear in this)
  int neighbors = 8;           ///< k of the kNN smoothness graph
  double tau_fraction = 0.15;  ///< tau_Nhd = 0.15 R (5.3.2): feature neighbourhood and smoothness fall-off
  int up_axis = 1;             ///< collection up axis (0 x, 1 y, 2 z): the features measure angles to it
  bool even = true;            ///< blue-noise sampling (better neighbourhood graphs) instead of plain random
  std::uint64_t seed = 1;
  int threads = 1;             ///< per-shape threads; collection runners parallelise over shapes instead
};

/// Indices of the local_shape_features columns used by templates: the two eigenvalue ratios and the two angles
/// to the up axis. The angles to the second horizontal axis change under the fitter's quarter turns about the
/// up axis, so they cannot be compared with a template's feature means; they are left out.
inline constexpr std::array<int, 4> template_feature_columns = {0, 1, 2, 4};

namespace detail {

inline shape_samples finish_samples(Eigen::Matrix<double, Eigen::Dynamic, 3> P,
                                    Eigen::Matrix<double, Eigen::Dynamic, 3> N, std::vector<index_t> faces,
                                    const shape_sampling_options& opt, const char* who) {
  shape_samples s;
  const Eigen::Vector3d lo = P.colwise().minCoeff().transpose(), hi = P.colwise().maxCoeff().transpose();
  s.center = 0.5 * (lo + hi);
  s.scale = (hi - lo).norm();
  if (!(s.scale > 0))
    throw invalid_input(input_error::degenerate_face, no_index,
                        std::string(who) + ": the shape has zero extent (all samples coincide)");
  s.points = (P.rowwise() - s.center.transpose()) / s.scale;
  s.faces = std::move(faces);
  local_shape_features_options fo;
  fo.radius_fraction = opt.tau_fraction;
  fo.up_axis = {0, 0, 0};
  fo.up_axis[static_cast<std::size_t>(opt.up_axis)] = 1;
  fo.second_axis = {0, 0, 0};
  fo.second_axis[static_cast<std::size_t>((opt.up_axis + 1) % 3)] = 1;
  fo.threads = opt.threads;
  fo.validation = validation_level::trust;
  const auto lf = local_shape_features<double>(s.points, fo);
  s.features.resize(s.points.rows(), static_cast<index_t>(template_feature_columns.size()));
  for (std::size_t c = 0; c < template_feature_columns.size(); ++c)
    s.features.col(static_cast<index_t>(c)) = lf.features.col(template_feature_columns[c]);
  s.normals = N.rows() == s.points.rows() ? N : lf.normals;
  const double tau = opt.tau_fraction * std::max(1e-12, lf.shape_diameter);
  knn_index<double, 3> index(s.points);
  const auto nn = index.knn_batch(s.points, opt.neighbors + 1, opt.threads);
  std::vector<std::pair<index_t, index_t>> pairs;
  for (index_t i = 0; i < nn.indices.rows(); ++i)
    for (index_t k = 0; k < nn.indices.cols(); ++k) {
      const index_t j = nn.indices(i, k);
      if (j != i) pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  s.edges.reserve(pairs.size());
  for (const auto& [a, b] : pairs)
    s.edges.push_back({a, b,
                       smoothness_weight(s.normals.row(a).transpose(), s.normals.row(b).transpose(),
                                         (s.points.row(a) - s.points.row(b)).norm(), tau)});
  return s;
}

inline void check_sampling_options(const shape_sampling_options& opt, const char* who) {
  if (opt.points < 2 || opt.neighbors < 1 || !(opt.tau_fraction > 0) || opt.up_axis < 0 || opt.up_axis > 2 ||
      opt.threads < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": needs points >= 2, neighbors >= 1, tau_fraction > 0, up_axis in "
                                           "{0, 1, 2} and threads >= 0");
}

}  // namespace detail

/// Samples a triangle mesh or polygon soup (faces need not share vertices, nor be manifold) for fitting:
/// `points` area-weighted samples with their face normals and source faces, the canonical frame, local shape
/// features (template_feature_columns of local_shape_features) and the kNN smoothness graph.
/// \throws invalid_input empty / non_finite / bad_face (validate_mesh), degenerate_face (zero total area or
///         extent), bad_parameter (options). O(points log points + F).
template <SurfaceMesh Mesh>
[[nodiscard]] shape_samples make_shape_samples(const Mesh& mesh, const shape_sampling_options& opt = {}) {
  constexpr const char* who = "make_shape_samples";
  detail::check_sampling_options(opt, who);
  const auto m = to_triangle_mesh<double>(mesh);
  validate_mesh(m.V, m.F, who);
  surface_sampling_options so;
  so.seed = opt.seed;
  so.threads = opt.threads;
  so.oversampling = 3.0;
  so.validation = validation_level::trust;
  const auto ss = opt.even ? sample_surface_even<double>(m.V, m.F, opt.points, so)
                           : sample_surface_random<double>(m.V, m.F, opt.points, so);
  std::vector<index_t> faces(ss.faces.data(), ss.faces.data() + ss.faces.size());
  return detail::finish_samples(ss.points, ss.normals, std::move(faces), opt, who);
}

/// Point-cloud overload: the points themselves are the samples (use `points` of them, evenly spaced by index,
/// when there are more); normals come from the local covariance (local_shape_features). Faces are no_index.
/// \throws invalid_input empty / non_finite (validate_points), bad_parameter. O(P log P).
template <PointSet Points>
  requires(!SurfaceMesh<Points>)
[[nodiscard]] shape_samples make_shape_samples(const Points& cloud, const shape_sampling_options& opt = {}) {
  constexpr const char* who = "make_shape_samples";
  detail::check_sampling_options(opt, who);
  using traits = point_set_traits_t<Points>;
  static_assert(traits::dimension == 3, "make_shape_samples: point clouds must be 3-D");
  const index_t n = static_cast<index_t>(traits::num_points(cloud));
  Eigen::Matrix<double, Eigen::Dynamic, 3> all(n, 3);
  for (index_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) all(i, d) = static_cast<double>(traits::coord(cloud, i, d));
  validate_points(all, who);
  const index_t m = std::min(n, opt.points);
  Eigen::Matrix<double, Eigen::Dynamic, 3> P(m, 3);
  for (index_t i = 0; i < m; ++i) P.row(i) = all.row(i * n / m);
  return detail::finish_samples(std::move(P), {}, std::vector<index_t>(static_cast<std::size_t>(m), no_index), opt,
                                who);
}

}  // namespace shapestruct
