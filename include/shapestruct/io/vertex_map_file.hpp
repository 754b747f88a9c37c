// SPDX-License-Identifier: MIT
// vertex_map_file: reading and writing dense .map files (the 0-based target vertex of each source vertex).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/io/file_bytes.hpp"
#include "shapestruct/io/mesh_write_options.hpp"
#include "shapestruct/io/text_scanner.hpp"

namespace shapestruct {

/// Parses a dense .map file (the BIM benchmark format): line i holds the 0-based id of the target vertex
/// that source vertex i maps to. Blank lines and `#` comments are ignored.
/// \param bytes the file contents.
/// \param name_for_errors the path or name used in error messages.
/// \param target_vertices when not no_index, ids must lie in [0, target_vertices).
/// \param source_vertices when not no_index, the file must hold exactly this many lines of ids.
/// \returns the target id of each source vertex.
/// \throws io_error syntax (not one integer per line; file:line), bad_index (negative id or id out of the
///         target's range; file:line), bad_value (count differs from source_vertices).
/// Complexity: O(file size).
[[nodiscard]] inline std::vector<index_t> read_vertex_map(std::string_view bytes, std::string_view name_for_errors,
                                                          index_t target_vertices = no_index,
                                                          index_t source_vertices = no_index) {
  io_detail::text_scanner sc(bytes, std::string(name_for_errors), '#');
  std::vector<index_t> map;
  map.reserve(bytes.size() / 2);
  while (sc.next_content_line()) {
    const std::int64_t id = sc.read_int("target vertex id");
    if (id < 0 || (target_vertices != no_index && id >= target_vertices))
      sc.fail(file_error::bad_index, "target vertex id " + std::to_string(id) + " is out of range" +
                                         (target_vertices != no_index ? " [0, " + std::to_string(target_vertices) + ")" : ""));
    if (!sc.at_line_end()) sc.fail(file_error::syntax, "expected one vertex id per line, found more text after it");
    map.push_back(static_cast<index_t>(id));
    sc.skip_rest_of_line();
  }
  if (source_vertices != no_index && static_cast<index_t>(map.size()) != source_vertices)
    throw io_error(file_error::bad_value, std::string(name_for_errors), 0, 0,
                   "holds " + std::to_string(map.size()) + " vertex ids but the source mesh has " +
                       std::to_string(source_vertices) + " vertices");
  return map;
}

/// Reads a .map file; see read_vertex_map(std::string_view, std::string_view, index_t, index_t).
/// \throws io_error as the in-memory overload, and cannot_open.
[[nodiscard]] inline std::vector<index_t> read_vertex_map(const std::filesystem::path& path,
                                                          index_t target_vertices = no_index,
                                                          index_t source_vertices = no_index) {
  const std::string bytes = io_detail::read_file_bytes(path);
  return read_vertex_map(bytes, path.string(), target_vertices, source_vertices);
}

/// Writes one 0-based target id per line, atomically (temporary file + rename).
/// \throws invalid_input bad_parameter for a negative id; io_error cannot_open or write_failed.
/// Complexity: O(#ids).
inline void write_vertex_map(const std::filesystem::path& path, std::span<const index_t> target_of_source) {
  std::string out;
  out.reserve(target_of_source.size() * 6);
  for (std::size_t i = 0; i < target_of_source.size(); ++i) {
    if (target_of_source[i] < 0)
      throw invalid_input(input_error::bad_parameter, static_cast<index_t>(i),
                          "write_vertex_map: source vertex " + std::to_string(i) + " has no target (id " +
                              std::to_string(target_of_source[i]) + "); a dense .map needs one for every vertex");
    io_detail::append_number(out, target_of_source[i]);
    out += '\n';
  }
  io_detail::write_file_atomically(path, out);
}

}  // namespace shapestruct
