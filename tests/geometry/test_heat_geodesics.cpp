// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/heat_geodesics.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {
struct errors {
  double heat = 0, dijkstra = 0;
};
/// Mean relative error of heat and Dijkstra distances against the exact great-circle distance on the unit
/// sphere, over all vertices farther than 0.1 (relative error is meaningless at the source) from each source.
template <class S>
errors sphere_errors(const triangle_mesh<double>& m, const matrix_x<S>& H, const matrix_x<S>& D,
                     const std::vector<index_t>& src) {
  errors e;
  long count = 0;
  for (std::size_t k = 0; k < src.size(); ++k)
    for (index_t v = 0; v < m.V.rows(); ++v) {
      const double exact = std::acos(std::clamp(m.V.row(src[k]).dot(m.V.row(v)) / m.V.row(v).norm() /
                                                    m.V.row(src[k]).norm(), -1.0, 1.0));
      if (exact < 0.1) continue;
      e.heat += std::abs(double(H(v, index_t(k))) - exact) / exact;
      e.dijkstra += std::abs(double(D(v, index_t(k))) - exact) / exact;
      ++count;
    }
  e.heat /= double(count);
  e.dijkstra /= double(count);
  return e;
}
}  // namespace

TEST_CASE("heat geodesics vs exact great-circle distance on a fine icosphere: closer than Dijkstra") {
  const auto ico = make_icosphere(5);  // 10,242 vertices
  const heat_geodesic_solver<double> heat(ico.V, ico.F);
  REQUIRE(heat.info() == status::ok);
  const dijkstra_geodesics<double> dij(ico.V, ico.F);
  const std::vector<index_t> src = {0, 17, 333, 4000, 10241};
  const auto H = heat.distance_table(src, 2);
  REQUIRE(H.info == status::ok);
  const auto D = dij.distance_table(src, 2);
  const auto e = sphere_errors(ico, H.distances, D, src);
  MESSAGE("icosphere(5) mean relative error vs great circle: heat " << e.heat << ", Dijkstra " << e.dijkstra);
  CHECK(e.heat < 0.02);       // measured 0.7%
  CHECK(e.dijkstra > 0.03);   // measured 6.9%: edge paths zig-zag
  CHECK(e.heat < e.dijkstra / 3);
  CHECK(H.distances.allFinite());
  for (std::size_t k = 0; k < src.size(); ++k) CHECK(H.distances(src[k], index_t(k)) == 0.0);
  CHECK(H.distances.minCoeff() >= 0.0);
  // antipode of vertex 0 is at distance pi
  index_t antipode = 0;
  (ico.V * ico.V.row(0).transpose()).minCoeff(&antipode);
  CHECK(H.distances(antipode, 0) == doctest::Approx(std::acos(-1.0)).epsilon(0.02));
}

TEST_CASE("heat geodesics: table equals single queries, identical for 1 and 2 threads, legacy mesh agrees") {
  const auto m = test::jittered_icosphere(3, 21, 0.02);
  const auto legacy = test::to_legacy(m);
  const heat_geodesic_solver<double> heat(m);
  const heat_geodesic_solver<float> heatl(legacy);
  REQUIRE(heatl.info() == status::ok);
  const std::vector<index_t> src = {1, 50, 99, 300, 641};
  const auto T1 = heat.distance_table(src, 1);
  const auto T2 = heat.distance_table(src, 2);
  CHECK(T1.distances == T2.distances);
  for (std::size_t k = 0; k < src.size(); ++k) {
    const auto r = heat.distances(src[k]);
    CHECK(r.info == status::ok);
    CHECK(r.distance == T1.distances.col(index_t(k)));
  }
  const auto L1 = heatl.distance_table(src, 1);
  const auto L2 = heatl.distance_table(src, 2);
  CHECK(L1.distances == L2.distances);
  CHECK((L1.distances.cast<double>() - T1.distances).cwiseAbs().maxCoeff() < 1e-3);
}

