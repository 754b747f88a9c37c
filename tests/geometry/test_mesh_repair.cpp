// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/geometry/mesh_repair.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

using test::without_faces;

/// The faces of m around vertex v.
std::vector<index_t> faces_around(const triangle_mesh<double>& m, index_t v) {
  std::vector<index_t> out;
  for (index_t f = 0; f < m.F.rows(); ++f)
    if ((m.F.row(f).array() == v).any()) out.push_back(f);
  return out;
}

template <class Fn>
void on_both_models(const triangle_mesh<double>& m, Fn&& fn) {
  {
    INFO("model: triangle_mesh<double>");
    fn(m, 1e-12);
  }
  {
    INFO("model: legacy_mesh");
    fn(test::to_legacy(m), 1e-6);
  }
}

template <class Fn>
void expect_reason(input_error reason, index_t element, Fn&& fn) {
  try {
    fn();
    FAIL("no throw");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == reason);
    CHECK(e.element() == element);
  }
}

}  // namespace

TEST_CASE("keep_largest_component keeps the piece of largest area") {
  const auto small = test::tetrahedron();  // area ~ 13.9
  auto big = make_icosphere(1);            // area ~ 12.4 at radius 1: scale to radius 3
  big.V *= 3.0;
  triangle_mesh<double> m;
  // layout: stray vertex 0, tetrahedron 1..4, sphere 5..46
  m.V.resize(1 + 4 + big.V.rows(), 3);
  m.V << Eigen::RowVector3d(9, 9, 9), small.V, (big.V.rowwise() + Eigen::RowVector3d(10, 0, 0));
  m.F.resize(4 + big.F.rows(), 3);
  m.F << (small.F.array() + 1).matrix(), (big.F.array() + 5).matrix();
  on_both_models(m, [&](const auto& mesh, double tol) {
    const auto r = keep_largest_component(mesh);
    CHECK(r.mesh.V.rows() == big.V.rows());
    CHECK(r.mesh.F == big.F);
    CHECK((r.mesh.V.template cast<double>().rowwise() - Eigen::RowVector3d(10, 0, 0) - big.V).cwiseAbs().maxCoeff() <
          tol * 100);
    CHECK(r.removed_vertices == 5);
    CHECK(r.removed_faces == 4);
    CHECK(r.old_to_new(0) == no_index);
    CHECK(r.old_to_new(4) == no_index);
    CHECK(r.old_to_new(5) == 0);
    CHECK(r.old_to_new(46) == 41);
    CHECK(check_mesh(r.mesh).is_closed_genus0_manifold());
  });
}

TEST_CASE("keep_largest_component: invalid input") {
  expect_reason(input_error::bad_face, 3, [] { (void)keep_largest_component(test::with_bad_index()); });
  expect_reason(input_error::non_finite, 2, [] { (void)keep_largest_component(test::with_nan_vertex()); });
  expect_reason(input_error::empty, no_index, [] { (void)keep_largest_component(triangle_mesh<double>{}); });
}

TEST_CASE("close_small_holes fills a triangle hole with one face") {
  const auto ico = make_icosphere(1);
  on_both_models(without_faces(ico, {7}), [&](const auto& mesh, double) {
    const auto r = close_small_holes(mesh, 3);
    CHECK(r.holes_filled == 1);
    CHECK(r.holes_left == 0);
    CHECK(r.added_vertices == 0);
    CHECK(r.added_faces == 1);
    CHECK(r.filled_loop_lengths == std::vector<index_t>{3});
    const auto rep = check_mesh(r.mesh);
    CHECK(rep.is_closed_genus0_manifold());
    CHECK(rep.num_inconsistent_edges == 0);
  });
}

