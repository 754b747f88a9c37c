// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "shapestruct/adapters/std_arrays.hpp"
#include "shapestruct/geometry/local_shape_features.hpp"
#include "shapestruct/geometry/surface_sampling.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

// A 60 x 60 grid with spacing 1/30 in the plane through `origin` spanned by the columns of `frame`; a grid is
// symmetric under quarter turns, so interior neighbourhoods are exactly isotropic in the plane.
matrix_x3<double> grid_plane(const Eigen::Matrix3d& frame, const Eigen::Vector3d& origin) {
  matrix_x3<double> P(3600, 3);
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j) {
      const Eigen::Vector3d p = origin + frame.col(0) * (i / 30.0 - 1.0) + frame.col(1) * (j / 30.0 - 1.0);
      P.row(i * 60 + j) = p.transpose();
    }
  return P;
}

bool interior(const matrix_x3<double>& P, const Eigen::Matrix3d& frame, const Eigen::Vector3d& origin, index_t i,
              double margin) {
  const Eigen::Vector3d d = P.row(i).transpose() - origin;
  const double u = d.dot(frame.col(0)), v = d.dot(frame.col(1));
  return std::abs(u + 1.0 / 60) < 1 - margin && std::abs(v + 1.0 / 60) < 1 - margin;
}

}  // namespace

TEST_CASE("local_shape_features: on a plane the normal is the plane normal and planarity is 1") {
  const Eigen::Matrix3d frame = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d origin(0.3, -2, 5);
  const auto P = grid_plane(frame, origin);
  const auto f = local_shape_features<double>(P, {.radius = 0.21, .threads = 2});
  CHECK(f.radius == 0.21);  // no grid point lies at exactly this distance, so rounding cannot break the symmetry
  CHECK(f.degenerate == 0);
  int checked = 0;
  for (index_t i = 0; i < P.rows(); ++i) {
    CHECK(std::abs(f.normals.row(i).dot(frame.col(2).transpose())) > 1 - 1e-9);
    CHECK(f.features(i, 1) < 1e-12);  // lambda3 / lambda1
    CHECK(f.scattering[i] < 1e-12);
    CHECK(f.linearity[i] + f.planarity[i] + f.scattering[i] == doctest::Approx(1.0));
    if (interior(P, frame, origin, i, 0.25)) {
      CHECK(f.planarity[i] == doctest::Approx(1.0).epsilon(1e-9));
      CHECK(f.features(i, 0) == doctest::Approx(1.0).epsilon(1e-9));  // lambda2 / lambda1
      ++checked;
    }
  }
  CHECK(checked > 1000);
}

TEST_CASE("local_shape_features: on a line linearity is 1 and v1 is the line direction, angle features") {
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 0, 0);
  matrix_x3<double> P(500, 3);
  for (index_t i = 0; i < P.rows(); ++i) P.row(i) = (Eigen::Vector3d(0, 2, 1) + dir * (i / 100.0)).transpose();
  const auto f = local_shape_features<double>(P, {.k = 12});
  for (index_t i = 0; i < P.rows(); ++i) {
    CHECK(f.linearity[i] == doctest::Approx(1.0).epsilon(1e-9));
    CHECK(std::abs(f.principal_axes.row(i).dot(dir.transpose())) > 1 - 1e-12);
    CHECK(f.features(i, 2) == doctest::Approx(0.5));  // v1 is horizontal: 90 degrees from a_up = +Y
    CHECK(f.features(i, 3) == doctest::Approx(0.0));  // v1 = a_2 = +X
    CHECK(f.neighbor_counts[i] == 12);
  }
  // A vertical line: v1 is along a_up.
  matrix_x3<double> Q(50, 3);
  for (index_t i = 0; i < Q.rows(); ++i) Q.row(i) << 0.5, i / 10.0, 0;
  const auto g = local_shape_features<double>(Q, {.radius = 0.35});
  CHECK(g.features(25, 2) == doctest::Approx(0.0));
  CHECK(g.features(25, 3) == doctest::Approx(0.5));
  CHECK(g.neighbor_counts[25] == 7);  // the point and 3 on each side (inclusive radius 0.35 > 0.3)
}

