// SPDX-License-Identifier: MIT
// PLY reader/writer: ASCII and both binary byte orders, property types and order, colours, lists, unknown
// elements, triangle strips, and one test per file_error reason.
#include <bit>
#include <cstring>

#include <doctest/doctest.h>

#include "io_test_helpers.hpp"
#include "shapestruct/io/ply_format.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;
using shapestruct::test::require_io_error;

namespace {
/// Appends a value in the given byte order (for building binary PLY bodies by hand).
template <class T>
void put(std::string& out, T v, std::endian order) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (order != std::endian::native) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

/// A binary PLY with unusual types and order: z before x, a short y, float colours, an unknown element
/// between vertex and face, a face property before the list, a uint16 count and uint32 indices.
std::string unusual_binary(std::endian order) {
  std::string s = std::string("ply\nformat ") + (order == std::endian::little ? "binary_little_endian" : "binary_big_endian") +
                  " 1.0\ncomment hand made\nobj_info test\nelement vertex 4\nproperty double z\nproperty float x\n"
                  "property short y\nproperty float blue\nproperty float red\nproperty float green\nproperty uchar quality\n"
                  "element material 2\nproperty list uchar float coefficients\nproperty int id\n"
                  "element face 2\nproperty uint8 flags\nproperty list uint16 uint32 vertex_index\nend_header\n";
  const double xyz[4][3] = {{0, 0, 1.5}, {1, 0, 1.5}, {1, 1, 1.5}, {0, 1, 1.5}};
  for (int i = 0; i < 4; ++i) {
    put(s, xyz[i][2], order);
    put(s, float(xyz[i][0]), order);
    put(s, std::int16_t(xyz[i][1]), order);
    put(s, 1.0f, order);   // blue
    put(s, 0.0f, order);   // red
    put(s, 0.5f, order);   // green
    put(s, std::uint8_t(9), order);
  }
  for (int m = 0; m < 2; ++m) {
    put(s, std::uint8_t(2), order);
    put(s, 0.25f, order);
    put(s, 0.75f, order);
    put(s, std::int32_t(m), order);
  }
  put(s, std::uint8_t(0), order);
  put(s, std::uint16_t(4), order);
  for (std::uint32_t v : {0u, 1u, 2u, 3u}) put(s, v, order);
  put(s, std::uint8_t(0), order);
  put(s, std::uint16_t(3), order);
  for (std::uint32_t v : {0u, 2u, 3u}) put(s, v, order);
  return s;
}
}  // namespace

TEST_CASE("read_ply: binary little- and big-endian, any property types and order, float colours, skipped elements") {
  for (std::endian order : {std::endian::little, std::endian::big}) {
    CAPTURE(order == std::endian::little);
    const auto m = read_ply(unusual_binary(order), "u.ply");
    REQUIRE(m.mesh.num_vertices() == 4);
    CHECK(m.mesh.V(2, 0) == 1.0);
    CHECK(m.mesh.V(2, 1) == 1.0);
    CHECK(m.mesh.V(2, 2) == 1.5);
    REQUIRE(m.vertex_colors.rows() == 4);
    CHECK(int(m.vertex_colors(0, 0)) == 0);
    CHECK(int(m.vertex_colors(0, 1)) == 128);
    CHECK(int(m.vertex_colors(0, 2)) == 255);
    CHECK(m.mesh.num_faces() == 3);
    CHECK(m.face_polygon == std::vector<index_t>{0, 0, 1});
  }
}

TEST_CASE("read_ply: ASCII with uchar colours, polygons, faces before vertices, records across lines") {
  const auto m = read_ply("ply\nformat ascii 1.0\nelement face 2\nproperty list uchar int vertex_indices\nproperty uchar k\n"
                          "element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                          "property uchar green\nproperty uchar blue\nend_header\n"
                          "4 0 1 2 3 7\n3 0 2\n3 1\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 10 20 30\n",
                          "a.ply");
  CHECK(m.mesh.num_vertices() == 4);
  CHECK(m.mesh.num_faces() == 3);
  REQUIRE(m.vertex_colors.rows() == 4);
  CHECK(int(m.vertex_colors(3, 2)) == 30);
}

TEST_CASE("read_ply: tristrips with -1 restarts") {
  const auto m = read_ply("ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                          "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 0\n8 0 1 2 3 -1 1 3 4\n",
                          "s.ply");
  REQUIRE(m.mesh.num_faces() == 3);
  CHECK(m.mesh.F.row(0) == Eigen::RowVector3<index_t>(0, 1, 2));
  CHECK(m.mesh.F.row(1) == Eigen::RowVector3<index_t>(2, 1, 3));  // flipped to keep the orientation
  CHECK(m.mesh.F.row(2) == Eigen::RowVector3<index_t>(1, 3, 4));
}

