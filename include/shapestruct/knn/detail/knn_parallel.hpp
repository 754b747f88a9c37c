// SPDX-License-Identifier: MIT
// Private helpers of knn/ and the geometry queries built on it: thread-count resolution and a deterministic
// block-parallel loop over std::thread. No stability promise.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct::detail {

/// Resolves a `threads` option: 0 means all hardware threads.
/// \throws invalid_input (bad_parameter) if threads < 0.
inline unsigned knn_resolve_threads(int threads, const char* who) {
  if (threads < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": threads must be >= 0 (0 = all cores), got " + std::to_string(threads));
  if (threads == 0) return std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(threads);
}

/// Runs body(i) for every i in [0, n) on up to `workers` std::threads. Work is handed out in blocks of
/// `block` items through an atomic counter, so uneven query costs balance out. Every body writes only its own
/// outputs, hence results do not depend on the worker count or the schedule. The first exception thrown by a
/// body is rethrown on the calling thread after all workers have stopped.
template <class Body>
void knn_parallel_for(index_t n, unsigned workers, Body&& body, index_t block = 64) {
  if (n <= 0) return;
  block = std::max<index_t>(1, block);
  const index_t blocks = (n + block - 1) / block;
  workers = static_cast<unsigned>(std::min<index_t>(static_cast<index_t>(std::max(1u, workers)), blocks));
  if (workers == 1) {
    for (index_t i = 0; i < n; ++i) body(i);
    return;
  }
  std::atomic<index_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&]() {
    try {
      for (index_t b = next.fetch_add(1); b < blocks && !failed.load(std::memory_order_relaxed);
           b = next.fetch_add(1)) {
        const index_t end = std::min(n, (b + 1) * block);
        for (index_t i = b * block; i < end; ++i) body(i);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      failed.store(true);
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (unsigned w = 1; w < workers; ++w) pool.emplace_back(run);
  run();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace shapestruct::detail
