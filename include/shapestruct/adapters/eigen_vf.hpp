// SPDX-License-Identifier: MIT
// eigen_mesh_view: a zero-copy SurfaceMesh view over libigl-style (V, F) Eigen matrices.
#pragma once

#include <array>

#include <Eigen/Core>

#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"

namespace shapestruct {

/// Views `V (#V x 3)` and `F (#F x 3)` of any Eigen scalar/index types (e.g. libigl's MatrixXd / MatrixXi)
/// as a SurfaceMesh, without copying. The view must not outlive the matrices.
template <class MatrixV, class MatrixF>
class eigen_mesh_view {
 public:
  using scalar_type = typename MatrixV::Scalar;
  eigen_mesh_view(const MatrixV& V, const MatrixF& F) : V_(&V), F_(&F) {}
  [[nodiscard]] const MatrixV& V() const noexcept { return *V_; }
  [[nodiscard]] const MatrixF& F() const noexcept { return *F_; }

 private:
  const MatrixV* V_;
  const MatrixF* F_;
};

template <class MatrixV, class MatrixF>
struct surface_traits<eigen_mesh_view<MatrixV, MatrixF>> {
  using mesh = eigen_mesh_view<MatrixV, MatrixF>;
  using scalar_type = typename MatrixV::Scalar;
  static index_t num_vertices(const mesh& m) { return m.V().rows(); }
  static index_t num_faces(const mesh& m) { return m.F().rows(); }
  static std::array<scalar_type, 3> position(const mesh& m, index_t i) {
    return {m.V()(i, 0), m.V()(i, 1), m.V()(i, 2)};
  }
  static std::array<index_t, 3> face(const mesh& m, index_t f) {
    return {static_cast<index_t>(m.F()(f, 0)), static_cast<index_t>(m.F()(f, 1)),
            static_cast<index_t>(m.F()(f, 2))};
  }
  static const MatrixV& vertex_matrix(const mesh& m) { return m.V(); }
  static const MatrixF& face_matrix(const mesh& m) { return m.F(); }
};

/// The vertices of the view are a point set.
template <class MatrixV, class MatrixF>
struct point_set_traits<eigen_mesh_view<MatrixV, MatrixF>> {
  using scalar_type = typename MatrixV::Scalar;
  static constexpr int dimension = 3;
  static index_t num_points(const eigen_mesh_view<MatrixV, MatrixF>& m) { return m.V().rows(); }
  static scalar_type coord(const eigen_mesh_view<MatrixV, MatrixF>& m, index_t i, int d) { return m.V()(i, d); }
};

}  // namespace shapestruct