TEST_CASE("close_small_holes fills a larger hole with a centroid fan, keeping existing indices") {
  const auto ico = make_icosphere(1);
  const auto fan = faces_around(ico, 20);  // a valence-6 vertex of the subdivided icosahedron
  REQUIRE(fan.size() == 6);
  const auto holed = without_faces(ico, fan);
  on_both_models(holed, [&](const auto& mesh, double tol) {
    SUBCASE("long enough limit") {
      const auto r = close_small_holes(mesh, 6);
      CHECK(r.holes_filled == 1);
      CHECK(r.added_vertices == 1);
      CHECK(r.added_faces == 6);
      CHECK(r.mesh.F.topRows(holed.F.rows()) == holed.F);
      CHECK((r.mesh.V.topRows(holed.V.rows()).template cast<double>() - holed.V).cwiseAbs().maxCoeff() < tol);
      const auto rep = check_mesh(r.mesh);
      CHECK(rep.num_boundary_edges == 0);
      CHECK(rep.num_inconsistent_edges == 0);
      // vertex 20 is now unreferenced, the rest is a closed sphere
      CHECK(rep.num_unreferenced_vertices == 1);
      CHECK(rep.genus == 0);
      CHECK(rep.components.size() == 1);
      // the new vertex is the centroid of the ring around vertex 20
      Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
      for (const index_t f : fan)
        for (int k = 0; k < 3; ++k)
          if (ico.F(f, k) != 20) c += ico.V.row(ico.F(f, k)) / 12.0;  // each ring vertex appears twice
      CHECK((r.mesh.V.row(holed.V.rows()).template cast<double>() - c).norm() < tol * 10);
    }
    SUBCASE("too short a limit leaves the hole") {
      const auto r = close_small_holes(mesh, 5);
      CHECK(r.holes_filled == 0);
      CHECK(r.holes_left == 1);
      CHECK(r.longest_loop_left == 6);
      CHECK(r.mesh.F.rows() == holed.F.rows());
    }
  });
}

TEST_CASE("close_small_holes turns a disk into a sphere") {
  on_both_models(make_disk(2, 10), [](const auto& mesh, double) {
    const auto r = close_small_holes(mesh, 10);
    CHECK(r.holes_filled == 1);
    CHECK(check_mesh(r.mesh).is_closed_genus0_manifold());
  });
}

TEST_CASE("close_small_holes: invalid input") {
  expect_reason(input_error::bad_parameter, no_index, [] { (void)close_small_holes(make_disk(1, 5), 2); });
  expect_reason(input_error::non_manifold, 0, [] { (void)close_small_holes(test::bowtie(), 10); });
  expect_reason(input_error::bad_face, 3, [] { (void)close_small_holes(test::with_bad_index(), 10); });
  expect_reason(input_error::non_finite, 2, [] { (void)close_small_holes(test::with_nan_vertex(), 10); });
  expect_reason(input_error::empty, no_index, [] { (void)close_small_holes(triangle_mesh<double>{}, 10); });
}

TEST_CASE("remove_unreferenced_vertices drops stray vertices and renumbers") {
  const auto oct = test::octahedron();
  // strays at new indices 0 and 4: old vertex i maps to i + 1 (i < 3) or i + 2 (i >= 3)
  triangle_mesh<double> m;
  m.V.resize(8, 3);
  m.V << Eigen::RowVector3d(7, 7, 7), oct.V.topRows(3), Eigen::RowVector3d(8, 8, 8), oct.V.bottomRows(3);
  m.F = oct.F;
  for (index_t f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) m.F(f, k) += m.F(f, k) < 3 ? 1 : 2;
  on_both_models(m, [&](const auto& mesh, double tol) {
    const auto r = remove_unreferenced_vertices(mesh);
    CHECK(r.removed_vertices == 2);
    CHECK(r.removed_faces == 0);
    CHECK(r.mesh.F == oct.F);
    CHECK((r.mesh.V.template cast<double>() - oct.V).cwiseAbs().maxCoeff() < tol);
    CHECK(r.old_to_new(0) == no_index);
    CHECK(r.old_to_new(4) == no_index);
    CHECK(r.old_to_new(5) == 3);
  });
}

