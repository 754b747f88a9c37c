// SPDX-License-Identifier: MIT
// ShapeAligner: aligns two shapes of a collection and returns every alternative alignment it considered.
#pragma once

#include <concepts>

#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Aligns shape `source` to shape `target` of the collection it was built on (shapes by index) and returns the
/// alternatives with their per-sample scores a(p_i, p_j) (ch. 4.3.3-4.3.4). Called concurrently from several
/// threads for different pairs, so align must be safe to call in parallel; its result must depend only on the
/// pair (never on the order or the thread), which keeps the collection's results independent of the thread count.
/// Models: extrinsic_aligner, intrinsic_aligner, matcher_aligner (a user's PairwiseMatcher + AlignmentScore).
template <class A>
concept ShapeAligner = requires(const A& a, index_t source, index_t target) {
  { a.align(source, target) } -> std::same_as<pair_alignment>;
};

}  // namespace shapestruct
