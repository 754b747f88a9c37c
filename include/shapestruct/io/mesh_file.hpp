// SPDX-License-Identifier: MIT
// mesh_file: what a mesh reader returns — the triangulated mesh plus the per-vertex and per-face extras.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// The contents of a mesh file. Polygons are triangulated on reading; `face_polygon` maps each triangle
/// back to the polygon (0-based, in file order) it came from, so per-polygon data (e.g. a .seg file written
/// for the polygon mesh) can be transferred to the triangles.
template <class Scalar = double>
struct mesh_file {
  triangle_mesh<Scalar> mesh;
  /// `#V x 3` 8-bit RGB colours, or empty (0 rows) when the file has none.
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3> vertex_colors;
  /// Source polygon (0-based index among the file's faces/facets) of each triangle; size #F.
  std::vector<index_t> face_polygon;
  /// OBJ only: index into group_names of each triangle (size #F), empty when the file has no `o`/`g` lines.
  std::vector<index_t> face_group;
  /// OBJ only: the names of the `o`/`g` objects and groups, in order of first appearance.
  std::vector<std::string> group_names;
  /// Faces of fewer than 3 corners in the file (OFF `2 0 1`, OBJ `f 1 2`): they bound no surface, so they are
  /// not in `mesh`; counted here so that a caller can say so rather than lose them silently.
  index_t short_faces = 0;
  /// Where the first of them is: a line (text formats) or a byte offset (binary PLY), 0 if there is none.
  std::int64_t first_short_face_at = 0;
  bool short_face_at_is_byte_offset = false;

  /// "FILE:LINE: N faces with fewer than 3 corners are not surfaces and were left out", or "" when none.
  [[nodiscard]] std::string short_faces_note(const std::string& file) const {
    if (short_faces == 0) return "";
    return file + (short_face_at_is_byte_offset ? ": byte " : ":") + std::to_string(first_short_face_at) + ": " +
           (short_faces == 1 ? std::string("a face with") : std::to_string(short_faces) + " faces with") +
           " fewer than 3 corners (a face needs 3) " + (short_faces == 1 ? "is" : "are") +
           " not part of the surface and left out" + (short_faces > 1 ? " (the first is here)" : "");
  }
};

}  // namespace shapestruct
