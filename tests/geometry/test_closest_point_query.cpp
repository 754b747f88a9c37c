// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "shapestruct/geometry/closest_point_query.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * (double(rng() >> 11) * 0x1.0p-53);
}

Eigen::Matrix<double, Eigen::Dynamic, 3> random_queries(index_t n, double extent, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::Matrix<double, Eigen::Dynamic, 3> Q(n, 3);
  for (index_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) Q(i, d) = uniform(rng, -extent, extent);
  return Q;
}

// An independent oracle for one triangle: project onto the plane, keep the projection if its barycentric
// coordinates (from the 2x2 normal equations) are all >= 0, otherwise the best of the three edges.
double oracle_sq_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
  auto seg = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
    const Eigen::Vector3d e = y - x;
    const double ee = e.squaredNorm();
    const double t = ee > 0 ? std::clamp((p - x).dot(e) / ee, 0.0, 1.0) : 0.0;
    return (p - (x + t * e)).squaredNorm();
  };
  double best = std::min({seg(a, b), seg(b, c), seg(c, a)});
  const Eigen::Vector3d u = b - a, v = c - a, w = p - a;
  const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), det = uu * vv - uv * uv;
  if (det > 1e-12 * uu * vv) {
    const double s = (vv * w.dot(u) - uv * w.dot(v)) / det, t = (uu * w.dot(v) - uv * w.dot(u)) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) best = std::min(best, (p - (a + s * u + t * v)).squaredNorm());
  }
  return best;
}

// Brute force over all faces with the library's tie rule (lowest face index among equal distances).
closest_point_result<double> brute_force(const triangle_mesh<double>& m, const Eigen::Vector3d& p) {
  closest_point_result<double> best;
  for (index_t f = 0; f < m.F.rows(); ++f) {
    const auto r = closest_point_on_triangle<double>(p, m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(),
                                                     m.V.row(m.F(f, 2)).transpose());
    if (r.sq_distance < best.sq_distance) {
      best.sq_distance = r.sq_distance;
      best.point = r.point;
      best.location.face = f;
      best.location.bary = r.bary;
    }
  }
  return best;
}

