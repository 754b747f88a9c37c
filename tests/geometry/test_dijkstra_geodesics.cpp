// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {
/// Oracle: Bellman-Ford over the faces' edges (O(V E), independent of the CSR and the heap).
Eigen::VectorXd bellman_ford(const triangle_mesh<double>& m, const std::vector<index_t>& sources) {
  Eigen::VectorXd d = Eigen::VectorXd::Constant(m.V.rows(), std::numeric_limits<double>::infinity());
  for (const index_t s : sources) d[s] = 0;
  for (index_t it = 0; it < m.V.rows(); ++it) {
    bool changed = false;
    for (index_t f = 0; f < m.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const index_t a = m.F(f, k), b = m.F(f, (k + 1) % 3);
        const double w = (m.V.row(a) - m.V.row(b)).norm();
        if (d[a] + w < d[b]) d[b] = d[a] + w, changed = true;
        if (d[b] + w < d[a]) d[a] = d[b] + w, changed = true;
      }
    if (!changed) break;
  }
  return d;
}
}  // namespace

TEST_CASE("Dijkstra on a grid equals the closed form |a - b| + sqrt(2) min(a, b), on both mesh models") {
  const int n = 12;
  const auto grid = test::grid_mesh(n, n, 0.5);
  const dijkstra_geodesics<double> geo(grid.V, grid.F);
  const dijkstra_geodesics<float> geol(test::to_legacy(grid));
  const auto d = geo.distances_from(0);
  const auto dl = geol.distances_from(0);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double expected = 0.5 * (std::abs(i - j) + std::sqrt(2.0) * std::min(i, j));
      CHECK(d[j * (n + 1) + i] == doctest::Approx(expected).epsilon(1e-12));
      CHECK(double(dl[j * (n + 1) + i]) == doctest::Approx(expected).epsilon(1e-5));
    }
  // Early-exit query agrees with the full run, both directions.
  const index_t far = (n + 1) * (n + 1) - 1;
  CHECK(geo.geodesic_distance(0, far) == doctest::Approx(0.5 * std::sqrt(2.0) * n));
  CHECK(geo.geodesic_distance(far, 0) == doctest::Approx(0.5 * std::sqrt(2.0) * n));
  CHECK(geo.geodesic_distance(5, 5) == 0.0);
  CHECK(double(geol.geodesic_distance(0, 7)) == doctest::Approx(3.5).epsilon(1e-6));
}

TEST_CASE("Dijkstra on a path (a one-triangle-wide strip) sums the edge lengths") {
  const auto strip = test::grid_mesh(20, 1, 0.25);
  const dijkstra_geodesics<double> geo(strip.V, strip.F);
  const auto d = geo.distances_from(0);
  for (int i = 0; i <= 20; ++i) CHECK(d[i] == doctest::Approx(0.25 * i));
}

TEST_CASE("Dijkstra equals Bellman-Ford on random jittered meshes, single and multi-source") {
  std::mt19937_64 rng(20240601);
  for (int trial = 0; trial < 6; ++trial) {
    const auto m = test::jittered_icosphere(2, rng(), 0.08);
    const dijkstra_geodesics<double> geo(m.V, m.F);
    std::uniform_int_distribution<index_t> pick(0, m.V.rows() - 1);
    const std::vector<index_t> one = {pick(rng)};
    const std::vector<index_t> several = {pick(rng), pick(rng), pick(rng)};
    CHECK((geo.distances_from(one[0]) - bellman_ford(m, one)).cwiseAbs().maxCoeff() < 1e-12);
    CHECK((geo.distances_from(several) - bellman_ford(m, several)).cwiseAbs().maxCoeff() < 1e-12);
    const index_t t = pick(rng);
    CHECK(geo.geodesic_distance(one[0], t) == doctest::Approx(bellman_ford(m, one)[t]).epsilon(1e-12));
  }
}

