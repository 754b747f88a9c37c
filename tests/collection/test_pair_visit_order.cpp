// SPDX-License-Identifier: MIT
// Tests of pair_visit_order: a permutation that keeps pairs sharing shapes together, so that a small cache of
// prepared shapes is reused.
#include <algorithm>
#include <list>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include "shapestruct/collection/pair_visit_order.hpp"

using namespace shapestruct;

namespace {
using pair_list = std::vector<std::pair<index_t, index_t>>;

// Shapes prepared by an aligner that keeps the `capacity` least recently used ones, visiting `pairs` in `order`.
std::size_t cache_misses(const pair_list& pairs, const std::vector<std::size_t>& order, std::size_t capacity) {
  std::list<index_t> cache;
  std::size_t misses = 0;
  for (const std::size_t i : order)
    for (const index_t s : {pairs[i].first, pairs[i].second}) {
      const auto it = std::find(cache.begin(), cache.end(), s);
      if (it != cache.end()) cache.erase(it);
      else ++misses;
      cache.push_front(s);
      if (cache.size() > capacity) cache.pop_back();
    }
  return misses;
}

// N shapes, each paired with `per_shape` random others (no repeats): the shape of a collection's alignment graph.
pair_list random_pairs(index_t shapes, int per_shape, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<index_t> pick(0, shapes - 1);
  pair_list out;
  for (index_t a = 0; a < shapes; ++a)
    for (int k = 0; k < per_shape; ++k) {
      const index_t b = pick(rng);
      const std::pair<index_t, index_t> p{std::min(a, b), std::max(a, b)};
      if (a != b && std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
    }
  return out;
}
}  // namespace

TEST_CASE("pair_visit_order follows a shared shape, and is a permutation") {
  CHECK(pair_visit_order({}).empty());
  // (0,1) first; then (1,2), which shares shape 1, before (2,3); then (2,3), which shares shape 2.
  CHECK(pair_visit_order({{0, 1}, {2, 3}, {1, 2}}) == std::vector<std::size_t>{0, 2, 1});
  const pair_list pairs = random_pairs(60, 5, 3);
  std::vector<std::size_t> order = pair_visit_order(pairs);
  CHECK(order == pair_visit_order(pairs));  // deterministic
  std::sort(order.begin(), order.end());
  std::vector<std::size_t> all(pairs.size());
  std::iota(all.begin(), all.end(), std::size_t(0));
  CHECK(order == all);
}

TEST_CASE("pair_visit_order prepares fewer shapes than the given order through a small cache") {
  for (const std::uint32_t seed : {1u, 2u, 3u}) {
    const pair_list pairs = random_pairs(80, 5, seed);
    std::vector<std::size_t> given(pairs.size());
    std::iota(given.begin(), given.end(), std::size_t(0));
    std::vector<std::size_t> shuffled = given;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(seed));
    const std::vector<std::size_t> ordered = pair_visit_order(pairs);
    for (const std::size_t capacity : {4u, 8u, 16u}) {
      const std::size_t in_order = cache_misses(pairs, ordered, capacity);
      MESSAGE("seed " << seed << ", cache " << capacity << ": " << in_order << " misses, given order "
                      << cache_misses(pairs, given, capacity) << ", shuffled " << cache_misses(pairs, shuffled, capacity));
      CHECK(in_order < cache_misses(pairs, given, capacity));
      CHECK(double(in_order) < 0.8 * double(cache_misses(pairs, shuffled, capacity)));
    }
  }
}