TEST_CASE("heat geodesics: multi-source distance is close to the minimum of single-source distances") {
  const auto m = make_icosphere(4);
  const heat_geodesic_solver<double> heat(m.V, m.F);
  const std::vector<index_t> src = {0, 2000};
  const auto multi = heat.distances(src).distance;
  const auto a = heat.distances(src[0]).distance, b = heat.distances(src[1]).distance;
  const Eigen::VectorXd mn = a.cwiseMin(b);
  CHECK(((multi - mn).cwiseAbs().mean()) < 0.02 * mn.maxCoeff());
  CHECK(multi[0] == 0.0);
  CHECK(multi[2000] == 0.0);
}

TEST_CASE("heat geodesics on a flat grid: close to Euclidean distance from a corner") {
  const auto grid = test::grid_mesh(40, 40, 1.0 / 40);
  const heat_geodesic_solver<double> heat(grid.V, grid.F);
  const auto d = heat.distances(0).distance;
  double err = 0;
  int c = 0;
  for (index_t v = 0; v < grid.V.rows(); ++v) {
    const double exact = grid.V.row(v).norm();
    if (exact < 0.2) continue;
    err += std::abs(d[v] - exact) / exact;
    ++c;
  }
  MESSAGE("grid mean relative error " << err / c);
  CHECK(err / c < 0.03);  // boundary effects (Neumann condition) included
}

TEST_CASE("heat geodesics on degenerate faces and several components: no NaN") {
  const auto m = test::degenerate_grid();
  const heat_geodesic_solver<double> heat(m.V, m.F);
  const auto r = heat.distances(0);
  CHECK(r.info == status::ok);
  CHECK(r.distance.allFinite());
  CHECK(r.distance[24] > r.distance[1]);  // far corner farther than a neighbour
  auto a = test::octahedron();
  triangle_mesh<double> two;
  two.V.resize(12, 3);
  two.V << a.V, (a.V.array() + 5.0).matrix();
  two.F.resize(16, 3);
  two.F << a.F, (a.F.array() + 6).matrix();
  const heat_geodesic_solver<double> h2(two.V, two.F);
  const auto d = h2.distances(0).distance;
  CHECK(d.head(6).allFinite());
  CHECK((d.tail(6).array() == std::numeric_limits<double>::infinity()).all());
  const std::vector<index_t> both = {0, 7};
  CHECK(h2.distances(both).distance.allFinite());
}

TEST_CASE("heat geodesics: a failed factorisation is a status, not an exception") {
  // All vertices at one point: every face is degenerate, L and M are zero, h = 0.
  triangle_mesh<double> m = test::octahedron();
  m.V.setZero();
  const heat_geodesic_solver<double> heat(m.V, m.F);
  CHECK(heat.info() == status::numerical_issue);
  const auto r = heat.distances(0);
  CHECK(r.info == status::numerical_issue);
  CHECK((r.distance.array() == std::numeric_limits<double>::infinity()).all());
}

TEST_CASE("heat geodesics: one test per invalid_input reason") {
  triangle_mesh<double> empty;
  test::expect_invalid([&] { (void)heat_geodesic_solver<double>(empty.V, empty.F); }, input_error::empty, no_index);
  test::expect_invalid([&] { (void)heat_geodesic_solver<double>(test::with_nan_vertex()); }, input_error::non_finite,
                       2);
  test::expect_invalid([&] { (void)heat_geodesic_solver<float>(test::to_legacy(test::with_bad_index())); },
                       input_error::bad_face, 3);
  const auto oct = test::octahedron();
  test::expect_invalid([&] { (void)heat_geodesic_solver<double>(oct, {.time_factor = 0}); },
                       input_error::bad_parameter);
  test::expect_invalid([&] { (void)heat_geodesic_solver<double>(oct, {.regularisation = -1}); },
                       input_error::bad_parameter);
  const heat_geodesic_solver<double> heat(oct);
  test::expect_invalid([&] { (void)heat.distances(6); }, input_error::bad_parameter, 6);
  test::expect_invalid([&] { (void)heat.distances(std::span<const index_t>()); }, input_error::empty);
  const std::vector<index_t> ok = {0};
  test::expect_invalid([&] { (void)heat.distance_table(ok, -3); }, input_error::bad_parameter);
}
