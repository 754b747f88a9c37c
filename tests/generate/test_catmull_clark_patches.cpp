// SPDX-License-Identifier: MIT
// catmull_clark_patches: counts, shared patch borders, known limit behaviour on a cube, and its errors.
#include <doctest/doctest.h>

#include <set>

#include "shapestruct/generate/catmull_clark_patches.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

using namespace shapestruct;

namespace {

/// A cube as a quad cage (corners k = x + 2y + 4z as in make_box), counter-clockwise from outside.
void cube(std::vector<Eigen::Vector3d>& X, std::vector<std::array<index_t, 4>>& Q) {
  X.clear();
  for (int k = 0; k < 8; ++k) X.emplace_back((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
  Q = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
}

}  // namespace

TEST_CASE("catmull_clark_patches on a cube: counts, shared borders, and a rounded limit inside the cage") {
  std::vector<Eigen::Vector3d> X;
  std::vector<std::array<index_t, 4>> Q;
  cube(X, Q);
  for (int levels = 0; levels <= 4; ++levels) {
    CAPTURE(levels);
    const auto g = catmull_clark_patches(X, Q, std::vector<bool>(6, true), levels);
    const int n = 1 << levels;
    CHECK(g.size == n);
    std::set<index_t> used;
    for (const auto& grid : g.grid) {
      REQUIRE(grid.size() == static_cast<std::size_t>((n + 1) * (n + 1)));
      used.insert(grid.begin(), grid.end());
    }
    // A closed quad mesh with F = 6 * 4^L quads has E = 2F edges and, by Euler, V = F + 2 vertices.
    CHECK(used.size() == static_cast<std::size_t>(6 * n * n + 2));
    // Corners of each grid are the (moved) cage corners, in the documented order.
    for (std::size_t q = 0; q < 6; ++q) {
      CHECK(g.grid[q][0] == Q[q][0]);
      CHECK(g.grid[q][static_cast<std::size_t>(n)] == Q[q][1]);
      CHECK(g.grid[q][static_cast<std::size_t>(n * (n + 1) + n)] == Q[q][2]);
      CHECK(g.grid[q][static_cast<std::size_t>(n * (n + 1))] == Q[q][3]);
    }
    // Bilinear evaluation agrees across a shared edge: quad 0 (-z) and quad 2 (-y) share the edge 0-1.
    for (double t = 0; t <= 1.0; t += 0.125) {
      // Edge 0 -> 1 is v = 0 of quad 2 (corners 0, 1, ...) and u = 0 of quad 0 (corners 0, 2, 3, 1: 0 -> 1 is v).
      const Eigen::Vector3d a = g.evaluate(2, t, 0), b = g.evaluate(0, 0, t);
      CHECK((a - b).norm() < 1e-12);
    }
    for (const auto& p : g.positions) CHECK(p.cwiseAbs().maxCoeff() <= 1.0 + 1e-12);
    if (levels == 4) {
      // Oracle: the limit of a valence-n vertex is (n^2 P + 4 sum(edge neighbours) + sum(diagonal
      // neighbours)) / (n (n + 5)); for the cube corner (1,1,1) that is (9 + 4 - 1) / 24 = 1/2 per coordinate.
      // Four steps get within 1e-3 of it.
      CHECK(std::abs(g.positions[7].x() - g.positions[7].y()) < 1e-12);
      CHECK(std::abs(g.positions[7].x() - 0.5) < 1e-3);
      // Face centres of the cube stay on the faces' planes' axis and move inwards.
      const Eigen::Vector3d centre = g.evaluate(1, 0.5, 0.5);
      CHECK(std::abs(centre.x()) < 1e-12);
      CHECK(std::abs(centre.y()) < 1e-12);
      CHECK(centre.z() > 0.7);
      CHECK(centre.z() < 1.0);
    }
  }
}

TEST_CASE("catmull_clark_patches rejects bad levels and open cages") {
  std::vector<Eigen::Vector3d> X;
  std::vector<std::array<index_t, 4>> Q;
  cube(X, Q);
  try {
    (void)catmull_clark_patches(X, Q, std::vector<bool>(6, true), 7);
    FAIL("expected invalid_input");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == input_error::bad_parameter);
  }
  std::vector<bool> open(6, true);
  open[3] = false;  // remove the +y quad: its four edges now have one quad each
  try {
    (void)catmull_clark_patches(X, Q, open, 1);
    FAIL("expected invalid_input");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == input_error::non_manifold);
    CHECK(e.element() >= 0);
  }
}
