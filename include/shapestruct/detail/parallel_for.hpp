// SPDX-License-Identifier: MIT
// parallel_for: the one deterministic std::thread loop every stage uses, and the `threads` option's meaning.
#pragma once

#include <algorithm>
#include <atomic>
#include <concepts>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct::detail {

/// Resolves a `threads` option: 0 means all hardware threads (at least 1).
/// \throws invalid_input (bad_parameter) if threads < 0; `who` names the caller in the message.
inline unsigned resolve_threads(int threads, const char* who = "shapestruct") {
  if (threads < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": threads must be >= 0 (0 = all cores), got " + std::to_string(threads));
  if (threads == 0) return std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(threads);
}

/// Runs body for every i in [0, n) on up to `workers` std::threads (the calling thread is one of them).
/// body is called as body(i), or as body(worker, i) with worker in [0, workers) for per-worker scratch space.
/// Items are handed out in blocks of `block` through an atomic counter, so uneven costs balance out. Each item
/// must write only its own outputs, hence results never depend on the worker count or the schedule: this is
/// how every parallel routine of shapestruct stays deterministic. The first exception thrown by a body stops
/// the loop and is rethrown on the calling thread after all workers have joined.
template <std::integral Index, class Body>
void parallel_for(Index n, unsigned workers, Body&& body, Index block = 1) {
  if (n < Index{1}) return;  // also right for unsigned Index
  block = std::max<Index>(Index{1}, block);
  const Index blocks = (n + block - 1) / block;
  workers = static_cast<unsigned>(std::min<Index>(static_cast<Index>(std::max(1u, workers)), blocks));
  auto call = [&](unsigned worker, Index i) {
    if constexpr (std::is_invocable_v<Body&, Index>)
      body(i);
    else
      body(worker, i);
  };
  if (workers == 1) {
    for (Index i = 0; i < n; ++i) call(0u, i);
    return;
  }
  std::atomic<Index> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&](unsigned worker) {
    try {
      for (Index b = next.fetch_add(1); b < blocks && !failed.load(std::memory_order_relaxed); b = next.fetch_add(1)) {
        const Index end = std::min(n, (b + 1) * block);
        for (Index i = b * block; i < end; ++i) call(worker, i);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      failed.store(true);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (unsigned w = 1; w < workers; ++w) pool.emplace_back(run, w);
  run(0);
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace shapestruct::detail
