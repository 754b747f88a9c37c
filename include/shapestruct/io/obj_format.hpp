// SPDX-License-Identifier: MIT
// obj_format: reading and writing Wavefront OBJ polygon meshes (with objects/groups and vertex colours).
#pragma once

#include <charconv>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/file_bytes.hpp"
#include "shapestruct/io/mesh_file.hpp"
#include "shapestruct/io/mesh_write_options.hpp"
#include "shapestruct/io/polygon_soup.hpp"
#include "shapestruct/io/text_scanner.hpp"

namespace shapestruct {

/// Reads a Wavefront OBJ file from memory: `v x y z [w]` or `v x y z r g b` (colours 0..1, or 0..255 when
/// above 1), `f` polygons with 1-based, negative (relative) and `v/vt/vn`, `v//vn`, `v/vt` corners, `o` and
/// `g` lines (each distinct name becomes a group; triangles before the first one go to a group "default"),
/// `#` comments. Texture coordinates, normals, materials, smoothing groups, lines, points and unknown
/// statements are skipped. Vertex colours are returned only when every vertex has them.
/// \param bytes the file contents.
/// \param name_for_errors the path or name used in error messages.
/// \throws io_error: syntax (malformed number or corner), bad_value (non-finite or out-of-range coordinate,
///         colour out of range), bad_index (corner 0, or beyond the vertices defined so far). Every message
///         names the line.
/// Complexity: O(file size) plus triangulation of non-convex polygons.
[[nodiscard]] inline mesh_file<double> read_obj(std::string_view bytes, std::string_view name_for_errors) {
  using io_detail::text_scanner;
  text_scanner sc(bytes, std::string(name_for_errors), '#');
  std::vector<double> xyz;
  std::vector<std::uint8_t> rgb;
  std::size_t colored = 0;
  io_detail::polygon_soup soup;
  std::unordered_map<std::string, index_t> group_ids;
  std::vector<std::string> group_names;
  index_t group = no_index;
  bool any_group = false;
  xyz.reserve(bytes.size() / 16);  // "v x y z" lines are rarely shorter than ~30 bytes; cheap over-reserve
  while (sc.next_content_line()) {
    const std::string_view kw = sc.token();
    if (kw == "v") {
      for (int k = 0; k < 3; ++k) xyz.push_back(sc.read_double("vertex coordinate"));
      double extra[4];
      int n_extra = 0;
      while (n_extra < 4 && !sc.at_line_end()) extra[n_extra++] = sc.read_double("vertex colour or weight");
      if (n_extra >= 3) {
        // Colours either as 0..1 reals (MeshLab, the common extension) or as 0..255 values.
        const bool bytes_scale = extra[0] > 1 || extra[1] > 1 || extra[2] > 1;
        for (int k = 0; k < 3; ++k) {
          const double c = bytes_scale ? extra[k] : extra[k] * 255.0;
          if (c < 0 || c > 255.5) sc.fail(file_error::bad_value, "vertex colour component out of 0..1 / 0..255");
          rgb.push_back(static_cast<std::uint8_t>(c + 0.5 > 255 ? 255 : c + 0.5));
        }
        ++colored;
      } else {
        rgb.insert(rgb.end(), {0, 0, 0});
      }
    } else if (kw == "f") {
      const std::int64_t nv = static_cast<std::int64_t>(xyz.size() / 3);
      for (;;) {
        const std::string_view t = sc.token();
        if (t.empty()) break;
        std::int64_t idx = 0;
        const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), idx);
        const bool well_formed = ec == std::errc() && (ptr == t.data() + t.size() || *ptr == '/');
        if (!well_formed) {
          if (ec == std::errc::result_out_of_range)
            sc.fail(file_error::bad_index, "corner '" + text_scanner::clip(t) + "' is out of range");
          sc.fail(file_error::syntax, "expected a face corner (v, v/vt, v/vt/vn or v//vn), found '" + text_scanner::clip(t) + "'");
        }
        for (const char* q = ptr; q != t.data() + t.size(); ++q)
          if (!((*q >= '0' && *q <= '9') || *q == '/' || *q == '-'))
            sc.fail(file_error::syntax, "malformed face corner '" + text_scanner::clip(t) + "'");
        if (idx == 0) sc.fail(file_error::bad_index, "face corner index 0: OBJ indices start at 1");
        const std::int64_t resolved = idx > 0 ? idx - 1 : nv + idx;
        if (resolved < 0 || resolved >= nv)
          sc.fail(file_error::bad_index, "face corner " + std::to_string(idx) + " refers to a vertex that is not defined (" +
                                             std::to_string(nv) + " vertices so far)");
        soup.corners.push_back(resolved);
      }
      soup.close_polygon(sc.line());
      soup.group.push_back(group);
    } else if (kw == "o" || kw == "g") {
      std::string name(sc.rest_of_line());
      if (name.empty()) name = "default";
      const auto [it, inserted] = group_ids.try_emplace(name, static_cast<index_t>(group_names.size()));
      if (inserted) group_names.push_back(name);
      group = it->second;
      any_group = true;
    }
    sc.skip_rest_of_line();
  }

  mesh_file<double> out;
  const index_t n = static_cast<index_t>(xyz.size() / 3);
  out.mesh.V.resize(n, 3);
  for (index_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) out.mesh.V(i, c) = xyz[static_cast<std::size_t>(3 * i + c)];
  if (n > 0 && colored == static_cast<std::size_t>(n)) {
    out.vertex_colors.resize(n, 3);
    for (index_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) out.vertex_colors(i, c) = rgb[static_cast<std::size_t>(3 * i + c)];
  }
  if (any_group) {
    index_t fallback = no_index;
    for (index_t& g : soup.group)
      if (g == no_index) {
        if (fallback == no_index) {
          const auto [it, inserted] = group_ids.try_emplace("default", static_cast<index_t>(group_names.size()));
          if (inserted) group_names.push_back("default");
          fallback = it->second;
        }
        g = fallback;
      }
    out.group_names = std::move(group_names);
  } else {
    soup.group.clear();
  }
  io_detail::triangulate_soup(soup, sc.name(), out);
  return out;
}

