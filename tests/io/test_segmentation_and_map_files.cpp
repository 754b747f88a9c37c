// SPDX-License-Identifier: MIT
// .seg and .map files: round trips, blank lines and comments, errors with file:line.
#include <doctest/doctest.h>

#include "io_test_helpers.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "shapestruct/io/vertex_map_file.hpp"

using namespace shapestruct;
using shapestruct::test::require_io_error;

TEST_CASE("segmentation files: read, write, round trip") {
  CHECK(read_segmentation("0\n1\n\n# comment\n1\r\n2", "a.seg") == std::vector<index_t>{0, 1, 1, 2});
  shapestruct::test::temp_folder tmp;
  const std::vector<index_t> labels{3, 1, 4, 1, 5, 9, 2, 6};
  write_segmentation(tmp.path / "x.seg", labels);
  CHECK(read_segmentation(tmp.path / "x.seg") == labels);
  CHECK(read_segmentation(tmp.path / "x.seg", 8) == labels);
}

TEST_CASE("segmentation files: errors name file and line") {
  auto e = require_io_error([] { (void)read_segmentation("0\n1\nleg\n2\n", "bad.seg"); }, file_error::syntax);
  CHECK(e.line() == 3);
  CHECK(std::string(e.what()).starts_with("bad.seg:3:"));
  e = require_io_error([] { (void)read_segmentation("0\n1 2\n", "bad.seg"); }, file_error::syntax);
  CHECK(e.line() == 2);
  require_io_error([] { (void)read_segmentation("0\n99999999999999999999999\n", "bad.seg"); }, file_error::bad_value);
  require_io_error([] { (void)read_segmentation("0\n1\n", "n.seg", 3); }, file_error::bad_value);
  require_io_error([] { (void)read_segmentation(std::filesystem::path("/nonexistent/x.seg")); }, file_error::cannot_open);
}

TEST_CASE("vertex map files: read, write, range checks") {
  CHECK(read_vertex_map("5\n0\n\n3\n", "a.map") == std::vector<index_t>{5, 0, 3});
  shapestruct::test::temp_folder tmp;
  const std::vector<index_t> map{2, 0, 1, 1};
  write_vertex_map(tmp.path / "m.map", map);
  CHECK(read_vertex_map(tmp.path / "m.map", 3, 4) == map);
  auto e = require_io_error([] { (void)read_vertex_map("0\n1\n7\n", "r.map", 5); }, file_error::bad_index);
  CHECK(e.line() == 3);
  e = require_io_error([] { (void)read_vertex_map("0\n-1\n", "r.map"); }, file_error::bad_index);
  CHECK(e.line() == 2);
  e = require_io_error([] { (void)read_vertex_map("0\n1.5\n", "r.map"); }, file_error::syntax);
  CHECK(e.line() == 2);
  require_io_error([] { (void)read_vertex_map("0\n1\n", "r.map", no_index, 3); }, file_error::bad_value);
  CHECK_THROWS_AS(write_vertex_map(tmp.path / "n.map", std::vector<index_t>{0, -1}), invalid_input);
  CHECK(!std::filesystem::exists(tmp.path / "n.map"));
}