TEST_CASE("read_ply errors: syntax, truncated, too_large, bad_value, bad_index, unsupported, cannot_open") {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  auto e = require_io_error([&] { (void)read_ply(head + "0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n", "s.ply"); }, file_error::syntax);
  CHECK(e.line() == 12);
  e = require_io_error([] { (void)read_ply("ply\nformat ascii 1.0\nelement vertex 3\nproperty quad x\n", "s.ply"); }, file_error::syntax);
  CHECK(e.line() == 4);
  require_io_error([] { (void)read_ply("plx\n", "s.ply"); }, file_error::syntax);
  require_io_error([&] { (void)read_ply(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "t.ply"); }, file_error::truncated);
  require_io_error([] { (void)read_ply("ply\nformat ascii 1.0\nelement vertex 3\n", "t.ply"); }, file_error::truncated);
  e = require_io_error([] { (void)read_ply("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                                           "property float y\nproperty float z\nend_header\n\x01\x02",
                                           "big.ply"); },
                       file_error::too_large);
  CHECK(e.byte_offset() > 0);
  e = require_io_error([&] { (void)read_ply(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", "i.ply"); }, file_error::bad_index);
  CHECK(e.line() == 13);
  e = require_io_error([&] { (void)read_ply(head + "0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", "v.ply"); }, file_error::bad_value);
  CHECK(e.line() == 11);
  require_io_error([] { (void)read_ply("ply\nformat ascii 1.0\nelement vertex -2\n", "v.ply"); }, file_error::bad_value);
  require_io_error([] { (void)read_ply("ply\nformat binary_middle_endian 1.0\nend_header\n", "u.ply"); }, file_error::unsupported);
  require_io_error([] { (void)read_ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float u\nend_header\n1\n", "u.ply"); },
                   file_error::unsupported);
  require_io_error([] { (void)read_ply(std::filesystem::path("/nonexistent/shapestruct/x.ply")); }, file_error::cannot_open);
}

TEST_CASE("read_ply errors: binary positions are byte offsets") {
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::size_t body = s.size();
  std::string good = s, bad = s;
  for (int i = 0; i < 9; ++i) {
    put(good, 0.0f, std::endian::little);
    put(bad, i == 4 ? std::numeric_limits<float>::quiet_NaN() : 0.0f, std::endian::little);
  }
  put(bad, std::uint8_t(3), std::endian::little);
  const auto e = require_io_error([&] { (void)read_ply(bad, "b.ply"); }, file_error::bad_value);
  CHECK(e.byte_offset() == static_cast<std::int64_t>(body + 16));
  CHECK(e.line() == 0);
  // The face's list says 3 indices; the file ends after its count byte.
  const auto t = require_io_error([&] { (void)read_ply(good + '\x03', "b.ply"); }, file_error::truncated);
  CHECK(t.byte_offset() == static_cast<std::int64_t>(body + 37));
}

TEST_CASE("format_ply/read_ply round trips: ASCII, binary both byte orders, colours, float and double, legacy_mesh") {
  const auto torus = make_torus<double>(1.0, 0.25, 9, 7);
  mesh_write_options opt;
  opt.vertex_colors.resize(torus.V.rows(), 3);
  for (index_t i = 0; i < torus.V.rows(); ++i) opt.vertex_colors.row(i) << std::uint8_t(i), std::uint8_t(200 - i), std::uint8_t(17);
  for (int variant = 0; variant < 3; ++variant) {
    CAPTURE(variant);
    opt.binary = variant > 0;
    opt.byte_order = variant == 2 ? std::endian::big : std::endian::little;
    const auto back = read_ply(format_ply<double>(torus.V, torus.F, opt), "rt.ply");
    CHECK(back.mesh.V == torus.V);
    CHECK(back.mesh.F == torus.F);
    CHECK(back.vertex_colors == opt.vertex_colors);
  }
  const triangle_mesh<float> f{torus.V.cast<float>(), torus.F};
  const auto fb = read_ply(format_ply<float>(f.V, f.F, {.binary = true}), "f.ply");
  CHECK(fb.mesh.V.cast<float>() == f.V);

  shapestruct::test::temp_folder tmp;
  const auto oct = shapestruct::test::octahedron<double>();
  write_ply(tmp.path / "legacy.ply", shapestruct::test::to_legacy(oct), {.binary = true, .byte_order = std::endian::big});
  const auto lb = read_ply(tmp.path / "legacy.ply");
  CHECK(lb.mesh.V == oct.V);
  CHECK(lb.mesh.F == oct.F);
}

TEST_CASE("format_ply writes the standard header MeshLab expects for coloured vertices") {
  const auto tet = shapestruct::test::tetrahedron<double>();
  mesh_write_options opt;
  opt.vertex_colors = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3>::Constant(4, 3, 100);
  const std::string s = format_ply<double>(tet.V, tet.F, opt);
  CHECK(s.starts_with("ply\nformat ascii 1.0\n"));
  CHECK(s.find("element vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                "element face 4\nproperty list uchar int vertex_indices\nend_header\n") != std::string::npos);
}
