// SPDX-License-Identifier: MIT
// Static tests of SurfaceMesh / ContiguousSurfaceMesh: the models satisfy them, and a mock missing any single
// required expression does not. Compiling this file is passing it.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/adapters/eigen_vf.hpp"
#include "shapestruct/adapters/std_arrays.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "support/legacy_mesh.hpp"

namespace ss = shapestruct;

// Models.
static_assert(ss::SurfaceMesh<ss::triangle_mesh<double>>);
static_assert(ss::SurfaceMesh<ss::triangle_mesh<float>>);
static_assert(ss::SurfaceMesh<const ss::triangle_mesh<double>&>);
static_assert(ss::SurfaceMesh<ss::eigen_mesh_view<Eigen::MatrixXd, Eigen::MatrixXi>>);
static_assert(ss::SurfaceMesh<ss::eigen_mesh_view<Eigen::MatrixXf, Eigen::MatrixXi>>);
static_assert(ss::SurfaceMesh<ss::std_array_mesh_view<double, int>>);
static_assert(ss::SurfaceMesh<ss::std_array_mesh_view<float, std::uint32_t>>);
static_assert(ss::SurfaceMesh<ss::test::legacy_mesh>);

// The contiguous refinement: only adapters that hand out Eigen storage.
static_assert(ss::ContiguousSurfaceMesh<ss::triangle_mesh<double>>);
static_assert(ss::ContiguousSurfaceMesh<ss::eigen_mesh_view<Eigen::MatrixXd, Eigen::MatrixXi>>);
static_assert(!ss::ContiguousSurfaceMesh<ss::test::legacy_mesh>);
static_assert(!ss::ContiguousSurfaceMesh<ss::std_array_mesh_view<double, int>>);

// Non-models: not adapted at all, and adapted with one required expression missing or wrong.
namespace mocks {
struct not_adapted {};
struct no_scalar {};
struct int_scalar {};
struct no_num_vertices {};
struct no_num_faces {};
struct no_position {};
struct position_2d {};
struct no_face {};
struct face_wrong_type {};
}  // namespace mocks

template <>
struct ss::surface_traits<mocks::no_scalar> {
  static ss::index_t num_vertices(const mocks::no_scalar&) { return 0; }
  static ss::index_t num_faces(const mocks::no_scalar&) { return 0; }
  static std::array<double, 3> position(const mocks::no_scalar&, ss::index_t) { return {}; }
  static std::array<ss::index_t, 3> face(const mocks::no_scalar&, ss::index_t) { return {}; }
};
template <>
struct ss::surface_traits<mocks::int_scalar> {
  using scalar_type = int;  // not floating point
  static ss::index_t num_vertices(const mocks::int_scalar&) { return 0; }
  static ss::index_t num_faces(const mocks::int_scalar&) { return 0; }
  static std::array<int, 3> position(const mocks::int_scalar&, ss::index_t) { return {}; }
  static std::array<ss::index_t, 3> face(const mocks::int_scalar&, ss::index_t) { return {}; }
};
template <>
struct ss::surface_traits<mocks::no_num_vertices> {
  using scalar_type = double;
  static ss::index_t num_faces(const mocks::no_num_vertices&) { return 0; }
  static std::array<double, 3> position(const mocks::no_num_vertices&, ss::index_t) { return {}; }
  static std::array<ss::index_t, 3> face(const mocks::no_num_vertices&, ss::index_t) { return {}; }
};
template <>
struct ss::surface_traits<mocks::no_num_faces> {
  using scalar_type = double;
  static ss::index_t num_vertices(const mocks::no_num_faces&) { return 0; }
  static std::array<double, 3> position(const mocks::no_num_faces&, ss::index_t) { return {}; }
  static std::array<ss::index_t, 3> face(const mocks::no_num_faces&, ss::index_t) { return {}; }
};
template <>
struct ss::surface_traits<mocks::no_position> {
  using scalar_type = double;
  static ss::index_t num_vertices(const mocks::no_position&) { return 0; }
  static ss::index_t num_faces(const mocks::no_position&) { return 0; }
  static std::array<ss::index_t, 3> face(const mocks::no_position&, ss::index_t) { return {}; }
};
template <>
struct ss::surface_traits<mocks::position_2d> {
  using scalar_type = double;
  static ss::index_t num_vertices(const mocks::position_2d&) { return 0; }
  static ss::index_t num_faces(const mocks::position_2d&) { return 0; }
  static double position(const mocks::position_2d&, ss::index_t) { return 0; }  // not indexable
  static std::array<ss::index_t, 3> face(const mocks::position_2d&, ss::index_t) { return {}; }
};
template <>
struct ss::surface_traits<mocks::no_face> {
  using scalar_type = double;
  static ss::index_t num_vertices(const mocks::no_face&) { return 0; }
  static ss::index_t num_faces(const mocks::no_face&) { return 0; }
  static std::array<double, 3> position(const mocks::no_face&, ss::index_t) { return {}; }
};
template <>
struct ss::surface_traits<mocks::face_wrong_type> {
  using scalar_type = double;
  static ss::index_t num_vertices(const mocks::face_wrong_type&) { return 0; }
  static ss::index_t num_faces(const mocks::face_wrong_type&) { return 0; }
  static std::array<double, 3> position(const mocks::face_wrong_type&, ss::index_t) { return {}; }
  static std::vector<int> face(const mocks::face_wrong_type&, ss::index_t) { return {}; }
};

static_assert(!ss::SurfaceMesh<mocks::not_adapted>);
static_assert(!ss::SurfaceMesh<mocks::no_scalar>);
static_assert(!ss::SurfaceMesh<mocks::int_scalar>);
static_assert(!ss::SurfaceMesh<mocks::no_num_vertices>);
static_assert(!ss::SurfaceMesh<mocks::no_num_faces>);
static_assert(!ss::SurfaceMesh<mocks::no_position>);
static_assert(!ss::SurfaceMesh<mocks::position_2d>);
static_assert(!ss::SurfaceMesh<mocks::no_face>);
static_assert(!ss::SurfaceMesh<mocks::face_wrong_type>);
static_assert(!ss::SurfaceMesh<int>);
