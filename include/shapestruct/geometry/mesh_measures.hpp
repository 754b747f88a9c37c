// SPDX-License-Identifier: MIT
// mesh_measures: face and vertex areas, face and vertex normals, total area, bounding-box diagonal, mean edge length.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/detail/eigen_forward.hpp"
#include "shapestruct/geometry/detail/geometry_common.hpp"

namespace shapestruct {

/// Area of every triangle, |(b - a) x (c - a)| / 2. Degenerate faces get area 0.
/// \param V (#V x 3) vertex positions  \param F (#F x 3) triangles
/// \returns (#F) areas, all >= 0 and finite.
/// \throws invalid_input (empty, non_finite, bad_face) from validate_mesh.
/// Complexity O(F).
template <class Scalar>
[[nodiscard]] vector_x<Scalar> face_areas(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                          const Eigen::Ref<const face_matrix>& F,
                                          validation_level level = validation_level::full) {
  validate_mesh(V, F, "face_areas", level);
  vector_x<Scalar> A(F.rows());
  vec3<Scalar> a, b, c;
  for (index_t f = 0; f < F.rows(); ++f) {
    detail::geometry_corners(V, F, f, a, b, c);
    A[f] = Scalar(0.5) * (b - a).cross(c - a).norm();
  }
  return A;
}

/// Barycentric vertex areas: each vertex gets one third of the area of every incident face, so the entries
/// sum to the total area. Unreferenced vertices get 0.
/// \returns (#V) areas. \throws invalid_input as face_areas. Complexity O(V + F).
template <class Scalar>
[[nodiscard]] vector_x<Scalar> vertex_areas(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                            const Eigen::Ref<const face_matrix>& F,
                                            validation_level level = validation_level::full) {
  const vector_x<Scalar> A = face_areas<Scalar>(V, F, level);
  vector_x<Scalar> out = vector_x<Scalar>::Zero(V.rows());
  for (index_t f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out[F(f, k)] += A[f] / Scalar(3);
  return out;
}

/// Unit normal of every triangle, oriented by the corner order (counter-clockwise seen from outside).
/// Degenerate faces (zero cross product) get the zero vector rather than NaN.
/// \returns (#F x 3) normals. \throws invalid_input as face_areas. Complexity O(F).
template <class Scalar>
[[nodiscard]] matrix_x3<Scalar> face_normals(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                             const Eigen::Ref<const face_matrix>& F,
                                             validation_level level = validation_level::full) {
  validate_mesh(V, F, "face_normals", level);
  matrix_x3<Scalar> N(F.rows(), 3);
  vec3<Scalar> a, b, c;
  for (index_t f = 0; f < F.rows(); ++f) {
    detail::geometry_corners(V, F, f, a, b, c);
    const vec3<Scalar> n = (b - a).cross(c - a);
    const Scalar len = n.norm();
    if (len > Scalar(0)) N.row(f) = (n / len).transpose();
    else N.row(f).setZero();
  }
  return N;
}

/// Area-weighted vertex normals: the normalised sum of the incident faces' unit normals times their areas
/// (i.e. of the raw cross products). Vertices whose weighted sum vanishes (unreferenced, or only degenerate
/// or cancelling faces) get the zero vector.
/// \returns (#V x 3) normals. \throws invalid_input as face_areas. Complexity O(V + F).
template <class Scalar>
[[nodiscard]] matrix_x3<Scalar> vertex_normals(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                               const Eigen::Ref<const face_matrix>& F,
                                               validation_level level = validation_level::full) {
  validate_mesh(V, F, "vertex_normals", level);
  matrix_x3<Scalar> N = matrix_x3<Scalar>::Zero(V.rows(), 3);
  vec3<Scalar> a, b, c;
  for (index_t f = 0; f < F.rows(); ++f) {
    detail::geometry_corners(V, F, f, a, b, c);
    const vec3<Scalar> n = (b - a).cross(c - a);  // |n| = 2 * area: area weighting for free
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n.transpose();
  }
  for (index_t i = 0; i < N.rows(); ++i) {
    const Scalar len = N.row(i).norm();
    if (len > Scalar(0)) N.row(i) /= len;
  }
  return N;
}

/// Total surface area (sum of face areas). \throws invalid_input as face_areas. Complexity O(F).
template <class Scalar>
[[nodiscard]] Scalar total_area(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                                validation_level level = validation_level::full) {
  return face_areas<Scalar>(V, F, level).sum();
}

/// Length of the diagonal of the axis-aligned bounding box of the points (0 for a single point).
/// \param V (#V x 3) points. \throws invalid_input (empty, non_finite). Complexity O(V).
template <class Scalar>
[[nodiscard]] Scalar bounding_box_diagonal(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                           validation_level level = validation_level::full) {
  validate_points(V, "bounding_box_diagonal", level);
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

/// Mean length of the mesh's undirected edges, each edge counted once per incident face (interior edges of a
/// closed mesh twice, uniformly, so the mean is the same as over unique edges there). Used as the spacing h.
/// \returns the mean (0 if every edge has length 0). \throws invalid_input as face_areas. Complexity O(F).
template <class Scalar>
[[nodiscard]] Scalar mean_edge_length(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                      const Eigen::Ref<const face_matrix>& F,
                                      validation_level level = validation_level::full) {
  validate_mesh(V, F, "mean_edge_length", level);
  double sum = 0;  // double accumulator: 1e5+ terms in float would drift
  for (index_t f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) sum += double((V.row(F(f, k)) - V.row(F(f, (k + 1) % 3))).norm());
  return static_cast<Scalar>(sum / double(3 * F.rows()));
}

// ---- Convenience overloads: any dense Eigen (V, F), and any SurfaceMesh. ----

/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto face_areas(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F) {
  return face_areas<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>());
}
/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto vertex_areas(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F) {
  return vertex_areas<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>());
}
/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto face_normals(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F) {
  return face_normals<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>());
}
/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto vertex_normals(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F) {
  return vertex_normals<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>());
}
/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto total_area(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F) {
  return total_area<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>());
}
/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV>
[[nodiscard]] auto bounding_box_diagonal(const Eigen::MatrixBase<DV>& V) {
  return bounding_box_diagonal<typename DV::Scalar>(V.derived());
}
/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto mean_edge_length(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F) {
  return mean_edge_length<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>());
}

