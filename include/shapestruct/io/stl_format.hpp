// SPDX-License-Identifier: MIT
// stl_format: reading (ASCII and binary, welded into an indexed mesh) and writing STL files.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/file_bytes.hpp"
#include "shapestruct/io/mesh_file.hpp"
#include "shapestruct/io/mesh_write_options.hpp"
#include "shapestruct/io/polygon_soup.hpp"
#include "shapestruct/io/text_scanner.hpp"

namespace shapestruct {

namespace io_detail {

/// Merges STL corners that have exactly the same position, turning the triangle soup into an indexed mesh.
/// Exact comparison (not a tolerance) because STL writers repeat the same float for shared corners; a
/// tolerance would also merge distinct nearby vertices. -0 and +0 are the same position.
class vertex_welder {
 public:
  explicit vertex_welder(std::size_t expected) {
    map_.reserve(expected);
    xyz_.reserve(expected * 3);
  }
  index_t add(double x, double y, double z) {
    const key k{bits(x), bits(y), bits(z)};
    const auto [it, inserted] = map_.try_emplace(k, static_cast<index_t>(map_.size()));
    if (inserted) xyz_.insert(xyz_.end(), {x, y, z});
    return it->second;
  }
  void move_into(matrix_x3<double>& V) const {
    const index_t n = static_cast<index_t>(xyz_.size() / 3);
    V.resize(n, 3);
    for (index_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) V(i, c) = xyz_[static_cast<std::size_t>(3 * i + c)];
  }

 private:
  using key = std::array<std::uint64_t, 3>;
  struct key_hash {
    std::size_t operator()(const key& k) const noexcept {
      std::uint64_t h = 0x9E3779B97F4A7C15ull;
      for (std::uint64_t v : k) h = (h ^ v) * 0xBF58476D1CE4E5B9ull, h ^= h >> 31;
      return static_cast<std::size_t>(h);
    }
  };
  static std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v == 0 ? 0.0 : v); }
  std::unordered_map<key, index_t, key_hash> map_;
  std::vector<double> xyz_;
};

inline std::uint32_t load_le_u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}

/// True when the size is exactly 80 + 4 + 50 n with n the triangle count at byte 80: a binary STL.
inline bool stl_binary_size_matches(std::string_view bytes) {
  return bytes.size() >= 84 && 84 + 50ull * load_le_u32(bytes.data() + 80) == bytes.size();
}

inline bool looks_like_ascii_stl(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && text_scanner::is_space(bytes[i])) ++i;
  return bytes.size() - i >= 5 && iequals(bytes.substr(i, 5), "solid");
}

inline mesh_file<double> read_stl_binary(std::string_view bytes, const std::string& name) {
  const std::uint32_t n = load_le_u32(bytes.data() + 80);
  const std::uint64_t need = 84 + 50ull * n;
  if (need > bytes.size())
    throw io_error(file_error::truncated, name, 0, 80,
                   "binary STL announces " + std::to_string(n) + " triangles (" + std::to_string(need) +
                       " bytes) but the file has " + std::to_string(bytes.size()) + " bytes");
  mesh_file<double> out;
  vertex_welder weld(n);
  polygon_soup soup;
  soup.binary = true;
  soup.corners.reserve(3ull * n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const std::size_t base = 84 + 50ull * t;
    for (int c = 0; c < 3; ++c) {
      float p[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = std::bit_cast<float>(load_le_u32(bytes.data() + base + 12 + 12 * c + 4 * k));
        if (!std::isfinite(p[k]))
          throw io_error(file_error::bad_value, name, 0, static_cast<std::int64_t>(base + 12 + 12 * c + 4 * k),
                         "triangle " + std::to_string(t) + " has a non-finite coordinate");
      }
      soup.corners.push_back(weld.add(p[0], p[1], p[2]));
    }
    soup.close_polygon(static_cast<std::int64_t>(base));
  }
  weld.move_into(out.mesh.V);
  triangulate_soup(soup, name, out);
  return out;
}

inline mesh_file<double> read_stl_ascii(std::string_view bytes, const std::string& name) {
  text_scanner sc(bytes, name, '\0');
  auto next = [&](const char* what) {
    if (!sc.next_content_line()) sc.fail(file_error::truncated, std::string("the file ends where ") + what + " was expected");
    return sc.token();
  };
  auto expect = [&](std::string_view word) {
    const std::string_view t = next(std::string(word).c_str());
    if (!iequals(t, word))
      sc.fail(file_error::syntax, "expected '" + std::string(word) + "', found '" + text_scanner::clip(t) + "'");
  };
  mesh_file<double> out;
  vertex_welder weld(bytes.size() / 64);  // a facet takes about 200 bytes of text: 3 corners
  polygon_soup soup;
  bool any_solid = false;
  while (sc.next_content_line()) {
    const std::string_view start = sc.token();
    if (!iequals(start, "solid")) sc.fail(file_error::syntax, "expected 'solid', found '" + text_scanner::clip(start) + "'");
    any_solid = true;
    sc.skip_rest_of_line();  // the solid's name
    for (;;) {
      const std::string_view t = next("'facet' or 'endsolid'");
      if (iequals(t, "endsolid")) {
        sc.skip_rest_of_line();
        break;
      }
      if (!iequals(t, "facet")) sc.fail(file_error::syntax, "expected 'facet' or 'endsolid', found '" + text_scanner::clip(t) + "'");
      const std::int64_t facet_line = sc.line();
      // "normal nx ny nz" is skipped unparsed: consumers recompute normals, and some writers emit NaN there.
      std::string_view after = next("'normal' or 'outer'");
      if (iequals(after, "normal")) {
        for (int k = 0; k < 3; ++k) (void)next("a normal component");
        after = next("'outer'");
      }
      if (!iequals(after, "outer")) sc.fail(file_error::syntax, "expected 'outer', found '" + text_scanner::clip(after) + "'");
      expect("loop");
      for (;;) {
        const std::string_view v = next("'vertex' or 'endloop'");
        if (iequals(v, "endloop")) break;
        if (!iequals(v, "vertex")) sc.fail(file_error::syntax, "expected 'vertex' or 'endloop', found '" + text_scanner::clip(v) + "'");
        const double x = sc.read_double("vertex x coordinate");
        const double y = sc.read_double("vertex y coordinate");
        const double z = sc.read_double("vertex z coordinate");
        soup.corners.push_back(weld.add(x, y, z));
      }
      expect("endfacet");
      soup.close_polygon(facet_line);
    }
  }
  if (!any_solid) sc.fail(file_error::truncated, "the file is empty");
  weld.move_into(out.mesh.V);
  triangulate_soup(soup, name, out);
  return out;
}

}  // namespace io_detail

