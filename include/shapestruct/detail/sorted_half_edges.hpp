// SPDX-License-Identifier: MIT
// sorted_half_edges: a triangle list's edges, one entry per face corner, sorted so that the faces of an edge meet.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "shapestruct/core/types.hpp"

namespace shapestruct::detail {

/// The edge opposite corner `corner` of face `face`, as its lower and its higher point index.
struct half_edge {
  index_t lo, hi, face;
  int corner;
};

/// The half-edges of the triangles `F` (#F x 3 point indices), sorted by (lo, hi, face): the faces sharing an
/// edge are consecutive, in increasing face order. O(F log F).
template <class Faces>
[[nodiscard]] std::vector<half_edge> sorted_half_edges(const Faces& F) {
  std::vector<half_edge> halves;
  halves.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (index_t f = 0; f < static_cast<index_t>(F.rows()); ++f)
    for (int k = 0; k < 3; ++k) {
      const index_t i = F(f, (k + 1) % 3), j = F(f, (k + 2) % 3);
      halves.push_back({std::min(i, j), std::max(i, j), f, k});
    }
  std::sort(halves.begin(), halves.end(), [](const half_edge& x, const half_edge& y) {
    return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : x.face < y.face);
  });
  return halves;
}

}  // namespace shapestruct::detail
