// SPDX-License-Identifier: MIT
// blended_shape's repairs (off by default): one test per repair on a mesh built to have exactly that defect, what
// repairs() reports, how vertex numbers map back, and the typed errors (defect, element, problem, remedy).
#include <algorithm>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "blended_fixtures.hpp"
#include "shapestruct/blended/blended_shape.hpp"
#include "support/fixtures.hpp"

using namespace shapestruct;

namespace {

blended_shape_options small() {
  blended_shape_options o;
  o.num_samples = 64;
  o.threads = 2;
  return o;
}

blended_shape_options all_repairs() {
  auto o = small();
  o.repairs = sphere_repair_options::all();
  return o;
}

/// The error blended_shape throws for this mesh and these options (fails the test if none).
mesh_defect_error defect_of(const triangle_mesh<double>& m, const blended_shape_options& o) {
  try {
    (void)blended_shape<double>(m.V, m.F, o);
  } catch (const mesh_defect_error& e) {
    return e;
  }
  FAIL("no mesh_defect_error");
  throw std::logic_error("unreachable");
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }


/// A face sharing an edge with face 0.
index_t neighbour_of_face0(const triangle_mesh<double>& m) {
  for (index_t f = 1; f < m.F.rows(); ++f) {
    int shared = 0;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) shared += m.F(0, a) == m.F(f, b);
    if (shared == 2) return f;
  }
  return no_index;
}

}  // namespace

TEST_CASE("blended_shape: a clean mesh needs no repair, and none is reported") {
  const auto m = make_icosphere(2);
  const blended_shape<double> s(m.V, m.F, all_repairs());
  CHECK_FALSE(s.repairs().any());
  CHECK(s.repairs().to_string().empty());
  CHECK(s.mesh().F.rows() == m.F.rows());
}

TEST_CASE("blended_shape repair: holes are filled and their sizes reported") {
  const auto sphere = make_icosphere(2);
  const auto holed = test::without_faces(sphere, {0, neighbour_of_face0(sphere)});  // one hole of 4 edges
  const auto e = defect_of(holed, small());
  CHECK(e.defect() == mesh_defect::hole);
  CHECK(e.reason() == input_error::unsupported_topology);
  CHECK(contains(e.problem(), "4 boundary edges in 1 loop"));
  CHECK(e.remedy() == "the repair close_small_holes fills holes of up to max_hole_edges edges");
  auto o = small();
  o.repairs.close_small_holes = true;
  const blended_shape<double> s(holed.V, holed.F, o);
  CHECK(s.repairs().holes_filled == std::vector<index_t>{4});
  CHECK(s.repairs().to_string() == "filled 1 hole (4 edges)");
  CHECK(s.mesh().V.rows() == sphere.V.rows() + 1);  // the fan's centre
  CHECK(s.original_vertex(sphere.V.rows()) == no_index);
  o.repairs.max_hole_edges = 3;  // too short: the problem says by how much
  const auto left = defect_of(holed, o);
  CHECK(left.defect() == mesh_defect::hole);
  CHECK(contains(left.problem(), "longer than the 3 edges the hole filling closes (the longest has 4 edges)"));
  CHECK(left.remedy() == "raise max_hole_edges to fill it");
}

TEST_CASE("blended_shape repair: duplicate and collapsed faces are removed") {
  const auto sphere = make_icosphere(2);
  auto m = sphere;
  const index_t n = sphere.F.rows();
  m.F.conservativeResize(n + 1, 3);
  m.F.row(n) << sphere.F(5, 1), sphere.F(5, 0), sphere.F(5, 2);
  const auto e = defect_of(m, small());
  CHECK(e.defect() == mesh_defect::non_manifold_edge);
  CHECK(e.reason() == input_error::non_manifold);
  CHECK(contains(e.remedy(), "remove_bad_faces"));
  m.F.conservativeResize(n + 2, 3);
  m.F.row(n + 1) << 3, 7, 3;
  CHECK_THROWS_AS((void)blended_shape<double>(m.V, m.F, small()), invalid_input);  // validate_mesh: repeated corner
  auto o = small();
  o.repairs.remove_bad_faces = true;
  const blended_shape<double> s(m.V, m.F, o);
  CHECK(s.repairs().duplicate_faces_removed == 1);
  CHECK(s.repairs().collapsed_faces_removed == 1);
  CHECK(s.repairs().to_string() == "removed 1 collapsed face (a corner repeated); removed 1 duplicate face");
  CHECK(s.mesh().F.rows() == n);
}

