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
};

}  // namespace shapestruct
