// SPDX-License-Identifier: MIT
// PairwiseMatcher: computes a correspondence map between two surfaces.
#pragma once

#include "shapestruct/core/concepts/correspondence_map.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"

namespace shapestruct {

/// A matcher maps the vertices of `a` onto `b`. It may keep per-shape caches (hence non-const).
/// Models: blended_matcher (blended/), and any user type with a conforming `match`.
template <class Mt, class Src, class Tgt>
concept PairwiseMatcher = SurfaceMesh<Src> && SurfaceMesh<Tgt> &&
                          requires(Mt& m, const Src& a, const Tgt& b) {
                            { m.match(a, b) } -> MatchResult;
                          };

}  // namespace shapestruct