// A soup of random triangles plus degenerate ones: collinear, two coincident corners, all three coincident.
triangle_mesh<double> soup_with_degenerates(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const index_t n = 300;
  triangle_mesh<double> m;
  m.V.resize(3 * n + 9, 3);
  m.F.resize(n + 3, 3);
  for (index_t f = 0; f < n; ++f) {
    Eigen::Vector3d c(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    for (int k = 0; k < 3; ++k) {
      for (int d = 0; d < 3; ++d) m.V(3 * f + k, d) = c[d] + uniform(rng, -0.2, 0.2);
      m.F(f, k) = 3 * f + k;
    }
  }
  const index_t b = 3 * n;
  m.V.row(b + 0) << 0, 0, 0;  // collinear
  m.V.row(b + 1) << 1, 1, 1;
  m.V.row(b + 2) << 2, 2, 2;
  m.V.row(b + 3) << -1, 0.5, 0.3;  // two coincident corners
  m.V.row(b + 4) << -1, 0.5, 0.3;
  m.V.row(b + 5) << -0.5, 0.9, 0.3;
  m.V.row(b + 6) << 0.7, -0.7, 0.1;  // all three coincident
  m.V.row(b + 7) << 0.7, -0.7, 0.1;
  m.V.row(b + 8) << 0.7, -0.7, 0.1;
  m.F.row(n) << b, b + 1, b + 2;
  m.F.row(n + 1) << b + 3, b + 4, b + 5;
  m.F.row(n + 2) << b + 6, b + 7, b + 8;
  return m;
}

void check_against_brute_force(const triangle_mesh<double>& m, const Eigen::Matrix<double, Eigen::Dynamic, 3>& Q) {
  const closest_point_query<double> cpq(m.V, m.F, {.leaf_size = 3});
  for (index_t i = 0; i < Q.rows(); ++i) {
    const Eigen::Vector3d p = Q.row(i).transpose();
    const auto got = cpq.query(p);
    const auto want = brute_force(m, p);
    REQUIRE(got.location.valid());
    CHECK(got.location.face == want.location.face);
    CHECK(got.sq_distance == want.sq_distance);
    CHECK(std::isfinite(got.sq_distance));
    CHECK(got.location.bary.sum() == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(got.location.bary.minCoeff() >= -1e-12);
    CHECK((got.location.position(m.V, m.F) - got.point).norm() < 1e-12);
    // The exact test agrees with an independently derived per-triangle oracle.
    const index_t f = got.location.face;
    const double oracle = oracle_sq_distance(p, m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(),
                                             m.V.row(m.F(f, 2)).transpose());
    CHECK(got.sq_distance == doctest::Approx(oracle).epsilon(1e-9).scale(1e-12));
  }
}

}  // namespace

TEST_CASE("closest_point_on_triangle equals an independent oracle in every Voronoi region") {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0.5, 1.5, 0.2);
  const auto Q = random_queries(3000, 3.0, 7);
  for (index_t i = 0; i < Q.rows(); ++i) {
    const Eigen::Vector3d p = Q.row(i).transpose();
    const auto r = closest_point_on_triangle<double>(p, a, b, c);
    CHECK(r.sq_distance == doctest::Approx(oracle_sq_distance(p, a, b, c)).epsilon(1e-10).scale(1e-12));
    CHECK((r.bary[0] * a + r.bary[1] * b + r.bary[2] * c - r.point).norm() < 1e-12);
  }
  // Degenerate triangles: finite answers, equal to the segment oracle.
  const Eigen::Vector3d z(1, 1, 1);
  for (index_t i = 0; i < 200; ++i) {
    const Eigen::Vector3d p = Q.row(i).transpose();
    const auto coincident = closest_point_on_triangle<double>(p, z, z, z);
    CHECK(coincident.sq_distance == doctest::Approx((p - z).squaredNorm()));
    CHECK(coincident.bary.allFinite());
    const auto collinear = closest_point_on_triangle<double>(p, a, z, Eigen::Vector3d(2 * z));
    CHECK(collinear.bary.allFinite());
    CHECK(collinear.sq_distance ==
          doctest::Approx(oracle_sq_distance(p, a, z, Eigen::Vector3d(2 * z))).epsilon(1e-10).scale(1e-12));
  }
}

TEST_CASE("closest_point_query equals brute force over all triangles") {
  SUBCASE("icosphere, random queries inside and outside") {
    check_against_brute_force(make_icosphere(3), random_queries(400, 1.6, 1));
  }
  SUBCASE("soup with degenerate faces") {
    const auto m = soup_with_degenerates(3);
    check_against_brute_force(m, random_queries(400, 1.5, 2));
    // Queries near the degenerate faces themselves.
    Eigen::Matrix<double, Eigen::Dynamic, 3> near(3, 3);
    near << 1.05, 1.0, 0.95, -0.9, 0.6, 0.35, 0.7, -0.69, 0.12;
    check_against_brute_force(m, near);
  }
  SUBCASE("on-surface queries have zero distance") {
    const auto m = make_icosphere(2);
    const closest_point_query<double> cpq(m);
    std::mt19937_64 rng(5);
    for (index_t f = 0; f < m.F.rows(); f += 3) {
      const double r1 = uniform(rng, 0, 1), r2 = uniform(rng, 0, 1);
      const double s = std::sqrt(r1);
      const surface_point<double> sp{f, Eigen::Vector3d(1 - s, s * (1 - r2), s * r2)};
      const Eigen::Vector3d p = sp.position(m.V, m.F);
      const auto got = cpq.query(p);
      CHECK(got.sq_distance < 1e-24);
      CHECK((got.point - p).norm() < 1e-12);
    }
    // Vertices lie on several faces: the lowest-index incident face wins.
    for (index_t v = 0; v < m.V.rows(); v += 5) {
      const auto got = cpq.query(m.V.row(v));
      CHECK(got.sq_distance == 0.0);
      index_t lowest = m.F.rows();
      for (index_t f = 0; f < m.F.rows(); ++f)
        if (m.F(f, 0) == v || m.F(f, 1) == v || m.F(f, 2) == v) lowest = std::min(lowest, f);
      CHECK(got.location.face == lowest);
    }
  }
}

