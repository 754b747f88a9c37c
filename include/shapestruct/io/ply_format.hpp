// SPDX-License-Identifier: MIT
// ply_format: reading and writing Stanford PLY files (ASCII, binary little- and big-endian).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
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

namespace io_detail {

enum class ply_type : std::uint8_t { i8, u8, i16, u16, i32, u32, f32, f64 };

inline bool parse_ply_type(std::string_view s, ply_type& t) {
  if (s == "char" || s == "int8") t = ply_type::i8;
  else if (s == "uchar" || s == "uint8") t = ply_type::u8;
  else if (s == "short" || s == "int16") t = ply_type::i16;
  else if (s == "ushort" || s == "uint16") t = ply_type::u16;
  else if (s == "int" || s == "int32") t = ply_type::i32;
  else if (s == "uint" || s == "uint32") t = ply_type::u32;
  else if (s == "float" || s == "float32") t = ply_type::f32;
  else if (s == "double" || s == "float64") t = ply_type::f64;
  else return false;
  return true;
}

inline std::size_t ply_size(ply_type t) {
  switch (t) {
    case ply_type::i8: case ply_type::u8: return 1;
    case ply_type::i16: case ply_type::u16: return 2;
    case ply_type::i32: case ply_type::u32: case ply_type::f32: return 4;
    case ply_type::f64: return 8;
  }
  return 1;
}

inline bool ply_is_float(ply_type t) { return t == ply_type::f32 || t == ply_type::f64; }

struct ply_property {
  std::string name;
  bool is_list = false;
  ply_type count_type = ply_type::u8;
  ply_type value_type = ply_type::f32;
};

struct ply_element {
  std::string name;
  std::int64_t count = 0;
  std::int64_t line = 0;  ///< header line, for messages
  std::vector<ply_property> props;
};

/// An index or count stored in a floating-point property: accepted when it is a whole number.
template <class Source>
std::int64_t integral_value(const Source& src, double v, const char* what) {
  // 2^62: beyond it a double no longer converts exactly and no real file has such indices.
  if (!(std::abs(v) < 4.6e18) || std::floor(v) != v)
    src.fail(file_error::bad_value, std::string(what) + " " + std::to_string(v) + " is not a whole number");
  return static_cast<std::int64_t>(v);
}

/// Values of the body of an ASCII PLY file: whitespace-separated tokens, records may span lines.
class ply_ascii_source {
 public:
  explicit ply_ascii_source(text_scanner& sc) : sc_(sc) {}
  [[noreturn]] void fail(file_error r, const std::string& problem) const { sc_.fail(r, problem); }
  [[nodiscard]] std::size_t remaining() const { return sc_.remaining(); }
  /// The line of the next value (moving past line ends first, so a record is reported where it starts).
  [[nodiscard]] std::int64_t where() {
    (void)sc_.next_content_line();
    return sc_.line();
  }

  double value(ply_type t, const char* what) {
    const std::string_view tok = next(what);
    if (ply_is_float(t)) return sc_.parse_double(tok, what);
    return static_cast<double>(sc_.parse_int(tok, what));
  }
  std::int64_t integer(ply_type t, const char* what) {
    const std::string_view tok = next(what);
    if (!ply_is_float(t)) return sc_.parse_int(tok, what);
    return integral_value(*this, sc_.parse_double(tok, what), what);
  }
  void skip(ply_type, std::int64_t n) {
    for (std::int64_t i = 0; i < n; ++i) (void)next("property value");
  }

 private:
  std::string_view next(const char* what) {
    if (!sc_.next_content_line())
      sc_.fail(file_error::truncated, std::string("the file ends where a ") + what + " was expected");
    return sc_.token();
  }
  text_scanner& sc_;
};

/// Values of the body of a binary PLY file in either byte order.
class ply_binary_source {
 public:
  ply_binary_source(std::string_view bytes, std::size_t pos, std::endian order, std::string name)
      : bytes_(bytes), pos_(pos), order_(order), name_(std::move(name)) {}
  [[noreturn]] void fail(file_error r, const std::string& problem) const {
    throw io_error(r, name_, 0, static_cast<std::int64_t>(pos_), problem);
  }
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - pos_; }
  [[nodiscard]] std::int64_t where() const { return static_cast<std::int64_t>(pos_); }