/// Face areas of any SurfaceMesh (gathered into canonical form first). Scalar = the mesh's scalar type.
template <SurfaceMesh Mesh>
[[nodiscard]] vector_x<mesh_scalar_t<Mesh>> face_areas(const Mesh& mesh) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return face_areas<mesh_scalar_t<Mesh>>(m.V, m.F);
}
/// Barycentric vertex areas of any SurfaceMesh.
template <SurfaceMesh Mesh>
[[nodiscard]] vector_x<mesh_scalar_t<Mesh>> vertex_areas(const Mesh& mesh) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return vertex_areas<mesh_scalar_t<Mesh>>(m.V, m.F);
}
/// Unit face normals of any SurfaceMesh.
template <SurfaceMesh Mesh>
[[nodiscard]] matrix_x3<mesh_scalar_t<Mesh>> face_normals(const Mesh& mesh) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return face_normals<mesh_scalar_t<Mesh>>(m.V, m.F);
}
/// Area-weighted vertex normals of any SurfaceMesh.
template <SurfaceMesh Mesh>
[[nodiscard]] matrix_x3<mesh_scalar_t<Mesh>> vertex_normals(const Mesh& mesh) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return vertex_normals<mesh_scalar_t<Mesh>>(m.V, m.F);
}
/// Total area of any SurfaceMesh.
template <SurfaceMesh Mesh>
[[nodiscard]] mesh_scalar_t<Mesh> total_area(const Mesh& mesh) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return total_area<mesh_scalar_t<Mesh>>(m.V, m.F);
}
/// Bounding-box diagonal of any SurfaceMesh's vertices.
template <SurfaceMesh Mesh>
[[nodiscard]] mesh_scalar_t<Mesh> bounding_box_diagonal(const Mesh& mesh) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return bounding_box_diagonal<mesh_scalar_t<Mesh>>(m.V);
}
/// Mean edge length of any SurfaceMesh.
template <SurfaceMesh Mesh>
[[nodiscard]] mesh_scalar_t<Mesh> mean_edge_length(const Mesh& mesh) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return mean_edge_length<mesh_scalar_t<Mesh>>(m.V, m.F);
}

}  // namespace shapestruct
