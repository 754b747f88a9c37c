// SPDX-License-Identifier: MIT
// alignment_store: the pairwise alignments of a collection, computed in parallel once and cached on disk.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shapestruct/collection/collection_files.hpp"
#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/concepts/shape_aligner.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/detail/parallel_for.hpp"

namespace shapestruct {

/// Every pairwise alignment a collection run has made, keyed by the unordered pair (smaller index first; the
/// alignment itself runs from the smaller to the larger index). With a folder, each alignment is written there
/// the moment it is finished (atomically, named after the two shapes), and read back instead of recomputed: an
/// interrupted run resumes where it stopped and loses at most the alignments in flight. An alignment depends only
/// on its pair, so the store's contents do not depend on the thread count or on where a run was interrupted.
class alignment_store {
 public:
  using key = std::pair<index_t, index_t>;

  /// \param records the collection's shapes (names key the cache files)  \param folder "" = memory only
  /// \throws io_error (cannot_open) if the folder cannot be created.
  explicit alignment_store(const std::vector<shape_record>& records, std::filesystem::path folder = {})
      : records_(&records), folder_(std::move(folder)) {
    if (!folder_.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(folder_, ec);
      if (ec) throw io_error(file_error::cannot_open, folder_.string(), 0, 0, "cannot create the cache folder: " + ec.message());
    }
  }

  [[nodiscard]] static key make_key(index_t a, index_t b) { return a < b ? key{a, b} : key{b, a}; }
  [[nodiscard]] bool contains(index_t a, index_t b) const { return alignments_.count(make_key(a, b)) != 0; }
  /// The alignment of the pair (its source is the smaller index). \throws std::out_of_range if absent.
  [[nodiscard]] const pair_alignment& at(index_t a, index_t b) const { return alignments_.at(make_key(a, b)); }
  [[nodiscard]] std::size_t size() const noexcept { return alignments_.size(); }
  [[nodiscard]] const std::map<key, pair_alignment>& all() const noexcept { return alignments_; }
  /// Alignments computed in this process (the rest came from the cache).
  [[nodiscard]] std::size_t computed() const noexcept { return computed_; }

  [[nodiscard]] std::filesystem::path file_of(const key& k) const {
    const auto& r = *records_;
    return folder_ / (r[std::size_t(k.first)].name + "__" + r[std::size_t(k.second)].name + ".align");
  }

  /// Makes sure every pair in `pairs` is aligned: read from the cache folder where a file exists, else aligned
  /// with `aligner` on up to `threads` threads and written. `on_done(done, total)` reports progress (called
  /// under a lock, from any worker).
  /// \throws whatever the aligner throws for a pair (after the other workers stopped), io_error when a cache
  ///         file cannot be written.
  template <ShapeAligner Aligner>
  void ensure(const std::vector<key>& pairs, const Aligner& aligner, int threads,
              const std::function<void(std::size_t, std::size_t)>& on_done = {}) {
    std::vector<key> todo;
    std::set<key> queued;
    for (const auto& p0 : pairs) {
      const key p = make_key(p0.first, p0.second);
      if (alignments_.count(p) || !queued.insert(p).second) continue;
      if (!folder_.empty() && std::filesystem::exists(file_of(p))) {
        try {
          pair_alignment a = read_pair_alignment(file_of(p));
          if (a.source == p.first && a.target == p.second) {
            alignments_.emplace(p, std::move(a));
            continue;
          }
        } catch (const io_error&) {
          // a damaged cache file (an interrupted write of an older version): align the pair again
        }
      }
      todo.push_back(p);
    }
    std::vector<pair_alignment> results(todo.size());
    std::mutex m;
    std::size_t done = 0;
    const unsigned workers = detail::resolve_threads(threads, "alignment_store::ensure");
    detail::parallel_for(static_cast<index_t>(todo.size()), workers, [&](index_t i) {
      const auto t0 = std::chrono::steady_clock::now();
      pair_alignment a = aligner.align(todo[std::size_t(i)].first, todo[std::size_t(i)].second);
      a.source = todo[std::size_t(i)].first;
      a.target = todo[std::size_t(i)].second;
      a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!folder_.empty()) write_pair_alignment(file_of(todo[std::size_t(i)]), a);
      results[std::size_t(i)] = std::move(a);
      std::lock_guard lock(m);
      ++done;
      if (on_done) on_done(done, todo.size());
    });
    for (std::size_t i = 0; i < todo.size(); ++i) alignments_.emplace(todo[i], std::move(results[i]));
    computed_ += todo.size();
  }

 private:
  const std::vector<shape_record>* records_;
  std::filesystem::path folder_;
  std::map<key, pair_alignment> alignments_;
  std::size_t computed_ = 0;
};

}  // namespace shapestruct
