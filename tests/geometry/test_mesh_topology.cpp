// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <string>

#include "shapestruct/geometry/mesh_topology.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

/// Calls require_closed_genus0_manifold on both mesh models and checks that each throws `reason` with
/// `element` and a message containing every string of `needles`.
void expect_rejection(const triangle_mesh<double>& m, input_error reason, index_t element,
                      std::initializer_list<const char*> needles) {
  for (int model = 0; model < 2; ++model) {
    INFO("model " << (model == 0 ? "triangle_mesh" : "legacy_mesh"));
    try {
      if (model == 0)
        (void)require_closed_genus0_manifold(m, "test_algorithm");
      else
        (void)require_closed_genus0_manifold(test::to_legacy(m), "test_algorithm");
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == reason);
      CHECK(e.element() == element);
      const std::string what = e.what();
      CHECK(what.find("test_algorithm") != std::string::npos);
      for (const char* n : needles) {
        INFO("message: " << what << "\nexpected to contain: " << n);
        CHECK(what.find(n) != std::string::npos);
      }
    }
  }
}

}  // namespace

TEST_CASE("require_closed_genus0_manifold accepts spheres") {
  for (const auto& m : test::closed_genus0_meshes()) {
    CHECK_NOTHROW((void)require_closed_genus0_manifold(m, "test"));
    CHECK_NOTHROW((void)require_closed_genus0_manifold(test::to_legacy(m), "test"));
    const Eigen::MatrixXd V = m.V;
    const Eigen::MatrixXi F = m.F.cast<int>();
    const auto r = require_closed_genus0_manifold(V, F, "test");
    CHECK(r.num_faces == m.F.rows());
    CHECK(r.is_closed_genus0_manifold());
  }
}

TEST_CASE("require_closed_genus0_manifold: unsupported_topology, boundary") {
  // the disk's boundary is its outer ring, vertices 9..16 for 2 rings of 8
  const auto disk = make_disk(2, 8);
  const auto r = check_mesh(disk);
  REQUIRE(!r.boundary_edge_examples.empty());
  expect_rejection(disk, input_error::unsupported_topology, r.boundary_edge_examples.front()[0],
                   {"boundary", "close_small_holes", "merge_duplicate_vertices", "8 boundary edges"});
  CHECK(r.boundary_edge_examples.front()[0] >= 9);
}

TEST_CASE("require_closed_genus0_manifold: unsupported_topology, genus") {
  expect_rejection(make_torus(1.0, 0.3, 10, 6), input_error::unsupported_topology, no_index, {"genus 1", "no repair"});
}

TEST_CASE("require_closed_genus0_manifold: unsupported_topology, several components") {
  const auto a = test::tetrahedron();
  triangle_mesh<double> m;
  m.V.resize(8, 3);
  m.V << a.V, (a.V.rowwise() + Eigen::RowVector3d(4, 0, 0));
  m.F.resize(8, 3);
  m.F << a.F, (a.F.array() + 4).matrix();
  expect_rejection(m, input_error::unsupported_topology, 4, {"2 connected components", "keep_largest_component"});
}

TEST_CASE("require_closed_genus0_manifold: unsupported_topology, stray vertex") {
  auto m = test::octahedron();
  m.V.conservativeResize(7, 3);
  m.V.row(6) << 3, 3, 3;
  expect_rejection(m, input_error::unsupported_topology, 6, {"remove_unreferenced_vertices"});
}

TEST_CASE("require_closed_genus0_manifold: non_manifold edge and vertex") {
  expect_rejection(test::fin(), input_error::non_manifold, 0, {"edge (0, 1)", "more than two faces"});
  expect_rejection(test::bowtie(), input_error::non_manifold, 0, {"vertex 0", "bowtie", "split_non_manifold_vertices"});
}

TEST_CASE("require_closed_genus0_manifold: validation reasons come first") {
  expect_rejection(test::with_nan_vertex(), input_error::non_finite, 2, {"vertex 2"});
  expect_rejection(test::with_bad_index(), input_error::bad_face, 3, {"face 3"});
  expect_rejection(triangle_mesh<double>{}, input_error::empty, no_index, {"empty"});
}
