// SPDX-License-Identifier: MIT
// alignment_store: the pairwise alignments of a collection, computed in parallel once and cached on disk.
#pragma once

#include <chrono>
#include <exception>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shapestruct/collection/collection_files.hpp"
#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/collection/pair_visit_order.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/concepts/shape_aligner.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/work_share.hpp"
#include "shapestruct/detail/parallel_for.hpp"

namespace shapestruct {

/// Every pairwise alignment a collection run has made, keyed by the unordered pair (smaller index first; the
/// alignment itself runs from the smaller to the larger index). With a folder, each alignment is written there
/// the moment it is finished (atomically, named after the two shapes), and read back instead of recomputed: an
/// interrupted run resumes where it stopped and loses at most the alignments in flight. An alignment depends only
/// on its pair, so the store's contents do not depend on the thread count or on where a run was interrupted.
///
/// With a folder the score blocks need not stay in memory: they are the largest part of a collection run's
/// memory (about 6 pairs per shape, a few alternatives each, a sparse K x K block per alternative) and grow with
/// the collection. Unless `in_memory` is set, the store keeps only each pair's summary and reads the pair back
/// from its file whenever it is visited. The file format is lossless, so results are the same either way.
class alignment_store {
 public:
  using key = std::pair<index_t, index_t>;

  /// \param records the collection's shapes (names key the cache files)  \param folder "" = memory only
  /// \param in_memory with a folder: keep every alignment in memory too (faster visits, memory grows with the
  ///        pairs) rather than reading it back from its file; without a folder alignments are always in memory.
  /// \throws io_error (cannot_open) if the folder cannot be created.
  explicit alignment_store(const std::vector<shape_record>& records, std::filesystem::path folder = {},
                           bool in_memory = true)
      : records_(&records), folder_(std::move(folder)), in_memory_(in_memory || folder_.empty()) {
    if (!folder_.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(folder_, ec);
      if (ec) throw io_error(file_error::cannot_open, folder_.string(), 0, 0, "cannot create the cache folder: " + ec.message());
    }
  }

  [[nodiscard]] static key make_key(index_t a, index_t b) { return a < b ? key{a, b} : key{b, a}; }
  [[nodiscard]] bool contains(index_t a, index_t b) const { return summaries_.count(make_key(a, b)) != 0; }
  /// How many alternatives the pair's aligner produced (0: it rejected the pair). \throws std::out_of_range if absent.
  [[nodiscard]] index_t alternative_count(index_t a, index_t b) const { return summaries_.at(make_key(a, b)).alternatives; }
  /// The pair's initial alternative (highest global score). \throws std::out_of_range if absent.
  [[nodiscard]] index_t initial(index_t a, index_t b) const { return summaries_.at(make_key(a, b)).initial; }
  /// Calls fn(const pair_alignment&) with the pair's alignment (its source is the smaller index) and returns what
  /// fn returns, by value (the alignment may be a temporary read from its file); safe from several threads at once.
  /// \throws std::out_of_range if absent; io_error if its cache file was removed or damaged during the run.
  template <class Fn>
  auto visit(index_t a, index_t b, Fn&& fn) const {
    const key k = make_key(a, b);
    if (!summaries_.count(k)) throw std::out_of_range("alignment_store: the pair was never aligned");
    if (in_memory_) return fn(alignments_.at(k));
    const pair_alignment read = read_pair_alignment(file_of(k));
    if (read.source != k.first || read.target != k.second || index_t(read.alternatives.size()) != summaries_.at(k).alternatives)
      throw io_error(file_error::bad_value, file_of(k).string(), 0, 0,
                     "the cached alignment changed during the run (another run writing into the same folder?)");
    return fn(read);
  }
  [[nodiscard]] std::size_t size() const noexcept { return summaries_.size(); }
  /// Alignments computed in this process (the rest came from the cache).
  [[nodiscard]] std::size_t computed() const noexcept { return computed_; }

  [[nodiscard]] std::filesystem::path file_of(const key& k) const {
    const auto& r = *records_;
    return folder_ / (r[std::size_t(k.first)].name + "__" + r[std::size_t(k.second)].name + ".align");
  }

