// SPDX-License-Identifier: MIT
// Mesh repairs that make a scan acceptable to algorithms needing a clean closed surface: keep the largest
// piece, fill small holes, drop stray vertices, merge coincident vertices.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"
#include "shapestruct/geometry/connected_components.hpp"

namespace shapestruct {

/// Result of a repair that renumbers vertices.
template <class Scalar>
struct repaired_mesh {
  triangle_mesh<Scalar> mesh;
  /// #V_old: the new index of each old vertex, or no_index if it was dropped.
  Eigen::Matrix<index_t, Eigen::Dynamic, 1> old_to_new;
  index_t removed_vertices = 0;
  index_t removed_faces = 0;
};

/// Result of close_small_holes(): the old vertices and faces keep their indices, new ones are appended.
template <class Scalar>
struct hole_filling_result {
  triangle_mesh<Scalar> mesh;
  index_t holes_filled = 0;
  index_t holes_left = 0;  ///< loops longer than max_boundary_loop_length
  index_t added_vertices = 0;
  index_t added_faces = 0;
  index_t longest_loop_left = 0;  ///< the length (edges) of the longest loop left open, 0 if none
  std::vector<index_t> filled_loop_lengths;  ///< the length (edges) of every loop filled, in the order filled
};

/// Result of remove_collapsed_and_duplicate_faces(): vertices are untouched, faces keep their order.
template <class Scalar>
struct face_removal_result {
  triangle_mesh<Scalar> mesh;
  std::vector<index_t> kept_faces;  ///< for each face of the result, its index in the input
  index_t collapsed_faces = 0;      ///< removed: a corner repeated (the face is a segment or a point)
  index_t duplicate_faces = 0;      ///< removed: the same three corners as an earlier face, in any order
  index_t first_collapsed = no_index, first_duplicate = no_index;  ///< input index of the first of each, if any
};

/// Result of split_non_manifold_vertices(): old vertices keep their indices, the copies are appended.
template <class Scalar>
struct vertex_split_result {
  triangle_mesh<Scalar> mesh;
  /// For each appended vertex (index #V_old + i), the old vertex it copies.
  Eigen::Matrix<index_t, Eigen::Dynamic, 1> copied_from;
  index_t split_vertices = 0;  ///< old vertices that had more than one fan
};

namespace detail {

/// Calls fn(V, F) on the canonical form of mesh: in place for a triangle_mesh, else on a gathered copy.
template <class Scalar, class Mesh, class Fn>
auto on_canonical(const Mesh& mesh, Fn&& fn) {
  if constexpr (std::is_same_v<std::remove_cvref_t<Mesh>, triangle_mesh<Scalar>>) {
    return fn(mesh.V, mesh.F);
  } else {
    const triangle_mesh<Scalar> m = to_triangle_mesh<Scalar>(mesh);
    return fn(m.V, m.F);
  }
}

/// Keeps the vertices with keep[v] (in their order) and the faces with keep_face[f]; faces must only use
/// kept vertices.
template <class Scalar>
repaired_mesh<Scalar> compact(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                              const std::vector<char>& keep, const std::vector<char>& keep_face) {
  repaired_mesh<Scalar> out;
  out.old_to_new = Eigen::Matrix<index_t, Eigen::Dynamic, 1>::Constant(V.rows(), no_index);
  index_t nv = 0;
  for (index_t v = 0; v < V.rows(); ++v)
    if (keep[static_cast<std::size_t>(v)]) out.old_to_new(v) = nv++;
  index_t nf = 0;
  for (index_t f = 0; f < F.rows(); ++f) nf += keep_face[static_cast<std::size_t>(f)] ? 1 : 0;
  out.mesh.V.resize(nv, 3);
  out.mesh.F.resize(nf, 3);
  for (index_t v = 0; v < V.rows(); ++v)
    if (out.old_to_new(v) != no_index) out.mesh.V.row(out.old_to_new(v)) = V.row(v);
  index_t g = 0;
  for (index_t f = 0; f < F.rows(); ++f)
    if (keep_face[static_cast<std::size_t>(f)]) {
      for (int k = 0; k < 3; ++k) out.mesh.F(g, k) = out.old_to_new(F(f, k));
      ++g;
    }
  out.removed_vertices = V.rows() - nv;
  out.removed_faces = F.rows() - nf;
  return out;
}

}  // namespace detail

// ------------------------------------------------------------------------------------- keep_largest_component

/// Kernel of keep_largest_component(). \param V #V x 3, \param F #F x 3 (validated here).
template <class Scalar>
repaired_mesh<Scalar> keep_largest_component_kernel(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                    const Eigen::Ref<const face_matrix>& F) {
  validate_mesh(V, F, "keep_largest_component");
  const component_labels cc = connected_components(F, V.rows());
  std::vector<double> area(static_cast<std::size_t>(cc.count), 0.0);
  for (index_t f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).template cast<double>().transpose();
    const Eigen::Vector3d b = V.row(F(f, 1)).template cast<double>().transpose();
    const Eigen::Vector3d c = V.row(F(f, 2)).template cast<double>().transpose();
    area[static_cast<std::size_t>(cc.face_label(f))] += 0.5 * (b - a).cross(c - a).norm();
  }
  // Ties (e.g. two equal pieces, or all pieces degenerate) go to the component with the smallest vertex.
  index_t best = cc.face_label(0);
  for (index_t l = 0; l < cc.count; ++l)
    if (area[static_cast<std::size_t>(l)] > area[static_cast<std::size_t>(best)]) best = l;
  std::vector<char> keep(static_cast<std::size_t>(V.rows())), keep_face(static_cast<std::size_t>(F.rows()));
  for (index_t v = 0; v < V.rows(); ++v) keep[static_cast<std::size_t>(v)] = cc.vertex_label(v) == best;
  for (index_t f = 0; f < F.rows(); ++f) keep_face[static_cast<std::size_t>(f)] = cc.face_label(f) == best;
  return detail::compact<Scalar>(V, F, keep, keep_face);
}