  double value(ply_type t, const char* what) {
    switch (t) {
      case ply_type::i8: return get<std::int8_t>(what);
      case ply_type::u8: return get<std::uint8_t>(what);
      case ply_type::i16: return get<std::int16_t>(what);
      case ply_type::u16: return get<std::uint16_t>(what);
      case ply_type::i32: return get<std::int32_t>(what);
      case ply_type::u32: return get<std::uint32_t>(what);
      case ply_type::f32: {
        const float v = get<float>(what);
        if (!std::isfinite(v)) { pos_ -= 4; fail(file_error::bad_value, std::string(what) + " is not finite"); }
        return v;
      }
      case ply_type::f64: {
        const double v = get<double>(what);
        if (!std::isfinite(v)) { pos_ -= 8; fail(file_error::bad_value, std::string(what) + " is not finite"); }
        return v;
      }
    }
    return 0;
  }
  std::int64_t integer(ply_type t, const char* what) {
    switch (t) {
      case ply_type::i8: return get<std::int8_t>(what);
      case ply_type::u8: return get<std::uint8_t>(what);
      case ply_type::i16: return get<std::int16_t>(what);
      case ply_type::u16: return get<std::uint16_t>(what);
      case ply_type::i32: return get<std::int32_t>(what);
      case ply_type::u32: return get<std::uint32_t>(what);
      case ply_type::f32: case ply_type::f64: return integral_value(*this, value(t, what), what);
    }
    return 0;
  }
  void skip(ply_type t, std::int64_t n) {
    const std::size_t need = ply_size(t);
    if (n < 0 || static_cast<std::uint64_t>(n) > remaining() / need)
      fail(file_error::truncated, "the file ends inside a list of " + std::to_string(n) + " values");
    pos_ += need * static_cast<std::size_t>(n);
  }

