// SPDX-License-Identifier: MIT
// vertex_map: a correspondence from source vertices to target vertices (the benchmark's dense .map form).
#pragma once

#include <utility>
#include <vector>

#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Source vertex i -> target vertex targets[i] (no_index = unmapped). Models CorrespondenceMap.
template <class Scalar = double>
struct vertex_map {
  using scalar_type = Scalar;
  std::vector<index_t> targets;

  vertex_map() = default;
  explicit vertex_map(std::vector<index_t> t) : targets(std::move(t)) {}

  [[nodiscard]] index_t source_size() const noexcept { return static_cast<index_t>(targets.size()); }
  [[nodiscard]] index_t target_vertex(index_t i) const { return targets[static_cast<std::size_t>(i)]; }
};

}  // namespace shapestruct
