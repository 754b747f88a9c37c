// SPDX-License-Identifier: MIT
// edge_graph: the mesh's undirected edge graph in CSR form (vertex adjacency with edge lengths).
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/heap_bytes.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/detail/eigen_forward.hpp"

namespace shapestruct {

/// `#E x 2` undirected edges, each stored once as (smaller index, larger index).
using edge_matrix = Eigen::Matrix<index_t, Eigen::Dynamic, 2>;

/// The unique undirected edges of the triangles F, sorted lexicographically, as (i, j) with i < j; an edge
/// shared by several faces appears once.
/// \param F (#F x 3) triangles; indices must be valid for some vertex count (not checked here).
/// \returns (#E x 2). Complexity O(F log F).
[[nodiscard]] inline edge_matrix unique_edges(const Eigen::Ref<const face_matrix>& F) {
  std::vector<std::pair<index_t, index_t>> e;
  e.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (index_t f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) e.emplace_back(std::minmax(F(f, k), F(f, (k + 1) % 3)));
  std::sort(e.begin(), e.end());
  e.erase(std::unique(e.begin(), e.end()), e.end());
  edge_matrix out(static_cast<index_t>(e.size()), 2);
  for (std::size_t i = 0; i < e.size(); ++i) out.row(static_cast<index_t>(i)) << e[i].first, e[i].second;
  return out;
}

/// Undirected edge graph of a triangle mesh in compressed sparse row form: the neighbours of vertex v are
/// `neighbours[offsets[v] .. offsets[v+1])`, sorted ascending, with the Euclidean edge lengths in `lengths` at
/// the same positions and the undirected edge's row in `edges` in `edge_ids`. Each undirected edge appears
/// twice (once from each end); edges shared by several faces are merged. Unreferenced vertices have degree 0.
/// The CSR arrays are contiguous so that graph searches (Dijkstra) stream through memory.
template <class Scalar = double>
struct edge_graph {
  std::vector<index_t> offsets;     ///< #V + 1 row starts
  std::vector<index_t> neighbours;  ///< 2 #E neighbour vertex indices
  std::vector<Scalar> lengths;      ///< 2 #E edge lengths, >= 0
  std::vector<index_t> edge_ids;    ///< 2 #E row of the undirected edge in `edges`
  edge_matrix edges;                ///< #E x 2 unique edges (i < j), sorted

  edge_graph() = default;

  /// Builds the graph of (V, F).
  /// \param V (#V x 3) vertex positions  \param F (#F x 3) triangles
  /// \throws invalid_input (empty, non_finite, bad_face) from validate_mesh. Complexity O(V + F log F).
  edge_graph(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
             validation_level level = validation_level::full) {
    validate_mesh(V, F, "edge_graph", level);
    edges = unique_edges(F);
    const index_t n = V.rows(), ne = edges.rows();
    offsets.assign(static_cast<std::size_t>(n + 1), 0);
    for (index_t e = 0; e < ne; ++e) {
      ++offsets[static_cast<std::size_t>(edges(e, 0) + 1)];
      ++offsets[static_cast<std::size_t>(edges(e, 1) + 1)];
    }
    for (std::size_t i = 1; i < offsets.size(); ++i) offsets[i] += offsets[i - 1];
    neighbours.resize(static_cast<std::size_t>(2 * ne));
    lengths.resize(static_cast<std::size_t>(2 * ne));
    edge_ids.resize(static_cast<std::size_t>(2 * ne));
    std::vector<index_t> fill(offsets.begin(), offsets.end() - 1);
    // Edges are sorted by (i, j), so visiting them in order fills every row in ascending neighbour order:
    // row i receives its j > i from the first slot of each edge, in increasing j, after the j' < i that
    // arrived earlier as second slots of edges (j', i) with j' < i.
    for (index_t e = 0; e < ne; ++e) {
      const index_t a = edges(e, 0), b = edges(e, 1);
      const Scalar len = (V.row(a) - V.row(b)).norm();
      const auto pa = static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++);
      const auto pb = static_cast<std::size_t>(fill[static_cast<std::size_t>(b)]++);
      neighbours[pa] = b, lengths[pa] = len, edge_ids[pa] = e;
      neighbours[pb] = a, lengths[pb] = len, edge_ids[pb] = e;
    }
  }

  [[nodiscard]] index_t num_vertices() const noexcept {
    return offsets.empty() ? 0 : static_cast<index_t>(offsets.size()) - 1;
  }
  [[nodiscard]] index_t num_edges() const noexcept { return edges.rows(); }
  /// Number of neighbours of v (v in [0, #V), unchecked).
  [[nodiscard]] index_t degree(index_t v) const noexcept {
    return offsets[static_cast<std::size_t>(v + 1)] - offsets[static_cast<std::size_t>(v)];
  }
  /// Degrees of all vertices (#V).
  [[nodiscard]] Eigen::Matrix<index_t, Eigen::Dynamic, 1> degrees() const {
    Eigen::Matrix<index_t, Eigen::Dynamic, 1> d(num_vertices());
    for (index_t v = 0; v < num_vertices(); ++v) d[v] = degree(v);
    return d;
  }
  /// Bytes held on the heap (core/heap_bytes.hpp).
  [[nodiscard]] std::size_t heap_bytes() const noexcept {
    using shapestruct::heap_bytes;
    return heap_bytes(offsets) + heap_bytes(neighbours) + heap_bytes(lengths) + heap_bytes(edge_ids) + heap_bytes(edges);
  }
};

/// Edge graph of any dense Eigen (V, F).
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] edge_graph<typename DV::Scalar> make_edge_graph(const Eigen::MatrixBase<DV>& V,
                                                              const Eigen::MatrixBase<DF>& F) {
  return edge_graph<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>());
}

/// Edge graph of any SurfaceMesh (Scalar = the mesh's scalar type).
template <SurfaceMesh Mesh>
[[nodiscard]] edge_graph<mesh_scalar_t<Mesh>> make_edge_graph(const Mesh& mesh) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return edge_graph<mesh_scalar_t<Mesh>>(m.V, m.F);
}

}  // namespace shapestruct