/// Keeps the connected component of largest surface area (isolated vertices have zero area and are always
/// dropped), removing every other vertex and face. Vertex and face order is preserved.
/// \param mesh any SurfaceMesh with at least one face
/// \throws invalid_input empty / non_finite / bad_face (validate_mesh)
/// \returns the mesh and old_to_new (#V_old, no_index for dropped vertices)
/// Complexity: O(V + F alpha(V)).
template <SurfaceMesh Mesh>
[[nodiscard]] repaired_mesh<mesh_scalar_t<Mesh>> keep_largest_component(const Mesh& mesh) {
  using S = mesh_scalar_t<Mesh>;
  return detail::on_canonical<S>(mesh,
                                 [&](const auto& V, const auto& F) { return keep_largest_component_kernel<S>(V, F); });
}

// ----------------------------------------------------------------------------------- remove_unreferenced

/// Kernel of remove_unreferenced_vertices(). F indices must be in range (checked: bad_face).
template <class Scalar>
repaired_mesh<Scalar> remove_unreferenced_vertices_kernel(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                          const Eigen::Ref<const face_matrix>& F) {
  for (index_t f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= V.rows())
        throw invalid_input(input_error::bad_face, f,
                            "remove_unreferenced_vertices: face " + std::to_string(f) + " refers to vertex " +
                                std::to_string(F(f, k)) + ", outside [0, " + std::to_string(V.rows()) + ")");
  std::vector<char> keep(static_cast<std::size_t>(V.rows()), 0), keep_face(static_cast<std::size_t>(F.rows()), 1);
  for (index_t f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) keep[static_cast<std::size_t>(F(f, k))] = 1;
  return detail::compact<Scalar>(V, F, keep, keep_face);
}

/// Drops the vertices no face uses and renumbers the others (order preserved); faces are kept as they are
/// (renumbered). Coordinates are not inspected, so it also works on meshes with non-finite stray vertices.
/// \throws invalid_input bad_face (face index) when an index is out of range
/// \returns the mesh and old_to_new (#V_old, no_index for dropped vertices)
/// Complexity: O(V + F).
template <SurfaceMesh Mesh>
[[nodiscard]] repaired_mesh<mesh_scalar_t<Mesh>> remove_unreferenced_vertices(const Mesh& mesh) {
  using S = mesh_scalar_t<Mesh>;
  return detail::on_canonical<S>(
      mesh, [&](const auto& V, const auto& F) { return remove_unreferenced_vertices_kernel<S>(V, F); });
}

// ---------------------------------------------------------------------------------- merge_duplicate_vertices

