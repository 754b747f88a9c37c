// SPDX-License-Identifier: MIT
// triangle_mesh: shapestruct's built-in mesh type and the canonical (V, F) form every algorithm works on.
#pragma once

#include <array>

#include <Eigen/Core>

#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// A triangle mesh stored as plain Eigen arrays, libigl-style.
///   V  (#V x 3) vertex positions
///   F  (#F x 3) vertex indices of each triangle, counter-clockwise seen from outside
/// Public entry points gather any SurfaceMesh into this form (to_triangle_mesh) and then call kernels that
/// take Eigen::Ref of V and F, so a user with five mesh types instantiates five thin gathers, not five solvers.
template <class Scalar = double>
struct triangle_mesh {
  static_assert(std::is_floating_point_v<Scalar>, "shapestruct: triangle_mesh needs a floating-point scalar");
  using scalar_type = Scalar;

  matrix_x3<Scalar> V;
  face_matrix F;

  [[nodiscard]] index_t num_vertices() const noexcept { return V.rows(); }
  [[nodiscard]] index_t num_faces() const noexcept { return F.rows(); }
};

template <class Scalar>
struct surface_traits<triangle_mesh<Scalar>> {
  using scalar_type = Scalar;
  static index_t num_vertices(const triangle_mesh<Scalar>& m) { return m.V.rows(); }
  static index_t num_faces(const triangle_mesh<Scalar>& m) { return m.F.rows(); }
  static auto position(const triangle_mesh<Scalar>& m, index_t i) { return vec3<Scalar>(m.V.row(i)); }
  static std::array<index_t, 3> face(const triangle_mesh<Scalar>& m, index_t f) {
    return {m.F(f, 0), m.F(f, 1), m.F(f, 2)};
  }
  static const matrix_x3<Scalar>& vertex_matrix(const triangle_mesh<Scalar>& m) { return m.V; }
  static const ::shapestruct::face_matrix& face_matrix(const triangle_mesh<Scalar>& m) { return m.F; }
};

/// The vertices of a triangle_mesh are a point set.
template <class Scalar>
struct point_set_traits<triangle_mesh<Scalar>> {
  using scalar_type = Scalar;
  static constexpr int dimension = 3;
  static index_t num_points(const triangle_mesh<Scalar>& m) { return m.V.rows(); }
  static Scalar coord(const triangle_mesh<Scalar>& m, index_t i, int d) { return m.V(i, d); }
};

/// Gathers any SurfaceMesh into a triangle_mesh<Scalar> (O(V + F)). Indices are copied as given: validate
/// the result (core/validate.hpp) before trusting them.
template <class Scalar = double, SurfaceMesh Mesh>
[[nodiscard]] triangle_mesh<Scalar> to_triangle_mesh(const Mesh& mesh) {
  using traits = surface_traits_t<Mesh>;
  triangle_mesh<Scalar> out;
  const index_t nv = static_cast<index_t>(traits::num_vertices(mesh));
  const index_t nf = static_cast<index_t>(traits::num_faces(mesh));
  out.V.resize(nv, 3);
  out.F.resize(nf, 3);
  for (index_t i = 0; i < nv; ++i) {
    const auto p = traits::position(mesh, i);
    out.V(i, 0) = static_cast<Scalar>(p[0]);
    out.V(i, 1) = static_cast<Scalar>(p[1]);
    out.V(i, 2) = static_cast<Scalar>(p[2]);
  }
  for (index_t f = 0; f < nf; ++f) {
    const std::array<index_t, 3> t = traits::face(mesh, f);
    out.F(f, 0) = t[0];
    out.F(f, 1) = t[1];
    out.F(f, 2) = t[2];
  }
  return out;
}

/// Overload for meshes with contiguous Eigen storage: one bulk copy and cast instead of per-element calls.
template <class Scalar = double, ContiguousSurfaceMesh Mesh>
[[nodiscard]] triangle_mesh<Scalar> to_triangle_mesh(const Mesh& mesh) {
  using traits = surface_traits_t<Mesh>;
  triangle_mesh<Scalar> out;
  out.V = traits::vertex_matrix(mesh).template cast<Scalar>();
  out.F = traits::face_matrix(mesh).template cast<index_t>();
  return out;
}

}  // namespace shapestruct
