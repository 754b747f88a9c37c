// SPDX-License-Identifier: MIT
// The customization points of shapestruct: traits a user specializes to plug in their own types.
//
// Inventory of every customization point (there are no others: no member-function or ADL hooks):
//   surface_traits<Mesh>     makes Mesh a SurfaceMesh      (core/concepts/surface_mesh.hpp)
//                            required: scalar_type, num_vertices, num_faces, position, face
//                            optional: vertex_matrix, face_matrix (ContiguousSurfaceMesh, zero-copy gather)
//   point_set_traits<Points> makes Points a PointSet       (core/concepts/point_set.hpp)
//                            required: scalar_type, dimension, num_points, coord
// Policies (matchers, scores, solvers, energy terms) are plain value types checked by their concepts.
#pragma once

#include <type_traits>

namespace shapestruct {

/// Specialize for your mesh type; see adapters/ for ready-made models. Deliberately left undefined, so
/// that "not adapted" (incomplete type) and "adapted wrongly" (a missing member) give different errors.
template <class Mesh>
struct surface_traits;

/// Specialize for your point container; see adapters/ for ready-made models. Undefined for the same reason.
template <class Points>
struct point_set_traits;

template <class Mesh>
using surface_traits_t = surface_traits<std::remove_cvref_t<Mesh>>;

template <class Points>
using point_set_traits_t = point_set_traits<std::remove_cvref_t<Points>>;

template <class Mesh>
using mesh_scalar_t = typename surface_traits_t<Mesh>::scalar_type;

template <class Points>
using point_scalar_t = typename point_set_traits_t<Points>::scalar_type;

namespace detail {
template <class T, class = void>
struct is_complete : std::false_type {};
template <class T>
struct is_complete<T, std::void_t<decltype(sizeof(T))>> : std::true_type {};
}  // namespace detail

}  // namespace shapestruct
