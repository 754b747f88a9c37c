// SPDX-License-Identifier: MIT
// Several "processes" of a work_share played by threads of one test: the exchange an MPI job would do.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "shapestruct/core/work_share.hpp"

namespace shapestruct::test {

/// A rendezvous of `parts` threads: each calls exchange(part, message) and gets every part's message.
class thread_exchange {
 public:
  explicit thread_exchange(std::size_t parts) : slots_(parts) {}

  std::vector<std::string> exchange(std::size_t part, const std::string& message) {
    std::unique_lock lock(m_);
    const std::size_t round = round_;
    slots_[part] = message;
    if (++arrived_ == slots_.size()) {
      result_ = slots_;
      arrived_ = 0;
      ++round_;
      cv_.notify_all();
      return result_;
    }
    cv_.wait(lock, [&] { return round_ != round; });
    return result_;  // copied under the lock: the next round cannot complete before this part joins it
  }

  /// The work_share of `part`.
  work_share share(std::size_t part) {
    return {part, slots_.size(), [this, part](const std::string& m) { return exchange(part, m); }};
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  std::vector<std::string> slots_, result_;
  std::size_t arrived_ = 0, round_ = 0;
};

/// Runs job(share) on `parts` threads, one per part, and returns their results in part order.
template <class Job>
auto run_parts(std::size_t parts, Job job) {
  thread_exchange ex(parts);
  using result = decltype(job(ex.share(0)));
  std::vector<result> out(parts);
  std::vector<std::exception_ptr> failure(parts);
  std::vector<std::thread> threads;
  for (std::size_t p = 0; p < parts; ++p)
    threads.emplace_back([&, p] {
      try {
        out[p] = job(ex.share(p));
      } catch (...) {
        failure[p] = std::current_exception();
      }
    });
  for (auto& t : threads) t.join();
  for (auto& f : failure)
    if (f) std::rethrow_exception(f);
  return out;
}

}  // namespace shapestruct::test
