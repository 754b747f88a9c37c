// SPDX-License-Identifier: MIT
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include "blended/blended_fixtures.hpp"
#include "shapestruct/core/concepts/map_refiner.hpp"
#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/refine/no_refinement.hpp"
#include "shapestruct/refine/zoomout_refiner.hpp"

using namespace shapestruct;

static_assert(MapRefiner<zoomout_refiner>);
static_assert(MapRefiner<no_refinement>);
static_assert(MapRefiner<zoomout_refiner, float>);

namespace {

/// A map to `b` that sends v to truth[v] moved `steps` random edges away: right globally, wrong locally.
surface_map<double> noisy_map(const triangle_mesh<double>& b, const std::vector<index_t>& truth, int steps,
                              std::uint64_t seed) {
  std::vector<std::vector<index_t>> adjacent(static_cast<std::size_t>(b.V.rows()));
  std::vector<std::pair<index_t, int>> corner(static_cast<std::size_t>(b.V.rows()));
  for (index_t f = 0; f < b.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      adjacent[static_cast<std::size_t>(b.F(f, c))].push_back(b.F(f, (c + 1) % 3));
      corner[static_cast<std::size_t>(b.F(f, c))] = {f, c};
    }
  std::mt19937_64 rng(seed);
  surface_map<double> m;
  for (index_t t : truth) {
    for (int s = 0; s < steps; ++s) {
      const auto& n = adjacent[static_cast<std::size_t>(t)];
      t = n[static_cast<std::size_t>(rng() % n.size())];
    }
    surface_point<double> p;
    p.face = corner[static_cast<std::size_t>(t)].first;
    p.bary[corner[static_cast<std::size_t>(t)].second] = 1;
    m.points.push_back(p);
    m.nearest.push_back(t);
  }
  return m;
}

struct map_quality {
  double mean = 0;      ///< mean geodesic error / sqrt(area)
  double exact = 0;     ///< fraction of vertices sent to their true image
};

map_quality quality(const triangle_mesh<double>& b, const surface_map<double>& m, const std::vector<index_t>& truth) {
  const dijkstra_geodesics<double> geo(b.V, b.F);
  std::vector<index_t> pred(m.nearest.begin(), m.nearest.end());
  const auto e = benchmark_geodesic_errors(b.V, b.F, geo, std::span<const index_t>(pred), std::span<const index_t>(truth));
  map_quality q;
  q.mean = summarize_errors(std::span<const double>(e)).mean;
  for (std::size_t i = 0; i < truth.size(); ++i) q.exact += pred[i] == truth[i] ? 1.0 : 0.0;
  q.exact /= static_cast<double>(truth.size());
  return q;
}

zoomout_options small_options() {
  zoomout_options o;
  o.initial_size = 10;
  o.final_size = 40;
  o.step = 5;
  o.samples = 600;
  return o;
}

}  // namespace

TEST_CASE("zoomout_refiner: a locally scrambled map of an isometric copy becomes nearly exact") {
  const auto a = test::armed_sphere(4);  // 2,562 vertices
  std::vector<index_t> perm;
  const auto b = test::moved_and_permuted(a, perm, 7);
  const auto initial = noisy_map(b, perm, 4, 11);
  const auto before = quality(b, initial, perm);
  const auto refined = zoomout_refiner(small_options()).refine(a, b, initial, 2);
  REQUIRE(refined.source_size() == a.V.rows());
  const auto after = quality(b, refined, perm);
  MESSAGE("mean error " << before.mean << " -> " << after.mean << ", exact " << before.exact << " -> " << after.exact);
  CHECK(before.mean > 0.03);
  CHECK(after.mean < 0.25 * before.mean);
  CHECK(after.exact > 0.8);
  for (index_t v = 0; v < refined.source_size(); ++v) {
    const auto& p = refined.point(v);
    REQUIRE(p.valid());
    CHECK(p.nearest_corner(b.F) == refined.target_vertex(v));
  }
}

TEST_CASE("zoomout_refiner: the local final search agrees with the exhaustive one, whatever the thread count") {
  const auto a = test::armed_sphere(4);
  std::vector<index_t> perm;
  const auto b = test::moved_and_permuted(a, perm, 3);
  const auto initial = noisy_map(b, perm, 3, 5);
  auto o = small_options();
  const auto local = zoomout_refiner(o).refine(a, b, initial, 2);
  const auto local_one_thread = zoomout_refiner(o).refine(a, b, initial, 1);
  o.dense_search = zoomout_dense_search::exact;
  const auto exact = zoomout_refiner(o).refine(a, b, initial, 2);
  CHECK(local.nearest == local_one_thread.nearest);
  index_t same = 0;
  for (index_t v = 0; v < a.V.rows(); ++v) same += local.target_vertex(v) == exact.target_vertex(v) ? 1 : 0;
  CHECK(static_cast<double>(same) / static_cast<double>(a.V.rows()) > 0.98);
}

TEST_CASE("zoomout_refiner: bad options and a map of the wrong size are bad input") {
  const auto a = test::armed_sphere(3);
  const auto initial = noisy_map(a, std::vector<index_t>(static_cast<std::size_t>(a.V.rows()), 0), 0, 1);
  auto o = small_options();
  o.final_size = 5;  // below initial_size
  CHECK_THROWS_AS((void)zoomout_refiner(o).refine(a, a, initial, 1), invalid_input);
  surface_map<double> short_map = initial;
  short_map.points.pop_back();
  short_map.nearest.pop_back();
  try {
    (void)zoomout_refiner(small_options()).refine(a, a, short_map, 1);
    FAIL("expected invalid_input");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == input_error::size_mismatch);
  }
}

TEST_CASE("no_refinement returns the map it is given") {
  const auto a = test::armed_sphere(3);
  std::vector<index_t> perm;
  const auto b = test::moved_and_permuted(a, perm, 1);
  const auto m = noisy_map(b, perm, 2, 3);
  const auto r = no_refinement{}.refine(a, b, m, 1);
  CHECK(r.nearest == m.nearest);
}

TEST_CASE("zoomout_refiner with samples = 0 iterates on every vertex and still recovers the isometry") {
  const auto a = test::armed_sphere(3);  // 642 vertices
  std::vector<index_t> perm;
  const auto b = test::moved_and_permuted(a, perm, 9);
  auto o = small_options();
  o.samples = 0;
  const auto refined = zoomout_refiner(o).refine(a, b, noisy_map(b, perm, 2, 4), 2);
  CHECK(quality(b, refined, perm).exact > 0.8);
}
