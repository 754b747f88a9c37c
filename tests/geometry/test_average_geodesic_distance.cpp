// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
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

namespace {
// Brute force: m's persistence is f(m) minus the highest level t at which the superlevel set {f >= t} (in the
// tie-broken order) joins m to a vertex ranked above it; the top vertex of a component gets f(m) - min f there.
double brute_force_persistence(const edge_graph<double>& g, const Eigen::VectorXd& f, index_t m) {
  const index_t n = g.num_vertices();
  auto above = [&](index_t u, index_t v) { return f[u] > f[v] || (f[u] == f[v] && u < v); };
  std::vector<index_t> levels(static_cast<std::size_t>(n));
  std::iota(levels.begin(), levels.end(), index_t{0});
  std::sort(levels.begin(), levels.end(), above);
  double lowest = f[m];
  for (const index_t t : levels) {  // the level set of every vertex ranked at or above t, highest t first
    if (above(m, t) == false && t != m) continue;
    std::vector<char> seen(static_cast<std::size_t>(n), 0);
    std::vector<index_t> stack{m};
    seen[static_cast<std::size_t>(m)] = 1;
    bool joined = false;
    while (!stack.empty()) {
      const index_t v = stack.back();
      stack.pop_back();
      lowest = std::min(lowest, f[v]);
      if (above(v, m)) joined = true;
      for (index_t k = g.offsets[static_cast<std::size_t>(v)]; k < g.offsets[static_cast<std::size_t>(v + 1)]; ++k) {
        const index_t u = g.neighbours[static_cast<std::size_t>(k)];
        if (!seen[static_cast<std::size_t>(u)] && (u == t || above(u, t))) {
          seen[static_cast<std::size_t>(u)] = 1;
          stack.push_back(u);
        }
      }
    }
    if (joined) return f[m] - f[t];
  }
  return f[m] - lowest;
}
}  // namespace

TEST_CASE("maximum_persistence: the dip between two ridges, and a vertex that is no maximum") {
  // Columns of a 5 x 2 grid carry 0, 3, 1, 2, 0 (both rows alike, the upper row 0.01 lower): the ridge at x = 1
  // is the top (persistence 3 - 0), the one at x = 3 meets it at the dip x = 2 (2 - 1).
  const auto grid = test::grid_mesh(4, 1);
  const double column[5] = {0, 3, 1, 2, 0};
  Eigen::VectorXd f(10);
  for (int i = 0; i < 5; ++i) {
    f[i] = column[i];
    f[5 + i] = column[i] - 0.01;
  }
  const edge_graph<double> g(grid.V, grid.F);
  const std::vector<index_t> asked{1, 3, 2};
  const auto p = maximum_persistence<double>(g, f, asked);
  REQUIRE(p.size() == 3);
  CHECK(p[0] == doctest::Approx(3.01));  // down to the lowest vertex, 5 (-0.01)
  CHECK(p[1] == doctest::Approx(1.0));
  CHECK(p[2] == 0.0);  // x = 2 is a dip, not a maximum
  CHECK(agd_local_maxima(grid.V, grid.F, f, 0.5) == std::vector<index_t>{1, 3});
}

TEST_CASE("maximum_persistence equals the brute-force superlevel-set definition on random functions") {
  const auto grid = test::grid_mesh(7, 6);
  const edge_graph<double> g(grid.V, grid.F);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> level(0, 9);  // few levels: many ties, broken by index
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd f(grid.V.rows());
    for (index_t v = 0; v < f.size(); ++v) f[v] = level(rng);
    std::vector<index_t> all(static_cast<std::size_t>(f.size()));
    std::iota(all.begin(), all.end(), index_t{0});
    const auto p = maximum_persistence<double>(g, f, all);
    for (const index_t v : all) CHECK(p[static_cast<std::size_t>(v)] == brute_force_persistence(g, f, v));
  }
}

TEST_CASE("maximum_persistence: non-finite values are no region, two components each keep their top") {
  auto two = test::grid_mesh(2, 1);
  const index_t n = two.V.rows();
  two.V.conservativeResize(2 * n, 3);
  two.V.bottomRows(n) = two.V.topRows(n).rowwise() + Eigen::RowVector3d(10, 0, 0);
  const index_t nf = two.F.rows();
  two.F.conservativeResize(2 * nf, 3);
  two.F.bottomRows(nf) = two.F.topRows(nf).array() + n;
  Eigen::VectorXd f(2 * n);
  f << 1, 5, 2, 0, 1, 1, 4, 3, 9, 3, 3, 3;
  f[4] = std::numeric_limits<double>::quiet_NaN();
  const edge_graph<double> g(two.V, two.F);
  const std::vector<index_t> asked{1, 8, 4};
  const auto p = maximum_persistence<double>(g, f, asked);
  CHECK(p[0] == 5.0);  // the first piece's top: down to its lowest vertex (0)
  CHECK(p[1] == 6.0);  // the second piece's top: down to 3, not to the first piece's 0
  CHECK(p[2] == 0.0);  // NaN
  test::expect_invalid([&] { (void)maximum_persistence<double>(g, Eigen::VectorXd(Eigen::VectorXd::Ones(3)), asked); },
                       input_error::size_mismatch);
  const std::vector<index_t> outside{12};
  test::expect_invalid([&] { (void)maximum_persistence<double>(g, f, outside); }, input_error::bad_parameter, 12);
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
