// SPDX-License-Identifier: MIT
// Static tests of PointSet: models satisfy it, a mock missing any single required expression does not.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/adapters/eigen_points.hpp"
#include "shapestruct/adapters/eigen_vf.hpp"
#include "shapestruct/adapters/std_arrays.hpp"
#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/triangle_mesh.hpp"

namespace ss = shapestruct;

static_assert(ss::PointSet<Eigen::MatrixX3d>);
static_assert(ss::PointSet<Eigen::MatrixX3f>);
static_assert(ss::PointSet<Eigen::Matrix<double, Eigen::Dynamic, 8>>);
static_assert(ss::PointSet<Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>>);
static_assert(ss::PointSet<std::vector<std::array<double, 3>>>);
static_assert(ss::PointSet<std::vector<std::array<float, 2>>>);
static_assert(ss::PointSet<ss::triangle_mesh<double>>);
static_assert(ss::PointSet<ss::eigen_mesh_view<Eigen::MatrixXd, Eigen::MatrixXi>>);
static_assert(ss::point_set_traits<Eigen::Matrix<double, Eigen::Dynamic, 8>>::dimension == 8);

namespace mocks {
struct no_scalar {};
struct no_dimension {};
struct no_num_points {};
struct no_coord {};
}  // namespace mocks

template <>
struct ss::point_set_traits<mocks::no_scalar> {
  static constexpr int dimension = 3;
  static ss::index_t num_points(const mocks::no_scalar&) { return 0; }
  static double coord(const mocks::no_scalar&, ss::index_t, int) { return 0; }
};
template <>
struct ss::point_set_traits<mocks::no_dimension> {
  using scalar_type = double;
  static ss::index_t num_points(const mocks::no_dimension&) { return 0; }
  static double coord(const mocks::no_dimension&, ss::index_t, int) { return 0; }
};
template <>
struct ss::point_set_traits<mocks::no_num_points> {
  using scalar_type = double;
  static constexpr int dimension = 3;
  static double coord(const mocks::no_num_points&, ss::index_t, int) { return 0; }
};
template <>
struct ss::point_set_traits<mocks::no_coord> {
  using scalar_type = double;
  static constexpr int dimension = 3;
  static ss::index_t num_points(const mocks::no_coord&) { return 0; }
};

static_assert(!ss::PointSet<Eigen::MatrixXd>);  // dynamic column count: no compile-time dimension
static_assert(!ss::PointSet<mocks::no_scalar>);
static_assert(!ss::PointSet<mocks::no_dimension>);
static_assert(!ss::PointSet<mocks::no_num_points>);
static_assert(!ss::PointSet<mocks::no_coord>);
static_assert(!ss::PointSet<std::vector<double>>);