/// Kernel of merge_duplicate_vertices(). \param V #V x 3, \param F #F x 3 (validated here).
template <class Scalar>
repaired_mesh<Scalar> merge_duplicate_vertices_kernel(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                      const Eigen::Ref<const face_matrix>& F) {
  validate_mesh(V, F, "merge_duplicate_vertices");
  const index_t n = V.rows();
  std::vector<index_t> order(static_cast<std::size_t>(n));
  for (index_t v = 0; v < n; ++v) order[static_cast<std::size_t>(v)] = v;
  std::sort(order.begin(), order.end(), [&](index_t x, index_t y) {
    for (int d = 0; d < 3; ++d) {
      if (V(x, d) < V(y, d)) return true;
      if (V(y, d) < V(x, d)) return false;
    }
    return x < y;
  });
  // representative = the lowest index with the same position (first of its run, thanks to the index tie-break)
  std::vector<index_t> rep(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < order.size(); ++i)
    rep[static_cast<std::size_t>(order[i])] =
        (i > 0 && V.row(order[i]) == V.row(order[i - 1])) ? rep[static_cast<std::size_t>(order[i - 1])] : order[i];
  std::vector<char> keep(static_cast<std::size_t>(n)), keep_face(static_cast<std::size_t>(F.rows()), 1);
  for (index_t v = 0; v < n; ++v) keep[static_cast<std::size_t>(v)] = rep[static_cast<std::size_t>(v)] == v;
  face_matrix Fm(F.rows(), 3);
  for (index_t f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) Fm(f, k) = rep[static_cast<std::size_t>(F(f, k))];
    // a face with two corners at one point has collapsed to a segment: it carries no surface
    if (Fm(f, 0) == Fm(f, 1) || Fm(f, 1) == Fm(f, 2) || Fm(f, 0) == Fm(f, 2))
      keep_face[static_cast<std::size_t>(f)] = 0;
  }
  auto out = detail::compact<Scalar>(V, Fm, keep, keep_face);
  for (index_t v = 0; v < n; ++v) out.old_to_new(v) = out.old_to_new(rep[static_cast<std::size_t>(v)]);
  return out;
}

/// Merges vertices at exactly the same position into the lowest-indexed one (e.g. the split seams of
/// OBJ/STL exports), removes the faces that collapse (two corners merged) and renumbers the vertices (order
/// of the kept ones preserved). Exact equality, not a tolerance: nearby but distinct vertices are different
/// points of a scan.
/// \throws invalid_input empty / non_finite / bad_face (validate_mesh)
/// \returns the mesh and old_to_new (#V_old; a merged vertex maps to its representative's new index)
/// Complexity: O(V log V + F).
template <SurfaceMesh Mesh>
[[nodiscard]] repaired_mesh<mesh_scalar_t<Mesh>> merge_duplicate_vertices(const Mesh& mesh) {
  using S = mesh_scalar_t<Mesh>;
  return detail::on_canonical<S>(
      mesh, [&](const auto& V, const auto& F) { return merge_duplicate_vertices_kernel<S>(V, F); });
}

// -------------------------------------------------------------------------------- split_non_manifold_vertices

