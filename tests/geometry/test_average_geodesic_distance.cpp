// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/geometry/average_geodesic_distance.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

TEST_CASE("AGD with every vertex as a source is the area-weighted mean distance (brute force)") {
  const auto m = test::jittered_icosphere(2, 13, 0.05);
  const auto agd = average_geodesic_distance(m, {.num_sources = 100000});
  const dijkstra_geodesics<double> geo(m.V, m.F);
  const auto area = vertex_areas(m);
  for (index_t v = 0; v < m.V.rows(); v += 11) {
    const Eigen::VectorXd d = geo.distances_from(v);
    CHECK(agd[v] == doctest::Approx(d.dot(area) / area.sum()).epsilon(1e-12));
  }
}

TEST_CASE("AGD from 64 FPS sources approximates the exact AGD, identical for 1 and 2 threads, legacy mesh agrees") {
  const auto m = test::elongated_ellipsoid(3, 3.0);
  const auto legacy = test::to_legacy(m);
  const auto exact = average_geodesic_distance(m.V, m.F, {.num_sources = m.V.rows()});
  const auto a1 = average_geodesic_distance(m.V, m.F, {.threads = 1});
  const auto a2 = average_geodesic_distance(m.V, m.F, {.threads = 2});
  const auto al = average_geodesic_distance(legacy, {.threads = 2});
  CHECK(a1 == a2);
  const double rel = ((a1 - exact).cwiseAbs().array() / exact.array()).mean();
  MESSAGE("mean relative error of 64-source AGD: " << rel);
  CHECK(rel < 0.02);
  CHECK((al.cast<double>() - a1).cwiseAbs().maxCoeff() < 1e-3 * a1.maxCoeff());
}

TEST_CASE("AGD maxima on an elongated ellipsoid are at its two ends, on both mesh models") {
  const auto m = test::elongated_ellipsoid(3, 4.0);
  const auto legacy = test::to_legacy(m);
  const auto agd = average_geodesic_distance(m);
  const auto maxima = agd_local_maxima(m, agd);
  const auto agdl = average_geodesic_distance(legacy);
  const auto maximal = agd_local_maxima(legacy, agdl);
  REQUIRE(maxima.size() >= 2);
  REQUIRE(maximal.size() >= 2);
  CHECK(agd[maxima[0]] >= agd[maxima[1]]);
  // the two strongest maxima are the tips x = +-4 (one each)
  CHECK(std::abs(m.V(maxima[0], 0)) > 3.9);
  CHECK(std::abs(m.V(maxima[1], 0)) > 3.9);
  CHECK(m.V(maxima[0], 0) * m.V(maxima[1], 0) < 0);
  CHECK(std::abs(m.V(maximal[0], 0)) > 3.9);
  CHECK(std::abs(m.V(maximal[1], 0)) > 3.9);
  // the AGD minimum is on the waist
  index_t lo = 0;
  agd.minCoeff(&lo);
  CHECK(std::abs(m.V(lo, 0)) < 0.5);
  // a radius larger than the shape leaves only the global maximum
  const auto one = agd_local_maxima(m.V, m.F, agd, 100.0);
  REQUIRE(one.size() == 1);
  CHECK(one[0] == maxima[0]);
}

TEST_CASE("agd_local_maxima: a plateau gives one maximum, non-finite values are skipped") {
  const auto grid = test::grid_mesh(6, 6);
  Eigen::VectorXd f = Eigen::VectorXd::Constant(grid.V.rows(), 2.0);
  const auto one = agd_local_maxima(grid.V, grid.F, f, 100.0);
  REQUIRE(one.size() == 1);
  CHECK(one[0] == 0);  // ties go to the smallest index
  f[5] = std::numeric_limits<double>::infinity();
  f[9] = 3.0;
  const auto m = agd_local_maxima(grid.V, grid.F, f, 100.0);
  REQUIRE(m.size() == 1);
  CHECK(m[0] == 9);
}

TEST_CASE("AGD: one test per invalid_input reason") {
  triangle_mesh<double> empty;
  const auto oct = test::octahedron();
  test::expect_invalid([&] { (void)average_geodesic_distance(empty); }, input_error::empty, no_index);
  test::expect_invalid([&] { (void)average_geodesic_distance(test::with_nan_vertex()); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)average_geodesic_distance(test::to_legacy(test::with_bad_index())); },
                       input_error::bad_face, 3);
  test::expect_invalid([&] { (void)average_geodesic_distance(oct, {.num_sources = 0}); }, input_error::bad_parameter);
  test::expect_invalid([&] { (void)average_geodesic_distance(oct, {.first = 6}); }, input_error::bad_parameter, 6);
  test::expect_invalid([&] { (void)average_geodesic_distance(oct, {.threads = -1}); }, input_error::bad_parameter);
  const Eigen::VectorXd agd = Eigen::VectorXd::Ones(6);
  test::expect_invalid([&] { (void)agd_local_maxima(empty.V, empty.F, agd); }, input_error::empty);
  test::expect_invalid([&] { (void)agd_local_maxima(test::with_bad_index(), agd); }, input_error::bad_face, 3);
  test::expect_invalid([&] { (void)agd_local_maxima(oct, Eigen::VectorXd(Eigen::VectorXd::Ones(5))); },
                       input_error::size_mismatch);
  test::expect_invalid([&] { (void)agd_local_maxima(oct, agd, -1.0); }, input_error::bad_parameter);
  test::expect_invalid([&] { (void)agd_local_maxima(oct, agd, std::nan("")); }, input_error::bad_parameter);
}
