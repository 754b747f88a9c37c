// SPDX-License-Identifier: MIT
// polygon_soup: the readers' common intermediate — polygons as read, turned into triangles at the end.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/io/mesh_file.hpp"
#include "shapestruct/io/polygon_triangulation.hpp"

namespace shapestruct::io_detail {

/// Polygons collected while parsing. Triangulation waits until all vertices are known (PLY may list faces
/// before vertices), and each polygon keeps where it was read (line or byte offset) so that an index out of
/// range is reported at its place in the file.
struct polygon_soup {
  std::vector<index_t> corners;
  std::vector<std::size_t> starts{0};  ///< polygon k holds corners[starts[k] .. starts[k+1])
  std::vector<std::int64_t> where;     ///< line (text) or byte offset (binary) of each polygon
  std::vector<index_t> group;          ///< OBJ group of each polygon, or empty
  bool binary = false;                 ///< whether `where` holds byte offsets

  [[nodiscard]] std::size_t size() const noexcept { return where.size(); }
  void close_polygon(std::int64_t at) {
    starts.push_back(corners.size());
    where.push_back(at);
  }
};

/// Checks every corner against the vertex count, triangulates, and fills out.mesh.F, out.face_polygon and
/// (when soup.group is set) out.face_group. V must already be in out.mesh.V.
/// \throws io_error bad_index naming the polygon's line or byte offset.
template <class Scalar>
void triangulate_soup(const polygon_soup& soup, const std::string& name, mesh_file<Scalar>& out) {
  const index_t nv = out.mesh.V.rows();
  std::vector<std::array<index_t, 3>> tris;
  tris.reserve(soup.corners.size() / 3 + 1);
  std::vector<index_t> origin;
  origin.reserve(soup.corners.size() / 3 + 1);
  for (std::size_t k = 0; k < soup.size(); ++k) {
    const std::span<const index_t> poly(soup.corners.data() + soup.starts[k], soup.starts[k + 1] - soup.starts[k]);
    for (std::size_t c = 0; c < poly.size(); ++c)
      if (poly[c] < 0 || poly[c] >= nv)
        throw io_error(file_error::bad_index, name, soup.binary ? 0 : soup.where[k], soup.binary ? soup.where[k] : 0,
                       "face " + std::to_string(k) + " refers to vertex " + std::to_string(poly[c]) + " but the file has " +
                           std::to_string(nv) + " vertices (valid: 0.." + std::to_string(nv - 1) + ")");
    if (poly.size() < 3) {
      if (out.short_faces++ == 0) {
        out.first_short_face_at = soup.where[k];
        out.short_face_at_is_byte_offset = soup.binary;
      }
      continue;
    }
    const std::size_t before = tris.size();
    triangulate_polygon(out.mesh.V, poly, tris);
    origin.insert(origin.end(), tris.size() - before, static_cast<index_t>(k));
  }
  out.mesh.F.resize(static_cast<index_t>(tris.size()), 3);
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int c = 0; c < 3; ++c) out.mesh.F(static_cast<index_t>(t), c) = tris[t][static_cast<std::size_t>(c)];
  out.face_polygon = std::move(origin);
  if (!soup.group.empty()) {
    out.face_group.resize(out.face_polygon.size());
    for (std::size_t t = 0; t < out.face_polygon.size(); ++t)
      out.face_group[t] = soup.group[static_cast<std::size_t>(out.face_polygon[t])];
  }
}

}  // namespace shapestruct::io_detail