/// Kernel of split_non_manifold_vertices(). \param V #V x 3, \param F #F x 3 (validated here).
template <class Scalar>
vertex_split_result<Scalar> split_non_manifold_vertices_kernel(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                               const Eigen::Ref<const face_matrix>& F) {
  validate_mesh(V, F, "split_non_manifold_vertices");
  const index_t n = V.rows(), m = F.rows();
  // Corners 3 f + k of one vertex are joined when their faces share an edge at that vertex; each resulting
  // class is one fan (the same construction check_mesh uses to count non-manifold vertices).
  struct side {
    index_t lo, hi, corner_lo, corner_hi;
  };
  std::vector<side> sides;
  sides.reserve(static_cast<std::size_t>(3 * m));
  for (index_t f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const int k2 = (k + 1) % 3;
      const index_t s = F(f, k), t = F(f, k2);
      if (s < t)
        sides.push_back({s, t, 3 * f + k, 3 * f + k2});
      else
        sides.push_back({t, s, 3 * f + k2, 3 * f + k});
    }
  std::sort(sides.begin(), sides.end(),
            [](const side& a, const side& b) { return a.lo != b.lo ? a.lo < b.lo : a.hi < b.hi; });
  detail::disjoint_sets corners(3 * m);
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i + 1;
    while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi) {
      corners.unite(sides[i].corner_lo, sides[j].corner_lo);
      corners.unite(sides[i].corner_hi, sides[j].corner_hi);
      ++j;
    }
    i = j;
  }
  // The fan met first (in face order) keeps the vertex; every other fan gets an appended copy.
  std::vector<index_t> first_fan(static_cast<std::size_t>(n), no_index);
  std::vector<index_t> copy_of_fan(static_cast<std::size_t>(3 * m), no_index);
  std::vector<index_t> copied_from;
  std::vector<char> was_split(static_cast<std::size_t>(n), 0);
  vertex_split_result<Scalar> out;
  out.mesh.F = F;
  for (index_t f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const index_t v = F(f, k), fan = corners.find(3 * f + k);
      index_t& first = first_fan[static_cast<std::size_t>(v)];
      if (first == no_index) first = fan;
      if (first == fan) continue;
      index_t& copy = copy_of_fan[static_cast<std::size_t>(fan)];
      if (copy == no_index) {
        copy = n + static_cast<index_t>(copied_from.size());
        copied_from.push_back(v);
        if (!was_split[static_cast<std::size_t>(v)]) {
          was_split[static_cast<std::size_t>(v)] = 1;
          ++out.split_vertices;
        }
      }
      out.mesh.F(f, k) = copy;
    }
  const index_t added = static_cast<index_t>(copied_from.size());
  out.mesh.V.resize(n + added, 3);
  out.mesh.V.topRows(n) = V;
  out.copied_from.resize(added);
  for (index_t i = 0; i < added; ++i) {
    out.copied_from(i) = copied_from[static_cast<std::size_t>(i)];
    out.mesh.V.row(n + i) = V.row(out.copied_from(i));
  }
  return out;
}

/// Gives every fan of a non-manifold ("bowtie") vertex its own vertex: the fan met first in face order keeps
/// the original index, each other fan is re-attached to an appended copy at the same position. Old vertex
/// indices (e.g. dense ground-truth correspondences) therefore stay valid. A sphere pinched at a vertex (every
/// SCAPE template mesh, at vertex 419) becomes a closed genus-0 manifold. Non-manifold edges are left as they
/// are. The copies coincide with their originals, so merge_duplicate_vertices() would undo this.
/// \param mesh any SurfaceMesh
/// \throws invalid_input empty / non_finite / bad_face (validate_mesh)
/// \returns the mesh, the source of each appended vertex and how many vertices were split
/// Complexity: O(F log F + V).
template <SurfaceMesh Mesh>
[[nodiscard]] vertex_split_result<mesh_scalar_t<Mesh>> split_non_manifold_vertices(const Mesh& mesh) {
  using S = mesh_scalar_t<Mesh>;
  return detail::on_canonical<S>(
      mesh, [&](const auto& V, const auto& F) { return split_non_manifold_vertices_kernel<S>(V, F); });
}

// ------------------------------------------------------------------------ remove_collapsed_and_duplicate_faces

