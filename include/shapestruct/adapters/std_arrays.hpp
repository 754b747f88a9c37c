// SPDX-License-Identifier: MIT
// std_array_mesh_view and std::vector<std::array> point sets: models for plain standard-library soups.
#pragma once

#include <array>
#include <vector>

#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"

namespace shapestruct {

/// Views a soup `std::vector<std::array<S, 3>>` of positions and `std::vector<std::array<I, 3>>` of
/// triangles as a SurfaceMesh, without copying. The view must not outlive the vectors.
template <class Scalar, class Index>
class std_array_mesh_view {
 public:
  using scalar_type = Scalar;
  std_array_mesh_view(const std::vector<std::array<Scalar, 3>>& positions,
                      const std::vector<std::array<Index, 3>>& triangles)
      : positions_(&positions), triangles_(&triangles) {}
  [[nodiscard]] const std::vector<std::array<Scalar, 3>>& positions() const noexcept { return *positions_; }
  [[nodiscard]] const std::vector<std::array<Index, 3>>& triangles() const noexcept { return *triangles_; }

 private:
  const std::vector<std::array<Scalar, 3>>* positions_;
  const std::vector<std::array<Index, 3>>* triangles_;
};

template <class Scalar, class Index>
struct surface_traits<std_array_mesh_view<Scalar, Index>> {
  using mesh = std_array_mesh_view<Scalar, Index>;
  using scalar_type = Scalar;
  static index_t num_vertices(const mesh& m) { return static_cast<index_t>(m.positions().size()); }
  static index_t num_faces(const mesh& m) { return static_cast<index_t>(m.triangles().size()); }
  static const std::array<Scalar, 3>& position(const mesh& m, index_t i) {
    return m.positions()[static_cast<std::size_t>(i)];
  }
  static std::array<index_t, 3> face(const mesh& m, index_t f) {
    const auto& t = m.triangles()[static_cast<std::size_t>(f)];
    return {static_cast<index_t>(t[0]), static_cast<index_t>(t[1]), static_cast<index_t>(t[2])};
  }
};

/// `std::vector<std::array<S, D>>` is a D-dimensional point set.
template <class Scalar, std::size_t D>
struct point_set_traits<std::vector<std::array<Scalar, D>>> {
  using scalar_type = Scalar;
  static constexpr int dimension = static_cast<int>(D);
  static index_t num_points(const std::vector<std::array<Scalar, D>>& p) { return static_cast<index_t>(p.size()); }
  static Scalar coord(const std::vector<std::array<Scalar, D>>& p, index_t i, int d) {
    return p[static_cast<std::size_t>(i)][static_cast<std::size_t>(d)];
  }
};

}  // namespace shapestruct
