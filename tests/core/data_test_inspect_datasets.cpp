// SPDX-License-Identifier: MIT
// check_mesh on real benchmark meshes, against counts recorded from an independent count
// (scripts/independent_mesh_count.py; see docs/inspect.md). Only numbers are stored here, never mesh data.
#include <doctest/doctest.h>

#include <cstdio>
#include <string>

#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/geometry/mesh_repair.hpp"
#include "shapestruct/geometry/mesh_topology.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "support/data_path.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

struct expected_counts {
  const char* file;
  index_t vertices, faces, edges, components, boundary_edges, boundary_loops, non_manifold_vertices, chi, genus;
};

void check_counts(const std::filesystem::path& root, const expected_counts& e) {
  INFO("file: " << e.file);
  const auto mf = read_mesh(root / e.file);
  // both mesh models: the reader's triangle_mesh<double> and the float legacy_mesh
  for (const mesh_report& r : {check_mesh(mf.mesh), check_mesh(test::to_legacy(mf.mesh))}) {
    CHECK(r.num_vertices == e.vertices);
    CHECK(r.num_faces == e.faces);
    CHECK(r.num_edges == e.edges);
    CHECK(r.num_components == e.components);
    CHECK(r.num_boundary_edges == e.boundary_edges);
    CHECK(r.num_boundary_loops == e.boundary_loops);
    CHECK(r.num_non_manifold_edges == 0);
    CHECK(r.num_non_manifold_vertices == e.non_manifold_vertices);
    CHECK(r.euler_characteristic == e.chi);
    CHECK(r.genus == e.genus);
    CHECK(r.num_out_of_range_faces == 0);
    CHECK(r.num_non_finite_vertices == 0);
  }
}

}  // namespace

TEST_CASE("inspect data: SCAPE mesh000 is a sphere pinched at one vertex") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "SCAPE");
  check_counts(dir, {"Meshes/mesh000.off", 12500, 24998, 37497, 1, 0, 0, 1, 1, -1});
  const auto mf = read_mesh(dir / "Meshes/mesh000.off");
  CHECK(check_mesh(mf.mesh).non_manifold_vertex_examples.at(0) == 419);
  try {
    (void)require_closed_genus0_manifold(mf.mesh, "data_test");
    FAIL("no throw");
  } catch (const invalid_input& ex) {
    CHECK(ex.reason() == input_error::non_manifold);
    CHECK(ex.element() == 419);
  }
  // giving the second fan its own vertex makes it a sphere, keeping all 12,500 vertex ids
  const auto split = split_non_manifold_vertices(mf.mesh);
  CHECK(split.split_vertices == 1);
  CHECK(split.mesh.V.rows() == 12501);
  CHECK_NOTHROW((void)require_closed_genus0_manifold(split.mesh, "data_test"));
}

TEST_CASE("inspect data: every SCAPE template mesh is pinched at vertex 419 and split into a sphere") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "SCAPE");
  int template_meshes = 0;
  for (int id = 0; id <= 73; ++id) {
    char name[32];
    std::snprintf(name, sizeof name, "Meshes/mesh%03d.off", id);
    const auto mf = read_mesh(dir / name);
    if (mf.mesh.num_vertices() != 12500) continue;  // mesh051, 071, 073 are not template-aligned
    ++template_meshes;
    INFO(name);
    const auto r = check_mesh(mf.mesh);
    CHECK(r.num_non_manifold_vertices == 1);
    CHECK(r.non_manifold_vertex_examples.at(0) == 419);
    CHECK(r.num_boundary_edges == 0);
    CHECK(check_mesh(split_non_manifold_vertices(mf.mesh).mesh).is_closed_genus0_manifold());
  }
  CHECK(template_meshes == 71);
}

TEST_CASE("inspect data: FAUST registration is a closed genus-0 manifold") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "faust_registrations");
  check_counts(dir, {"registrations/tr_reg_000.ply", 6890, 13776, 20664, 1, 0, 0, 0, 2, 0});
  const auto mf = read_mesh(dir / "registrations/tr_reg_000.ply");
  CHECK(check_mesh(mf.mesh).is_closed_genus0_manifold());
  CHECK_NOTHROW((void)require_closed_genus0_manifold(mf.mesh, "data_test"));
}

TEST_CASE("inspect data: the two non-genus-0 SHREC'07 humans are ids 5 and 16") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "watertight_shrec07");
  check_counts(dir, {"Meshes/1.off", 4706, 9408, 14112, 1, 0, 0, 0, 2, 0});
  check_counts(dir, {"Meshes/5.off", 15154, 30308, 45462, 1, 0, 0, 0, 0, 1});
  check_counts(dir, {"Meshes/16.off", 15223, 30450, 45675, 1, 0, 0, 0, -2, 2});
  // every other human (class 1: ids 1-20) is a topological sphere
  for (int id = 1; id <= 20; ++id) {
    const auto r = check_mesh(read_mesh(dir / "Meshes" / (std::to_string(id) + ".off")).mesh);
    INFO("SHREC'07 id " << id);
    CHECK(r.is_closed_manifold());
    CHECK(r.genus == (id == 5 ? 1 : id == 16 ? 2 : 0));
  }
}

TEST_CASE("inspect data: holes in TOSCA cat0 and a COSEG tele-alien are filled by close_small_holes") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "TOSCA");
  check_counts(dir, {"Meshes/cat0.off", 27894, 55712, 83606, 1, 76, 2, 0, 0, 0});
  const auto cat = read_mesh(dir / "Meshes/cat0.off");
  const auto filled = close_small_holes(cat.mesh, 76);
  CHECK(filled.holes_filled == 2);
  const auto r = check_mesh(filled.mesh);
  CHECK(r.is_closed_genus0_manifold());
  CHECK(r.num_inconsistent_edges == 0);

  const auto root = ::shapestruct::test::data_root();
  const auto alien = *root / "coseg_subset/res/tele-aliens/shapes/1.off";
  if (std::filesystem::exists(alien)) {
    check_counts(*root / "coseg_subset/res", {"tele-aliens/shapes/1.off", 2522, 5038, 7559, 1, 4, 1, 0, 1, 0});
    const auto a = close_small_holes(read_mesh(alien).mesh, 4);
    CHECK(a.holes_filled == 1);
    CHECK(check_mesh(a.mesh).is_closed_genus0_manifold());
  }
}
