// SPDX-License-Identifier: MIT
// segmentation_file: reading and writing .seg files (one integer segment label per face, one per line).
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

/// Parses .seg text (PSB and COSEG ground truth): one integer label per face, one per line; blank lines and
/// `#` comments are ignored. Labels are returned as written (PSB is 0-based, COSEG 1-based).
/// \param bytes the file contents.
/// \param name_for_errors the path or name used in error messages.
/// \param expected_faces when not no_index, the number of labels the mesh needs.
/// \returns one label per face.
/// \throws io_error syntax (a line that is not one integer, reported as file:line), bad_value (a label out of
///         the index range, or a label count different from expected_faces).
/// Complexity: O(file size).
[[nodiscard]] inline std::vector<index_t> read_segmentation(std::string_view bytes, std::string_view name_for_errors,
                                                            index_t expected_faces = no_index) {
  io_detail::text_scanner sc(bytes, std::string(name_for_errors), '#');
  std::vector<index_t> labels;
  labels.reserve(bytes.size() / 2);
  while (sc.next_content_line()) {
    labels.push_back(static_cast<index_t>(sc.read_int("segment label")));
    if (!sc.at_line_end()) sc.fail(file_error::syntax, "expected one label per line, found more text after the label");
    sc.skip_rest_of_line();
  }
  if (expected_faces != no_index && static_cast<index_t>(labels.size()) != expected_faces)
    throw io_error(file_error::bad_value, std::string(name_for_errors), 0, 0,
                   "holds " + std::to_string(labels.size()) + " labels but the mesh has " + std::to_string(expected_faces) +
                       " faces");
  return labels;
}

/// Reads a .seg file; see read_segmentation(std::string_view, std::string_view, index_t).
/// \throws io_error as the in-memory overload, and cannot_open.
[[nodiscard]] inline std::vector<index_t> read_segmentation(const std::filesystem::path& path,
                                                            index_t expected_faces = no_index) {
  const std::string bytes = io_detail::read_file_bytes(path);
  return read_segmentation(bytes, path.string(), expected_faces);
}

/// Writes one label per line, atomically (temporary file + rename).
/// \param labels one label per face.
/// \throws io_error cannot_open or write_failed.
/// Complexity: O(#labels).
inline void write_segmentation(const std::filesystem::path& path, std::span<const index_t> labels) {
  std::string out;
  out.reserve(labels.size() * 4);
  for (index_t l : labels) {
    io_detail::append_number(out, l);
    out += '\n';
  }
  io_detail::write_file_atomically(path, out);
}

}  // namespace shapestruct
