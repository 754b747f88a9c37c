// SPDX-License-Identifier: MIT
// OFF reader/writer: keyword variants, comments, polygons, colours, and one test per file_error reason.
#include <cmath>

#include <doctest/doctest.h>
#include <Eigen/Geometry>

#include "io_test_helpers.hpp"
#include "shapestruct/io/off_format.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;
using shapestruct::test::require_io_error;

TEST_CASE("read_off: plain OFF with comments, blank lines and counts on the keyword line") {
  const auto m = read_off("# header comment\n\nOFF 4 2 0  # counts here\n0 0 0\n1 0 0\n\n1 1 0 # c\n0 1 0\n"
                          "3 0 1 2\n3 0 2 3\n",
                          "t.off");
  CHECK(m.mesh.num_vertices() == 4);
  CHECK(m.mesh.num_faces() == 2);
  CHECK(m.mesh.V(2, 0) == 1.0);
  CHECK(m.mesh.F(1, 2) == 3);
  CHECK(m.vertex_colors.rows() == 0);
  CHECK(m.face_polygon == std::vector<index_t>{0, 1});
}

TEST_CASE("read_off: COFF colours as bytes and as reals, CRLF line ends") {
  const auto m = read_off("COFF\r\n3 1 0\r\n0 0 0 255 0 0 255\r\n1 0 0 0 128 0 255\r\n0 1 0 0.0 0.0 1.0 1.0\r\n3 0 1 2\r\n", "c.off");
  REQUIRE(m.vertex_colors.rows() == 3);
  CHECK(int(m.vertex_colors(0, 0)) == 255);
  CHECK(int(m.vertex_colors(1, 1)) == 128);
  CHECK(int(m.vertex_colors(2, 2)) == 255);
  CHECK(int(m.vertex_colors(2, 0)) == 0);
}

TEST_CASE("read_off: NOFF, CNOFF and STOFF extra columns are skipped") {
  const auto n = read_off("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", "n.off");
  CHECK(n.mesh.V(1, 0) == 1.0);
  CHECK(n.mesh.V(1, 2) == 0.0);
  const auto cn = read_off("CNOFF\n3 1 0\n0 0 0 0 0 1 10 20 30 255\n1 0 0 0 0 1 1 2 3 4\n0 1 0 0 0 1 5 6 7 8\n3 0 1 2\n", "cn.off");
  REQUIRE(cn.vertex_colors.rows() == 3);
  CHECK(int(cn.vertex_colors(0, 1)) == 20);
  const auto st = read_off("STOFF\n3 1 0\n0 0 0 0.5 0.5\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2 1 0 0\n", "st.off");
  CHECK(st.mesh.num_faces() == 1);
  CHECK(st.mesh.V(2, 1) == 1.0);
}

TEST_CASE("read_off: polygons are triangulated and remember their source polygon") {
  // A quad, a concave 'L'-free arrow pentagon, a degenerate 2-gon and a triangle.
  const auto m = read_off("OFF\n7 4 0\n0 0 0\n2 0 0\n2 2 0\n1 0.5 0\n0 2 0\n5 5 0\n6 5 0\n"
                          "4 0 1 2 4\n5 0 1 2 3 4\n2 5 6\n3 0 5 6\n",
                          "p.off");
  CHECK(m.mesh.num_faces() == 2 + 3 + 0 + 1);
  CHECK(m.face_polygon == std::vector<index_t>{0, 0, 1, 1, 1, 3});
  // The concave pentagon (vertex 3 is reflex): a valid triangulation keeps every triangle's orientation and
  // covers exactly the polygon's area, 2.5 (a fan from vertex 0 would cover 3.5 with one flipped triangle).
  double area = 0;
  for (index_t f = 2; f < 5; ++f) {
    const Eigen::Vector3d a = m.mesh.V.row(m.mesh.F(f, 0)), b = m.mesh.V.row(m.mesh.F(f, 1)), c = m.mesh.V.row(m.mesh.F(f, 2));
    const double signed_area = 0.5 * (b - a).cross(c - a).z();
    CHECK(signed_area > 0);
    area += std::abs(signed_area);
  }
  CHECK(area == doctest::Approx(2.5));
}

