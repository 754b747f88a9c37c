// SPDX-License-Identifier: MIT
// parallel_for: static block partition of [0, n) over std::threads (deterministic: each index has one owner).
#pragma once

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

#include "shapestruct/core/types.hpp"

namespace shapestruct::detail {

/// Number of worker threads for a `threads` option (0 = hardware concurrency, at least 1).
inline unsigned blended_threads(int threads) {
  if (threads > 0) return static_cast<unsigned>(threads);
  return std::max(1u, std::thread::hardware_concurrency());
}

/// Calls fn(i) for every i in [0, n), interleaved over the workers (index i goes to worker i % workers, which
/// balances work whose cost drifts along the range). Results must be written to per-index slots, so they do
/// not depend on the number of threads. The first exception thrown by any worker is rethrown.
template <class Fn>
void blended_parallel_for(index_t n, int threads, Fn&& fn) {
  const unsigned workers = static_cast<unsigned>(std::min<index_t>(blended_threads(threads), std::max<index_t>(n, 1)));
  if (workers <= 1) {
    for (index_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::vector<std::exception_ptr> errors(workers);
  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (unsigned w = 0; w < workers; ++w)
    pool.emplace_back([&, w] {
      try {
        for (index_t i = w; i < n; i += workers) fn(i);
      } catch (...) {
        errors[w] = std::current_exception();
      }
    });
  for (auto& t : pool) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace shapestruct::detail
