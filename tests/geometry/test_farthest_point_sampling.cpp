// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/adapters/eigen_points.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {
template <class S>
void check_fps_properties(const farthest_point_result<S>& r, index_t count) {
  REQUIRE(index_t(r.indices.size()) == count);
  REQUIRE(r.radii.size() == r.indices.size());
  CHECK(std::set<index_t>(r.indices.begin(), r.indices.end()).size() == r.indices.size());  // distinct
  for (std::size_t k = 1; k < r.radii.size(); ++k) CHECK(r.radii[k] <= r.radii[k - 1]);
}
}  // namespace

TEST_CASE("Euclidean FPS: radii non-increasing, every point within the final radius, picks are far apart") {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  matrix_x3<double> P(2000, 3);
  for (index_t i = 0; i < P.rows(); ++i) P.row(i) << u(rng), u(rng), u(rng);
  const auto r = farthest_point_sampling(P, 50, 7);
  check_fps_properties(r, 50);
  CHECK(r.indices[0] == 7);
  for (index_t i = 0; i < P.rows(); ++i) {
    double best = 1e300;
    for (const index_t s : r.indices) best = std::min(best, (P.row(i) - P.row(s)).norm());
    CHECK(best <= r.radii.back() + 1e-12);
  }
  // Greedy max-min: every pick is at least the final radius from all earlier picks.
  for (std::size_t a = 0; a < r.indices.size(); ++a)
    for (std::size_t b = 0; b < a; ++b) CHECK((P.row(r.indices[a]) - P.row(r.indices[b])).norm() >= r.radii.back());
  // the second pick is the farthest point from the first
  index_t far = 0;
  (P.rowwise() - P.row(7)).rowwise().norm().maxCoeff(&far);
  CHECK(r.indices[1] == far);
}

TEST_CASE("Euclidean FPS on a triangle_mesh's vertices (PointSet model) and float points agree") {
  const auto ico = make_icosphere(3);
  const auto a = farthest_point_sampling(ico, 12);
  const matrix_x3<float> Pf = ico.V.cast<float>();
  const auto b = farthest_point_sampling(Pf, 12);
  check_fps_properties(a, 12);
  CHECK(a.indices.size() == b.indices.size());
  CHECK(a.radii.back() == doctest::Approx(double(b.radii.back())).epsilon(1e-5));
}

TEST_CASE("geodesic FPS: properties hold and the incremental field equals full Dijkstra, on both mesh models") {
  const auto m = test::jittered_icosphere(3, 4, 0.03);
  const auto legacy = test::to_legacy(m);
  const dijkstra_geodesics<double> geo(m.V, m.F);
  const auto r = geodesic_farthest_point_sampling(geo, 40, 0);
  const auto rl = geodesic_farthest_point_sampling(legacy, 40, 0);
  const auto rv = geodesic_farthest_point_sampling(m.V, m.F, 40, 0);
  check_fps_properties(r, 40);
  check_fps_properties(rl, 40);
  CHECK(rv.indices == r.indices);
  CHECK(rl.indices.front() == 0);
  CHECK(double(rl.radii.back()) == doctest::Approx(r.radii.back()).epsilon(0.05));
  const auto cover = geo.distances_from(r.indices);
  CHECK(cover.maxCoeff() == doctest::Approx(r.radii.back()).epsilon(1e-12));  // every vertex within the radius
  // each radius is the covering radius of the prefix
  for (std::size_t k : {std::size_t(0), std::size_t(9), std::size_t(25)}) {
    const std::vector<index_t> prefix(r.indices.begin(), r.indices.begin() + std::ptrdiff_t(k + 1));
    CHECK(geo.distances_from(prefix).maxCoeff() == doctest::Approx(r.radii[k]).epsilon(1e-12));
  }
}

TEST_CASE("FPS: count 0 gives nothing, count = #P picks everything with final radius 0") {
  const auto oct = test::octahedron();
  CHECK(farthest_point_sampling(oct.V, 0).indices.empty());
  const auto all = geodesic_farthest_point_sampling(oct, 6, 2);
  check_fps_properties(all, 6);
  CHECK(all.radii.back() == 0.0);
  CHECK(all.indices[1] == 3);  // -y is the only vertex two edges from +y
}

TEST_CASE("FPS: one test per invalid_input reason") {
  const auto oct = test::octahedron();
  matrix_x3<double> none(0, 3);
  test::expect_invalid([&] { (void)farthest_point_sampling(none, 1); }, input_error::empty);
  test::expect_invalid([&] { (void)farthest_point_sampling(test::with_nan_vertex().V, 1); }, input_error::non_finite,
                       2);
  test::expect_invalid([&] { (void)farthest_point_sampling(oct.V, 7); }, input_error::bad_parameter);
  test::expect_invalid([&] { (void)farthest_point_sampling(oct.V, -1); }, input_error::bad_parameter);
  test::expect_invalid([&] { (void)farthest_point_sampling(oct.V, 2, 6); }, input_error::bad_parameter, 6);
  triangle_mesh<double> empty;
  test::expect_invalid([&] { (void)geodesic_farthest_point_sampling(empty, 1); }, input_error::empty);
  test::expect_invalid([&] { (void)geodesic_farthest_point_sampling(test::to_legacy(test::with_bad_index()), 1); },
                       input_error::bad_face, 3);
  test::expect_invalid([&] { (void)geodesic_farthest_point_sampling(oct, 7); }, input_error::bad_parameter);
  test::expect_invalid([&] { (void)geodesic_farthest_point_sampling(oct, 3, -2); }, input_error::bad_parameter, -2);
}
