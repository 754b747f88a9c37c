// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <random>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/geometry/connected_components.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

/// Appends b to a with its vertices shifted by `offset` along x.
triangle_mesh<double> concat(const triangle_mesh<double>& a, const triangle_mesh<double>& b, double offset) {
  triangle_mesh<double> m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, (b.V.rowwise() + Eigen::RowVector3d(offset, 0, 0));
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + a.V.rows()).matrix();
  return m;
}

}  // namespace

TEST_CASE("connected_components: one piece") {
  const auto ico = make_icosphere(1);
  for (const auto& cc : {connected_components(ico), connected_components(test::to_legacy(ico))}) {
    CHECK(cc.count == 1);
    CHECK(cc.vertex_label.size() == ico.V.rows());
    CHECK(cc.face_label.size() == ico.F.rows());
    CHECK(cc.vertex_label.maxCoeff() == 0);
    CHECK(cc.face_label.maxCoeff() == 0);
  }
}

TEST_CASE("connected_components: three pieces and an isolated vertex") {
  auto m = concat(concat(test::tetrahedron(), test::octahedron(), 3.0), make_torus(1.0, 0.3, 8, 6), 6.0);
  // an extra vertex no face uses: its own component (documented)
  m.V.conservativeResize(m.V.rows() + 1, 3);
  m.V.row(m.V.rows() - 1) << 10, 10, 10;
  for (const auto& cc : {connected_components(m), connected_components(test::to_legacy(m))}) {
    CHECK(cc.count == 4);
    CHECK(cc.vertex_label.head(4).isConstant(0));
    CHECK(cc.vertex_label.segment(4, 6).isConstant(1));
    CHECK(cc.vertex_label.segment(10, 48).isConstant(2));
    CHECK(cc.vertex_label(58) == 3);
    CHECK(cc.face_label.head(4).isConstant(0));
    CHECK(cc.face_label.segment(4, 8).isConstant(1));
    CHECK(cc.face_label.tail(96).isConstant(2));
  }
}

TEST_CASE("connected_components: labels follow the smallest vertex, not the face order") {
  // Faces of the second piece come first; labels still start at the piece holding vertex 0.
  triangle_mesh<double> m;
  m.V = Eigen::MatrixX3d::Random(6, 3);
  m.F.resize(2, 3);
  m.F << 3, 4, 5, 0, 1, 2;
  const auto cc = connected_components(m);
  CHECK(cc.count == 2);
  CHECK(cc.vertex_label(0) == 0);
  CHECK(cc.vertex_label(5) == 1);
  CHECK(cc.face_label(0) == 1);
  CHECK(cc.face_label(1) == 0);
}

TEST_CASE("connected_components: random graphs agree with a BFS") {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const index_t n = std::uniform_int_distribution<index_t>(1, 40)(rng);
    const index_t m = std::uniform_int_distribution<index_t>(0, 15)(rng);
    face_matrix F(m, 3);
    std::uniform_int_distribution<index_t> idx(0, n - 1);
    for (index_t f = 0; f < m; ++f) F.row(f) << idx(rng), idx(rng), idx(rng);
    const auto cc = connected_components(F, n);
    // BFS oracle over the face sides
    std::vector<std::vector<index_t>> adj(static_cast<std::size_t>(n));
    for (index_t f = 0; f < m; ++f)
      for (int k = 0; k < 3; ++k) {
        adj[static_cast<std::size_t>(F(f, k))].push_back(F(f, (k + 1) % 3));
        adj[static_cast<std::size_t>(F(f, (k + 1) % 3))].push_back(F(f, k));
      }
    std::vector<index_t> lab(static_cast<std::size_t>(n), -1);
    index_t count = 0;
    for (index_t s = 0; s < n; ++s) {
      if (lab[static_cast<std::size_t>(s)] >= 0) continue;
      std::vector<index_t> queue{s};
      lab[static_cast<std::size_t>(s)] = count;
      for (std::size_t q = 0; q < queue.size(); ++q)
        for (const index_t w : adj[static_cast<std::size_t>(queue[q])])
          if (lab[static_cast<std::size_t>(w)] < 0) {
            lab[static_cast<std::size_t>(w)] = count;
            queue.push_back(w);
          }
      ++count;
    }
    CHECK(cc.count == count);
    for (index_t v = 0; v < n; ++v) CHECK(cc.vertex_label(v) == lab[static_cast<std::size_t>(v)]);
  }
}

TEST_CASE("connected_components: invalid input") {
  SUBCASE("bad_face") {
    const auto m = test::with_bad_index();
    try {
      (void)connected_components(m);
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::bad_face);
      CHECK(e.element() == 3);
      CHECK(std::string(e.what()).find("face 3") != std::string::npos);
    }
    CHECK_THROWS_AS((void)connected_components(test::to_legacy(m)), invalid_input);
  }
  SUBCASE("bad_parameter") {
    const face_matrix F(0, 3);
    try {
      (void)connected_components(F, -1);
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::bad_parameter);
    }
  }
  SUBCASE("empty is fine") {
    const face_matrix F(0, 3);
    CHECK(connected_components(F, 0).count == 0);
    CHECK(connected_components(F, 3).count == 3);
  }
}