TEST_CASE("read_off: keyword-less files are accepted") {
  const auto m = read_off("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "k.off");
  CHECK(m.mesh.num_faces() == 1);
}

TEST_CASE("read_off errors: syntax, with the line") {
  auto e = require_io_error([] { (void)read_off("OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", "s.off"); }, file_error::syntax);
  CHECK(e.line() == 4);
  CHECK(e.path() == "s.off");
  CHECK(std::string(e.what()).find("s.off:4:") == 0);
  e = require_io_error([] { (void)read_off("MOFF\n3 1 0\n", "k.off"); }, file_error::syntax);
  CHECK(e.line() == 1);
  e = require_io_error([] { (void)read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "f.off"); }, file_error::syntax);
  CHECK(e.line() == 6);
}

TEST_CASE("read_off errors: truncated") {
  auto e = require_io_error([] { (void)read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n", "t.off"); }, file_error::truncated);
  CHECK(std::string(e.what()).find("0 of 1 faces") != std::string::npos);
  require_io_error([] { (void)read_off("", "empty.off"); }, file_error::truncated);
  require_io_error([] { (void)read_off("OFF\n", "hdr.off"); }, file_error::truncated);
}

TEST_CASE("read_off errors: bad_index names the face's line") {
  const auto e = require_io_error([] { (void)read_off("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n", "i.off"); },
                                  file_error::bad_index);
  CHECK(e.line() == 7);
  require_io_error([] { (void)read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "n.off"); }, file_error::bad_index);
}

TEST_CASE("read_off errors: bad_value for non-finite coordinates and negative counts") {
  auto e = require_io_error([] { (void)read_off("OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "v.off"); }, file_error::bad_value);
  CHECK(e.line() == 4);
  require_io_error([] { (void)read_off("OFF\n3 1 0\n0 0 0\n1 1e999 0\n0 1 0\n3 0 1 2\n", "v.off"); }, file_error::bad_value);
  require_io_error([] { (void)read_off("OFF\n-3 1 0\n", "v.off"); }, file_error::bad_value);
}

TEST_CASE("read_off errors: too_large before allocating, unsupported, cannot_open") {
  const auto e = require_io_error([] { (void)read_off("OFF\n4000000000000 1 0\n0 0 0\n", "big.off"); }, file_error::too_large);
  CHECK(e.line() == 2);
  require_io_error([] { (void)read_off("OFF\n3 100000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "big.off"); }, file_error::too_large);
  require_io_error([] { (void)read_off("4OFF\n1 0 0\n0 0 0 1\n", "4d.off"); }, file_error::unsupported);
  require_io_error([] { (void)read_off("OFF BINARY\n", "b.off"); }, file_error::unsupported);
  require_io_error([] { (void)read_off(std::filesystem::path("/nonexistent/shapestruct/x.off")); }, file_error::cannot_open);
}

TEST_CASE("format_off/read_off round trip is exact, with colours, for triangle_mesh and legacy_mesh") {
  const auto torus = make_torus<double>(1.0, 0.3, 12, 8);
  mesh_write_options opt;
  opt.vertex_colors.resize(torus.V.rows(), 3);
  for (index_t i = 0; i < torus.V.rows(); ++i) opt.vertex_colors.row(i) << std::uint8_t(i % 256), std::uint8_t(7), std::uint8_t(255 - i % 256);
  const auto back = read_off(format_off<double>(torus.V, torus.F, opt), "rt.off");
  CHECK(back.mesh.V == torus.V);
  CHECK(back.mesh.F == torus.F);
  CHECK(back.vertex_colors == opt.vertex_colors);

  shapestruct::test::temp_folder tmp;
  const auto legacy = shapestruct::test::to_legacy(shapestruct::test::octahedron<double>());
  write_off(tmp.path / "legacy.off", legacy);
  const auto lb = read_off(tmp.path / "legacy.off");
  CHECK(lb.mesh.num_vertices() == 6);
  CHECK(lb.mesh.F == shapestruct::test::octahedron<double>().F);
}

TEST_CASE("read_off: a face of fewer than 3 corners is counted with its line, not silently dropped") {
  const auto m = read_off("OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n2 0 1\n1 3\n", "short.off");
  CHECK(m.mesh.num_faces() == 1);
  CHECK(m.short_faces == 2);
  CHECK(m.first_short_face_at == 8);
  CHECK_FALSE(m.short_face_at_is_byte_offset);
  CHECK(m.short_faces_note("short.off") ==
        "short.off:8: 2 faces with fewer than 3 corners (a face needs 3) are not part of the surface and left out "
        "(the first is here)");
  CHECK(read_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "ok.off").short_faces == 0);
}
