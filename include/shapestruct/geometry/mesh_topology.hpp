// SPDX-License-Identifier: MIT
// require_closed_genus0_manifold: the topological precondition of mid-edge uniformization and blended maps.
#pragma once

#include <Eigen/Core>
#include <string>
#include <type_traits>

#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"

namespace shapestruct {

namespace detail {

template <class DerivedV, class DerivedF>
mesh_report check_for_requirement(const Eigen::MatrixBase<DerivedV>& V, const Eigen::MatrixBase<DerivedF>& F) {
  using S = typename DerivedV::Scalar;
  if constexpr (std::is_same_v<typename DerivedF::Scalar, index_t>) {
    return check_mesh_kernel<S>(V.derived(), F.derived());
  } else {
    const face_matrix Fc = F.template cast<index_t>();
    return check_mesh_kernel<S>(V.derived(), Fc);
  }
}

inline std::string edge_name(const std::array<index_t, 2>& e) {
  // Built by appending: g++ 12 reports a false -Wrestrict on the equivalent "(" + std::to_string(...) chain.
  std::string s(1, '(');
  s += std::to_string(e[0]);
  s += ", ";
  s += std::to_string(e[1]);
  s += ')';
  return s;
}

}  // namespace detail

/// Checks that (V, F) is a closed, orientable, connected 2-manifold of genus 0 (a topological sphere) with no
/// stray vertices: the precondition of mid-edge uniformization (dissertation ch. 3), hence of blended
/// intrinsic maps. Runs validate_mesh() first.
/// \param V #V x 3 positions (floating point), \param F #F x 3 vertex indices (any integer type)
/// \param who the calling function, named at the start of every message
/// \throws mesh_defect_error (an invalid_input that also says which defect, and splits the message into the
///         problem and the remedy), checked in this order:
///   - empty / non_finite / bad_face from validate_mesh();
///   - non_manifold: element = the first vertex of a non-manifold edge (the message names the edge), else the
///     non-manifold (bowtie) vertex;
///   - unsupported_topology: element = the first vertex of a boundary edge (the mesh has holes); the smallest
///     vertex of the second component (several pieces or unreferenced vertices); no_index for a non-orientable
///     surface or genus > 0 (the message gives the genus).
///   Each message names the precondition and the repair (geometry/mesh_repair.hpp) that would make the mesh
///   acceptable, where one exists.
/// \returns the mesh_report of the accepted mesh (callers may reuse its counts).
/// Complexity: O(V log V + F log F).
template <class DerivedV, class DerivedF>
mesh_report require_closed_genus0_manifold(const Eigen::MatrixBase<DerivedV>& V, const Eigen::MatrixBase<DerivedF>& F,
                                           const char* who) {
  static_assert(std::is_floating_point_v<typename DerivedV::Scalar>, "V must have a floating-point scalar");
  validate_mesh(V, F, who);
  const mesh_report r = detail::check_for_requirement(V, F);
  const std::string pre = "needs a closed, connected, orientable manifold of genus 0 (a topological sphere), but ";
  const auto fail = [&](input_error reason, mesh_defect defect, index_t element, const std::string& problem,
                        const std::string& remedy) {
    throw mesh_defect_error(reason, defect, element, who, pre + problem, remedy);
  };
  if (r.num_non_manifold_edges > 0) {
    const auto& e = r.non_manifold_edge_examples.front();
    fail(input_error::non_manifold, mesh_defect::non_manifold_edge, e[0],
         "edge " + detail::edge_name(e) + " is shared by more than two faces (" +
             std::to_string(r.num_non_manifold_edges) + " such edges)",
         "remove_collapsed_and_duplicate_faces() removes repeated faces; otherwise no automatic repair exists: cut "
         "the extra faces off, or if they form a separate piece run keep_largest_component()");
  }
  if (r.num_non_manifold_vertices > 0) {
    const index_t v = r.non_manifold_vertex_examples.front();
    fail(input_error::non_manifold, mesh_defect::non_manifold_vertex, v,
         "vertex " + std::to_string(v) + " joins several fans of faces that share no edge there (a bowtie; " +
             std::to_string(r.num_non_manifold_vertices) + " such vertices)",
         "split_non_manifold_vertices() gives each fan its own vertex (appended, existing indices unchanged)");
  }
  if (r.num_boundary_edges > 0) {
    const auto& e = r.boundary_edge_examples.front();
    fail(input_error::unsupported_topology, mesh_defect::hole, e[0],
         "it has a boundary: " + std::to_string(r.num_boundary_edges) + " boundary edges in " +
             std::to_string(r.num_boundary_loops) + (r.num_boundary_loops == 1 ? " loop" : " loops") +
             " (holes), e.g. edge " + detail::edge_name(e),
         "merge_duplicate_vertices() closes seams of split vertices and close_small_holes() fills holes (set "
         "max_boundary_loop_length to at least the longest loop)");
  }
  if (r.num_components > 1) {
    // The first component starts at vertex 0; name the first vertex outside it.
    const index_t second = r.components.size() > 1                  ? r.components[1].first_vertex
                           : r.unreferenced_vertex_examples.empty() ? no_index
                                                                    : r.unreferenced_vertex_examples.front();
    const bool only_stray = r.components.size() == 1;
    fail(input_error::unsupported_topology, mesh_defect::several_pieces, second,
         "it has " + std::to_string(r.num_components) + " connected components (" +
             std::to_string(r.components.size()) + " with faces, " + std::to_string(r.num_unreferenced_vertices) +
             " vertices on no face), e.g. vertex " + std::to_string(second) + " is not connected to vertex 0",
         only_stray ? "remove_unreferenced_vertices() drops the stray vertices"
                    : "keep_largest_component() keeps the piece of largest area");
  }
  if (!r.orientable)
    fail(input_error::unsupported_topology, mesh_defect::non_orientable, no_index,
         "the surface is not orientable (no consistent choice of face orientations exists)",
         "no repair can make it a sphere");
  if (r.genus != 0)
    fail(input_error::unsupported_topology, mesh_defect::genus, no_index,
         "it has genus " + std::to_string(r.genus) + " (Euler characteristic " +
             std::to_string(r.euler_characteristic) + ")",
         "no repair removes handles: use a genus-0 version of the shape");
  return r;
}

/// require_closed_genus0_manifold for any SurfaceMesh (gathered into triangle_mesh form).
/// \throws invalid_input as the matrix overload. Complexity: O(V log V + F log F).
template <SurfaceMesh Mesh>
mesh_report require_closed_genus0_manifold(const Mesh& mesh, const char* who) {
  using S = mesh_scalar_t<Mesh>;
  if constexpr (std::is_same_v<std::remove_cvref_t<Mesh>, triangle_mesh<S>>) {
    return require_closed_genus0_manifold(mesh.V, mesh.F, who);
  } else {
    const triangle_mesh<S> m = to_triangle_mesh<S>(mesh);
    return require_closed_genus0_manifold(m.V, m.F, who);
  }
}

}  // namespace shapestruct