TEST_CASE("remove_unreferenced_vertices: invalid input") {
  expect_reason(input_error::bad_face, 3, [] { (void)remove_unreferenced_vertices(test::with_bad_index()); });
  // non-finite stray vertices are simply dropped
  auto m = test::octahedron();
  m.V.conservativeResize(7, 3);
  m.V.row(6).setConstant(std::numeric_limits<double>::quiet_NaN());
  const auto r = remove_unreferenced_vertices(m);
  CHECK(r.mesh.V.rows() == 6);
  CHECK(r.mesh.V.allFinite());
}

TEST_CASE("merge_duplicate_vertices welds a triangle soup back into a sphere") {
  const auto oct = test::octahedron();
  auto soup = test::as_soup(oct);
  // one extra face whose corners 0 and 1 are both copies of octahedron vertex 0: it collapses
  soup.V.conservativeResize(soup.V.rows() + 3, 3);
  soup.V.bottomRows(3) << oct.V.row(0), oct.V.row(0), oct.V.row(2);
  soup.F.conservativeResize(soup.F.rows() + 1, 3);
  soup.F.row(soup.F.rows() - 1) << 24, 25, 26;
  REQUIRE(check_mesh(soup).num_boundary_edges == 24 + 3);
  on_both_models(soup, [&](const auto& mesh, double) {
    const auto r = merge_duplicate_vertices(mesh);
    CHECK(r.mesh.V.rows() == 6);
    CHECK(r.mesh.F.rows() == 8);
    CHECK(r.removed_faces == 1);
    CHECK(r.removed_vertices == 27 - 6);
    CHECK(r.old_to_new(24) == r.old_to_new(25));
    // soup vertex 3 f + k is octahedron vertex F(f, k); merged copies all map to one new index
    for (index_t f = 0; f < oct.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) CHECK(r.mesh.F(f, k) == r.old_to_new(3 * f + k));
    const auto rep = check_mesh(r.mesh);
    CHECK(rep.is_closed_genus0_manifold());
    CHECK(rep.num_duplicate_vertices == 0);
  });
}

TEST_CASE("merge_duplicate_vertices: invalid input") {
  expect_reason(input_error::non_finite, 2, [] { (void)merge_duplicate_vertices(test::with_nan_vertex()); });
  expect_reason(input_error::bad_face, 3, [] { (void)merge_duplicate_vertices(test::with_bad_index()); });
  expect_reason(input_error::empty, no_index, [] { (void)merge_duplicate_vertices(triangle_mesh<double>{}); });
}

TEST_CASE("split_non_manifold_vertices separates a bowtie") {
  on_both_models(test::bowtie(), [](const auto& mesh, double tol) {
    const auto r = split_non_manifold_vertices(mesh);
    CHECK(r.split_vertices == 1);
    REQUIRE(r.copied_from.size() == 1);
    CHECK(r.copied_from(0) == 0);
    CHECK(r.mesh.V.rows() == 6);
    CHECK(r.mesh.F(0, 0) == 0);  // the first fan (face 0) keeps vertex 0
    CHECK(r.mesh.F(1, 0) == 5);  // the second fan moves to the copy
    CHECK((r.mesh.V.row(5) - r.mesh.V.row(0)).norm() < tol);
    const auto rep = check_mesh(r.mesh);
    CHECK(rep.num_non_manifold_vertices == 0);
    CHECK(rep.num_components == 2);
  });
}

