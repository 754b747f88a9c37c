// SPDX-License-Identifier: MIT
// read_mesh/write_mesh: dispatch by extension (any case) and by content, round trips through files in every
// format for both mesh models, and the crash-safety of writing (temporary file + rename).
#include <fstream>

#include <doctest/doctest.h>

#include "io_test_helpers.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/write_mesh.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;
using shapestruct::test::require_io_error;
using shapestruct::test::temp_folder;

namespace {
std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("write_mesh/read_mesh round trip through every format, both mesh models") {
  temp_folder tmp;
  const auto torus = make_torus<double>(1.0, 0.4, 8, 6);
  const auto legacy = shapestruct::test::to_legacy(torus);
  mesh_write_options colors;
  colors.vertex_colors.resize(torus.V.rows(), 3);
  for (index_t i = 0; i < torus.V.rows(); ++i) colors.vertex_colors.row(i) << std::uint8_t(5 * i), std::uint8_t(i), std::uint8_t(99);
  for (const char* name : {"a.off", "b.OBJ", "c.ply", "d.Ply", "e.stl", "f.STL"}) {
    CAPTURE(name);
    const std::filesystem::path p = tmp.path / name;
    mesh_write_options opt = colors;
    opt.binary = std::string(name).starts_with("d") || std::string(name).starts_with("f");
    write_mesh(p, torus, opt);
    const auto back = read_mesh(p);
    REQUIRE(back.mesh.num_vertices() == torus.V.rows());
    REQUIRE(back.mesh.num_faces() == torus.F.rows());
    // STL is a triangle soup without colours: welding renumbers the vertices, so only counts are compared.
    if (io_detail::lower_extension(p) == "stl") continue;
    CHECK(back.mesh.V == torus.V);
    CHECK(back.mesh.F == torus.F);
    CHECK(back.vertex_colors == colors.vertex_colors);

    // The float-based legacy model: same faces, positions equal to the float values.
    write_mesh(p, legacy);
    const auto lb = read_mesh(p);
    CHECK(lb.mesh.F == torus.F);
    CHECK(lb.mesh.V == torus.V.cast<float>().cast<double>());
    CHECK(lb.vertex_colors.rows() == 0);
  }
}

TEST_CASE("read_mesh sniffs the content when the extension is missing or unknown") {
  temp_folder tmp;
  const auto tet = shapestruct::test::tetrahedron<double>();
  const std::pair<std::string, std::string> files[] = {
      {"noext_off", format_off<double>(tet.V, tet.F)},
      {"x.mesh", format_obj<double>(tet.V, tet.F)},
      {"ply_data", format_ply<double>(tet.V, tet.F, {.binary = true})},
      {"stl_data.bin", format_stl<double>(tet.V, tet.F, {.binary = true})},
      {"stl_text", format_stl<double>(tet.V, tet.F)},
  };
  for (const auto& [name, bytes] : files) {
    CAPTURE(name);
    std::ofstream(tmp.path / name, std::ios::binary) << bytes;
    const auto m = read_mesh(tmp.path / name);
    CHECK(m.mesh.num_vertices() == 4);
    CHECK(m.mesh.num_faces() == 4);
  }
  std::ofstream(tmp.path / "commented_off") << "# an OFF file with a comment first\n" << format_off<double>(tet.V, tet.F);
  CHECK(read_mesh(tmp.path / "commented_off").mesh.num_faces() == 4);
  std::ofstream(tmp.path / "garbage.dat") << "hello world\n";
  require_io_error([&] { (void)read_mesh(tmp.path / "garbage.dat"); }, file_error::unsupported);
  require_io_error([&] { (void)read_mesh(tmp.path / "missing.off"); }, file_error::cannot_open);
  require_io_error([&] { (void)read_mesh(tmp.path); }, file_error::cannot_open);
}

TEST_CASE("write_mesh never leaves a half-written file and keeps the old one on failure") {
  temp_folder tmp;
  const auto tet = shapestruct::test::tetrahedron<double>();
  const auto p = tmp.path / "keep.off";
  write_mesh(p, tet);
  const std::string before = slurp(p);

  // Invalid data is rejected before anything is written.
  auto bad = tet;
  bad.F(2, 1) = 17;
  CHECK_THROWS_AS(write_mesh(p, bad), invalid_input);
  auto nan = tet;
  nan.V(1, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(write_mesh(p, nan), invalid_input);
  mesh_write_options wrong_colors;
  wrong_colors.vertex_colors.resize(3, 3);
  CHECK_THROWS_AS(write_mesh(p, tet, wrong_colors), invalid_input);
  CHECK(slurp(p) == before);

  // A folder that does not exist: cannot_open, nothing created.
  require_io_error([&] { write_mesh(tmp.path / "no" / "such" / "dir.off", tet); }, file_error::cannot_open);
  // A destination that cannot be replaced (a non-empty folder with that name): write_failed, temp removed.
  std::filesystem::create_directories(tmp.path / "occupied.off" / "child");
  require_io_error([&] { write_mesh(tmp.path / "occupied.off", tet); }, file_error::write_failed);
  // An unknown extension.
  require_io_error([&] { write_mesh(tmp.path / "x.vtk", tet); }, file_error::unsupported);
  CHECK(slurp(p) == before);
  // No temporary files are left behind.
  for (const auto& entry : std::filesystem::directory_iterator(tmp.path))
    CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
}
