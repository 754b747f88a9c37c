// SPDX-License-Identifier: MIT
// read_mesh: reads OFF, OBJ, PLY or STL, chosen by extension (case-insensitive) or, failing that, by content.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/file_bytes.hpp"
#include "shapestruct/io/mesh_file.hpp"
#include "shapestruct/io/obj_format.hpp"
#include "shapestruct/io/off_format.hpp"
#include "shapestruct/io/ply_format.hpp"
#include "shapestruct/io/stl_format.hpp"

namespace shapestruct {

/// The mesh formats shapestruct reads and writes.
enum class mesh_format { off, obj, ply, stl, unknown };

/// Guesses the format from the content: an exact binary-STL size, "ply", "solid", then the first statement
/// after blank and `#` comment lines (which both OFF and OBJ allow): an OFF keyword or an OBJ statement
/// (v, vt, vn, f, o, g, mtllib, usemtl, s). Returns unknown when nothing matches.
/// Complexity: O(length of the leading comment lines).
[[nodiscard]] inline mesh_format sniff_mesh_format(std::string_view bytes) {
  if (io_detail::stl_binary_size_matches(bytes)) return mesh_format::stl;
  std::size_t i = 0;
  while (i < bytes.size() && io_detail::text_scanner::is_space(bytes[i])) ++i;
  const std::string_view head = bytes.substr(i);
  if (head.starts_with("ply")) return mesh_format::ply;
  if (io_detail::looks_like_ascii_stl(bytes)) return mesh_format::stl;
  io_detail::text_scanner sc(bytes, "", '#');
  if (!sc.next_content_line()) return mesh_format::unknown;
  const std::string_view word = sc.token();
  if (word.size() >= 3 && word.substr(word.size() - 3) == "OFF") return mesh_format::off;
  for (std::string_view kw : {"v", "vt", "vn", "f", "o", "g", "mtllib", "usemtl", "s"})
    if (word == kw) return mesh_format::obj;
  return mesh_format::unknown;
}

/// The format for a path's extension (.off, .obj, .ply, .stl in any case), unknown otherwise.
[[nodiscard]] inline mesh_format mesh_format_of(const std::filesystem::path& path) {
  const std::string ext = io_detail::lower_extension(path);
  if (ext == "off") return mesh_format::off;
  if (ext == "obj") return mesh_format::obj;
  if (ext == "ply") return mesh_format::ply;
  if (ext == "stl") return mesh_format::stl;
  return mesh_format::unknown;
}

/// Reads a mesh held in memory in the given format (sniffed from the content when `format` is unknown).
/// \throws io_error from the format's reader, or unsupported when the format cannot be recognised.
[[nodiscard]] inline mesh_file<double> read_mesh(std::string_view bytes, std::string_view name_for_errors,
                                                 mesh_format format = mesh_format::unknown) {
  if (format == mesh_format::unknown) format = sniff_mesh_format(bytes);
  switch (format) {
    case mesh_format::off: return read_off(bytes, name_for_errors);
    case mesh_format::obj: return read_obj(bytes, name_for_errors);
    case mesh_format::ply: return read_ply(bytes, name_for_errors);
    case mesh_format::stl: return read_stl(bytes, name_for_errors);
    case mesh_format::unknown: break;
  }
  throw io_error(file_error::unsupported, std::string(name_for_errors), 0, 0,
                 "unknown mesh format: neither the extension nor the content is OFF, OBJ, PLY or STL");
}

/// Reads an OFF, OBJ, PLY or STL file, chosen by the extension (case-insensitive), or by the content when the
/// extension is missing or unknown. Polygons are triangulated; see mesh_file for what else is returned.
/// \param path the file.
/// \returns the mesh and its per-vertex / per-face extras.
/// \throws io_error cannot_open, unsupported (unknown format), and whatever the format's reader throws.
/// Complexity: O(file size) plus triangulation of non-convex polygons.
[[nodiscard]] inline mesh_file<double> read_mesh(const std::filesystem::path& path) {
  const std::string bytes = io_detail::read_file_bytes(path);
  return read_mesh(bytes, path.string(), mesh_format_of(path));
}

}  // namespace shapestruct
