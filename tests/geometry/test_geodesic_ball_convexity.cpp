// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/geodesic_ball_convexity.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

using namespace shapestruct;

namespace {
/// Exact geodesic (great-circle) distances on the unit sphere, (#V x #samples).
matrix_x<double> great_circle_table(const triangle_mesh<double>& m, const std::vector<index_t>& samples) {
  matrix_x<double> t(m.V.rows(), static_cast<index_t>(samples.size()));
  for (index_t s = 0; s < t.cols(); ++s)
    for (index_t v = 0; v < m.V.rows(); ++v) {
      const double c = m.V.row(v).normalized().dot(m.V.row(samples[static_cast<std::size_t>(s)]).normalized());
      t(v, s) = std::acos(std::clamp(c, -1.0, 1.0));
    }
  return t;
}
}  // namespace

TEST_CASE("geodesic_ball_convexity on a sphere: the cap's sagitta over r, whatever the face orientation") {
  const auto m = make_icosphere<double>(4);
  const std::vector<index_t> samples{0, 17, 200};
  const auto table = great_circle_table(m, samples);
  const std::vector<double> radii{0.3, 0.6};
  const auto c = geodesic_ball_convexity<double>(m.V, m.F, table, std::span<const index_t>(samples),
                                                 std::span<const double>(radii), 1);
  REQUIRE(c.rows() == 3);
  REQUIRE(c.cols() == 2);
  // A cap of geodesic radius r on the unit sphere has its centroid at height (1 + cos r) / 2 along the normal,
  // so the sample sticks out by (1 - cos r) / 2.
  for (index_t s = 0; s < 3; ++s)
    for (index_t k = 0; k < 2; ++k) {
      const double r = radii[static_cast<std::size_t>(k)];
      CHECK(c(s, k) == doctest::Approx((1 - std::cos(r)) / 2 / r).epsilon(0.05));
    }
  // Reversed faces (inward normals): the outward orientation is recovered from the signed volume.
  triangle_mesh<double> flipped = m;
  flipped.F.col(1).swap(flipped.F.col(2));
  const auto cf = geodesic_ball_convexity<double>(flipped.V, flipped.F, table, std::span<const index_t>(samples),
                                                  std::span<const double>(radii), 2);
  CHECK((cf - c).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("geodesic_ball_convexity: zero on a plane, negative in a dent") {
  auto m = test::grid_mesh(20, 20, 0.05);
  // Lift the plane to z = 1 so that its signed volume (from the origin) is positive and the +z face normals are
  // read as outward; an open sheet through the origin has no outside.
  m.V.col(2).array() += 1.0;
  const dijkstra_geodesics<double> geo(m.V, m.F);
  const index_t centre = 10 * 21 + 10;
  const std::vector<index_t> samples{centre};
  const std::vector<double> radii{0.2};
  const auto flat_table = geo.distance_table(std::span<const index_t>(samples), 1);
  const auto flat = geodesic_ball_convexity<double>(m.V, m.F, flat_table, std::span<const index_t>(samples),
                                                    std::span<const double>(radii));
  CHECK(std::abs(flat(0, 0)) < 1e-12);
  // Push the centre down against the normal (+z for the grid's counter-clockwise faces): a pit.
  m.V(centre, 2) = 0.95;
  const dijkstra_geodesics<double> geo2(m.V, m.F);
  const auto dent = geodesic_ball_convexity<double>(m.V, m.F, geo2.distance_table(std::span<const index_t>(samples), 1),
                                                    std::span<const index_t>(samples), std::span<const double>(radii));
  CHECK(dent(0, 0) < -0.01);
}

TEST_CASE("geodesic_ball_convexity rejects a table of the wrong size and a non-positive radius") {
  const auto m = make_icosphere<double>(1);
  const std::vector<index_t> samples{0, 1};
  const matrix_x<double> wrong = matrix_x<double>::Zero(m.V.rows(), 1);
  const matrix_x<double> right = matrix_x<double>::Zero(m.V.rows(), 2);
  const std::vector<double> good{0.1}, bad{0.1, 0.0};
  test::expect_invalid([&] { (void)geodesic_ball_convexity<double>(m.V, m.F, wrong, std::span<const index_t>(samples), std::span<const double>(good)); },
                       input_error::size_mismatch);
  test::expect_invalid([&] { (void)geodesic_ball_convexity<double>(m.V, m.F, right, std::span<const index_t>(samples), std::span<const double>(bad)); },
                       input_error::bad_parameter, 1);
}
