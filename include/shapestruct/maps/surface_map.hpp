// SPDX-License-Identifier: MIT
// surface_map: a precise correspondence from source vertices to surface points (face + barycentric) of a target.
#pragma once

#include <utility>
#include <vector>

#include "shapestruct/core/surface_point.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Source vertex i -> points[i] on the target surface, with the nearest target vertex cached (so that
/// target_vertex is O(1)). Models CorrespondenceMap.
template <class Scalar = double>
struct surface_map {
  using scalar_type = Scalar;
  std::vector<surface_point<Scalar>> points;  ///< (#source vertices) images; face == no_index if unmapped
  std::vector<index_t> nearest;               ///< (#source vertices) nearest target vertex of each image

  [[nodiscard]] index_t source_size() const noexcept { return static_cast<index_t>(points.size()); }
  [[nodiscard]] index_t target_vertex(index_t i) const { return nearest[static_cast<std::size_t>(i)]; }
  [[nodiscard]] const surface_point<Scalar>& point(index_t i) const { return points[static_cast<std::size_t>(i)]; }
};

/// The map whose image of source vertex i is the target vertex `vertices[i]` (a corner of one of its faces). A
/// vertex of b on no face cannot be an image: its entry is left unmapped (face and nearest no_index).
template <class Scalar>
[[nodiscard]] surface_map<Scalar> surface_map_at_vertices(const triangle_mesh<Scalar>& b,
                                                          const std::vector<index_t>& vertices) {
  std::vector<std::pair<index_t, int>> corner(static_cast<std::size_t>(b.V.rows()), {no_index, 0});
  for (index_t f = 0; f < b.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (corner[static_cast<std::size_t>(b.F(f, c))].first == no_index) corner[static_cast<std::size_t>(b.F(f, c))] = {f, c};
  surface_map<Scalar> m;
  m.points.resize(vertices.size());
  m.nearest = vertices;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const index_t v = vertices[i];
    const auto [f, c] = v >= 0 && v < b.V.rows() ? corner[static_cast<std::size_t>(v)] : std::pair<index_t, int>{no_index, 0};
    if (f == no_index) {
      m.nearest[i] = no_index;
      continue;
    }
    m.points[i].face = f;
    m.points[i].bary[c] = Scalar(1);
  }
  return m;
}

}  // namespace shapestruct
