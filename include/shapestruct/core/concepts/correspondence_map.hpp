// SPDX-License-Identifier: MIT
// CorrespondenceMap and MatchResult: what pairwise matchers produce.
#pragma once

#include <concepts>
#include <type_traits>

#include "shapestruct/core/status.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// A map from the vertices of a source shape to a target shape. Every map can at least answer "nearest target
/// vertex"; richer maps (surface points, fuzzy weights) add members.
/// Required: C::scalar_type; c.source_size() -> index_t; c.target_vertex(i) -> index_t for i in
/// [0, source_size()), returning no_index for an unmapped vertex.
/// Models: vertex_map, surface_map (maps/).
template <class C>
concept CorrespondenceMap = requires(const C& c, index_t i) {
  typename C::scalar_type;
  { c.source_size() } -> std::convertible_to<index_t>;
  { c.target_vertex(i) } -> std::convertible_to<index_t>;
};

/// What a matcher returns: a map plus the numerical status of the computation.
template <class R>
concept MatchResult = requires(const R& r) {
  requires CorrespondenceMap<std::remove_cvref_t<decltype(r.map)>>;
  { r.info } -> std::convertible_to<status>;
};

}  // namespace shapestruct
