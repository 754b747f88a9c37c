// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <set>
#include <utility>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/geometry/edge_graph.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

TEST_CASE("edge graph of the octahedron: 12 edges, degree 4, symmetric CSR, on both mesh models") {
  const auto oct = test::octahedron();
  const auto g = make_edge_graph(oct);
  const auto gl = make_edge_graph(test::to_legacy(oct));
  CHECK(g.num_vertices() == 6);
  CHECK(g.num_edges() == 12);
  CHECK(gl.num_edges() == 12);
  CHECK(g.degrees() == Eigen::Matrix<index_t, Eigen::Dynamic, 1>::Constant(6, 4));
  CHECK(gl.neighbours == g.neighbours);
  CHECK(gl.offsets == g.offsets);
  // 0 = +x is adjacent to all but 1 = -x; the edge length is sqrt(2)
  std::set<index_t> n0(g.neighbours.begin() + g.offsets[0], g.neighbours.begin() + g.offsets[1]);
  CHECK(n0 == std::set<index_t>{2, 3, 4, 5});
  for (std::size_t k = 0; k < g.lengths.size(); ++k) CHECK(g.lengths[k] == doctest::Approx(std::sqrt(2.0)));
}

TEST_CASE("edge graph: CSR rows sorted, each edge listed from both ends with its id, duplicates merged") {
  const auto m = test::jittered_icosphere(2, 3);
  const edge_graph<double> g(m.V, m.F);
  // Euler: closed genus 0, E = V + F - 2
  CHECK(g.num_edges() == m.V.rows() + m.F.rows() - 2);
  CHECK(g.neighbours.size() == std::size_t(2 * g.num_edges()));
  std::set<std::pair<index_t, index_t>> from_faces;
  for (index_t f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) from_faces.insert(std::minmax(m.F(f, k), m.F(f, (k + 1) % 3)));
  CHECK(from_faces.size() == std::size_t(g.num_edges()));
  for (index_t v = 0; v < g.num_vertices(); ++v)
    for (index_t k = g.offsets[std::size_t(v)]; k < g.offsets[std::size_t(v + 1)]; ++k) {
      const auto kk = std::size_t(k);
      const index_t u = g.neighbours[kk];
      if (k > g.offsets[std::size_t(v)]) CHECK(g.neighbours[kk - 1] < u);
      CHECK(from_faces.count(std::minmax(u, v)) == 1);
      const index_t e = g.edge_ids[kk];
      CHECK(g.edges(e, 0) == std::min(u, v));
      CHECK(g.edges(e, 1) == std::max(u, v));
      CHECK(g.lengths[kk] == doctest::Approx((m.V.row(u) - m.V.row(v)).norm()));
    }
  const auto E = unique_edges(m.F);
  CHECK(E == g.edges);
}

TEST_CASE("edge graph: unreferenced vertices have degree 0, faces sharing an edge twice merge it") {
  auto m = test::octahedron();
  m.V.conservativeResize(7, 3);
  m.V.row(6) << 5, 5, 5;
  face_matrix F(m.F.rows() + 1, 3);
  F << m.F, m.F.row(0);  // a duplicated face adds no edge
  const edge_graph<double> g(m.V, F);
  CHECK(g.num_edges() == 12);
  CHECK(g.degree(6) == 0);
}

TEST_CASE("edge graph: one test per invalid_input reason") {
  triangle_mesh<double> empty;
  test::expect_invalid([&] { (void)edge_graph<double>(empty.V, empty.F); }, input_error::empty, no_index);
  test::expect_invalid([&] { (void)make_edge_graph(test::with_nan_vertex()); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)make_edge_graph(test::to_legacy(test::with_bad_index())); }, input_error::bad_face, 3);
}
