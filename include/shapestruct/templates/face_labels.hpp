// SPDX-License-Identifier: MIT
// project_labels_to_faces: per-face labels of the original mesh from labeled sample points (5.4.3).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/templates/alpha_expansion.hpp"
#include "shapestruct/templates/shape_samples.hpp"

namespace shapestruct {

/// Options of project_labels_to_faces.
struct face_label_options {
  int voters = 6;  ///< nearest labeled samples voting for each face (inverse-distance weights)
  /// On faces that share edges, place the part boundaries by the fuzzy-cut variant (5.4.3, after Katz and Tal
  /// [64]): the boundary may move only inside the fuzzy region that the labeled points leave undecided, and there
  /// it follows the cheapest path, along concave creases. Off, or on polygon soups, faces keep their vote.
  bool smooth_manifold = true;
  /// A face is in the fuzzy region when its `fuzzy_voters` nearest labeled samples carry more than one label;
  /// every other face keeps the label all of them agree on. Larger values widen the region the boundary can move
  /// in (about sqrt(fuzzy_voters / pi) sample spacings either side of the labeled points' boundary).
  int fuzzy_voters = 24;
  /// Angular distance eta (1 - cos dihedral) of a convex edge relative to a concave one (Katz and Tal: 0.1-0.2):
  /// convex edges are costlier to cut, so boundaries prefer concave creases, where parts meet.
  double convex_eta = 0.2;
  /// Weight of the votes inside the fuzzy region, relative to cutting one average edge: small, so the geometry
  /// decides where the boundary goes and the votes only break ties on flat regions.
  double vote_weight = 0.05;
};

namespace detail {

/// Face adjacency of a mesh with the fuzzy-cut capacity of each shared edge: len / mean_len / (1 + ad / mean_ad),
/// ad = eta (1 - cos of the dihedral angle), eta = convex_eta on convex edges and 1 on concave ones (and on edges
/// whose two faces are oriented inconsistently, where convexity is unknown). Edges of more than two faces link
/// every pair. Polygon soups (no shared vertices) have none.
inline std::vector<potts_edge> fuzzy_cut_edges(const triangle_mesh<double>& m, double convex_eta) {
  const index_t nf = m.F.rows();
  struct half_edge {
    index_t lo, hi, face, from;  // edge (lo, hi) of `face`, walked from vertex `from`
  };
  std::vector<half_edge> half;
  half.reserve(static_cast<std::size_t>(3 * nf));
  for (index_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const index_t a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      half.push_back({std::min(a, b), std::max(a, b), f, a});
    }
  std::sort(half.begin(), half.end(), [](const half_edge& x, const half_edge& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  const matrix_x3<double> N = face_normals<double>(m.V, m.F, validation_level::trust);  // zero on degenerate faces
  auto opposite = [&](index_t f, index_t a, index_t b) {
    for (int k = 0; k < 3; ++k)
      if (m.F(f, k) != a && m.F(f, k) != b) return m.F(f, k);
    return m.F(f, 0);
  };
  std::vector<potts_edge> edges;
  std::vector<double> lengths, angular;
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    while (j < half.size() && half[j].lo == half[i].lo && half[j].hi == half[i].hi) ++j;
    for (std::size_t x = i; x < j; ++x)
      for (std::size_t y = x + 1; y < j; ++y) {
        const half_edge& p = half[x];
        const half_edge& q = half[y];
        if (p.face == q.face) continue;
        const double c = std::clamp(N.row(p.face).dot(N.row(q.face)), -1.0, 1.0);
        // Consistently oriented neighbours walk the shared edge in opposite directions; then the edge is concave
        // when q's far vertex lies on the side p's normal points to.
        double eta = 1.0;
        if (p.from != q.from) {
          const Eigen::RowVector3d to_far = m.V.row(opposite(q.face, p.lo, p.hi)) - m.V.row(p.lo);
          if (N.row(p.face).dot(to_far) < 0) eta = convex_eta;
        }
        edges.push_back({p.face, q.face, 0.0});
        lengths.push_back((m.V.row(p.lo) - m.V.row(p.hi)).norm());
        angular.push_back(eta * (1.0 - c));
      }
    i = j;
  }
  if (edges.empty()) return edges;
  double mean_len = 0, mean_ad = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    mean_len += lengths[e];
    mean_ad += angular[e];
  }
  mean_len /= static_cast<double>(edges.size());
  mean_ad /= static_cast<double>(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const double len = mean_len > 0 ? lengths[e] / mean_len : 1.0;
    edges[e].weight = len / (1.0 + (mean_ad > 0 ? angular[e] / mean_ad : 0.0));
  }
  return edges;
}

}  // namespace detail

/// Per-face labels of a mesh or soup from labels on its samples (shape_samples, in the input's coordinates via
/// s.center / s.scale). Every face first gets the vote of its `voters` nearest labeled samples (null-labeled
/// samples, label < 0, do not vote), weighted by 1 / (distance + eps): the chapter's rule for non-manifold meshes.
/// On faces that share edges (smooth_manifold), the boundaries are then placed by the fuzzy-cut variant of 5.4.3:
/// faces whose `fuzzy_voters` nearest labeled samples all agree keep that label (hard constraint); the others form
/// the fuzzy region, where a multi-label minimum cut (alpha-expansion) over the face adjacency, with Katz and
/// Tal's capacities (detail::fuzzy_cut_edges) and a small vote term, decides. So boundaries the labeled points
/// place roughly snap to the nearby concave creases, and faces far from any boundary never change.
/// \param labels per sample, in [0, L) or negative for null; at least one must be non-negative
/// \throws invalid_input size_mismatch (labels vs samples), empty (no labeled sample), bad_parameter (voters or
///         fuzzy_voters < 1, convex_eta or vote_weight negative or not finite), and validate_mesh's.
/// \returns one label per face. O(F log P + alpha-expansion on F nodes).
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
  if (opt.voters < 1 || opt.fuzzy_voters < 1 || !(opt.convex_eta >= 0) || !std::isfinite(opt.convex_eta) ||
      !(opt.vote_weight >= 0) || !std::isfinite(opt.vote_weight))
    throw invalid_input(input_error::bad_parameter, no_index,
                        "project_labels_to_faces: voters and fuzzy_voters must be >= 1, convex_eta and vote_weight "
                        "finite and >= 0");
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
  const bool refine = opt.smooth_manifold && L >= 2;
  const auto nn = index.knn_batch(C, refine ? std::max(opt.voters, opt.fuzzy_voters) : opt.voters, 1);
  auto label_of = [&](index_t f, index_t k) {
    return labels[static_cast<std::size_t>(keep[static_cast<std::size_t>(nn.indices(f, k))])];
  };
  const index_t n_votes = std::min<index_t>(opt.voters, nn.indices.cols());
  Eigen::MatrixXd votes = Eigen::MatrixXd::Zero(nf, L);
  const double eps = 1e-6 * s.scale;
  for (index_t f = 0; f < nf; ++f) {
    for (index_t k = 0; k < n_votes; ++k) votes(f, label_of(f, k)) += 1.0 / (std::sqrt(nn.sq_distances(f, k)) + eps);
    votes.row(f) /= votes.row(f).sum();
  }
  std::vector<index_t> out(static_cast<std::size_t>(nf));
  for (index_t f = 0; f < nf; ++f) votes.row(f).maxCoeff(&out[static_cast<std::size_t>(f)]);
  if (!refine) return out;
  const std::vector<potts_edge> edges = detail::fuzzy_cut_edges(m, opt.convex_eta);
  if (edges.empty()) return out;
  // Fixed faces get a cost no cut can outweigh for any other label; fuzzy faces a small vote term.
  double hard = 1;
  for (const auto& e : edges) hard += e.weight;
  Eigen::MatrixXd U(nf, L);
  const index_t n_fuzzy = std::min<index_t>(opt.fuzzy_voters, nn.indices.cols());
  for (index_t f = 0; f < nf; ++f) {
    bool agree = true;
    for (index_t k = 1; k < n_fuzzy && agree; ++k) agree = label_of(f, k) == label_of(f, 0);
    if (agree) {
      U.row(f).setConstant(hard);
      U(f, label_of(f, 0)) = 0;
      out[static_cast<std::size_t>(f)] = label_of(f, 0);
    } else {
      U.row(f) = opt.vote_weight * (Eigen::RowVectorXd::Ones(L) - votes.row(f));
    }
  }
  return alpha_expansion(U, edges, out, {.max_sweeps = 5}).labels;
}

}  // namespace shapestruct