/// Kernel of remove_collapsed_and_duplicate_faces(). \param V #V x 3, \param F #F x 3 (indices checked here;
/// repeated corners are what it removes, so it does not call validate_mesh's face check).
template <class Scalar>
face_removal_result<Scalar> remove_collapsed_and_duplicate_faces_kernel(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                                        const Eigen::Ref<const face_matrix>& F) {
  const index_t n = V.rows(), m = F.rows();
  for (index_t f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= n)
        throw invalid_input(input_error::bad_face, f,
                            "remove_collapsed_and_duplicate_faces: face " + std::to_string(f) + " refers to vertex " +
                                std::to_string(F(f, k)) + ", outside [0, " + std::to_string(n) + ")");
  face_removal_result<Scalar> out;
  std::vector<char> keep(static_cast<std::size_t>(m), 1);
  // Faces sorted by their sorted corner triple; within a run of equal triples the lowest face index stays.
  std::vector<std::array<index_t, 4>> key(static_cast<std::size_t>(m));
  for (index_t f = 0; f < m; ++f) {
    std::array<index_t, 3> c{F(f, 0), F(f, 1), F(f, 2)};
    std::sort(c.begin(), c.end());
    key[static_cast<std::size_t>(f)] = {c[0], c[1], c[2], f};
    if (c[0] == c[1] || c[1] == c[2]) {
      keep[static_cast<std::size_t>(f)] = 0;
      ++out.collapsed_faces;
      if (out.first_collapsed == no_index) out.first_collapsed = f;
    }
  }
  std::sort(key.begin(), key.end());
  for (std::size_t i = 1; i < key.size(); ++i) {
    const auto& a = key[i - 1];
    const auto& b = key[i];
    const index_t f = b[3];
    if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && keep[static_cast<std::size_t>(f)]) {
      keep[static_cast<std::size_t>(f)] = 0;
      ++out.duplicate_faces;
      out.first_duplicate = out.first_duplicate == no_index ? f : std::min(out.first_duplicate, f);
    }
  }
  out.mesh.V = V;
  out.mesh.F.resize(m - out.collapsed_faces - out.duplicate_faces, 3);
  index_t g = 0;
  for (index_t f = 0; f < m; ++f)
    if (keep[static_cast<std::size_t>(f)]) {
      out.mesh.F.row(g++) = F.row(f);
      out.kept_faces.push_back(f);
    }
  return out;
}

/// Removes the faces that carry no surface as a triangle: those with a repeated corner (collapsed to a
/// segment or a point) and repeats of an earlier face with the same three corners (in any order or
/// orientation; such a pair makes its edges non-manifold, each with 4 faces). The first copy of a repeated
/// face stays. Vertices are untouched (a vertex only the removed faces used becomes unreferenced).
/// Zero-area faces with three distinct corners are kept: removing one would open a hole in a closed surface.
/// \param mesh any SurfaceMesh; its face indices must be in range
/// \throws invalid_input bad_face (face index) when an index is out of range
/// \returns the mesh, which input face each kept face is, and how many of each kind were removed
/// Complexity: O(F log F).
template <SurfaceMesh Mesh>
[[nodiscard]] face_removal_result<mesh_scalar_t<Mesh>> remove_collapsed_and_duplicate_faces(const Mesh& mesh) {
  using S = mesh_scalar_t<Mesh>;
  return detail::on_canonical<S>(
      mesh, [&](const auto& V, const auto& F) { return remove_collapsed_and_duplicate_faces_kernel<S>(V, F); });
}

// ----------------------------------------------------------------------------------------- close_small_holes