 private:
  template <class T>
  T get(const char* what) {
    if (remaining() < sizeof(T)) fail(file_error::truncated, std::string("the file ends where a ") + what + " was expected");
    char b[sizeof(T)];
    std::memcpy(b, bytes_.data() + pos_, sizeof(T));
    if (order_ != std::endian::native)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    T v;
    std::memcpy(&v, b, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::string_view bytes_;
  std::size_t pos_;
  std::endian order_;
  std::string name_;
};

/// 0..255 from an integer (clamped) or a 0..1 real colour channel.
inline std::uint8_t ply_color(double v, ply_type t) {
  const double s = ply_is_float(t) ? v * 255.0 : v;
  return static_cast<std::uint8_t>(s <= 0 ? 0 : s >= 255 ? 255 : s + 0.5);
}

template <class Source>
void read_ply_body(Source& src, const std::vector<ply_element>& elements, bool binary, const std::string& name,
                   mesh_file<double>& out, polygon_soup& soup) {
  bool have_vertices = false;
  for (const ply_element& e : elements) {
    if (e.count == 0 || e.props.empty()) continue;  // nothing to read; avoids spinning on 0-byte records
    // Cheapest record: every scalar 1 byte / every list only its count (binary), or 2 characters per value
    // (ASCII). Rejecting counts the rest of the file cannot hold keeps hostile headers from allocating.
    std::size_t min_record = 0;
    for (const ply_property& p : e.props) min_record += binary ? ply_size(p.is_list ? p.count_type : p.value_type) : 2;
    if (static_cast<std::uint64_t>(e.count) > (src.remaining() + 1) / min_record)
      src.fail(file_error::too_large, "element '" + e.name + "' announces " + std::to_string(e.count) +
                                          " records but only " + std::to_string(src.remaining()) + " bytes remain");
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face", is_strip = e.name == "tristrips";
    if (is_vertex) {
      if (have_vertices) src.fail(file_error::syntax, "the file has two 'vertex' elements");
      have_vertices = true;
      int xyz[3] = {-1, -1, -1}, rgb[3] = {-1, -1, -1};
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const ply_property& p = e.props[k];
        if (p.is_list) continue;
        const char* names[] = {"x", "y", "z", "red", "green", "blue"};
        for (int c = 0; c < 6; ++c)
          if (p.name == names[c]) (c < 3 ? xyz[c] : rgb[c - 3]) = static_cast<int>(k);
      }
      if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
        throw io_error(file_error::unsupported, name, e.line, 0, "the vertex element has no x, y and z properties");
      const bool colors = rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0;
      out.mesh.V.resize(e.count, 3);
      if (colors) out.vertex_colors.resize(e.count, 3);
      for (std::int64_t i = 0; i < e.count; ++i)
        for (std::size_t k = 0; k < e.props.size(); ++k) {
          const ply_property& p = e.props[k];
          if (p.is_list) {
            src.skip(p.value_type, src.integer(p.count_type, "list length"));
            continue;
          }
          const double v = src.value(p.value_type, "vertex property value");
          const int ki = static_cast<int>(k);
          for (int c = 0; c < 3; ++c) {
            if (ki == xyz[c]) out.mesh.V(i, c) = v;
            if (colors && ki == rgb[c]) out.vertex_colors(i, c) = ply_color(v, p.value_type);
          }
        }
      continue;
    }
    int list = -1;
    if (is_face || is_strip)
      for (std::size_t k = 0; k < e.props.size(); ++k)
        if (e.props[k].is_list && (e.props[k].name == "vertex_indices" || e.props[k].name == "vertex_index"))
          list = static_cast<int>(k);
    if ((is_face || is_strip) && list < 0)
      throw io_error(file_error::unsupported, name, e.line, 0,
                     "the " + e.name + " element has no vertex_indices / vertex_index list property");
    if (is_face) {
      soup.corners.reserve(soup.corners.size() + static_cast<std::size_t>(e.count) * 3);
      soup.where.reserve(soup.where.size() + static_cast<std::size_t>(e.count));
    }
    for (std::int64_t i = 0; i < e.count; ++i)
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const ply_property& p = e.props[k];
        if (!p.is_list) {
          src.skip(p.value_type, 1);
          continue;
        }
        const std::int64_t at = src.where();
        const std::int64_t n = src.integer(p.count_type, "list length");
        if (n < 0) src.fail(file_error::bad_value, "negative list length " + std::to_string(n));
        if (static_cast<int>(k) != list) {
          src.skip(p.value_type, n);
          continue;
        }
        if (static_cast<std::uint64_t>(n) > src.remaining())
          src.fail(file_error::truncated, "a list of " + std::to_string(n) + " indices is longer than the rest of the file");
        if (is_face) {
          for (std::int64_t c = 0; c < n; ++c) soup.corners.push_back(src.integer(p.value_type, "vertex index"));
          soup.close_polygon(at);
        } else {
          // Triangle strip with -1 restarts; every other triangle is flipped to keep a consistent orientation.
          std::int64_t a = -1, b = -1, pos = 0;
          for (std::int64_t c = 0; c < n; ++c) {
            const std::int64_t v = src.integer(p.value_type, "vertex index");
            if (v < 0) { a = b = -1; pos = 0; continue; }
            if (pos >= 2 && a != b && b != v && a != v) {
              if (pos % 2 == 0) soup.corners.insert(soup.corners.end(), {a, b, v});
              else soup.corners.insert(soup.corners.end(), {b, a, v});
              soup.close_polygon(at);
            }
            a = b;
            b = v;
            ++pos;
          }
        }
      }
  }
  if (!have_vertices && !soup.corners.empty())
    throw io_error(file_error::syntax, name, 0, 0, "the file has faces but no vertex element");
}

}  // namespace io_detail

