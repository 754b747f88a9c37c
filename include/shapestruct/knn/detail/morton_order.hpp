// SPDX-License-Identifier: MIT
// Private helper of knn/ and the geometry queries: ordering points along a Morton (Z-order) curve for memory
// locality. No stability promise.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace shapestruct::detail {

/// Order of n points along a Morton (Z-order) curve: 21 bits per coordinate over the bounding box of the
/// first min(dims, 3) coordinates (coord(i, d) gives coordinate d of point i), ties by index, so the order is
/// deterministic. Neighbouring positions in the order are close in space, so processing points (or storing
/// them) in this order keeps a spatial search's working set in cache. O(n log n).
/// \returns order[j] = index of the j-th point along the curve (a permutation of [0, n)).
template <int Dims, class Coord>
std::vector<std::uint32_t> morton_order(std::size_t n, Coord&& coord) {
  constexpr int used = Dims < 3 ? Dims : 3;
  std::array<double, used> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < used; ++d) {
      lo[std::size_t(d)] = std::min(lo[std::size_t(d)], double(coord(i, d)));
      hi[std::size_t(d)] = std::max(hi[std::size_t(d)], double(coord(i, d)));
    }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t code = 0;
    for (int d = 0; d < used; ++d) {
      const double extent = hi[std::size_t(d)] - lo[std::size_t(d)];
      const double t = extent > 0 ? (double(coord(i, d)) - lo[std::size_t(d)]) / extent : 0.0;
      const auto q = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * double((1u << 21) - 1));
      for (int b = 0; b < 21; ++b) code |= ((q >> b) & 1u) << (used * b + d);
    }
    keys[i] = {code, static_cast<std::uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> order(n);
  for (std::size_t j = 0; j < n; ++j) order[j] = keys[j].second;
  return order;
}

}  // namespace shapestruct::detail
