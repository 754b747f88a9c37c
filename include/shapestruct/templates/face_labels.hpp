// SPDX-License-Identifier: MIT
// project_labels_to_faces: per-face labels of the original mesh from labeled sample points (5.4.3).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/templates/alpha_expansion.hpp"
#include "shapestruct/templates/shape_samples.hpp"

namespace shapestruct {

/// Options of project_labels_to_faces.
struct face_label_options {
  int voters = 6;               ///< nearest labeled samples voting for each face (inverse-distance weights)
  bool smooth_manifold = true;  ///< on faces sharing edges, refine the votes with a graph cut (see below)
  double smoothness = 0.5;      ///< weight of the face-adjacency term relative to the votes
};

/// Per-face labels of a mesh or soup from labels on its samples (shape_samples, in the input's coordinates via
/// s.center / s.scale). Every face gets votes from its `voters` nearest labeled samples (null-labeled samples,
/// label < 0, do not vote), weighted by 1 / (distance + eps) — the chapter's rule for non-manifold meshes. When
/// faces share edges and smooth_manifold is set, the votes become unary costs (1 - vote fraction) of an
/// alpha-expansion over the face adjacency graph whose edge weights grow with flatness and edge length
/// (a fuzzy-cut-like boundary that follows creases; the chapter uses fuzzy cuts [64]). Faces with no voter
/// within reach get the overall nearest labeled sample's label.
/// \param labels per sample, in [0, L) or negative for null; at least one must be non-negative
/// \throws invalid_input size_mismatch (labels vs samples), empty (no labeled sample), and validate_mesh's.
/// \returns one label per face. O(F log P + graph cut on F nodes).
template <SurfaceMesh Mesh>
[[nodiscard]] std::vector<index_t> project_labels_to_faces(const Mesh& mesh, const shape_samples& s,
                                                           const std::vector<index_t>& labels,
                                                           const face_label_options& opt = {}) {
  const auto m = to_triangle_mesh<double>(mesh);
  validate_mesh(m.V, m.F, "project_labels_to_faces");
  if (static_cast<index_t>(labels.size()) != s.size())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "project_labels_to_faces: " + std::to_string(labels.size()) + " labels for " +
                            std::to_string(s.size()) + " samples");
  std::vector<index_t> keep;
  index_t L = 0;
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] >= 0) {
      keep.push_back(static_cast<index_t>(i));
      L = std::max(L, labels[i] + 1);
    }
  if (keep.empty())
    throw invalid_input(input_error::empty, no_index, "project_labels_to_faces: no sample carries a label");
  Eigen::Matrix<double, Eigen::Dynamic, 3> P(static_cast<index_t>(keep.size()), 3);
  for (std::size_t k = 0; k < keep.size(); ++k)
    P.row(static_cast<index_t>(k)) = s.points.row(keep[k]) * s.scale + s.center.transpose();
  knn_index<double, 3> index(P);
  const index_t nf = m.F.rows();
  Eigen::Matrix<double, Eigen::Dynamic, 3> C(nf, 3);
  for (index_t f = 0; f < nf; ++f) C.row(f) = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3.0;
  const auto nn = index.knn_batch(C, opt.voters, 1);
  Eigen::MatrixXd votes = Eigen::MatrixXd::Zero(nf, L);
  const double eps = 1e-6 * s.scale;
  for (index_t f = 0; f < nf; ++f) {
    for (index_t k = 0; k < nn.indices.cols(); ++k) {
      const index_t j = nn.indices(f, k);
      votes(f, labels[static_cast<std::size_t>(keep[static_cast<std::size_t>(j)])]) +=
          1.0 / (std::sqrt(nn.sq_distances(f, k)) + eps);
    }
    votes.row(f) /= votes.row(f).sum();
  }
  std::vector<index_t> out(static_cast<std::size_t>(nf));
  for (index_t f = 0; f < nf; ++f) votes.row(f).maxCoeff(&out[static_cast<std::size_t>(f)]);
  if (!opt.smooth_manifold || L < 2) return out;
  // Face adjacency through shared edges (soups without shared vertices simply have none).
  std::vector<std::array<index_t, 3>> half;  // (min v, max v, face)
  half.reserve(static_cast<std::size_t>(3 * nf));
  for (index_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const index_t a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      half.push_back({std::min(a, b), std::max(a, b), f});
    }
  std::sort(half.begin(), half.end());
  Eigen::Matrix<double, Eigen::Dynamic, 3> N(nf, 3);
  for (index_t f = 0; f < nf; ++f) {
    const Eigen::Vector3d e1 = (m.V.row(m.F(f, 1)) - m.V.row(m.F(f, 0))).transpose();
    const Eigen::Vector3d e2 = (m.V.row(m.F(f, 2)) - m.V.row(m.F(f, 0))).transpose();
    const Eigen::Vector3d n = e1.cross(e2);
    N.row(f) = n.norm() > 0 ? Eigen::RowVector3d((n / n.norm()).transpose()) : Eigen::RowVector3d::Zero();
  }
  std::vector<potts_edge> edges;
  double mean_len = 0;
  for (std::size_t i = 0; i + 1 < half.size(); ++i)
    if (half[i][0] == half[i + 1][0] && half[i][1] == half[i + 1][1] && half[i][2] != half[i + 1][2]) {
      const double len = (m.V.row(half[i][0]) - m.V.row(half[i][1])).norm();
      const double c = std::clamp(N.row(half[i][2]).dot(N.row(half[i + 1][2])), -1.0, 1.0);
      // Concave creases (part boundaries) and sharp bends are cheap to cut; flat regions are expensive.
      const double w = len * std::exp(-3.0 * (1.0 - c));
      edges.push_back({half[i][2], half[i + 1][2], w});
      mean_len += len;
    }
  if (edges.empty()) return out;
  mean_len /= static_cast<double>(edges.size());
  for (auto& e : edges) e.weight *= opt.smoothness / mean_len;
  const Eigen::MatrixXd U = Eigen::MatrixXd::Ones(nf, L) - votes;
  return alpha_expansion(U, edges, out, {.max_sweeps = 5}).labels;
}

}  // namespace shapestruct
