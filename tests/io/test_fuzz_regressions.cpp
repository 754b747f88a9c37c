// SPDX-License-Identifier: MIT
// Replays every fuzzer finding (tests/fuzz/regressions/<format>/) and seed (tests/fuzz/corpus/<format>/)
// through its reader: each must either read or throw io_error — never crash, hang or throw anything else.
// Also hostile inputs written by hand: huge counts, deep lists, pathological polygons.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "shapestruct/io/read_mesh.hpp"

using namespace shapestruct;
namespace fs = std::filesystem;

namespace {

using reader_fn = std::function<mesh_file<double>(std::string_view, std::string_view)>;

const std::map<std::string, reader_fn>& readers() {
  static const std::map<std::string, reader_fn> r = {
      {"off", [](std::string_view b, std::string_view n) { return read_off(b, n); }},
      {"obj", [](std::string_view b, std::string_view n) { return read_obj(b, n); }},
      {"ply", [](std::string_view b, std::string_view n) { return read_ply(b, n); }},
      {"stl", [](std::string_view b, std::string_view n) { return read_stl(b, n); }},
  };
  return r;
}

/// Success or io_error, within a generous hang guard; the result, if any, is self-consistent.
void replay(const reader_fn& read, const std::string& bytes, const std::string& name) {
  CAPTURE(name);
  const auto start = std::chrono::steady_clock::now();
  try {
    const auto m = read(bytes, name);
    CHECK(m.mesh.V.allFinite());
    CHECK(static_cast<index_t>(m.face_polygon.size()) == m.mesh.num_faces());
    if (m.mesh.num_faces() > 0) {
      CHECK(m.mesh.F.minCoeff() >= 0);
      CHECK(m.mesh.F.maxCoeff() < m.mesh.num_vertices());
    }
  } catch (const io_error& e) {
    CHECK(!std::string(e.what()).empty());
  }
  // A hang guard for sanitizer builds on loaded machines; the fuzzers enforce 1 s per input in their own runs.
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
}

std::size_t replay_folder(const std::string& kind) {
  std::size_t n = 0;
  for (const auto& [format, read] : readers()) {
    const fs::path dir = fs::path(SHAPESTRUCT_TEST_SOURCE_DIR) / "fuzz" / kind / format;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (!entry.is_regular_file()) continue;
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      replay(read, bytes, entry.path().string());
      ++n;
    }
  }
  return n;
}

}  // namespace

TEST_CASE("fuzzer findings replay: success or io_error") {
  MESSAGE("replayed " << replay_folder("regressions") << " regression inputs");
}

TEST_CASE("fuzzer seed corpus replay: every seed reads successfully") {
  CHECK(replay_folder("corpus") >= 8);
  for (const auto& [format, read] : readers()) {
    const fs::path dir = fs::path(SHAPESTRUCT_TEST_SOURCE_DIR) / "fuzz" / "corpus" / format;
    for (const auto& entry : fs::directory_iterator(dir)) {
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      CAPTURE(entry.path().string());
      CHECK_NOTHROW((void)read(bytes, entry.path().string()));
    }
  }
}

TEST_CASE("hostile inputs: huge announced counts are refused before allocating") {
  const std::vector<std::string> offs = {
      "OFF\n18446744073709551615 1 0\n", "OFF\n9223372036854775807 9223372036854775807 0\n0 0 0\n",
      "OFF\n1 9223372036854775807 0\n0 0 0\n", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n9223372036854775807 0 1 2\n"};
  for (const std::string& off : offs)
    CHECK_THROWS_AS((void)read_off(off, "h.off"), io_error);
  const std::string ply_head = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  CHECK_THROWS_AS((void)read_ply(ply_head + "element face 9223372036854775807\nproperty list uint uint vertex_indices\nend_header\n" +
                                     std::string(36, '\0') + "\xff\xff\xff\xff",
                                 "h.ply"),
                  io_error);
  CHECK_THROWS_AS((void)read_ply(ply_head + "element face 1\nproperty list uint uint vertex_indices\nend_header\n" +
                                     std::string(36, '\0') + "\xff\xff\xff\xff\0\0\0\0",
                                 "h.ply"),
                  io_error);
  // An element without properties but an astronomic count: nothing to read, must not loop.
  const auto m = read_ply("ply\nformat ascii 1.0\nelement nothing 9223372036854775807\nelement vertex 0\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n",
                          "e.ply");
  CHECK(m.mesh.num_vertices() == 0);
  std::string stl(84, '\0');
  stl[80] = stl[81] = stl[82] = stl[83] = '\xff';
  CHECK_THROWS_AS((void)read_stl(stl, "h.stl"), io_error);
}

TEST_CASE("hostile inputs: a 200000-corner concave polygon reads quickly") {
  std::string obj;
  const int k = 100000;
  for (int i = 0; i < 2 * k; ++i) {
    const double r = i % 2 ? 0.5 : 1.0, a = 3.14159265358979 * i / k;
    obj.append("v ").append(std::to_string(r * std::cos(a))).append(" ").append(std::to_string(r * std::sin(a))).append(" 0\n");
  }
  obj += "f";
  for (int i = 1; i <= 2 * k; ++i) obj.append(" ").append(std::to_string(i));
  obj += "\n";
  replay(readers().at("obj"), obj, "star.obj");
}