TEST_CASE("distance_table: columns equal single-source runs, identical for 1, 2 and 0 threads") {
  const auto m = test::jittered_icosphere(3, 5);
  const auto legacy = test::to_legacy(m);
  const dijkstra_geodesics<double> geo(m);
  const dijkstra_geodesics<float> geol(legacy);
  std::vector<index_t> src;
  for (index_t k = 0; k < 23; ++k) src.push_back((k * 97) % m.V.rows());
  src.push_back(src.front());  // repeats allowed
  const auto T1 = geo.distance_table(src, 1);
  const auto T2 = geo.distance_table(src, 2);
  const auto T0 = geo.distance_table(src, 0);
  CHECK(T1.rows() == m.V.rows());
  CHECK(T1.cols() == index_t(src.size()));
  CHECK(T1 == T2);
  CHECK(T1 == T0);
  for (std::size_t k = 0; k < src.size(); k += 5) CHECK(T1.col(index_t(k)) == geo.distances_from(src[k]));
  const auto L1 = geol.distance_table(src, 1);
  const auto L2 = geol.distance_table(src, 2);
  CHECK(L1 == L2);
  CHECK((L1.cast<double>() - T1).cwiseAbs().maxCoeff() < 1e-4);
  // symmetry d(a, b) = d(b, a)
  CHECK(T1(src[3], 7) == doctest::Approx(T1(src[7], 3)).epsilon(1e-12));
}

TEST_CASE("full runs through the bucket queue equal the heap's runs to the last bit") {
  // update_distances from +infinity always runs the heap; distances_from and distance_table use the buckets here.
  const auto heap_run = [](const dijkstra_geodesics<double>& geo, const std::vector<index_t>& sources) {
    Eigen::VectorXd d = Eigen::VectorXd::Constant(geo.num_vertices(), std::numeric_limits<double>::infinity());
    typename dijkstra_geodesics<double>::workspace ws;
    for (const index_t s : sources) geo.update_distances(s, d, ws);
    return d;
  };
  std::mt19937_64 rng(777);
  for (int trial = 0; trial < 4; ++trial) {
    const auto m = test::jittered_icosphere(3, rng(), 0.3);
    const dijkstra_geodesics<double> geo(m.V, m.F);
    REQUIRE(geo.uses_buckets());
    std::uniform_int_distribution<index_t> pick(0, m.V.rows() - 1);
    std::vector<index_t> sources;
    for (int k = 0; k < 16; ++k) sources.push_back(pick(rng));
    const auto table = geo.distance_table(sources, 2);
    for (std::size_t k = 0; k < sources.size(); ++k) CHECK(table.col(index_t(k)) == heap_run(geo, {sources[k]}));
    const std::vector<index_t> several(sources.begin(), sources.begin() + 3);
    CHECK(geo.distances_from(several) == heap_run(geo, several));
  }
}

