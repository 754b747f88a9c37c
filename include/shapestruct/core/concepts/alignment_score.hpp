// SPDX-License-Identifier: MIT
// AlignmentScore: rates a correspondence map between two shapes (lower is better).
#pragma once

#include <concepts>
#include <optional>

#include "shapestruct/core/concepts/correspondence_map.hpp"

namespace shapestruct {

/// Lower is better; an empty optional rejects the map (as CGAL's GetCost). Must be deterministic and free of
/// side effects, so callers may evaluate candidates in parallel and in any order.
template <class S, class Map, class Src, class Tgt>
concept AlignmentScore = CorrespondenceMap<Map> && requires(const S& s, const Map& f, const Src& a, const Tgt& b) {
  typename S::scalar_type;
  { s(f, a, b) } -> std::convertible_to<std::optional<typename S::scalar_type>>;
};

}  // namespace shapestruct
