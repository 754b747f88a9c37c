// SPDX-License-Identifier: MIT
// connected_components: labels the vertices and faces of a mesh by connected piece (union-find).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"

namespace shapestruct {

/// Result of connected_components().
struct component_labels {
  index_t count = 0;                                       ///< number of components, isolated vertices included
  Eigen::Matrix<index_t, Eigen::Dynamic, 1> vertex_label;  ///< #V, in [0, count)
  Eigen::Matrix<index_t, Eigen::Dynamic, 1> face_label;    ///< #F, the label of the face's vertices
};

/// Connected components of the graph whose nodes are the vertices 0 .. num_vertices-1 and whose links are
/// the face sides. A vertex that no face uses is a component of its own (so count >= 1 whenever
/// num_vertices >= 1 and `count == 1` means "one piece, no stray vertices"). Labels are numbered in order of
/// each component's smallest vertex index, so they do not depend on the face order.
/// \param F #F x 3 vertex indices in [0, num_vertices); a repeated index in a face is allowed here
/// \param num_vertices #V >= 0
/// \throws invalid_input bad_face (face index) when an index is outside [0, num_vertices);
///         bad_parameter when num_vertices < 0
/// \returns count and the per-vertex and per-face labels
/// Complexity: O(V + F alpha(V)) time, O(V + F) memory.
[[nodiscard]] inline component_labels connected_components(const Eigen::Ref<const face_matrix>& F,
                                                           index_t num_vertices) {
  if (num_vertices < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        "connected_components: num_vertices is negative (" + std::to_string(num_vertices) + ")");
  for (index_t f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= num_vertices)
        throw invalid_input(input_error::bad_face, f,
                            "connected_components: face " + std::to_string(f) + " refers to vertex " +
                                std::to_string(F(f, k)) + ", outside [0, " + std::to_string(num_vertices) +
                                "); check_mesh() lists all such faces");
  detail::disjoint_sets sets(num_vertices);
  for (index_t f = 0; f < F.rows(); ++f) {
    sets.unite(F(f, 0), F(f, 1));
    sets.unite(F(f, 0), F(f, 2));
  }
  component_labels out;
  out.vertex_label.resize(num_vertices);
  std::vector<index_t> root_label(static_cast<std::size_t>(num_vertices), no_index);
  for (index_t v = 0; v < num_vertices; ++v) {
    index_t& l = root_label[static_cast<std::size_t>(sets.find(v))];
    if (l == no_index) l = out.count++;
    out.vertex_label(v) = l;
  }
  out.face_label.resize(F.rows());
  for (index_t f = 0; f < F.rows(); ++f) out.face_label(f) = out.vertex_label(F(f, 0));
  return out;
}

/// connected_components of any SurfaceMesh (its faces and vertex count).
/// \throws invalid_input bad_face as the kernel. Complexity: O(V + F alpha(V)).
template <SurfaceMesh Mesh>
[[nodiscard]] component_labels connected_components(const Mesh& mesh) {
  using S = mesh_scalar_t<Mesh>;
  if constexpr (std::is_same_v<std::remove_cvref_t<Mesh>, triangle_mesh<S>>) {
    return connected_components(mesh.F, mesh.num_vertices());
  } else {
    using traits = surface_traits_t<Mesh>;
    const index_t nf = static_cast<index_t>(traits::num_faces(mesh));
    face_matrix F(nf, 3);
    for (index_t f = 0; f < nf; ++f) {
      const std::array<index_t, 3> t = traits::face(mesh, f);
      F.row(f) << t[0], t[1], t[2];
    }
    return connected_components(F, static_cast<index_t>(traits::num_vertices(mesh)));
  }
}

}  // namespace shapestruct
