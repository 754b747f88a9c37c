// SPDX-License-Identifier: MIT
// OBJ reader/writer: corner syntaxes, negative indices, groups, colours, skipped statements, errors.
#include <doctest/doctest.h>

#include "io_test_helpers.hpp"
#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/io/obj_format.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;
using shapestruct::test::require_io_error;

TEST_CASE("read_obj: corner syntaxes, negative indices and skipped statements") {
  const auto m = read_obj("mtllib scene.mtl\n# a comment\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\n"
                          "usemtl red\ns 1\nf 1 2 3\nf 1/1 3/2 4/1\nf 1/1/1 2/2/1 3/1/1\nf 1//1 3//1 4//1\nf -4 -3 -2\n"
                          "l 1 2\np 3\n",
                          "a.obj");
  CHECK(m.mesh.num_vertices() == 4);
  REQUIRE(m.mesh.num_faces() == 5);
  CHECK(m.mesh.F.row(4) == m.mesh.F.row(0));
  CHECK(m.mesh.F(1, 2) == 3);
  CHECK(m.face_group.empty());
  CHECK(m.group_names.empty());
  CHECK(m.vertex_colors.rows() == 0);
}

TEST_CASE("read_obj: objects and groups, with a default group for faces before the first") {
  const auto m = read_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\no body\nf 1 3 4\ng arm left\nf 1 2 3 4\ng body\nf 2 3 4\n",
                          "g.obj");
  REQUIRE(m.mesh.num_faces() == 5);
  REQUIRE(m.group_names.size() == 3);
  CHECK(m.group_names[0] == "body");
  CHECK(m.group_names[1] == "arm left");
  CHECK(m.group_names[2] == "default");
  CHECK(m.face_group == std::vector<index_t>{2, 0, 1, 1, 0});
  CHECK(m.face_polygon == std::vector<index_t>{0, 1, 2, 2, 3});
}

TEST_CASE("read_obj: vertex colours (0..1 and 0..255), only when every vertex has them") {
  const auto m = read_obj("v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0 0 0 255\nf 1 2 3\n", "c.obj");
  REQUIRE(m.vertex_colors.rows() == 3);
  CHECK(int(m.vertex_colors(0, 0)) == 255);
  CHECK(int(m.vertex_colors(1, 1)) == 128);
  CHECK(int(m.vertex_colors(2, 2)) == 255);
  const auto partial = read_obj("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "p.obj");
  CHECK(partial.vertex_colors.rows() == 0);
  const auto w = read_obj("v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n", "w.obj");
  CHECK(w.vertex_colors.rows() == 0);
}

TEST_CASE("read_obj: polygon soup with a concave hexagon") {
  // An L-shaped hexagon: 4 triangles, all counter-clockwise, covering area 3.
  const auto m = read_obj("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n", "l.obj");
  REQUIRE(m.mesh.num_faces() == 4);
  double area = 0;
  for (index_t f = 0; f < 4; ++f) {
    const Eigen::RowVector3d a = m.mesh.V.row(m.mesh.F(f, 0)), b = m.mesh.V.row(m.mesh.F(f, 1)), c = m.mesh.V.row(m.mesh.F(f, 2));
    const double s = 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
    CHECK(s > 0);
    area += s;
  }
  CHECK(area == doctest::Approx(3.0));
}

TEST_CASE("read_obj errors: syntax, bad_index, bad_value with lines, cannot_open") {
  auto e = require_io_error([] { (void)read_obj("v 0 0 0\nv 1 x 0\n", "s.obj"); }, file_error::syntax);
  CHECK(e.line() == 2);
  e = require_io_error([] { (void)read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 a\n", "s.obj"); }, file_error::syntax);
  CHECK(e.line() == 5);
  e = require_io_error([] { (void)read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "i.obj"); }, file_error::bad_index);
  CHECK(e.line() == 4);
  e = require_io_error([] { (void)read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "i.obj"); }, file_error::bad_index);
  CHECK(e.line() == 4);
  e = require_io_error([] { (void)read_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n# c\nf -1 -2 -4\n", "i.obj"); }, file_error::bad_index);
  CHECK(e.line() == 5);
  e = require_io_error([] { (void)read_obj("v 0 0 0\nv inf 0 0\n", "v.obj"); }, file_error::bad_value);
  CHECK(e.line() == 2);
  require_io_error([] { (void)read_obj(std::filesystem::path("/nonexistent/shapestruct/x.obj")); }, file_error::cannot_open);
}

TEST_CASE("format_obj/read_obj round trip is exact, with colours, for triangle_mesh and legacy_mesh") {
  const auto sphere = make_icosphere<double>(2);
  mesh_write_options opt;
  opt.vertex_colors.resize(sphere.V.rows(), 3);
  for (index_t i = 0; i < sphere.V.rows(); ++i) opt.vertex_colors.row(i) << std::uint8_t(i % 256), std::uint8_t(3 * i % 256), std::uint8_t(1);
  const auto back = read_obj(format_obj<double>(sphere.V, sphere.F, opt), "rt.obj");
  CHECK(back.mesh.V == sphere.V);
  CHECK(back.mesh.F == sphere.F);
  CHECK(back.vertex_colors == opt.vertex_colors);

  shapestruct::test::temp_folder tmp;
  const auto tet = shapestruct::test::tetrahedron<double>();
  write_obj(tmp.path / "legacy.obj", shapestruct::test::to_legacy(tet));
  const auto lb = read_obj(tmp.path / "legacy.obj");
  CHECK(lb.mesh.V == tet.V);
  CHECK(lb.mesh.F == tet.F);
}

TEST_CASE("read_obj: a face of 2 corners is counted with its line and leaves no surface") {
  const auto m = read_obj("v 0 0 0\nv 1 0 0\nf 1 2\n", "two.obj");
  CHECK(m.mesh.num_faces() == 0);
  CHECK(m.short_faces == 1);
  CHECK(m.first_short_face_at == 3);
  CHECK(m.short_faces_note("two.obj") ==
        "two.obj:3: a face with fewer than 3 corners (a face needs 3) is not part of the surface and left out");
  // What is left is two vertices and no surface: no genus.
  const mesh_report r = check_mesh(m.mesh.V, m.mesh.F);
  CHECK(r.genus == -1);
  CHECK(r.to_string().find("genus undefined") != std::string::npos);
}