/// Reads an OBJ file; see read_obj(std::string_view, std::string_view).
/// \throws io_error as the in-memory overload, and cannot_open.
[[nodiscard]] inline mesh_file<double> read_obj(const std::filesystem::path& path) {
  const std::string bytes = io_detail::read_file_bytes(path);
  return read_obj(bytes, path.string());
}

/// Formats (V, F) as OBJ text: `v x y z` (plus `r g b` in 0..1 when options.vertex_colors is set) and 1-based
/// `f a b c` lines. Coordinates are written in the shortest form that reads back exactly.
/// \throws invalid_input non_finite, bad_face or size_mismatch.
/// Complexity: O(V + F).
template <class Scalar>
[[nodiscard]] std::string format_obj(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                                     const mesh_write_options& options = {}) {
  io_detail::check_writable<Scalar>(V, F, options, "write_obj");
  const bool colors = options.vertex_colors.rows() != 0;
  std::string out = "# written by shapestruct\n";
  out.reserve(static_cast<std::size_t>(V.rows()) * 40 + static_cast<std::size_t>(F.rows()) * 24 + 32);
  for (index_t i = 0; i < V.rows(); ++i) {
    out += 'v';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      io_detail::append_number(out, V(i, k));
    }
    if (colors)
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        // c / 255 as a float reads back to the same byte after * 255 and rounding.
        io_detail::append_number(out, static_cast<float>(options.vertex_colors(i, k)) / 255.0f);
      }
    out += '\n';
  }
  for (index_t f = 0; f < F.rows(); ++f) {
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      io_detail::append_number(out, F(f, k) + 1);
    }
    out += '\n';
  }
  return out;
}

/// Writes any SurfaceMesh as an OBJ file, atomically (temporary file + rename).
/// \throws invalid_input (see format_obj), io_error cannot_open / write_failed.
template <SurfaceMesh Mesh>
void write_obj(const std::filesystem::path& path, const Mesh& mesh, const mesh_write_options& options = {}) {
  const auto& m = io_detail::as_triangle_mesh(mesh);
  using S = typename std::remove_cvref_t<decltype(m)>::scalar_type;
  io_detail::write_file_atomically(path, format_obj<S>(m.V, m.F, options));
}

}  // namespace shapestruct
