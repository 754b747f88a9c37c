// SPDX-License-Identifier: MIT
// off_format: reading and writing Geomview OFF files (OFF, COFF, NOFF, CNOFF, STOFF, ... with polygons).
#pragma once

#include <cctype>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/file_bytes.hpp"
#include "shapestruct/io/mesh_file.hpp"
#include "shapestruct/io/mesh_write_options.hpp"
#include "shapestruct/io/polygon_soup.hpp"
#include "shapestruct/io/text_scanner.hpp"

namespace shapestruct {

namespace io_detail {

/// One colour component as written in COFF files: integers are 0..255, numbers with a point or exponent
/// are 0..1 (both conventions occur in the wild).
inline std::uint8_t parse_color_component(text_scanner& sc, std::string_view t) {
  const bool fractional = t.find_first_of(".eE") != std::string_view::npos;
  const double v = sc.parse_double(t, "colour component");
  const double scaled = fractional ? v * 255.0 : v;
  if (scaled < 0 || scaled > 255.5)
    sc.fail(file_error::bad_value, "colour component '" + text_scanner::clip(t) + "' is outside 0..255 (or 0..1)");
  return static_cast<std::uint8_t>(scaled + 0.5 > 255 ? 255 : scaled + 0.5);
}

/// Moves to the next token even if it is on a later line (OFF headers are free-format).
inline void next_header_token(text_scanner& sc, const char* what) {
  if (sc.at_line_end()) {
    sc.skip_rest_of_line();
    if (!sc.next_content_line())
      sc.fail(file_error::truncated, std::string("the file ends in the header, before the ") + what);
  }
}

}  // namespace io_detail

/// Reads an OFF file from memory. Accepts the keyword with any of the prefixes ST (texture coordinates),
/// C (vertex colours), N (normals) — e.g. OFF, COFF, NOFF, CNOFF, STCNOFF — or no keyword at all, `#`
/// comments and blank lines anywhere, the counts on the keyword's line or later, extra columns after the
/// data of each vertex or face (face colours), and polygons of any size, which are triangulated
/// (triangulate_polygon). COFF colours (0..255 integers or 0..1 reals) go to vertex_colors.
/// \param bytes the file contents.
/// \param name_for_errors the path or name used in error messages.
/// \returns the triangulated mesh, face_polygon, and vertex_colors for COFF files.
/// \throws io_error: syntax (bad keyword or token), truncated (fewer vertices/faces than announced), too_large
///         (counts that the remaining bytes cannot hold, checked before allocating), bad_value (negative count,
///         non-finite coordinate, colour out of range), bad_index (corner out of range), unsupported (4D,
///         n-dimensional or binary OFF). Every message names the line.
/// Complexity: O(file size) plus triangulation of non-convex polygons.
[[nodiscard]] inline mesh_file<double> read_off(std::string_view bytes, std::string_view name_for_errors) {
  using io_detail::text_scanner;
  text_scanner sc(bytes, std::string(name_for_errors), '#');
  if (!sc.next_content_line()) sc.fail(file_error::truncated, "the file is empty: expected the OFF keyword and counts");

  bool has_color = false, has_normal = false;
  std::string_view first = sc.token();
  const bool keyword_less = !(first.size() >= 3 && first.substr(first.size() - 3) == "OFF") && !first.empty() &&
                            (std::isdigit(static_cast<unsigned char>(first[0])) != 0);
  if (!keyword_less) {
    std::string_view kw = first;
    if (kw.size() < 3 || kw.substr(kw.size() - 3) != "OFF")
      sc.fail(file_error::syntax, "expected the OFF keyword (OFF, COFF, NOFF, ...), found '" + text_scanner::clip(first) + "'");
    kw.remove_suffix(3);
    if (kw.starts_with("ST")) kw.remove_prefix(2);
    if (kw.starts_with("C")) { has_color = true; kw.remove_prefix(1); }
    if (kw.starts_with("N")) { has_normal = true; kw.remove_prefix(1); }
    if (kw == "4" || kw == "n" || kw == "4n")
      sc.fail(file_error::unsupported, "'" + std::string(first) + "' (4D or n-dimensional OFF) is not supported, only 3D");
    if (!kw.empty()) sc.fail(file_error::syntax, "unknown OFF keyword '" + text_scanner::clip(first) + "'");
    // Anything else on the keyword line must be the counts.
    first = sc.token();
    if (first == "BINARY") sc.fail(file_error::unsupported, "binary OFF is not supported, only ASCII OFF");
  }
  // The vertex count is `first` when it was already consumed on the keyword line.
  std::int64_t nv = 0;
  if (!first.empty()) {
    nv = sc.parse_int(first, "vertex count");
  } else {
    io_detail::next_header_token(sc, "vertex count");
    nv = sc.read_int("vertex count");
  }
  io_detail::next_header_token(sc, "face count");
  const std::int64_t nf = sc.read_int("face count");
  if (!sc.at_line_end()) (void)sc.read_int("edge count");  // the edge count is optional and unused
  if (nv < 0 || nf < 0)
    sc.fail(file_error::bad_value, "negative count in the header (" + std::to_string(nv) + " vertices, " +
                                       std::to_string(nf) + " faces)");
  // Cheapest possible records: "0 0 0\n" (6 bytes) per vertex, "0\n" (2 bytes) per face. Anything more
  // than the remaining bytes could hold is rejected before V is allocated.
  const std::int64_t rem = static_cast<std::int64_t>(sc.remaining()) + 1;
  if (nv > rem / 6 || nf > (rem - 6 * nv) / 2)
    sc.fail(file_error::too_large, "the header announces " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                       " faces, more than the remaining " + std::to_string(rem - 1) + " bytes can hold");
  sc.skip_rest_of_line();

  mesh_file<double> out;
  out.mesh.V.resize(nv, 3);
  if (has_color) out.vertex_colors.resize(nv, 3);
  for (std::int64_t i = 0; i < nv; ++i) {
    if (!sc.next_content_line())
      sc.fail(file_error::truncated, "the file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    out.mesh.V(i, 0) = sc.read_double("vertex x coordinate");
    out.mesh.V(i, 1) = sc.read_double("vertex y coordinate");
    out.mesh.V(i, 2) = sc.read_double("vertex z coordinate");
    if (has_color) {
      if (has_normal)
        for (int k = 0; k < 3; ++k) (void)sc.read_double("vertex normal component");
      for (int k = 0; k < 3; ++k) {
        const std::string_view t = sc.token();
        if (t.empty()) sc.fail(file_error::syntax, "COFF vertex " + std::to_string(i) + " has no colour (expected r g b [a])");
        out.vertex_colors(i, k) = io_detail::parse_color_component(sc, t);
      }
    }
    sc.skip_rest_of_line();  // alpha, texture coordinates, anything else
  }

  io_detail::polygon_soup soup;
  soup.corners.reserve(static_cast<std::size_t>(nf) * 3);
  soup.starts.reserve(static_cast<std::size_t>(nf) + 1);
  soup.where.reserve(static_cast<std::size_t>(nf));
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!sc.next_content_line())
      sc.fail(file_error::truncated, "the file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const std::int64_t n = sc.read_int("face corner count");
    if (n < 0) sc.fail(file_error::bad_value, "face " + std::to_string(f) + " has a negative corner count " + std::to_string(n));
    for (std::int64_t c = 0; c < n; ++c) {
      const std::string_view t = sc.token();
      if (t.empty())
        sc.fail(file_error::syntax, "face " + std::to_string(f) + " announces " + std::to_string(n) +
                                        " corners but the line holds only " + std::to_string(c));
      soup.corners.push_back(static_cast<index_t>(sc.parse_int(t, "vertex index")));
    }
    soup.close_polygon(sc.line());
    sc.skip_rest_of_line();  // face colours
  }
  io_detail::triangulate_soup(soup, sc.name(), out);
  return out;
}

/// Reads an OFF file; see read_off(std::string_view, std::string_view).
/// \throws io_error as the in-memory overload, and cannot_open.
[[nodiscard]] inline mesh_file<double> read_off(const std::filesystem::path& path) {
  const std::string bytes = io_detail::read_file_bytes(path);
  return read_off(bytes, path.string());
}

/// Formats (V, F) as OFF text (COFF with integer 0..255 colours when options.vertex_colors is set).
/// Coordinates are written in the shortest form that reads back exactly.
/// \param V `#V x 3` positions, \param F `#F x 3` indices (checked: in range, finite coordinates).
/// \throws invalid_input non_finite, bad_face or size_mismatch.
/// Complexity: O(V + F).
template <class Scalar>
[[nodiscard]] std::string format_off(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                                     const mesh_write_options& options = {}) {
  io_detail::check_writable<Scalar>(V, F, options, "write_off");
  const bool colors = options.vertex_colors.rows() != 0;
  std::string out = colors ? "COFF\n" : "OFF\n";
  out.reserve(static_cast<std::size_t>(V.rows()) * 40 + static_cast<std::size_t>(F.rows()) * 24 + 32);
  out += std::to_string(V.rows()) + " " + std::to_string(F.rows()) + " 0\n";
  for (index_t i = 0; i < V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (k) out += ' ';
      io_detail::append_number(out, V(i, k));
    }
    if (colors)
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        io_detail::append_number(out, static_cast<int>(options.vertex_colors(i, k)));
      }
    if (colors) out += " 255";
    out += '\n';
  }
  for (index_t f = 0; f < F.rows(); ++f) {
    out += '3';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      io_detail::append_number(out, F(f, k));
    }
    out += '\n';
  }
  return out;
}

/// Writes any SurfaceMesh as an OFF file, atomically (temporary file + rename).
/// \throws invalid_input (see format_off), io_error cannot_open / write_failed.
template <SurfaceMesh Mesh>
void write_off(const std::filesystem::path& path, const Mesh& mesh, const mesh_write_options& options = {}) {
  const auto& m = io_detail::as_triangle_mesh(mesh);
  using S = typename std::remove_cvref_t<decltype(m)>::scalar_type;
  io_detail::write_file_atomically(path, format_off<S>(m.V, m.F, options));
}

}  // namespace shapestruct
