// SPDX-License-Identifier: MIT
// mesh_write_options: what the mesh writers accept besides the mesh, and the checks they share.
#pragma once

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <string>
#include <type_traits>

#include <Eigen/Core>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Options of write_mesh() and the per-format writers.
struct mesh_write_options {
  /// `#V x 3` RGB colours written per vertex (OFF: COFF, OBJ: `v x y z r g b`, PLY: uchar red/green/blue);
  /// empty for none. STL has no vertex colours: they are ignored there.
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3> vertex_colors{};
  /// PLY and STL: write the binary variant (smaller, faster, exact floats) instead of ASCII.
  bool binary = false;
  /// Binary PLY byte order (binary STL is always little-endian by definition).
  std::endian byte_order = std::endian::little;
};

namespace io_detail {

template <class T>
struct is_triangle_mesh : std::false_type {};
template <class S>
struct is_triangle_mesh<triangle_mesh<S>> : std::true_type {};

/// The mesh as a triangle_mesh: a reference for triangle_mesh itself (no copy), a gathered copy otherwise.
template <SurfaceMesh Mesh>
decltype(auto) as_triangle_mesh(const Mesh& mesh) {
  if constexpr (is_triangle_mesh<Mesh>::value) return (mesh);
  else return to_triangle_mesh<double>(mesh);
}

/// Rejects what no format could represent faithfully before anything is written.
/// \throws invalid_input non_finite (vertex), bad_face (face index out of range) or size_mismatch (colours).
template <class Scalar>
void check_writable(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                    const mesh_write_options& options, const char* who) {
  for (index_t i = 0; i < V.rows(); ++i)
    if (!V.row(i).allFinite())
      throw invalid_input(input_error::non_finite, i,
                          std::string(who) + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  for (index_t f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (F(f, c) < 0 || F(f, c) >= V.rows())
        throw invalid_input(input_error::bad_face, f,
                            std::string(who) + ": face " + std::to_string(f) + " refers to vertex " +
                                std::to_string(F(f, c)) + " of " + std::to_string(V.rows()));
  if (options.vertex_colors.rows() != 0 && options.vertex_colors.rows() != V.rows())
    throw invalid_input(input_error::size_mismatch, no_index,
                        std::string(who) + ": vertex_colors has " + std::to_string(options.vertex_colors.rows()) +
                            " rows for " + std::to_string(V.rows()) + " vertices (leave it empty for no colours)");
}

/// Appends the shortest decimal text that reads back as exactly `v`.
template <class T>
inline void append_number(std::string& out, T v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}

/// Appends the raw bytes of `v` in the requested byte order.
template <class T>
inline void append_binary(std::string& out, T v, std::endian order) {
  static_assert(std::is_trivially_copyable_v<T>);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));
  if (order != std::endian::native)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out.append(bytes, sizeof(T));
}

}  // namespace io_detail
}  // namespace shapestruct
