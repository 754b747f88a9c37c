// SPDX-License-Identifier: MIT
// mass_matrix: the lumped (diagonal) mass matrix of a triangle mesh, barycentric or mixed-Voronoi.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/detail/eigen_forward.hpp"
#include "shapestruct/geometry/detail/geometry_common.hpp"

namespace shapestruct {

/// How a face's area is split among its corners.
enum class mass_type {
  barycentric,  ///< one third to each corner
  voronoi,      ///< mixed Voronoi cells (Meyer et al. 2003): the circumcentric cell for non-obtuse faces; for
                ///< obtuse faces half the area to the obtuse corner and a quarter to each other corner
};

/// Diagonal lumped mass matrix: M_ii = area of vertex i's cell. Both types partition each face's area, so
/// the diagonal sums to the total area. Degenerate faces (zero area) give nothing; unreferenced vertices get
/// M_ii = 0 (M is then singular: regularise before inverting).
/// \param V (#V x 3) vertex positions  \param F (#F x 3) triangles  \param type barycentric or voronoi
/// \returns (#V x #V) diagonal sparse matrix with entries >= 0.
/// \throws invalid_input (empty, non_finite, bad_face) from validate_mesh. Complexity O(V + F).
template <class Scalar>
[[nodiscard]] Eigen::SparseMatrix<Scalar> mass_matrix(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                      const Eigen::Ref<const face_matrix>& F,
                                                      mass_type type = mass_type::barycentric,
                                                      validation_level level = validation_level::full) {
  validate_mesh(V, F, "mass_matrix", level);
  const index_t n = V.rows();
  vector_x<Scalar> m = vector_x<Scalar>::Zero(n);
  vec3<Scalar> p[3];
  for (index_t f = 0; f < F.rows(); ++f) {
    detail::geometry_corners(V, F, f, p[0], p[1], p[2]);
    const Scalar area = Scalar(0.5) * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    if (!(area > Scalar(0))) continue;
    if (type == mass_type::barycentric) {
      for (int k = 0; k < 3; ++k) m[F(f, k)] += area / Scalar(3);
      continue;
    }
    int obtuse = -1;
    for (int k = 0; k < 3; ++k)
      if ((p[(k + 1) % 3] - p[k]).dot(p[(k + 2) % 3] - p[k]) < Scalar(0)) obtuse = k;
    if (obtuse >= 0) {
      for (int k = 0; k < 3; ++k) m[F(f, k)] += k == obtuse ? area / Scalar(2) : area / Scalar(4);
      continue;
    }
    // Non-obtuse: corner k's circumcentric cell is (|e_ki|^2 cot(angle j) + |e_kj|^2 cot(angle i)) / 8.
    // With no obtuse angle every cot is in [0, inf); a right or near-degenerate angle is bounded by the clamp,
    // and the parts are renormalised to sum to the face area so rounding cannot create or lose area.
    Scalar cot[3], part[3], sum = 0;
    for (int k = 0; k < 3; ++k)
      cot[k] = detail::clamped_cot<Scalar>(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      part[k] = ((p[i] - p[k]).squaredNorm() * cot[j] + (p[j] - p[k]).squaredNorm() * cot[i]) / Scalar(8);
      sum += part[k];
    }
    for (int k = 0; k < 3; ++k) m[F(f, k)] += sum > Scalar(0) ? part[k] * (area / sum) : area / Scalar(3);
  }
  std::vector<Eigen::Triplet<Scalar, index_t>> trip;
  trip.reserve(static_cast<std::size_t>(n));
  for (index_t i = 0; i < n; ++i) trip.emplace_back(i, i, m[i]);
  Eigen::SparseMatrix<Scalar> M(n, n);
  M.setFromTriplets(trip.begin(), trip.end());
  return M;
}

/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto mass_matrix(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F,
                               mass_type type = mass_type::barycentric) {
  return mass_matrix<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>(), type);
}

/// Mass matrix of any SurfaceMesh (gathered into canonical form; Scalar = the mesh's scalar type).
template <SurfaceMesh Mesh>
[[nodiscard]] Eigen::SparseMatrix<mesh_scalar_t<Mesh>> mass_matrix(const Mesh& mesh,
                                                                   mass_type type = mass_type::barycentric) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return mass_matrix<mesh_scalar_t<Mesh>>(m.V, m.F, type);
}

}  // namespace shapestruct
