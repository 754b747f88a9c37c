// SPDX-License-Identifier: MIT
// surface_map: a precise correspondence from source vertices to surface points (face + barycentric) of a target.
#pragma once

#include <vector>

#include "shapestruct/core/surface_point.hpp"
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

}  // namespace shapestruct