TEST_CASE("closest_point_query: batch equals single, identical for 1 and 2 threads, both mesh models") {
  const auto ico = make_icosphere(3);
  const auto legacy = test::to_legacy(ico);
  const auto gathered = to_triangle_mesh<double>(legacy);  // the legacy mesh's float coordinates
  const closest_point_query<double> from_legacy(legacy);
  const closest_point_query<double> from_matrices(gathered.V, gathered.F);
  const closest_point_query<float> single_precision(legacy);
  const auto Q = random_queries(1500, 1.5, 9);  // >= 1024: the Morton-ordered batch path
  const auto b1 = from_legacy.query_batch(Q, 1);
  const auto b2 = from_legacy.query_batch(Q, 2);
  CHECK(b1.faces == b2.faces);
  CHECK(b1.bary == b2.bary);
  CHECK(b1.sq_distances == b2.sq_distances);
  const auto bm = from_matrices.query_batch(Q, 2);
  CHECK(bm.faces == b1.faces);
  CHECK(bm.points == b1.points);
  const auto bf = single_precision.query_batch(Q.cast<float>(), 2);
  for (index_t i = 0; i < Q.rows(); ++i) {
    const auto s = from_legacy.query(Q.row(i));
    CHECK(b1.faces[i] == s.location.face);
    CHECK(b1.sq_distances[i] == s.sq_distance);
    CHECK(b1.location(i).face == s.location.face);
    CHECK(std::sqrt(double(bf.sq_distances[i])) == doctest::Approx(std::sqrt(s.sq_distance)).epsilon(1e-4).scale(1e-3));
  }
  const auto once = closest_points(legacy, Q, 2);
  CHECK(once.faces == b1.faces);
}

TEST_CASE("closest_point_query: one test per invalid_input reason") {
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
    CHECK(reason_of([&] { closest_point_query<double> q(m); }).first == input_error::empty);
  }
  SUBCASE("non_finite vertex") {
    const auto m = test::with_nan_vertex();
    CHECK(reason_of([&] { closest_point_query<double> q(m); }) == std::make_pair(input_error::non_finite, index_t(2)));
  }
  SUBCASE("bad_face") {
    const auto m = test::with_bad_index();
    CHECK(reason_of([&] { closest_point_query<double> q(m); }) == std::make_pair(input_error::bad_face, index_t(3)));
  }
  SUBCASE("non_finite query") {
    const closest_point_query<double> q(test::octahedron());
    auto Q = random_queries(6, 1, 1);
    Q(4, 0) = std::numeric_limits<double>::infinity();
    CHECK(reason_of([&] { (void)q.query_batch(Q, 2); }) == std::make_pair(input_error::non_finite, index_t(4)));
    CHECK(reason_of([&] { (void)q.query(Eigen::Vector3d(std::nan(""), 0, 0)); }).first == input_error::non_finite);
  }
  SUBCASE("bad_parameter") {
    const auto m = test::octahedron();
    CHECK(reason_of([&] { closest_point_query<double> q(m, {.leaf_size = 0}); }).first == input_error::bad_parameter);
    const closest_point_query<double> q(m);
    CHECK(reason_of([&] { (void)q.query(Eigen::Vector2d(0, 0)); }).first == input_error::bad_parameter);
    CHECK(reason_of([&] { (void)q.query_batch(random_queries(2, 1, 1), -2); }).first == input_error::bad_parameter);
  }
}
