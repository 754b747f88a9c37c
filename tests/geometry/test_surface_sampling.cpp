// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "shapestruct/geometry/surface_sampling.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

// A fan of 20 triangles in the plane z = 0 with areas proportional to 1, 2, ..., 20, followed by two
// degenerate faces (collinear and coincident corners) that must never be sampled.
triangle_mesh<double> uneven_fan() {
  triangle_mesh<double> m;
  const index_t n = 20;
  m.V.resize(3 * n + 6, 3);
  m.F.resize(n + 2, 3);
  double x = 0;
  for (index_t f = 0; f < n; ++f) {
    const double base = double(f + 1);  // height 1, so area = base / 2
    m.V.row(3 * f) << x, 0, 0;
    m.V.row(3 * f + 1) << x + base, 0, 0;
    m.V.row(3 * f + 2) << x, 1, 0;
    m.F.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
    x += base + 1;
  }
  const index_t b = 3 * n;
  m.V.row(b) << 0, 5, 0;
  m.V.row(b + 1) << 1, 5, 0;
  m.V.row(b + 2) << 2, 5, 0;
  m.V.row(b + 3) << 3, 5, 0;
  m.V.row(b + 4) << 3, 5, 0;
  m.V.row(b + 5) << 3, 5, 0;
  m.F.row(n) << b, b + 1, b + 2;
  m.F.row(n + 1) << b + 3, b + 4, b + 5;
  return m;
}

double min_spacing(const matrix_x3<double>& P) {
  const knn_index<double> index(P);
  const auto nn = index.knn_batch(P, 2, 1);
  return std::sqrt(nn.sq_distances.col(1).minCoeff());
}

template <class Samples, class Mesh>
void check_consistent(const Samples& s, const Mesh& m, index_t count) {
  REQUIRE(s.size() == count);
  REQUIRE(s.faces.size() == count);
  for (index_t i = 0; i < count; ++i) {
    CHECK(s.bary.row(i).sum() == doctest::Approx(1.0).epsilon(1e-6));
    CHECK(s.bary.row(i).minCoeff() >= 0);
    CHECK((s.location(i).position(m.V, m.F) - s.points.row(i).transpose()).norm() < 1e-5);
    CHECK(s.normals.row(i).norm() == doctest::Approx(1.0).epsilon(1e-5));
  }
}

}  // namespace

TEST_CASE("sample_surface_random: exact count, consistent rows, deterministic per seed, two mesh models") {
  const auto ico = make_icosphere(3);
  const auto legacy = test::to_legacy(ico);
  const auto a = sample_surface_random<double>(ico.V, ico.F, 1000, {.seed = 7});
  check_consistent(a, ico, 1000);
  const auto again = sample_surface_random(ico, 1000, {.seed = 7});
  CHECK(again.points == a.points);
  CHECK(again.faces == a.faces);
  const auto other = sample_surface_random(ico, 1000, {.seed = 8});
  CHECK(other.faces != a.faces);
  // Outward normals on the sphere: the face normal is close to the position direction.
  for (index_t i = 0; i < a.size(); ++i) CHECK(a.normals.row(i).dot(a.points.row(i).normalized()) > 0.99);
  // legacy_mesh (float coordinates) gives the same faces and barycentrics, positions to float precision.
  const auto l = sample_surface_random(legacy, 1000, {.seed = 7});
  CHECK(l.faces == a.faces);
  CHECK((l.bary - a.bary).cwiseAbs().maxCoeff() == 0.0);
  CHECK((l.points - a.points).cwiseAbs().maxCoeff() < 1e-6);
  const auto lf = sample_surface_random<float>(legacy, 10, {.seed = 7});
  CHECK(lf.size() == 10);
  CHECK(sample_surface_random(ico, 0).size() == 0);
}

