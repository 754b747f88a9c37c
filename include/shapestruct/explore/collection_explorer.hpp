// SPDX-License-Identifier: MIT
// collection_explorer: answers many region-of-interest queries on one loaded fuzzy collection (ch. 4.5).
#pragma once
#include <algorithm>
#include <map>
#include <mutex>
#include <span>
#include <string>
#include <utility>
#include <vector>
#include <Eigen/Core>
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/explore/affine_alignment.hpp"
#include "shapestruct/explore/co_alignment.hpp"
#include "shapestruct/explore/facet_ranking.hpp"
#include "shapestruct/explore/region.hpp"
#include "shapestruct/explore/region_query.hpp"
#include "shapestruct/explore/sample_variance.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"

namespace shapestruct {

/// Options of collection_explorer.
struct collection_explorer_options {
  sample_variance_options variance;
  region_query_options query;
  /// Per-region distance vectors kept, so that adding, removing or reordering facets re-sorts without
  /// recomputing the regions that did not change.
  std::size_t cached_regions = 64;
};

/// One collection loaded for exploration: owns f and the shape records, computes each shape's variance and the
/// canonical view once (on first use), and answers region queries, facet rankings and per-shape details. All member
/// functions are const and may be called from several threads at once (a server's request handlers).
class collection_explorer {
 public:
  /// \throws invalid_input (size_mismatch) when the records and f disagree.
  collection_explorer(fuzzy_correspondence f, std::vector<shape_record> records,
                      const collection_explorer_options& options = {})
      : f_(std::move(f)), records_(std::move(records)), options_(options) {
    if (static_cast<index_t>(records_.size()) != f_.shapes())
      throw invalid_input(input_error::size_mismatch, no_index,
                          "collection_explorer: " + std::to_string(records_.size()) + " records for " +
                              std::to_string(f_.shapes()) + " embedded shapes");
  }

  [[nodiscard]] const fuzzy_correspondence& fuzzy() const noexcept { return f_; }
  [[nodiscard]] std::span<const shape_record> records() const noexcept { return records_; }
  [[nodiscard]] index_t shapes() const noexcept { return f_.shapes(); }

  /// The variance of shape k's samples, in [0, 1] (shape_variance; computed on first request, then kept: only
  /// the shapes a user looks at cost anything).
  [[nodiscard]] Eigen::VectorXf variance(index_t k) const {
    check_shape(k);
    {
      std::lock_guard lock(cache_mutex_);
      if (auto it = variance_.find(k); it != variance_.end()) return it->second;
    }
    Eigen::VectorXf v = shape_variance(f_.embedding(), k, options_.variance);
    std::lock_guard lock(cache_mutex_);
    variance_.emplace(k, v);
    return v;
  }

  [[nodiscard]] index_t canonical_reference() const {
    std::call_once(canonical_once_, [this] {
      reference_ = shapestruct::canonical_reference(f_);
      canonical_ = canonical_alignment(f_, records_, reference_, options_.query.threads);
    });
    return reference_;
  }
  /// For every shape, the affine map into the canonical view (computed on first use).
  [[nodiscard]] const std::vector<affine_transform>& canonical_transforms() const {
    (void)canonical_reference();
    return canonical_;
  }

  /// D_R of every shape for one region (cached).
  [[nodiscard]] std::vector<double> region_distances(const region& r) const {
    region checked = checked_region(f_.embedding(), r);
    auto key = std::make_pair(checked.shape, checked.samples);
    {
      std::lock_guard lock(cache_mutex_);
      if (auto it = cache_.find(key); it != cache_.end()) return it->second;
    }
    std::vector<double> d = region_query(f_, records_, std::move(checked), options_.query).distances();
    std::lock_guard lock(cache_mutex_);
    if (cache_.size() >= options_.cached_regions) cache_.clear();
    cache_.emplace(std::move(key), d);
    return d;
  }

  /// The collection sorted by the facets (one region each; rank_by_facets combines them).
  /// \throws invalid_input (empty) for no facets, and as checked_region for a bad one.
  [[nodiscard]] collection_ranking sort(std::span<const region> facets) const {
    if (facets.empty()) throw invalid_input(input_error::empty, no_index, "collection_explorer::sort: no regions given");
    std::vector<std::vector<double>> distances;
    std::vector<index_t> examples;
    for (const region& r : facets) {
      distances.push_back(region_distances(r));
      examples.push_back(r.shape);
    }
    return rank_by_facets(distances, examples);
  }

  /// What a view of each given shape shows for the facets: the alignment and orbit centre from the facets on
  /// the first example shape (their regions united: a view has one frame), and the highlight, the largest of the
  /// facets' highlights at each sample (every facet's corresponding region shows).
  /// \throws invalid_input as sort, and (bad_parameter) naming an unknown shape.
  [[nodiscard]] std::vector<region_match> details(std::span<const region> facets, std::span<const index_t> shapes) const {
    if (facets.empty()) throw invalid_input(input_error::empty, no_index, "collection_explorer::details: no regions given");
    for (const index_t k : shapes) check_shape(k);
    std::vector<region> checked;
    for (const region& r : facets) checked.push_back(checked_region(f_.embedding(), r));
    region frame{checked.front().shape, {}};
    for (const region& r : checked)
      if (r.shape == frame.shape) frame.samples.insert(frame.samples.end(), r.samples.begin(), r.samples.end());
    const region_query framing(f_, records_, frame, options_.query);
    std::vector<region_query> others;
    if (checked.size() > 1)
      for (const region& r : checked) others.emplace_back(f_, records_, r, options_.query);
    std::vector<region_match> out;
    for (const index_t k : shapes) {
      region_match m = framing.match(k);
      if (!others.empty()) {  // the highlight of several facets: each normalised, then the largest
        Eigen::VectorXd h = Eigen::VectorXd::Zero(m.correspondence.size());
        for (const region_query& q : others) h = h.cwiseMax(q.match(k).highlight());
        m.correspondence = h;
      }
      out.push_back(std::move(m));
    }
    return out;
  }

 private:
  void check_shape(index_t k) const {
    if (k < 0 || k >= f_.shapes())
      throw invalid_input(input_error::bad_parameter, k,
                          "shape " + std::to_string(k) + " is not in the collection (it has " +
                              std::to_string(f_.shapes()) + " shapes)");
  }

  fuzzy_correspondence f_;
  std::vector<shape_record> records_;
  collection_explorer_options options_;
  mutable std::once_flag canonical_once_;
  mutable std::map<index_t, Eigen::VectorXf> variance_;
  mutable index_t reference_ = 0;
  mutable std::vector<affine_transform> canonical_;
  mutable std::mutex cache_mutex_;
  mutable std::map<std::pair<index_t, std::vector<index_t>>, std::vector<double>> cache_;
};

}  // namespace shapestruct