TEST_CASE("split_non_manifold_vertices turns a pinched sphere back into a sphere") {
  // Glue vertex `far` of an icosphere onto vertex 0 (its antipode): one piece, one non-manifold vertex,
  // Euler characteristic 1 -- the shape of the SCAPE template meshes.
  const auto ico = make_icosphere(1);
  index_t far = 0;
  for (index_t v = 1; v < ico.V.rows(); ++v)
    if ((ico.V.row(v) - ico.V.row(0)).norm() > (ico.V.row(far) - ico.V.row(0)).norm()) far = v;
  triangle_mesh<double> pinched;
  pinched.V.resize(ico.V.rows() - 1, 3);
  index_t g = 0;
  for (index_t v = 0; v < ico.V.rows(); ++v)
    if (v != far) pinched.V.row(g++) = ico.V.row(v);
  pinched.V.row(0) = Eigen::RowVector3d::Zero();
  pinched.F = ico.F;
  for (index_t f = 0; f < ico.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const index_t v = ico.F(f, k);
      pinched.F(f, k) = v == far ? 0 : (v > far ? v - 1 : v);
    }
  const auto before = check_mesh(pinched);
  REQUIRE(before.num_non_manifold_vertices == 1);
  REQUIRE(before.euler_characteristic == 1);
  on_both_models(pinched, [&](const auto& mesh, double) {
    const auto r = split_non_manifold_vertices(mesh);
    CHECK(r.split_vertices == 1);
    CHECK(r.mesh.V.rows() == ico.V.rows());
    // untouched faces keep their indices
    index_t changed = 0;
    for (index_t f = 0; f < pinched.F.rows(); ++f) changed += (r.mesh.F.row(f) != pinched.F.row(f)) ? 1 : 0;
    CHECK(changed == 5);  // the five faces of one fan around the glued vertex (valence 5 on an icosphere)
    CHECK(check_mesh(r.mesh).is_closed_genus0_manifold());
  });
}

TEST_CASE("split_non_manifold_vertices leaves manifold meshes and fins alone") {
  const auto oct = test::octahedron();
  const auto r = split_non_manifold_vertices(oct);
  CHECK(r.split_vertices == 0);
  CHECK(r.mesh.F == oct.F);
  CHECK(r.mesh.V == oct.V);
  CHECK(split_non_manifold_vertices(test::fin()).split_vertices == 0);
}

TEST_CASE("split_non_manifold_vertices: invalid input") {
  expect_reason(input_error::non_finite, 2, [] { (void)split_non_manifold_vertices(test::with_nan_vertex()); });
  expect_reason(input_error::bad_face, 3, [] { (void)split_non_manifold_vertices(test::with_bad_index()); });
  expect_reason(input_error::empty, no_index, [] { (void)split_non_manifold_vertices(triangle_mesh<double>{}); });
}

TEST_CASE("remove_collapsed_and_duplicate_faces removes repeated-corner faces and repeats of a face") {
  const auto ico = make_icosphere(1);
  triangle_mesh<double> m = ico;
  const index_t n = ico.F.rows();
  m.F.conservativeResize(n + 3, 3);
  m.F.row(n) << ico.F(4, 2), ico.F(4, 1), ico.F(4, 0);  // face 4 again, reversed: its edges get 4 faces
  m.F.row(n + 1) << 0, 0, 1;                             // collapsed to a segment
  m.F.row(n + 2) << ico.F(4, 1), ico.F(4, 2), ico.F(4, 0);  // face 4 a third time, rotated
  REQUIRE(check_mesh(m).num_non_manifold_edges == 3);
  on_both_models(m, [&](const auto& mesh, double) {
    const auto r = remove_collapsed_and_duplicate_faces(mesh);
    CHECK(r.collapsed_faces == 1);
    CHECK(r.duplicate_faces == 2);
    CHECK(r.first_collapsed == n + 1);
    CHECK(r.first_duplicate == n);
    CHECK(r.mesh.F.rows() == n);
    CHECK(r.mesh.V.rows() == ico.V.rows());  // vertices untouched
    CHECK(r.kept_faces.size() == static_cast<std::size_t>(n));
    CHECK(r.kept_faces.back() == n - 1);  // the first copy stays, in order
    CHECK(check_mesh(r.mesh).is_closed_genus0_manifold());
  });
  // A clean mesh is returned as it is.
  const auto clean = remove_collapsed_and_duplicate_faces(ico);
  CHECK(clean.collapsed_faces + clean.duplicate_faces == 0);
  CHECK(clean.mesh.F == ico.F);
}

TEST_CASE("remove_collapsed_and_duplicate_faces: invalid input") {
  auto m = make_icosphere(1);
  m.F(3, 1) = m.V.rows();
  expect_reason(input_error::bad_face, 3, [&] { (void)remove_collapsed_and_duplicate_faces(m); });
}
