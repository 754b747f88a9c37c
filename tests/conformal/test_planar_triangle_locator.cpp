// SPDX-License-Identifier: MIT
#include <complex>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include "../blended/blended_fixtures.hpp"
#include "shapestruct/conformal/mid_edge_flattening.hpp"
#include "shapestruct/conformal/planar_triangle_locator.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

using namespace shapestruct;

namespace {
using complex = std::complex<double>;

// A 5 x 5 grid of points split into triangles, corner order alternating so that the walk has to cope with both.
planar_triangle_locator<double> grid_locator(std::vector<complex> pts) {
  Eigen::Matrix<index_t, Eigen::Dynamic, 3> tris(32, 3);
  index_t t = 0;
  for (index_t y = 0; y < 4; ++y)
    for (index_t x = 0; x < 4; ++x) {
      const index_t a = 5 * y + x, b = a + 1, c = a + 5, d = a + 6;
      tris.row(t++) << a, b, d;
      tris.row(t++) << a, c, d;  // clockwise: the walk must not rely on one corner order
    }
  return planar_triangle_locator<double>(std::move(pts), std::move(tris));
}

std::vector<complex> grid_points() {
  std::vector<complex> pts;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) pts.emplace_back(x, y);
  return pts;
}

void require_same(const planar_triangle_locator<double>::hit& a, const planar_triangle_locator<double>::hit& b) {
  REQUIRE(a.triangle == b.triangle);
  CHECK(a.bary == b.bary);
  CHECK(a.distance == b.distance);
}
}  // namespace

TEST_CASE("planar_triangle_locator::locate_from answers as locate, from any hint") {
  const auto loc = grid_locator(grid_points());
  for (index_t t = 0; t < loc.num_triangles(); ++t) CHECK(loc.walkable(t));  // no fold: the walk may answer anywhere
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-1.0, 5.0);
  for (int i = 0; i < 2000; ++i) {
    const complex q(coord(rng), coord(rng));  // inside, on edges (rarely), and outside the grid
    for (index_t start : {no_index, index_t(0), index_t(13), index_t(31), index_t(99)}) {
      index_t hint = start;
      const auto walked = loc.locate_from(q, hint);
      require_same(walked, loc.locate(q));
      CHECK(hint == walked.triangle);
    }
  }
  // Points on a shared edge and at a shared corner: the tolerance band is left to the tree.
  for (const complex q : {complex(1.5, 1.5), complex(2, 2), complex(2, 1.25)}) {
    index_t hint = 0;
    require_same(loc.locate_from(q, hint), loc.locate(q));
  }
  index_t hint = 5;
  require_same(loc.locate_from(complex(std::nan(""), 1), hint), loc.locate(complex(std::nan(""), 1)));
}

TEST_CASE("planar_triangle_locator::locate_from leaves folded regions to the tree") {
  // Pulling the interior point (1, 1) past its neighbour (3, 1) inverts triangles of its fan: they overlap
  // correctly oriented ones, and only the tree's order decides which answers there.
  auto pts = grid_points();
  pts[6] = complex(3.4, 1.1);
  const auto loc = grid_locator(pts);
  index_t walkable = 0;
  for (index_t t = 0; t < loc.num_triangles(); ++t) walkable += loc.walkable(t);
  CHECK(walkable > 0);                      // away from the fold the walk still answers
  CHECK(walkable < loc.num_triangles());    // but not in or over the fold
  for (index_t t : {0, 1, 3, 8, 10, 11}) CHECK_FALSE(loc.walkable(t));  // the moved point's fan
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-0.5, 4.5);
  for (int i = 0; i < 4000; ++i) {
    const complex q(coord(rng), coord(rng));
    for (index_t start : {index_t(0), index_t(2), index_t(9), index_t(20), index_t(31)}) {
      index_t hint = start;
      require_same(loc.locate_from(q, hint), loc.locate(q));
    }
  }
}

TEST_CASE("mid_edge_flattening::locate from a hint gives locate's surface point") {
  for (const auto& m : {test::armed_sphere(3), make_icosphere<double>(3)}) {
    const mid_edge_flattening<double> fl(m.V, m.F);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    index_t hint = no_index;
    // Images of every vertex under a slight rotation and scaling of the plane, visited in index order: the walk
    // starts from the previous answer, as blending does.
    const complex motion = std::polar(1.02, 0.01);
    for (index_t v = 0; v < m.V.rows(); ++v) {
      const complex z = motion * fl.coordinate(v) + complex(1e-3 * unit(rng), 0);
      const auto walked = fl.locate(z, hint);
      const auto direct = fl.locate(z);
      REQUIRE(walked.face == direct.face);
      CHECK(walked.bary == direct.bary);
    }
    // Far outside the image and at infinity: clamped by the tree.
    for (const complex z : {complex(1e6, -1e6), complex(std::numeric_limits<double>::infinity(), 0)}) {
      const auto walked = fl.locate(z, hint);
      const auto direct = fl.locate(z);
      CHECK(walked.face == direct.face);
      CHECK(walked.bary == direct.bary);
    }
  }
}