/// Reads a PLY file from memory: ASCII, binary_little_endian or binary_big_endian; properties of any type
/// (char..double, int8..float64) in any order; x, y, z and optional red, green, blue (uchar 0..255 or real
/// 0..1) of the `vertex` element; the `vertex_indices` or `vertex_index` list (any count and index type) of
/// `face` (polygons, triangulated) and `tristrips` (-1 restarts); every other element and property skipped.
/// \param bytes the file contents.
/// \param name_for_errors the path or name used in error messages.
/// \throws io_error: syntax (malformed header or token), truncated (data ends early), too_large (element
///         counts the file cannot hold, checked before allocating), bad_value (non-finite coordinate,
///         negative list length, fractional index), bad_index (index out of range), unsupported (unknown
///         format, vertex element without x/y/z). Text positions are lines, binary positions byte offsets.
/// Complexity: O(file size) plus triangulation of non-convex polygons.
[[nodiscard]] inline mesh_file<double> read_ply(std::string_view bytes, std::string_view name_for_errors) {
  using namespace io_detail;
  const std::string name(name_for_errors);
  text_scanner sc(bytes, name, '\0');
  if (!sc.next_content_line() || sc.token() != "ply")
    sc.fail(file_error::syntax, "not a PLY file: the first line must be 'ply'");
  sc.skip_rest_of_line();
  int format = -1;  // 0 ascii, 1 little, 2 big
  std::vector<ply_element> elements;
  bool ended = false;
  while (sc.next_content_line()) {
    const std::string_view kw = sc.token();
    if (kw == "comment" || kw == "obj_info") {
      sc.skip_rest_of_line();
      continue;
    }
    if (kw == "end_header") {
      sc.skip_rest_of_line();
      ended = true;
      break;
    }
    if (kw == "format") {
      const std::string_view f = sc.token();
      if (f == "ascii") format = 0;
      else if (f == "binary_little_endian") format = 1;
      else if (f == "binary_big_endian") format = 2;
      else sc.fail(file_error::unsupported, "unknown PLY format '" + text_scanner::clip(f) + "'");
      (void)sc.token();  // version
    } else if (kw == "element") {
      ply_element e;
      e.name = std::string(sc.token());
      if (e.name.empty()) sc.fail(file_error::syntax, "element without a name");
      e.count = sc.read_int("element count");
      if (e.count < 0) sc.fail(file_error::bad_value, "element '" + e.name + "' has a negative count");
      e.line = sc.line();
      elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (elements.empty()) sc.fail(file_error::syntax, "property before any element");
      ply_property p;
      std::string_view t = sc.token();
      if (t == "list") {
        p.is_list = true;
        const std::string_view ct = sc.token();
        if (!parse_ply_type(ct, p.count_type))
          sc.fail(file_error::syntax, "unknown list count type '" + text_scanner::clip(ct) + "'");
        t = sc.token();
      }
      if (!parse_ply_type(t, p.value_type)) sc.fail(file_error::syntax, "unknown property type '" + text_scanner::clip(t) + "'");
      p.name = std::string(sc.token());
      if (p.name.empty()) sc.fail(file_error::syntax, "property without a name");
      elements.back().props.push_back(std::move(p));
    } else {
      sc.fail(file_error::syntax, "unknown header keyword '" + text_scanner::clip(kw) + "'");
    }
    if (!sc.at_line_end()) sc.fail(file_error::syntax, "unexpected text at the end of the header line");
    sc.skip_rest_of_line();
  }
  if (!ended) sc.fail(file_error::truncated, "the file ends inside the header (no end_header line)");
  if (format < 0) sc.fail(file_error::syntax, "the header has no format line");

  mesh_file<double> out;
  polygon_soup soup;
  if (format == 0) {
    ply_ascii_source src(sc);
    read_ply_body(src, elements, false, name, out, soup);
  } else {
    soup.binary = true;
    ply_binary_source src(bytes, static_cast<std::size_t>(sc.position() - bytes.data()),
                          format == 1 ? std::endian::little : std::endian::big, name);
    read_ply_body(src, elements, true, name, out, soup);
  }
  triangulate_soup(soup, name, out);
  return out;
}