/// Reads an STL file from memory. Binary is recognised by its size (80-byte header + 4-byte count + 50 bytes
/// per triangle), not by the 'solid' keyword, which many binary writers put in their header; otherwise a file
/// starting with 'solid' is parsed as ASCII (several solids, polygonal facets allowed), and anything else
/// of at least 84 bytes as binary with a wrong size. Corners with exactly equal positions are welded, so the
/// result is an indexed mesh; face_polygon is the facet index. Normals and attribute bytes are ignored.
/// \param bytes the file contents.
/// \param name_for_errors the path or name used in error messages.
/// \throws io_error: syntax (bad keyword or number), truncated (data ends before the announced triangle count
///         or inside a facet), bad_value (non-finite coordinate). Binary positions are byte offsets.
/// Complexity: O(file size) expected (hash-based welding).
[[nodiscard]] inline mesh_file<double> read_stl(std::string_view bytes, std::string_view name_for_errors) {
  const std::string name(name_for_errors);
  if (io_detail::stl_binary_size_matches(bytes)) return io_detail::read_stl_binary(bytes, name);
  if (io_detail::looks_like_ascii_stl(bytes)) return io_detail::read_stl_ascii(bytes, name);
  if (bytes.size() >= 84) return io_detail::read_stl_binary(bytes, name);
  throw io_error(file_error::truncated, name, 0, 0,
                 "not an ASCII STL (no 'solid') and shorter than the 84-byte binary STL header (" +
                     std::to_string(bytes.size()) + " bytes)");
}

/// Reads an STL file; see read_stl(std::string_view, std::string_view).
/// \throws io_error as the in-memory overload, and cannot_open.
[[nodiscard]] inline mesh_file<double> read_stl(const std::filesystem::path& path) {
  const std::string bytes = io_detail::read_file_bytes(path);
  return read_stl(bytes, path.string());
}

/// Formats (V, F) as STL: binary (options.binary; float coordinates, little-endian, a header that does not
/// start with 'solid') or ASCII. Facet normals are the normalised cross products (0 for degenerate faces).
/// Vertex colours are ignored: STL has none.
/// \throws invalid_input non_finite, bad_face or bad_parameter (more than 2^32 - 1 triangles for binary).
/// Complexity: O(F).
template <class Scalar>
[[nodiscard]] std::string format_stl(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                                     const mesh_write_options& options = {}) {
  mesh_write_options no_colors;  // colours cannot be stored; do not reject a mismatched colour matrix here
  io_detail::check_writable<Scalar>(V, F, no_colors, "write_stl");
  auto normal = [&](index_t f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).template cast<double>(), b = V.row(F(f, 1)).template cast<double>(),
                          c = V.row(F(f, 2)).template cast<double>();
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
  };
  std::string out;
  if (options.binary) {
    if (F.rows() > 0xFFFFFFFFll)
      throw invalid_input(input_error::bad_parameter, no_index, "write_stl: binary STL holds at most 2^32 - 1 triangles");
    out.assign(80, ' ');
    const std::string_view header = "binary STL written by shapestruct";
    out.replace(0, header.size(), header);
    out.reserve(84 + 50 * static_cast<std::size_t>(F.rows()));
    io_detail::append_binary(out, static_cast<std::uint32_t>(F.rows()), std::endian::little);
    for (index_t f = 0; f < F.rows(); ++f) {
      const Eigen::Vector3d n = normal(f);
      for (int k = 0; k < 3; ++k) io_detail::append_binary(out, static_cast<float>(n[k]), std::endian::little);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) io_detail::append_binary(out, static_cast<float>(V(F(f, c), k)), std::endian::little);
      out.append(2, '\0');
    }
    return out;
  }
  out = "solid shapestruct\n";
  out.reserve(static_cast<std::size_t>(F.rows()) * 220 + 64);
  for (index_t f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d n = normal(f);
    out += "facet normal";
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      io_detail::append_number(out, n[k]);
    }
    out += "\n outer loop\n";
    for (int c = 0; c < 3; ++c) {
      out += "  vertex";
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        io_detail::append_number(out, V(F(f, c), k));
      }
      out += '\n';
    }
    out += " endloop\nendfacet\n";
  }
  out += "endsolid shapestruct\n";
  return out;
}

/// Writes any SurfaceMesh as an STL file, atomically (temporary file + rename).
/// \throws invalid_input (see format_stl), io_error cannot_open / write_failed.
template <SurfaceMesh Mesh>
void write_stl(const std::filesystem::path& path, const Mesh& mesh, const mesh_write_options& options = {}) {
  const auto& m = io_detail::as_triangle_mesh(mesh);
  using S = typename std::remove_cvref_t<decltype(m)>::scalar_type;
  io_detail::write_file_atomically(path, format_stl<S>(m.V, m.F, options));
}

}  // namespace shapestruct