TEST_CASE("sample_surface_random: face frequencies are proportional to area (chi-square, fixed seed)") {
  const auto m = uneven_fan();
  const index_t n = 200000;
  const auto s = sample_surface_random(m, n, {.seed = 2024});
  std::vector<double> counts(std::size_t(m.F.rows()), 0.0);
  for (index_t i = 0; i < n; ++i) counts[std::size_t(s.faces[i])] += 1;
  CHECK(counts[20] == 0);  // degenerate faces are never sampled
  CHECK(counts[21] == 0);
  double chi2 = 0;
  for (int f = 0; f < 20; ++f) {
    const double expected = double(n) * double(f + 1) / 210.0;  // 1 + 2 + ... + 20 = 210
    chi2 += (counts[std::size_t(f)] - expected) * (counts[std::size_t(f)] - expected) / expected;
  }
  // 19 degrees of freedom: P(chi2 > 43.8) = 0.001. Sampling faces uniformly instead would give chi2 ~ 1e5.
  CHECK(chi2 < 43.8);
  // Within a face the density is uniform: the corner sub-triangle {bary[0] > 1/2} holds a quarter of the area.
  double corner = 0;
  for (index_t i = 0; i < n; ++i) corner += s.bary(i, 0) > 0.5 ? 1 : 0;
  CHECK(corner / double(n) == doctest::Approx(0.25).epsilon(0.02));
}

TEST_CASE("sample_surface_even: exact count, deterministic, larger minimum spacing than random") {
  const auto ico = make_icosphere(3);
  const auto legacy = test::to_legacy(ico);
  const index_t count = 800;
  const auto even = sample_surface_even(ico, count, {.seed = 3, .threads = 1});
  check_consistent(even, ico, count);
  const auto even2 = sample_surface_even(ico, count, {.seed = 3, .threads = 2});
  CHECK(even2.points == even.points);
  const auto random = sample_surface_random(ico, count, {.seed = 3});
  const double d_even = min_spacing(even.points), d_random = min_spacing(random.points);
  MESSAGE("min spacing even " << d_even << " random " << d_random);
  CHECK(d_even > 3 * d_random);
  // Hexagonal packing of `count` points on the sphere's area has spacing 2 r_max; elimination should get a
  // good fraction of it (Yuksel reports minimum distances of about 0.7 * 2 r_max).
  const double area = 4 * 3.14159265358979;
  const double r_max = std::sqrt(area / (2 * std::sqrt(3.0) * double(count)));
  CHECK(d_even > 1.1 * r_max);
  const auto even_legacy = sample_surface_even(legacy, count, {.seed = 3});
  check_consistent(even_legacy, ico, count);
  CHECK(min_spacing(even_legacy.points) > 1.1 * r_max);
  CHECK(sample_surface_even(ico, 5, {.oversampling = 1.0}).size() == 5);
  CHECK(sample_surface_even(ico, 0).size() == 0);
}

TEST_CASE("surface sampling: one test per invalid_input reason") {
  auto reason_of = [](auto&& f) {
    try {
      f();
    } catch (const invalid_input& e) {
      return std::make_pair(e.reason(), e.element());
    }
    FAIL("no invalid_input thrown");
    return std::make_pair(input_error::empty, no_index);
  };
  SUBCASE("empty") {
    const triangle_mesh<double> m;
    CHECK(reason_of([&] { (void)sample_surface_random(m, 3); }).first == input_error::empty);
    CHECK(reason_of([&] { (void)sample_surface_even(m, 3); }).first == input_error::empty);
  }
  SUBCASE("non_finite") {
    const auto m = test::with_nan_vertex();
    CHECK(reason_of([&] { (void)sample_surface_random(m, 3); }) == std::make_pair(input_error::non_finite, index_t(2)));
  }
  SUBCASE("bad_face") {
    const auto m = test::with_bad_index();
    CHECK(reason_of([&] { (void)sample_surface_even(m, 3); }) == std::make_pair(input_error::bad_face, index_t(3)));
  }
  SUBCASE("degenerate_face: every face has zero area") {
    triangle_mesh<double> m;
    m.V.resize(4, 3);
    m.V << 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3;
    m.F.resize(2, 3);
    m.F << 0, 1, 2, 1, 2, 3;
    CHECK(reason_of([&] { (void)sample_surface_random(m, 3); }).first == input_error::degenerate_face);
    CHECK(reason_of([&] { (void)sample_surface_even(m, 3); }).first == input_error::degenerate_face);
  }
  SUBCASE("bad_parameter") {
    const auto m = test::octahedron();
    CHECK(reason_of([&] { (void)sample_surface_random(m, -1); }).first == input_error::bad_parameter);
    CHECK(reason_of([&] { (void)sample_surface_even(m, 4, {.oversampling = 0.5}); }).first ==
          input_error::bad_parameter);
    CHECK(reason_of([&] { (void)sample_surface_even(m, 4, {.threads = -1}); }).first == input_error::bad_parameter);
  }
}
