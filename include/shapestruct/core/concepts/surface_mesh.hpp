// SPDX-License-Identifier: MIT
// SurfaceMesh: any triangle mesh shapestruct can read, through surface_traits.
#pragma once

#include <array>
#include <concepts>
#include <type_traits>

#include "shapestruct/core/traits.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Something indexable as v[0], v[1], v[2] with values convertible to S (Eigen vectors, std::array, float[3]).
template <class V, class S>
concept Vec3Like = requires(const V& v) {
  { v[0] } -> std::convertible_to<S>;
  { v[1] } -> std::convertible_to<S>;
  { v[2] } -> std::convertible_to<S>;
};

/// A triangle mesh (polygon meshes must be triangulated by the adapter).
///
/// Required expressions, with T = surface_traits<std::remove_cvref_t<M>>:
///   T::scalar_type                 a floating-point type (float or double)
///   T::num_vertices(m)             -> index_t
///   T::num_faces(m)                -> index_t
///   T::position(m, i)              -> Vec3Like<scalar_type>, vertex i, i in [0, num_vertices)
///   T::face(m, f)                  -> std::array<index_t, 3>, face f, f in [0, num_faces)
/// Semantic requirements: position and face are O(1); face returns indices in [0, num_vertices) for valid
/// meshes (algorithms validate this on entry and throw invalid_input otherwise); views must not outlive their
/// source.
/// Models: triangle_mesh (core/triangle_mesh.hpp), eigen_mesh_view (adapters/eigen_vf.hpp),
/// std_array_mesh_view (adapters/std_arrays.hpp), OpenMesh TriMesh (adapters/openmesh.hpp), CGAL Surface_mesh
/// (adapters/cgal_surface_mesh.hpp).
///
/// How to adapt your own type (compiled in examples/plug_in_your_mesh.cpp):
/// \code
///   struct legacy_mesh { std::vector<vtx> verts; std::vector<tri> tris; };
///   template <> struct shapestruct::surface_traits<legacy_mesh> {
///     using scalar_type = float;
///     static index_t num_vertices(const legacy_mesh& m) { return index_t(m.verts.size()); }
///     static index_t num_faces(const legacy_mesh& m) { return index_t(m.tris.size()); }
///     static std::array<float, 3> position(const legacy_mesh& m, index_t i) {
///       return {m.verts[i].x, m.verts[i].y, m.verts[i].z}; }
///     static std::array<index_t, 3> face(const legacy_mesh& m, index_t f) {
///       return {m.tris[f].a, m.tris[f].b, m.tris[f].c}; }
///   };
/// \endcode
template <class M>
concept SurfaceMesh =
    detail::is_complete<surface_traits_t<M>>::value &&
    std::floating_point<typename surface_traits_t<M>::scalar_type> &&
    requires(const std::remove_cvref_t<M>& m, index_t i) {
      { surface_traits_t<M>::num_vertices(m) } -> std::convertible_to<index_t>;
      { surface_traits_t<M>::num_faces(m) } -> std::convertible_to<index_t>;
      { surface_traits_t<M>::position(m, i) } -> Vec3Like<typename surface_traits_t<M>::scalar_type>;
      { surface_traits_t<M>::face(m, i) } -> std::convertible_to<std::array<index_t, 3>>;
    };

/// Refinement: the adapter hands out contiguous `#V x 3` / `#F x 3` Eigen storage, so gathering is free.
/// Spelled "SurfaceMesh<M> && ..." so that it subsumes SurfaceMesh and overloads constrained on it win.
template <class M>
concept ContiguousSurfaceMesh = SurfaceMesh<M> && requires(const std::remove_cvref_t<M>& m) {
  { surface_traits_t<M>::vertex_matrix(m) };
  { surface_traits_t<M>::face_matrix(m) };
};

}  // namespace shapestruct