TEST_CASE("local_shape_features: scale invariance, thread independence, sphere normals, two mesh models") {
  const auto ico = make_icosphere(3);
  const auto legacy = test::to_legacy(ico);
  const auto s = sample_surface_even(ico, 2000, {.seed = 4});
  const auto base = local_shape_features<double>(s.points, {.threads = 1});
  CHECK(base.shape_diameter == doctest::Approx(2.0).epsilon(0.01));
  CHECK(base.radius == doctest::Approx(0.15 * base.shape_diameter));
  // Outward normals on the sphere.
  for (index_t i = 0; i < s.size(); ++i) CHECK(base.normals.row(i).dot(s.points.row(i).normalized()) > 0.99);
  const auto two = local_shape_features<double>(s.points, {.threads = 2});
  CHECK(two.features == base.features);
  CHECK(two.normals == base.normals);
  // Uniform scaling (a power of two, so coordinates scale exactly) leaves every output unchanged.
  const matrix_x3<double> scaled = s.points * 8.0;
  const auto big = local_shape_features(scaled);
  CHECK((big.features - base.features).cwiseAbs().maxCoeff() < 1e-9);
  CHECK((big.eigenvalues - base.eigenvalues).cwiseAbs().maxCoeff() < 1e-9);
  CHECK(big.radius == doctest::Approx(8 * base.radius));
  // Legacy model: samples of the legacy (float) mesh, features of its float points, and the PointSet overloads.
  const auto sl = sample_surface_even<float>(legacy, 2000, {.seed = 4});
  const auto fl = local_shape_features(sl.points);
  static_assert(std::is_same_v<decltype(fl.features), matrix_x<float>>);
  // Only the well-conditioned outputs are compared: on a sphere lambda1 ~ lambda2, so v1 and v2 (and their
  // angle features) may turn freely in the tangent plane between float and double inputs.
  CHECK((fl.features.leftCols(2).cast<double>() - base.features.leftCols(2)).cwiseAbs().maxCoeff() < 1e-3);
  CHECK((fl.normals.cast<double>() - base.normals).cwiseAbs().maxCoeff() < 1e-3);
  std::vector<std::array<double, 3>> arr;
  for (index_t i = 0; i < s.size(); ++i) arr.push_back({s.points(i, 0), s.points(i, 1), s.points(i, 2)});
  CHECK(local_shape_features(arr).features == base.features);
  const auto on_vertices = local_shape_features(ico);  // triangle_mesh is a PointSet of its vertices
  CHECK(on_vertices.features.rows() == ico.V.rows());
}

TEST_CASE("estimate_diameter is within 0.5% of the brute-force diameter, never above") {
  std::mt19937_64 rng(77);
  for (int trial = 0; trial < 5; ++trial) {
    matrix_x3<double> P(400, 3);
    for (index_t i = 0; i < P.rows(); ++i)
      for (int d = 0; d < 3; ++d) P(i, d) = (double(rng() >> 11) * 0x1.0p-53) * (d + 1.0 + trial);
    double exact = 0;
    for (index_t i = 0; i < P.rows(); ++i)
      for (index_t j = i + 1; j < P.rows(); ++j) exact = std::max(exact, (P.row(i) - P.row(j)).norm());
    const double est = estimate_diameter<double>(P);
    CHECK(est <= exact);
    CHECK(est >= 0.995 * exact);
  }
}

TEST_CASE("local_shape_features: coincident points are degenerate, not NaN") {
  matrix_x3<double> P = matrix_x3<double>::Zero(5, 3);
  const auto f = local_shape_features<double>(P, {.radius = 1.0});
  CHECK(f.degenerate == 5);
  CHECK(f.features.allFinite());
  CHECK(f.features(0, 2) == 0.25);
}

TEST_CASE("local_shape_features: one test per invalid_input reason") {
  auto reason_of = [](auto&& fn) {
    try {
      fn();
    } catch (const invalid_input& e) {
      return std::make_pair(e.reason(), e.element());
    }
    FAIL("no invalid_input thrown");
    return std::make_pair(input_error::empty, no_index);
  };
  const matrix_x3<double> P = make_icosphere(1).V;
  SUBCASE("empty") {
    CHECK(reason_of([&] { (void)local_shape_features<double>(matrix_x3<double>(0, 3)); }).first == input_error::empty);
  }
  SUBCASE("non_finite") {
    auto bad = P;
    bad(9, 0) = std::numeric_limits<double>::infinity();
    CHECK(reason_of([&] { (void)local_shape_features(bad); }) == std::make_pair(input_error::non_finite, index_t(9)));
  }
  SUBCASE("size_mismatch") {
    const Eigen::MatrixXd two_columns = Eigen::MatrixXd::Zero(5, 2);
    CHECK(reason_of([&] { (void)local_shape_features(two_columns); }).first == input_error::size_mismatch);
  }
  SUBCASE("bad_parameter") {
    CHECK(reason_of([&] { (void)local_shape_features(P, {.radius_fraction = 0}); }).first == input_error::bad_parameter);
    CHECK(reason_of([&] { (void)local_shape_features(P, {.radius = -1}); }).first == input_error::bad_parameter);
    CHECK(reason_of([&] { (void)local_shape_features(P, {.k = -3}); }).first == input_error::bad_parameter);
    CHECK(reason_of([&] { (void)local_shape_features(P, {.up_axis = {0, 0, 0}}); }).first == input_error::bad_parameter);
    CHECK(reason_of([&] { (void)local_shape_features(P, {.up_axis = {1, 0, 0}}); }).first == input_error::bad_parameter);
    CHECK(reason_of([&] { (void)local_shape_features(P, {.threads = -1}); }).first == input_error::bad_parameter);
    const matrix_x3<double> same = matrix_x3<double>::Ones(4, 3);
    CHECK(reason_of([&] { (void)local_shape_features(same); }).first == input_error::bad_parameter);
  }
}
