// SPDX-License-Identifier: MIT
// disjoint_sets: union-find with path halving and union by size, shared by the topology checks.
#pragma once

#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

#include "shapestruct/core/types.hpp"

namespace shapestruct::detail {

/// Union-find over the elements 0 .. n-1. find() and unite() run in amortized O(alpha(n)).
class disjoint_sets {
 public:
  explicit disjoint_sets(index_t n) : parent_(static_cast<std::size_t>(n)), size_(static_cast<std::size_t>(n), 1) {
    std::iota(parent_.begin(), parent_.end(), index_t{0});
  }

  /// The representative of x's set. Path halving keeps the trees flat without recursion (no stack depth
  /// limit on meshes with millions of elements).
  index_t find(index_t x) noexcept {
    while (parent_[static_cast<std::size_t>(x)] != x) {
      auto& p = parent_[static_cast<std::size_t>(x)];
      p = parent_[static_cast<std::size_t>(p)];
      x = p;
    }
    return x;
  }

  /// Merges the sets of a and b; returns true if they were different sets.
  bool unite(index_t a, index_t b) noexcept {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size_[static_cast<std::size_t>(a)] < size_[static_cast<std::size_t>(b)]) std::swap(a, b);
    parent_[static_cast<std::size_t>(b)] = a;
    size_[static_cast<std::size_t>(a)] += size_[static_cast<std::size_t>(b)];
    return true;
  }

  [[nodiscard]] index_t size() const noexcept { return static_cast<index_t>(parent_.size()); }

 private:
  std::vector<index_t> parent_;
  std::vector<index_t> size_;
};

}  // namespace shapestruct::detail
