// SPDX-License-Identifier: MIT
// cotan_laplacian: the positive semi-definite cotangent Laplacian of a triangle mesh, with clamped cotangents.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/detail/eigen_forward.hpp"
#include "shapestruct/geometry/detail/geometry_common.hpp"

namespace shapestruct {

/// Options of cotan_laplacian.
struct cotan_laplacian_options {
  /// Bound on |cot| of every triangle angle (must be > 0). The default 1e5 (an angle of 1e-5 rad) leaves every
  /// usable triangle untouched and keeps slivers and zero-area faces, common in scanned meshes such as SCAPE,
  /// from producing Inf/NaN or a Laplacian too ill-conditioned to factorise.
  double max_abs_cot = detail::max_abs_cot;
};

/// The cotangent Laplacian in the POSITIVE semi-definite convention:
///   L = sum over edges (i, j) of w_ij (e_i - e_j)(e_i - e_j)^T,  w_ij = (cot a_ij + cot b_ij) / 2,
/// a_ij, b_ij the angles opposite the edge in its (one or two) incident faces. So L_ij = -w_ij (i != j) and
/// L_ii = sum_j w_ij; x^T L x = sum w_ij (x_i - x_j)^2 is the Dirichlet energy (>= 0 when all w_ij >= 0, i.e. on
/// Delaunay meshes; obtuse angles can make some w_ij negative). L is exactly symmetric and every row sums to
/// zero exactly (the diagonal is computed as minus the sum of the row's stored off-diagonals), so constants are
/// in its null space. Cotangents are clamped to [-max_abs_cot, max_abs_cot]; no entry is ever NaN or Inf.
/// This is the stiffness matrix of linear finite elements: the weak (integrated) -Delta; pair it with
/// mass_matrix for the pointwise operator M^-1 L.
/// \param V (#V x 3) vertex positions  \param F (#F x 3) triangles
/// \returns (#V x #V) sparse symmetric matrix, column-major, compressed.
/// \throws invalid_input (empty, non_finite, bad_face) from validate_mesh; bad_parameter if max_abs_cot <= 0.
/// Complexity O(V + F log F) (triplet assembly).
template <class Scalar>
[[nodiscard]] Eigen::SparseMatrix<Scalar> cotan_laplacian(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                          const Eigen::Ref<const face_matrix>& F,
                                                          const cotan_laplacian_options& options = {},
                                                          validation_level level = validation_level::full) {
  validate_mesh(V, F, "cotan_laplacian", level);
  if (!(options.max_abs_cot > 0))
    throw invalid_input(input_error::bad_parameter, no_index,
                        "cotan_laplacian: options.max_abs_cot must be > 0, got " + std::to_string(options.max_abs_cot));
  const index_t n = V.rows();
  std::vector<Eigen::Triplet<Scalar, index_t>> trip;
  trip.reserve(static_cast<std::size_t>(6 * F.rows()));
  vec3<Scalar> p[3];
  for (index_t f = 0; f < F.rows(); ++f) {
    detail::geometry_corners(V, F, f, p[0], p[1], p[2]);
    for (int k = 0; k < 3; ++k) {
      // corner k is opposite the edge (i, j)
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const Scalar w = Scalar(0.5) * detail::clamped_cot<Scalar>(p[i] - p[k], p[j] - p[k], options.max_abs_cot);
      trip.emplace_back(F(f, i), F(f, j), -w);
      trip.emplace_back(F(f, j), F(f, i), -w);
    }
  }
  Eigen::SparseMatrix<Scalar> L(n, n);
  L.setFromTriplets(trip.begin(), trip.end());  // sums the two faces' halves of each edge weight
  // Diagonal = -(row sum of off-diagonals), computed from the stored values so that L * 1 = 0 holds to
  // the last bit of each row's own summation, and symmetry is untouched.
  vector_x<Scalar> diag = vector_x<Scalar>::Zero(n);
  for (index_t c = 0; c < L.outerSize(); ++c)
    for (typename Eigen::SparseMatrix<Scalar>::InnerIterator it(L, c); it; ++it) diag[it.row()] -= it.value();
  std::vector<Eigen::Triplet<Scalar, index_t>> dtrip;
  dtrip.reserve(static_cast<std::size_t>(n));
  for (index_t i = 0; i < n; ++i) dtrip.emplace_back(i, i, diag[i]);
  Eigen::SparseMatrix<Scalar> D(n, n);
  D.setFromTriplets(dtrip.begin(), dtrip.end());
  L += D;
  L.makeCompressed();
  return L;
}

/// Convenience overload for any dense Eigen arguments (V: #V x 3 of float or double; F: #F x 3 of any integer
/// type): forwards to the Eigen::Ref kernel above with Scalar = V's scalar and F cast to index_t. Same
/// results, exceptions and complexity as the kernel.
template <detail::geometry_dense_real DV, detail::geometry_dense DF>
[[nodiscard]] auto cotan_laplacian(const Eigen::MatrixBase<DV>& V, const Eigen::MatrixBase<DF>& F,
                                   const cotan_laplacian_options& options = {}) {
  return cotan_laplacian<typename DV::Scalar>(V.derived(), F.derived().template cast<index_t>(), options);
}

/// Cotangent Laplacian of any SurfaceMesh (gathered into canonical form; Scalar = the mesh's scalar type).
template <SurfaceMesh Mesh>
[[nodiscard]] Eigen::SparseMatrix<mesh_scalar_t<Mesh>> cotan_laplacian(const Mesh& mesh,
                                                                       const cotan_laplacian_options& options = {}) {
  const auto m = to_triangle_mesh<mesh_scalar_t<Mesh>>(mesh);
  return cotan_laplacian<mesh_scalar_t<Mesh>>(m.V, m.F, options);
}

}  // namespace shapestruct