TEST_CASE("blended_shape repair: a non-manifold vertex is split, and its copy maps back to it") {
  const auto sphere = make_icosphere(2);
  // Two spheres touching at one vertex: the second's vertex 0 is the first's vertex 0.
  auto two = test::two_copies(sphere, 2.0);
  const index_t nv = sphere.V.rows();
  for (index_t f = sphere.F.rows(); f < two.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (two.F(f, k) == nv) two.F(f, k) = 0;
  auto no_pinches = small();
  no_pinches.flattening.accept_pinched_vertices = false;
  const auto e = defect_of(two, no_pinches);
  CHECK(e.defect() == mesh_defect::non_manifold_vertex);
  CHECK(e.element() == 0);
  CHECK(e.remedy() == "the repair split_non_manifold_vertices gives each fan its own vertex");
  // Accepting pinches (the flattening's default) sees what the split would give: two spheres.
  CHECK(defect_of(two, small()).defect() == mesh_defect::several_pieces);
  auto o = small();
  o.repairs.split_non_manifold_vertices = true;
  const auto pieces = defect_of(two, o);  // split, the mesh is two spheres (and the stray old vertex nv)
  CHECK(pieces.defect() == mesh_defect::several_pieces);
  CHECK(pieces.remedy() == "the repair keep_largest_component keeps the largest piece");
  o.repairs.keep_largest_component = true;
  const blended_shape<double> s(two.V, two.F, o);
  CHECK(s.repairs().non_manifold_vertices_split == 1);
  CHECK(s.repairs().pieces_dropped == 1);
  CHECK(s.repairs().stray_vertices_dropped == 1);
  CHECK(s.repairs().to_string() ==
        "split 1 non-manifold vertex; dropped 1 smaller piece (" + std::to_string(nv) + " vertices, " +
            std::to_string(sphere.F.rows()) + " faces); dropped 1 vertex on no face");
  CHECK(s.mesh().V.rows() == nv);
  // Whichever sphere was kept, every internal vertex maps back to an input vertex, vertex 0 (or its copy) to 0.
  index_t zero = 0;
  for (index_t i = 0; i < s.mesh().V.rows(); ++i) {
    REQUIRE(s.original_vertex(i) != no_index);
    zero += s.original_vertex(i) == 0;
  }
  CHECK(zero == 1);
  CHECK(s.internal_vertex(0) != no_index);
}

TEST_CASE("blended_shape repair: the largest piece is kept, dropped input vertices have no internal vertex") {
  const auto sphere = make_icosphere(2);
  auto two = test::two_copies(sphere, 3.0);
  two.V.bottomRows(sphere.V.rows()) *= 0.5;  // the second copy is smaller
  auto o = small();
  o.repairs.keep_largest_component = true;
  const blended_shape<double> s(two.V, two.F, o);
  CHECK(s.repairs().pieces_dropped == 1);
  CHECK(s.repairs().vertices_dropped == sphere.V.rows());
  CHECK(s.repairs().faces_dropped == sphere.F.rows());
  CHECK(s.internal_vertex(0) == 0);
  CHECK(s.internal_vertex(sphere.V.rows()) == no_index);
  CHECK(s.original_size() == two.V.rows());
  // Pieces holding more than max_dropped_area_fraction of the area are parts of the shape: refused.
  o.repairs.max_dropped_area_fraction = 0.05;  // the small copy holds 0.25 / 1.25 = 20 %
  const auto e = defect_of(two, o);
  CHECK(e.defect() == mesh_defect::several_pieces);
  CHECK(contains(e.problem(), "hold 20 % of its area"));
  CHECK(contains(e.remedy(), "max_dropped_area_fraction >= 0.2"));
  o.repairs.max_dropped_area_fraction = 0.25;
  CHECK_NOTHROW((void)blended_shape<double>(two.V, two.F, o));
}

TEST_CASE("blended_shape errors: overflow, zero area, genus, each a typed defect with the problem in words") {
  auto huge = make_icosphere(1);
  huge.V *= 1e200;
  const auto o = defect_of(huge, small());
  CHECK(o.defect() == mesh_defect::coordinate_overflow);
  CHECK(o.reason() == input_error::non_finite);
  CHECK(contains(o.what(), "blended_shape: the mesh's area overflows the floating-point range (coordinates as large as 1e+200); scale the coordinates down"));
  auto flat = make_icosphere(1);
  flat.V.setZero();
  const auto z = defect_of(flat, small());
  CHECK(z.defect() == mesh_defect::zero_area);
  CHECK(contains(z.what(), "zero total area"));
  const auto g = defect_of(make_torus<double>(1.0, 0.4, 12, 8), all_repairs());
  CHECK(g.defect() == mesh_defect::genus);
  CHECK(contains(g.problem(), "genus 1"));
  CHECK(contains(g.remedy(), "no repair removes handles"));
}

TEST_CASE("blended_shape accepts a pinched sphere as the flattening does, unless pinches are refused") {
  const auto sphere = make_icosphere(2);
  const auto pinched = test::pinched_sphere(sphere, 0, 5);  // vertex 5 merged into 0; 5 is left on no face
  auto o = small();
  o.repairs.keep_largest_component = true;  // drops the stray vertex 5
  const blended_shape<double> s(pinched.V, pinched.F, o);
  CHECK(s.repairs().non_manifold_vertices_split == 0);
  CHECK(s.repairs().stray_vertices_dropped == 1);
  o.flattening.accept_pinched_vertices = false;
  CHECK(defect_of(pinched, o).defect() == mesh_defect::non_manifold_vertex);
}
