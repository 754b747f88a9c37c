// SPDX-License-Identifier: MIT
// Reads a few files of every benchmark data set under $SHAPESTRUCT_DATA and checks the vertex/face counts
// against the files' own headers (parsed here independently, with iostreams), plus the .seg and .map files.
#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "shapestruct/io/vertex_map_file.hpp"
#include "support/data_path.hpp"

using namespace shapestruct;
namespace fs = std::filesystem;

namespace {

/// The first `n` files with extension `ext` in `dir`, sorted by name (deterministic selection).
std::vector<fs::path> first_files(const fs::path& dir, const std::string& ext, std::size_t n) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ext) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  if (out.size() > n) out.resize(n);
  return out;
}

/// OFF header counts, read with iostreams (independent of the reader under test).
std::pair<index_t, index_t> off_header(const fs::path& p) {
  std::ifstream in(p);
  std::string kw;
  index_t nv = -1, nf = -1;
  in >> kw >> nv >> nf;
  return {nv, nf};
}

/// PLY header element counts.
index_t ply_count(const fs::path& p, const std::string& element) {
  std::ifstream in(p, std::ios::binary);
  std::string line;
  while (std::getline(in, line) && line.rfind("end_header", 0) != 0) {
    std::istringstream ls(line);
    std::string a, name;
    index_t n = -1;
    if (ls >> a >> name >> n && a == "element" && name == element) return n;
  }
  return -1;
}

/// Vertex count and triangle count (sum of corners - 2 over `f` lines) of an OBJ file.
std::pair<index_t, index_t> obj_counts(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  index_t nv = 0, nt = 0;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string kw, tok;
    ls >> kw;
    if (kw == "v") ++nv;
    if (kw == "f") {
      index_t corners = 0;
      while (ls >> tok) ++corners;
      nt += std::max<index_t>(0, corners - 2);
    }
  }
  return {nv, nt};
}

void check_off_folder(const fs::path& dir, std::size_t n) {
  const auto files = first_files(dir, ".off", n);
  REQUIRE(!files.empty());
  for (const auto& f : files) {
    CAPTURE(f.string());
    const auto [nv, nf] = off_header(f);
    const auto m = read_mesh(f);
    CHECK(m.mesh.num_vertices() == nv);
    CHECK(m.mesh.num_faces() == nf);  // these data sets hold triangles only
    CHECK(static_cast<index_t>(m.face_polygon.size()) == nf);
    CHECK(m.mesh.V.allFinite());
  }
}

}  // namespace

TEST_CASE("data: SCAPE meshes") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "SCAPE");
  check_off_folder(dir / "Meshes", 3);
  const auto m = read_mesh(dir / "Meshes" / "mesh000.off");
  CHECK(m.mesh.num_vertices() == 12500);
}

TEST_CASE("data: TOSCA meshes") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "TOSCA");
  check_off_folder(dir / "Meshes", 3);
}

TEST_CASE("data: watertight SHREC'07 meshes") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "watertight_shrec07");
  check_off_folder(dir / "Meshes", 3);
}

TEST_CASE("data: PSB meshes and their segmentations") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "psb");
  check_off_folder(dir / "data" / "off", 3);
  const auto m = read_mesh(dir / "data" / "off" / "1.off");
  for (const auto& seg : first_files(dir / "data" / "seg" / "Benchmark" / "1", ".seg", 3)) {
    CAPTURE(seg.string());
    const auto labels = read_segmentation(seg, m.mesh.num_faces());
    CHECK(*std::min_element(labels.begin(), labels.end()) >= 0);
  }
}

TEST_CASE("data: COSEG chairs and tele-aliens with ground-truth labels") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "coseg_subset");
  for (const char* set : {"chairs", "tele-aliens"}) {
    CAPTURE(set);
    check_off_folder(dir / "res" / set / "shapes", 2);
    for (const auto& shape : first_files(dir / "res" / set / "shapes", ".off", 2)) {
      const auto m = read_mesh(shape);
      const auto labels = read_segmentation(dir / "res" / set / "gt" / (shape.stem().string() + ".seg"), m.mesh.num_faces());
      CHECK(*std::min_element(labels.begin(), labels.end()) >= 1);  // COSEG labels are 1-based
    }
  }
}

TEST_CASE("data: FAUST registrations (binary little-endian PLY)") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "faust_registrations");
  for (const auto& f : first_files(dir / "registrations", ".ply", 3)) {
    CAPTURE(f.string());
    const auto m = read_mesh(f);
    CHECK(m.mesh.num_vertices() == ply_count(f, "vertex"));
    CHECK(m.mesh.num_faces() == ply_count(f, "face"));
    CHECK(m.mesh.num_vertices() == 6890);
    CHECK(m.mesh.num_faces() == 13776);
  }
}

TEST_CASE("data: common 3D test models (OBJ and PLY)") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "common-3d-test-models");
  for (const auto& f : first_files(dir / "data", ".obj", 100)) {
    CAPTURE(f.string());
    const auto [nv, nt] = obj_counts(f);
    const auto m = read_mesh(f);
    CHECK(m.mesh.num_vertices() == nv);
    // Degenerate polygons (repeated corners) yield fewer triangles than corners - 2, never more.
    CHECK(m.mesh.num_faces() <= nt);
    CHECK(m.mesh.num_faces() >= nt * 99 / 100);
  }
  for (const auto& f : first_files(dir / "data", ".ply", 10)) {
    CAPTURE(f.string());
    const auto m = read_mesh(f);
    CHECK(m.mesh.num_vertices() == ply_count(f, "vertex"));
    CHECK(m.mesh.num_faces() > 0);  // igea.ply stores triangle strips, so there is no face count to compare
  }
}

TEST_CASE("data: BIM sample dense map") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "SampleMaps");
  const auto map = read_vertex_map(dir / "scape_0_to_1_blended.map", 12500, 12500);
  CHECK(map.size() == 12500);
}