  /// Makes sure every pair in `pairs` is aligned: read from the cache folder where a file exists, else aligned
  /// with `aligner` on up to `threads` threads and written. `on_done(done, total)` reports progress (called
  /// under a lock, from any worker). With a distributed `share`, this process aligns only its own pairs (every
  /// share-th of the requested ones), then reads the others' from the cache folder (required then); every
  /// process must call ensure with the same pairs at the same point.
  /// \throws whatever the aligner throws for a pair (after the other workers stopped; on the other processes of
  ///         a share, a std::runtime_error naming the pair), io_error when a cache file cannot be written or read.
  template <ShapeAligner Aligner>
  void ensure(const std::vector<key>& pairs, const Aligner& aligner, int threads,
              const std::function<void(std::size_t, std::size_t)>& on_done = {}, const work_share& share = {}) {
    share.validate("alignment_store::ensure");
    if (share.distributed() && folder_.empty())
      throw invalid_input(input_error::bad_parameter, no_index,
                          "alignment_store::ensure: several processes share alignments through the cache folder: set one");
    std::vector<key> requested;  // new pairs, in request order: the same list on every process
    std::set<key> queued;
    for (const auto& p0 : pairs) {
      const key p = make_key(p0.first, p0.second);
      if (!summaries_.count(p) && queued.insert(p).second) requested.push_back(p);
    }
    std::vector<key> todo;
    for (std::size_t r = 0; r < requested.size(); ++r) {
      if (!share.owns(r)) continue;
      if (auto cached = read_cached(requested[r])) keep(requested[r], std::move(*cached));
      else todo.push_back(requested[r]);
    }
    // Unless in memory, only each finished pair's summary is kept: holding a whole batch until it ends (N M pairs
    // in the first round) would grow memory with the collection as much as keeping every alignment.
    std::vector<pair_alignment> results(in_memory_ ? todo.size() : 0);
    std::vector<summary> finished(todo.size());
    std::vector<std::string> failure(todo.size());
    std::exception_ptr first_failure;
    std::mutex m;
    std::size_t done = 0;
    const unsigned workers = detail::resolve_threads(threads, "alignment_store::ensure");
    // Pairs that share shapes run one after the other, so that an aligner's cache of prepared shapes is reused
    // (intrinsic_aligner's); each pair's result is the same in any order.
    const std::vector<std::size_t> visit = pair_visit_order(todo);
    detail::parallel_for(static_cast<index_t>(todo.size()), workers, [&](index_t step) {
      const std::size_t i = visit[std::size_t(step)];
      const key& p = todo[i];
      try {
        const auto t0 = std::chrono::steady_clock::now();
        pair_alignment a = aligner.align(p.first, p.second);
        a.source = p.first;
        a.target = p.second;
        a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (!folder_.empty()) write_pair_alignment(file_of(p), a);
        finished[i] = summary_of(a);
        if (in_memory_) results[i] = std::move(a);
      } catch (const std::exception& e) {
        if (!share.distributed()) throw;  // one process: the loop stops and rethrows it as it is
        std::lock_guard lock(m);
        failure[i] = e.what();
        if (!first_failure) first_failure = std::current_exception();
      }
      std::lock_guard lock(m);
      ++done;
      if (on_done) on_done(done, todo.size());
    });
    for (std::size_t i = 0; i < todo.size(); ++i) {
      if (!failure[i].empty()) continue;
      summaries_[todo[i]] = finished[i];
      if (in_memory_) alignments_.emplace(todo[i], std::move(results[i]));
    }
    computed_ += todo.size();
    if (!share.distributed()) return;
    std::string failed_pair;  // the first failure of any process, in part order
    std::vector<std::string> mine;
    for (std::size_t i = 0; i < todo.size() && mine.empty(); ++i)
      if (!failure[i].empty()) mine = {pair_name(todo[i]), failure[i]};
    for (const auto& message : share.all_gather(detail::pack_strings(mine))) {
      const auto items = detail::unpack_strings(message);
      if (failed_pair.empty() && items.size() == 2) failed_pair = items[0] + ": " + items[1];
    }
    if (first_failure) std::rethrow_exception(first_failure);
    if (!failed_pair.empty()) throw std::runtime_error("alignment of " + failed_pair + " (in another process)");
    for (std::size_t r = 0; r < requested.size(); ++r) {
      if (share.owns(r)) continue;
      auto cached = read_cached(requested[r]);
      if (!cached)
        throw io_error(file_error::cannot_open, file_of(requested[r]).string(), 0, 0,
                       "the alignment made by another process is missing or damaged");
      keep(requested[r], std::move(*cached));
    }
  }

 private:
  struct summary {
    index_t alternatives = 0;
    index_t initial = 0;
  };
  [[nodiscard]] static summary summary_of(const pair_alignment& a) {
    return {static_cast<index_t>(a.alternatives.size()), a.initial};
  }
  void keep(const key& k, pair_alignment&& a) {
    summaries_[k] = summary_of(a);
    if (in_memory_) alignments_.emplace(k, std::move(a));
  }
  /// The cached alignment of p, if its file exists and holds p; nullopt otherwise (also for a damaged file, the
  /// leftover of an interrupted write of an older version: the pair is aligned again).
  [[nodiscard]] std::optional<pair_alignment> read_cached(const key& p) const {
    if (folder_.empty() || !std::filesystem::exists(file_of(p))) return std::nullopt;
    try {
      pair_alignment a = read_pair_alignment(file_of(p));
      if (a.source == p.first && a.target == p.second) return a;
    } catch (const io_error&) {
    }
    return std::nullopt;
  }
  [[nodiscard]] std::string pair_name(const key& p) const {
    return (*records_)[std::size_t(p.first)].name + " -> " + (*records_)[std::size_t(p.second)].name;
  }

  const std::vector<shape_record>* records_;
  std::filesystem::path folder_;
  bool in_memory_ = true;
  std::map<key, summary> summaries_;         // every pair aligned so far
  std::map<key, pair_alignment> alignments_;  // the pairs themselves, when kept in memory
  std::size_t computed_ = 0;
};

}  // namespace shapestruct
