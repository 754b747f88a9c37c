// SPDX-License-Identifier: MIT
// triangulate_polygon: convex fans, concave ear clipping (planar and tilted/non-planar), degenerate input.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include <doctest/doctest.h>
#include <Eigen/Geometry>

#include "shapestruct/io/polygon_triangulation.hpp"

using namespace shapestruct;

namespace {
using tris = std::vector<std::array<index_t, 3>>;

/// Signed area of each triangle seen along `normal`, and their sum of absolute values.
double area_along(const matrix_x3<double>& V, const tris& t, const Eigen::Vector3d& normal, bool& all_positive) {
  double total = 0;
  all_positive = true;
  for (const auto& f : t) {
    const Eigen::Vector3d a = V.row(f[0]), b = V.row(f[1]), c = V.row(f[2]);
    const double s = 0.5 * (b - a).cross(c - a).dot(normal);
    all_positive = all_positive && s > 0;
    total += std::abs(s);
  }
  return total;
}

/// A star polygon (alternating radii 1 and 0.4) with k points: concave, area known in closed form.
matrix_x3<double> star(int k) {
  matrix_x3<double> V(2 * k, 3);
  for (int i = 0; i < 2 * k; ++i) {
    const double r = i % 2 ? 0.4 : 1.0, a = std::numbers::pi * i / k;
    V.row(i) << r * std::cos(a), r * std::sin(a), 0;
  }
  return V;
}
}  // namespace

TEST_CASE("triangulate_polygon: convex polygons are fanned, orientation kept") {
  matrix_x3<double> V(5, 3);
  for (int i = 0; i < 5; ++i) V.row(i) << std::cos(2 * std::numbers::pi * i / 5), std::sin(2 * std::numbers::pi * i / 5), 0;
  const std::vector<index_t> poly{0, 1, 2, 3, 4};
  tris out;
  triangulate_polygon(V, poly, out);
  REQUIRE(out.size() == 3);
  CHECK(out[0] == std::array<index_t, 3>{0, 1, 2});
  bool positive = false;
  CHECK(area_along(V, out, Eigen::Vector3d::UnitZ(), positive) == doctest::Approx(2.5 * std::sin(2 * std::numbers::pi / 5)));
  CHECK(positive);
}

TEST_CASE("triangulate_polygon: concave stars, also rotated out of the xy plane and slightly non-planar") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  for (int k : {3, 5, 8, 13}) {
    CAPTURE(k);
    matrix_x3<double> V = star(k);
    const double expected = k * 1.0 * 0.4 * std::sin(std::numbers::pi / k);  // 2k triangles of the star's fan
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    for (bool rotated : {false, true}) {
      matrix_x3<double> W = V;
      if (rotated) {
        W = (V * R.transpose()).eval();
        for (index_t i = 0; i < W.rows(); ++i) W(i, 0) += noise(rng);
      }
      std::vector<index_t> poly(static_cast<std::size_t>(2 * k));
      for (int i = 0; i < 2 * k; ++i) poly[static_cast<std::size_t>(i)] = i;
      tris out;
      triangulate_polygon(W, poly, out);
      REQUIRE(out.size() == static_cast<std::size_t>(2 * k - 2));
      bool positive = false;
      const Eigen::Vector3d n = rotated ? Eigen::Vector3d(R * Eigen::Vector3d::UnitZ()) : Eigen::Vector3d::UnitZ();
      CHECK(area_along(W, out, n, positive) == doctest::Approx(expected).epsilon(rotated ? 1e-2 : 1e-9));
      CHECK(positive);
    }
  }
}

TEST_CASE("triangulate_polygon: degenerate polygons never fail") {
  matrix_x3<double> V(6, 3);
  V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 1, 1, 0, 0, 0, 0;  // 0-3 collinear, 5 duplicates 0's position
  tris out;
  triangulate_polygon(V, std::vector<index_t>{0, 1, 2, 3}, out);  // collinear: fanned, 2 (flat) triangles
  CHECK(out.size() == 2);
  out.clear();
  triangulate_polygon(V, std::vector<index_t>{0, 0, 1, 1}, out);  // only 2 distinct corners
  CHECK(out.empty());
  triangulate_polygon(V, std::vector<index_t>{4, 1, 1, 2, 4}, out);  // repeats collapse to a triangle
  CHECK(out.size() == 1);
  out.clear();
  triangulate_polygon(V, std::vector<index_t>{}, out);
  triangulate_polygon(V, std::vector<index_t>{3}, out);
  CHECK(out.empty());
  // Self-intersecting bow tie: still k - 2 triangles.
  matrix_x3<double> B(4, 3);
  B << 0, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1, 0;
  triangulate_polygon(B, std::vector<index_t>{0, 1, 2, 3}, out);
  CHECK(out.size() == 2);
  // A triangle with a repeated corner is passed through unchanged (faithful to the file).
  out.clear();
  triangulate_polygon(V, std::vector<index_t>{1, 1, 2}, out);
  CHECK(out.size() == 1);
}

TEST_CASE("triangulate_polygon: huge non-convex polygons stay fast (fan above the ear-clipping limit)") {
  const int k = 5000;
  const matrix_x3<double> V = star(k);
  std::vector<index_t> poly(2 * k);
  for (int i = 0; i < 2 * k; ++i) poly[static_cast<std::size_t>(i)] = i;
  tris out;
  triangulate_polygon(V, poly, out);
  CHECK(out.size() == static_cast<std::size_t>(2 * k - 2));
}

TEST_CASE("triangulate_polygon: adversarial self-intersecting polygons cost O(n^2), not O(n^3)") {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  const std::size_t n = ear_clipping_max_corners;
  matrix_x3<double> V(static_cast<index_t>(n), 3);
  for (index_t i = 0; i < V.rows(); ++i) V.row(i) << u(rng), u(rng), 0.01 * u(rng);
  std::vector<index_t> poly(n);
  for (std::size_t i = 0; i < n; ++i) poly[i] = static_cast<index_t>(i);
  const auto start = std::chrono::steady_clock::now();
  for (int rep = 0; rep < 200; ++rep) {
    std::shuffle(poly.begin(), poly.end(), rng);
    tris out;
    triangulate_polygon(V, poly, out);
    REQUIRE(out.size() == n - 2);
  }
  // A hang guard, not a speed target (those live in bench/): 200 polygons x 4 n^2 tests is ~5 * 10^7 cheap
  // operations (about 0.2 s in a release build), O(n^3) clipping would be ~50 times more.
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(30));
}