/// Reads a PLY file; see read_ply(std::string_view, std::string_view).
/// \throws io_error as the in-memory overload, and cannot_open.
[[nodiscard]] inline mesh_file<double> read_ply(const std::filesystem::path& path) {
  const std::string bytes = io_detail::read_file_bytes(path);
  return read_ply(bytes, path.string());
}

/// Formats (V, F) as a PLY file with the standard header MeshLab, Blender and CloudCompare read: `vertex`
/// with x, y, z (float for float meshes, double for double meshes, so values round-trip exactly) and
/// uchar red, green, blue when options.vertex_colors is set; `face` with `list uchar int vertex_indices`.
/// options.binary selects binary in options.byte_order, otherwise ASCII.
/// \throws invalid_input non_finite, bad_face or size_mismatch.
/// Complexity: O(V + F).
template <class Scalar>
[[nodiscard]] std::string format_ply(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                                     const mesh_write_options& options = {}) {
  io_detail::check_writable<Scalar>(V, F, options, "write_ply");
  if (F.rows() > 0 && V.rows() > std::numeric_limits<std::int32_t>::max())
    throw invalid_input(input_error::bad_parameter, no_index, "write_ply: more than 2^31 vertices do not fit PLY int indices");
  const bool colors = options.vertex_colors.rows() != 0;
  const char* type = std::is_same_v<Scalar, float> ? "float" : "double";
  std::string out = "ply\nformat ";
  out += !options.binary ? "ascii" : options.byte_order == std::endian::big ? "binary_big_endian" : "binary_little_endian";
  out += " 1.0\ncomment written by shapestruct\nelement vertex " + std::to_string(V.rows()) + "\n";
  for (const char* c : {"x", "y", "z"}) out += std::string("property ") + type + " " + c + "\n";
  if (colors) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out += "element face " + std::to_string(F.rows()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  out.reserve(out.size() + static_cast<std::size_t>(V.rows()) * 40 + static_cast<std::size_t>(F.rows()) * 24);
  using W = std::conditional_t<std::is_same_v<Scalar, float>, float, double>;
  for (index_t i = 0; i < V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (options.binary) io_detail::append_binary(out, static_cast<W>(V(i, k)), options.byte_order);
      else {
        if (k) out += ' ';
        io_detail::append_number(out, static_cast<W>(V(i, k)));
      }
    }
    if (colors)
      for (int k = 0; k < 3; ++k) {
        if (options.binary) out += static_cast<char>(options.vertex_colors(i, k));
        else {
          out += ' ';
          io_detail::append_number(out, static_cast<int>(options.vertex_colors(i, k)));
        }
      }
    if (!options.binary) out += '\n';
  }
  for (index_t f = 0; f < F.rows(); ++f) {
    if (options.binary) {
      out += static_cast<char>(3);
      for (int k = 0; k < 3; ++k) io_detail::append_binary(out, static_cast<std::int32_t>(F(f, k)), options.byte_order);
    } else {
      out += '3';
      for (int k = 0; k < 3; ++k) {
        out += ' ';
        io_detail::append_number(out, F(f, k));
      }
      out += '\n';
    }
  }
  return out;
}

/// Writes any SurfaceMesh as a PLY file, atomically (temporary file + rename).
/// \throws invalid_input (see format_ply), io_error cannot_open / write_failed.
template <SurfaceMesh Mesh>
void write_ply(const std::filesystem::path& path, const Mesh& mesh, const mesh_write_options& options = {}) {
  const auto& m = io_detail::as_triangle_mesh(mesh);
  using S = typename std::remove_cvref_t<decltype(m)>::scalar_type;
  io_detail::write_file_atomically(path, format_ply<S>(m.V, m.F, options));
}

}  // namespace shapestruct