/// Kernel of close_small_holes(). \param V #V x 3, \param F #F x 3 (validated here).
template <class Scalar>
hole_filling_result<Scalar> close_small_holes_kernel(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                     const Eigen::Ref<const face_matrix>& F,
                                                     index_t max_boundary_loop_length) {
  validate_mesh(V, F, "close_small_holes");
  if (max_boundary_loop_length < 3)
    throw invalid_input(input_error::bad_parameter, no_index,
                        "close_small_holes: max_boundary_loop_length must be at least 3 (a triangle), got " +
                            std::to_string(max_boundary_loop_length));
  const index_t n = V.rows();
  // Directed edges of all faces, sorted, to find the ones whose reverse and whose twin are absent.
  struct dir_edge {
    index_t lo, hi;
    index_t from, to;
  };
  std::vector<dir_edge> edges;
  edges.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (index_t f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const index_t s = F(f, k), t = F(f, (k + 1) % 3);
      edges.push_back({std::min(s, t), std::max(s, t), s, t});
    }
  std::sort(edges.begin(), edges.end(),
            [](const dir_edge& a, const dir_edge& b) { return a.lo != b.lo ? a.lo < b.lo : a.hi < b.hi; });
  // next[v] = the end of the boundary edge leaving v (in face orientation)
  std::vector<index_t> next(static_cast<std::size_t>(n), no_index);
  index_t boundary_edges = 0;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    if (j - i == 1) {
      const auto& e = edges[i];
      auto& slot = next[static_cast<std::size_t>(e.from)];
      if (slot != no_index)
        throw invalid_input(input_error::non_manifold, e.from,
                            "close_small_holes: boundary vertex " + std::to_string(e.from) +
                                " starts two boundary edges (two holes touch there), so its loops are ambiguous; "
                                "check_mesh() lists the non-manifold vertices");
      slot = e.to;
      ++boundary_edges;
    }
    i = j;
  }

  hole_filling_result<Scalar> out;
  std::vector<std::array<index_t, 3>> new_faces;
  std::vector<Eigen::Matrix<Scalar, 1, 3>> new_vertices;
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  std::vector<index_t> loop;
  for (index_t s = 0; s < n; ++s) {
    if (next[static_cast<std::size_t>(s)] == no_index || used[static_cast<std::size_t>(s)]) continue;
    loop.clear();
    index_t v = s;
    bool closed = true;
    while (!used[static_cast<std::size_t>(v)]) {
      used[static_cast<std::size_t>(v)] = 1;
      loop.push_back(v);
      v = next[static_cast<std::size_t>(v)];
      if (v == no_index) {  // cannot happen on a boundary of consistently oriented faces
        closed = false;
        break;
      }
    }
    if (!closed || v != s) {
      // A chain that does not return to its start: inconsistently oriented faces along the boundary.
      ++out.holes_left;
      out.longest_loop_left = std::max<index_t>(out.longest_loop_left, static_cast<index_t>(loop.size()));
      continue;
    }
    const index_t len = static_cast<index_t>(loop.size());
    if (len > max_boundary_loop_length) {
      ++out.holes_left;
      out.longest_loop_left = std::max(out.longest_loop_left, len);
      continue;
    }
    ++out.holes_filled;
    out.filled_loop_lengths.push_back(len);
    // The boundary runs v_i -> v_(i+1) in its face, so the filling faces run v_(i+1) -> v_i to agree with it.
    if (len == 3) {
      new_faces.push_back({loop[2], loop[1], loop[0]});
      continue;
    }
    // A fan around the loop's centroid: no self-overlap for star-shaped holes (the usual small scan hole),
    // and the new vertex keeps every fill triangle non-degenerate unless the loop itself is.
    Eigen::Matrix<Scalar, 1, 3> c = Eigen::Matrix<Scalar, 1, 3>::Zero();
    for (const index_t u : loop) c += V.row(u);
    c /= static_cast<Scalar>(len);
    const index_t ci = n + static_cast<index_t>(new_vertices.size());
    new_vertices.push_back(c);
    for (index_t i = 0; i < len; ++i)
      new_faces.push_back({loop[static_cast<std::size_t>((i + 1) % len)], loop[static_cast<std::size_t>(i)], ci});
  }

  out.added_vertices = static_cast<index_t>(new_vertices.size());
  out.added_faces = static_cast<index_t>(new_faces.size());
  out.mesh.V.resize(n + out.added_vertices, 3);
  out.mesh.V.topRows(n) = V;
  for (index_t i = 0; i < out.added_vertices; ++i) out.mesh.V.row(n + i) = new_vertices[static_cast<std::size_t>(i)];
  out.mesh.F.resize(F.rows() + out.added_faces, 3);
  out.mesh.F.topRows(F.rows()) = F;
  for (index_t i = 0; i < out.added_faces; ++i)
    for (int k = 0; k < 3; ++k)
      out.mesh.F(F.rows() + i, k) = new_faces[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
  return out;
}

/// Fills every boundary loop of at most max_boundary_loop_length edges: a loop of 3 edges with one triangle,
/// longer ones with a fan of triangles around a new vertex at the loop's centroid, oriented like the
/// surrounding faces. Existing vertices and faces keep their indices; new ones are appended. Loops are found
/// by following boundary edges in face orientation, so the boundary must be manifold.
/// \param mesh any SurfaceMesh
/// \param max_boundary_loop_length longest loop (in edges) to fill, >= 3
/// \throws invalid_input empty / non_finite / bad_face (validate_mesh); bad_parameter when
///         max_boundary_loop_length < 3; non_manifold (vertex) when a vertex starts two boundary edges
/// \returns the filled mesh and how many loops were filled or left open
/// Complexity: O(F log F + V).
template <SurfaceMesh Mesh>
[[nodiscard]] hole_filling_result<mesh_scalar_t<Mesh>> close_small_holes(const Mesh& mesh,
                                                                         index_t max_boundary_loop_length) {
  using S = mesh_scalar_t<Mesh>;
  return detail::on_canonical<S>(
      mesh, [&](const auto& V, const auto& F) { return close_small_holes_kernel<S>(V, F, max_boundary_loop_length); });
}

}  // namespace shapestruct
