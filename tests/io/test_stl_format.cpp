// SPDX-License-Identifier: MIT
// STL reader/writer: binary detection by size, ASCII with several solids, welding, errors.
#include <cstring>

#include <doctest/doctest.h>

#include "io_test_helpers.hpp"
#include "shapestruct/io/stl_format.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;
using shapestruct::test::require_io_error;

namespace {
std::string binary_stl(const std::vector<std::array<float, 9>>& tris, const std::string& header) {
  std::string out = header;
  out.resize(80, ' ');
  const auto n = static_cast<std::uint32_t>(tris.size());
  out.append(reinterpret_cast<const char*>(&n), 4);  // test machines are little-endian (x86-64, arm64)
  for (const auto& t : tris) {
    const float normal[3] = {0, 0, 1};
    out.append(reinterpret_cast<const char*>(normal), 12);
    out.append(reinterpret_cast<const char*>(t.data()), 36);
    out.append(2, '\0');
  }
  return out;
}
}  // namespace

TEST_CASE("read_stl: binary detected by size even when the header starts with 'solid', corners welded") {
  const std::string bytes = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 1, 1, 0, 0, 1, 0}, {-0.0f, 0, 0, 0, 1, 0, 1, 0, 0}},
                                       "solid looks like ascii but is binary");
  const auto m = read_stl(bytes, "b.stl");
  CHECK(m.mesh.num_vertices() == 4);  // -0 welded with +0
  REQUIRE(m.mesh.num_faces() == 3);
  CHECK(m.mesh.F(1, 0) == 1);
  CHECK(m.mesh.F(2, 0) == 0);
  CHECK(m.face_polygon == std::vector<index_t>{0, 1, 2});
}

TEST_CASE("read_stl: ASCII with several solids, polygonal facets, NaN normals, upper-case keywords") {
  const auto m = read_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                          "endsolid a\nSOLID b\nFACET NORMAL nan nan nan\nOUTER LOOP\nVERTEX 1 0 0\nVERTEX 2 0 0\nVERTEX 2 1 0\n"
                          "VERTEX 1 1 0\nENDLOOP\nENDFACET\nENDSOLID b\n",
                          "a.stl");
  CHECK(m.mesh.num_vertices() == 6);
  CHECK(m.mesh.num_faces() == 3);
  CHECK(m.face_polygon == std::vector<index_t>{0, 1, 1});
}

TEST_CASE("read_stl errors") {
  // syntax with the line
  auto e = require_io_error([] { (void)read_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvortex 1 0 0\n", "s.stl"); },
                            file_error::syntax);
  CHECK(e.line() == 5);
  // truncated: ASCII inside a facet, binary shorter than its count, too short for either
  require_io_error([] { (void)read_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "t.stl"); }, file_error::truncated);
  std::string bin = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, 0, 0, 0, 1, 0}}, "binary");
  bin.resize(bin.size() - 10);
  e = require_io_error([&] { (void)read_stl(bin, "t.stl"); }, file_error::truncated);
  CHECK(e.byte_offset() == 80);
  require_io_error([] { (void)read_stl("xyz", "t.stl"); }, file_error::truncated);
  // bad_value: a non-finite coordinate, with its byte offset / line
  const float inf = std::numeric_limits<float>::infinity();
  e = require_io_error([&] { (void)read_stl(binary_stl({{0, 0, 0, 1, inf, 0, 0, 1, 0}}, "binary"), "v.stl"); }, file_error::bad_value);
  CHECK(e.byte_offset() == 84 + 12 + 12 + 4);
  e = require_io_error([] { (void)read_stl("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 nan 0\n", "v.stl"); }, file_error::bad_value);
  CHECK(e.line() == 4);
  require_io_error([] { (void)read_stl(std::filesystem::path("/nonexistent/shapestruct/x.stl")); }, file_error::cannot_open);
}

TEST_CASE("format_stl/read_stl round trip (binary and ASCII) for triangle_mesh and legacy_mesh") {
  const auto torus = make_torus<double>(2.0, 0.5, 10, 6);
  for (bool binary : {true, false}) {
    CAPTURE(binary);
    const auto back = read_stl(format_stl<double>(torus.V, torus.F, {.binary = binary}), "rt.stl");
    REQUIRE(back.mesh.num_vertices() == torus.V.rows());
    REQUIRE(back.mesh.num_faces() == torus.F.rows());
    // Welding renumbers vertices in order of first appearance; compare positions corner by corner.
    for (index_t f = 0; f < torus.F.rows(); ++f)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k)
          CHECK(back.mesh.V(back.mesh.F(f, c), k) == doctest::Approx(torus.V(torus.F(f, c), k)).epsilon(1e-6));
  }
  shapestruct::test::temp_folder tmp;
  const auto oct = shapestruct::test::octahedron<double>();
  write_stl(tmp.path / "legacy.stl", shapestruct::test::to_legacy(oct), {.binary = true});
  const auto lb = read_stl(tmp.path / "legacy.stl");
  CHECK(lb.mesh.num_vertices() == 6);
  CHECK(lb.mesh.num_faces() == 8);
  CHECK(std::filesystem::file_size(tmp.path / "legacy.stl") == 84 + 50 * 8);
}