TEST_CASE("the heap serves meshes whose shortest edge is tiny against their size, float and graphs alone") {
  auto m = test::grid_mesh(30, 30, 1.0);
  const dijkstra_geodesics<double> even(m.V, m.F);
  CHECK(even.uses_buckets());
  CHECK_FALSE(dijkstra_geodesics<double>(edge_graph<double>(m.V, m.F)).uses_buckets());
  const Eigen::MatrixX3f Vf = m.V.cast<float>();
  CHECK_FALSE(dijkstra_geodesics<float>(Vf, m.F).uses_buckets());
  // One vertex moved next to its neighbour: the shortest edge is 1e-6 of the grid's size.
  m.V.row(1) = m.V.row(0) + Eigen::RowVector3d(1e-6 * 30, 0, 0);
  const dijkstra_geodesics<double> skewed(m.V, m.F);
  CHECK_FALSE(skewed.uses_buckets());
  const std::vector<index_t> source = {17};
  CHECK((skewed.distances_from(17) - bellman_ford(m, source)).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("update_distances lowers an existing field to the multi-source distance") {
  const auto m = test::jittered_icosphere(2, 9);
  const dijkstra_geodesics<double> geo(m.V, m.F);
  Eigen::VectorXd d = geo.distances_from(3);
  geo.update_distances(40, d);
  const std::vector<index_t> both = {3, 40};
  CHECK((d - geo.distances_from(both)).cwiseAbs().maxCoeff() == 0.0);
  geo.update_distances(40, d);  // idempotent
  CHECK((d - geo.distances_from(both)).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("visit_within visits exactly the ball, in increasing order, and stops on request") {
  const auto grid = test::grid_mesh(10, 10);
  const dijkstra_geodesics<double> geo(grid.V, grid.F);
  const auto d = geo.distances_from(60);
  dijkstra_geodesics<double>::workspace ws;
  for (int rep = 0; rep < 2; ++rep) {  // the workspace is reusable
    std::vector<index_t> seen;
    double last = -1;
    bool ordered = true;
    geo.visit_within(
        60, 2.5,
        [&](std::int32_t v, double dv) {
          seen.push_back(v);
          ordered &= dv >= last && dv == d[v];
          last = dv;
          return true;
        },
        ws);
    CHECK(ordered);
    CHECK(seen.front() == 60);
    CHECK(std::size_t((d.array() <= 2.5).count()) == seen.size());
  }
  int calls = 0;
  geo.visit_within(60, 100.0, [&](std::int32_t, double) { return ++calls < 3; }, ws);
  CHECK(calls == 3);
}

TEST_CASE("Dijkstra: several components give +inf, never NaN") {
  auto a = test::octahedron();
  triangle_mesh<double> m;
  m.V.resize(12, 3);
  m.V << a.V, (a.V.array() + 5.0).matrix();
  m.F.resize(16, 3);
  m.F << a.F, (a.F.array() + 6).matrix();
  const dijkstra_geodesics<double> geo(m.V, m.F);
  const auto d = geo.distances_from(0);
  CHECK(d.head(6).allFinite());
  CHECK((d.tail(6).array() == std::numeric_limits<double>::infinity()).all());
  CHECK(geo.geodesic_distance(0, 7) == std::numeric_limits<double>::infinity());
}

TEST_CASE("Dijkstra: one test per invalid_input reason") {
  triangle_mesh<double> empty;
  test::expect_invalid([&] { (void)dijkstra_geodesics<double>(empty.V, empty.F); }, input_error::empty, no_index);
  test::expect_invalid([&] { (void)dijkstra_geodesics<double>(test::with_nan_vertex()); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)dijkstra_geodesics<float>(test::to_legacy(test::with_bad_index())); },
                       input_error::bad_face, 3);
  const dijkstra_geodesics<double> geo(test::octahedron());
  test::expect_invalid([&] { (void)geo.distances_from(6); }, input_error::bad_parameter, 6);
  test::expect_invalid([&] { (void)geo.distances_from(-1); }, input_error::bad_parameter, -1);
  test::expect_invalid([&] { (void)geo.distances_from(std::span<const index_t>()); }, input_error::empty);
  const std::vector<index_t> src = {0, 9};
  test::expect_invalid([&] { (void)geo.distance_table(src); }, input_error::bad_parameter, 9);
  const std::vector<index_t> ok = {0, 1};
  test::expect_invalid([&] { (void)geo.distance_table(ok, -1); }, input_error::bad_parameter);
  test::expect_invalid([&] { (void)geo.distance_table(std::span<const index_t>()); }, input_error::empty);
  test::expect_invalid([&] { (void)geo.geodesic_distance(0, 6); }, input_error::bad_parameter, 6);
  Eigen::VectorXd wrong(3);
  test::expect_invalid([&] { geo.update_distances(0, wrong); }, input_error::size_mismatch);
  dijkstra_geodesics<double>::workspace ws;
  test::expect_invalid([&] { geo.visit_within(0, -1.0, [](std::int32_t, double) { return true; }, ws); },
                       input_error::bad_parameter);
}
