// SPDX-License-Identifier: MIT
// intrinsic_aligner: blended intrinsic maps as the pairwise alignments of a collection (ch. 4.3.4, eq. 4.4-4.5).
#pragma once

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <map>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/heap_bytes.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/maps/surface_map.hpp"

namespace shapestruct {

/// Options of intrinsic_aligner.
struct intrinsic_alignment_options {
  /// The blended matcher (its threads are forced to 1: pairs run in parallel). Its refinement is off here: the
  /// alignment reads every group's map, not only the selected one, and the refiner would recompute both shapes'
  /// Laplace-Beltrami bases for every pair. So are the second feature set (below) and the reverse match.
  blended_matcher_options matcher = unrefined();
  /// sigma_intrinsic(S) = sigma_fraction sqrt(area(S)). The chapter (4.3.4) uses 0.3; 0.15 measured better on
  /// all 11 SHREC'07 classes together (docs/fuzzy.md: consistent blended 0.870 against 0.857 within 0.25, margin 0).
  double sigma_fraction = 0.15;
  index_t max_entries_per_row = 16;   ///< a(p_i, .) keeps this many largest entries per row
  float keep_fraction = 1e-3f;        ///< and drops entries below this fraction of the row's largest
  /// Prepared shapes kept in memory, at most this many and at most cache_bytes together (the least recently
  /// used is dropped first; the newest stays even when it alone is larger). A prepared shape holds about 5 KB per
  /// vertex (blended_shape::heap_bytes: 65 MB for a 12,500-vertex SCAPE scan), so the count alone let 24 TOSCA
  /// humans of 50,000 vertices take 6 GB.
  index_t cache_shapes = 24;
  std::size_t cache_bytes = std::size_t(1) << 31;  ///< 2 GiB
  /// An edge starts (iteration 0) from the blended map the matcher selects instead of the one with the best B
  /// (the chapter's). B is intrinsic and cannot tell a map from its symmetric flip; the matcher's selection
  /// (area, confidence and convexity ranks) often can. Off by default: on SHREC'07 it is 0.011 worse within 0.25 (glasses and pliers; docs/fuzzy.md).
  bool start_from_matcher_selection = false;
  /// Shapes with bumps of low persistence (blended_shape_options::alternative_feature_persistence) are matched
  /// with both feature sets, and every blended map of both is an alternative of the edge. The edge starts from
  /// the full set's map of the best B, as with one set, and the second set's maps compete through consistency;
  /// the matcher's distortion rule decides the preferred one. Off by default: it doubles those pairs' matching
  /// and lost on SHREC'07 (docs/fuzzy.md).
  bool both_feature_sets = false;

  static blended_matcher_options unrefined() {
    blended_matcher_options o;
    o.refine = false;
    // One feature set: the alignment keeps every group's map of one match as alternatives, and a second set
    // would double each pair's matching; the collection's consistency chooses among them instead.
    o.shape.alternative_feature_persistence = 0;
    // One direction: the alignment keeps every group's map whatever the selection, so the reverse pass would
    // only cost time.
    o.both_directions = false;
    return o;
  }
};

namespace detail {

/// c_m(p) of ch. 4.3.4 at the vertices `at`: 2 / (r + 1/r) with r the ratio of the 1-ring's area after and
/// before the map, each area relative to its surface's total (so a global scale change is not distortion).
inline std::vector<double> map_area_confidence(const triangle_mesh<double>& source, const triangle_mesh<double>& target,
                                               const surface_map<double>& map, const std::vector<index_t>& at) {
  const double As = total_area<double>(source.V, source.F), At = total_area<double>(target.V, target.F);
  auto image = [&](index_t v) -> Eigen::Vector3d {
    const auto& sp = map.point(v);
    if (sp.face == no_index) return Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) x += sp.bary[c] * target.V.row(target.F(sp.face, c)).transpose();
    return x;
  };
  // 1-rings of the requested vertices only: one pass over the faces.
  std::map<index_t, std::size_t> slot;
  for (std::size_t i = 0; i < at.size(); ++i) slot.emplace(at[i], i);
  std::vector<double> before(at.size(), 0.0), after(at.size(), 0.0);
  for (index_t f = 0; f < source.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto it = slot.find(source.F(f, c));
      if (it == slot.end()) continue;
      const Eigen::Vector3d a = source.V.row(source.F(f, 0)), b = source.V.row(source.F(f, 1)),
                            d = source.V.row(source.F(f, 2));
      before[it->second] += 0.5 * (b - a).cross(d - a).norm() / As;
      const Eigen::Vector3d ia = image(source.F(f, 0)), ib = image(source.F(f, 1)), id = image(source.F(f, 2));
      const double mapped = 0.5 * (ib - ia).cross(id - ia).norm() / At;
      after[it->second] += std::isfinite(mapped) ? mapped : 0.0;
    }
  std::vector<double> c(at.size(), 0.0);
  for (std::size_t i = 0; i < at.size(); ++i)
    if (before[i] > 0 && after[i] > 0) c[i] = 2.0 / (after[i] / before[i] + before[i] / after[i]);
  return c;
}

/// Keeps, per row, the `keep` largest entries at least `fraction` of the row's largest (the largest always).
inline Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t> sparsify_rows(const Eigen::MatrixXf& dense,
                                                                                index_t keep, float fraction) {
  Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t> s(dense.rows(), dense.cols());
  s.reserve(dense.rows() * std::min(keep, dense.cols()));
  std::vector<std::int32_t> order(static_cast<std::size_t>(dense.cols()));
  for (index_t i = 0; i < dense.rows(); ++i) {
    std::iota(order.begin(), order.end(), 0);
    const auto n = static_cast<std::ptrdiff_t>(std::min<index_t>(keep, dense.cols()));
    std::partial_sort(order.begin(), order.begin() + n, order.end(), [&](std::int32_t a, std::int32_t b) {
      return dense(i, a) > dense(i, b) || (dense(i, a) == dense(i, b) && a < b);
    });
    const float top = dense(i, order[0]);
    std::vector<std::int32_t> cols(order.begin(), order.begin() + n);
    std::sort(cols.begin(), cols.end());
    s.startVec(i);
    for (const auto j : cols)
      if (dense(i, j) >= fraction * top && (dense(i, j) > 0 || j == order[0])) s.insertBack(i, j) = dense(i, j);
  }
  s.finalize();
  return s;
}

}  // namespace detail

/// ShapeAligner of intrinsic collections: the blended matcher (ch. 3) on the two shapes, every blended map it
/// builds (one per consistent group of conformal maps) kept as an alternative, scored by eq. 4.4-4.5:
/// a(p_i, p_j) = c_m(p_i) exp(-d_geo(m(p_i), p_j)^2 / sigma^2) * B with B = mean_i c_m(p_i). The geodesic
/// distance is read from the target record's sample table at the sample nearest to m(p_i), which is exact up
/// to the sampling's covering radius (about a fifth of sigma for K = 128).
/// Meshes come from `load(index)` (a file read, typically); prepared shapes are cached (LRU, thread-safe).
class intrinsic_aligner {
 public:
  using loader = std::function<triangle_mesh<double>(index_t)>;

  intrinsic_aligner(const std::vector<shape_record>& records, loader load, intrinsic_alignment_options options = {})
      : records_(&records), load_(std::move(load)), options_(std::move(options)) {
    options_.matcher.threads = 1;
    options_.matcher.full_maps_for_all_groups = true;
    options_.matcher.on_stage = {};
    if (options_.both_feature_sets) {
      auto& persistence = options_.matcher.shape.alternative_feature_persistence;
      if (!(persistence > 0)) persistence = blended_shape_options{}.alternative_feature_persistence;
      options_.matcher.keep_both_feature_sets = true;
    }
    if (!(options_.sigma_fraction > 0) || options_.max_entries_per_row < 1 || options_.cache_shapes < 2 ||
        options_.cache_bytes == 0)
      throw invalid_input(input_error::bad_parameter, no_index,
                          "intrinsic_aligner: need sigma_fraction > 0, max_entries_per_row >= 1, cache_shapes >= 2 "
                          "and cache_bytes > 0");
  }

  [[nodiscard]] const intrinsic_alignment_options& options() const noexcept { return options_; }

  /// The blended match of a pair with every group's map filled (the consistent blended map needs them).
  [[nodiscard]] blended_match_result<double> match(index_t source, index_t target) const {
    const auto a = prepared(source);
    const auto b = prepared(target);
    return blended_matcher<>(options_.matcher).match(a->shape, b->shape);
  }

  /// Alternatives of eq. 4.4-4.5 from a blended match of (source, target).
  [[nodiscard]] pair_alignment alignment_from(index_t source, index_t target,
                                              const blended_match_result<double>& r) const {
    const auto a = prepared(source);
    const auto b = prepared(target);
    return alignment_from(*a, *b, source, target, r);
  }

  /// Any map of source vertices onto the target scored as an alternative of eq. 4.4-4.5 (parameters empty), so
  /// a map made elsewhere can compete with the blended ones. \throws as alignment_from.
  [[nodiscard]] alignment_alternative score_map(index_t source, index_t target, const surface_map<double>& map) const {
    const auto a = prepared(source);
    const auto b = prepared(target);
    const shape_record& rs = (*records_)[std::size_t(source)];
    const shape_record& rt = (*records_)[std::size_t(target)];
    check_geodesic_samples(rs, rt, source);
    if (map.source_size() != a->mesh.V.rows())
      throw invalid_input(input_error::size_mismatch, source,
                          "intrinsic_aligner::score_map: the map has " + std::to_string(map.source_size()) +
                              " points but shape '" + rs.name + "' has " + std::to_string(a->mesh.V.rows()) + " vertices");
    return alternative_of(*a, *b, rs, rt, map);
  }

  /// Shape k prepared for the blended matcher (unit area, samples, sample distances), for measures of maps
  /// between prepared shapes (sample_map_measures.hpp); shared with the cache.
  [[nodiscard]] std::shared_ptr<const blended_shape<double>> prepared_shape(index_t k) const {
    auto e = prepared(k);
    return {e, &e->shape};
  }

  /// The mesh of shape k as loaded (the numbering every map of this aligner uses); shared with the cache.
  [[nodiscard]] std::shared_ptr<const triangle_mesh<double>> mesh(index_t k) const {
    auto e = prepared(k);
    return {e, &e->mesh};
  }

  /// How many times a shape was prepared (a cache miss; the first use of each shape included), and the bytes
  /// the cache holds now.
  [[nodiscard]] std::size_t preparations() const {
    std::lock_guard lock(mutex_);
    return preparations_;
  }
  [[nodiscard]] std::size_t cached_bytes() const {
    std::lock_guard lock(mutex_);
    return cached_bytes_;
  }

  /// The collection's records (the ones given at construction).
  [[nodiscard]] const std::vector<shape_record>& records() const noexcept { return *records_; }

  /// ShapeAligner: every blended map of the pair as an alternative, the one with the highest B first chosen.
  [[nodiscard]] pair_alignment align(index_t source, index_t target) const {
    const auto a = prepared(source);
    const auto b = prepared(target);
    return alignment_from(*a, *b, source, target, blended_matcher<>(options_.matcher).match(a->shape, b->shape));
  }

 private:
  struct entry {
    triangle_mesh<double> mesh;
    blended_shape<double> shape;
    std::size_t bytes = 0;
  };

  /// alignment_from on shapes already prepared (align holds them from the match on, so that a small cache does
  /// not prepare them again in between).
  pair_alignment alignment_from(const entry& a, const entry& b, index_t source, index_t target,
                                const blended_match_result<double>& r) const {
    const shape_record& rs = (*records_)[std::size_t(source)];
    const shape_record& rt = (*records_)[std::size_t(target)];
    check_geodesic_samples(rs, rt, source);
    pair_alignment out;
    out.source = source;
    out.target = target;
    std::size_t full_set_maps = 0;  // a pooled match lists the full feature set's maps before the second set's
    for (std::size_t g = 0; g < r.blended.size(); ++g) {
      if (r.blended[g].map.points.empty()) continue;
      if (!r.blended[g].alternative_features) full_set_maps = out.alternatives.size() + 1;
      out.alternatives.push_back(alternative_of(a, b, rs, rt, r.blended[g].map));
      out.alternatives.back().parameters = {double(g)};
    }
    // The edge starts from the full set's maps, as with one set; the second set's compete through consistency.
    out.initial = best_global_alternative(std::span(out.alternatives).first(full_set_maps));
    for (std::size_t k = 0; k < out.alternatives.size(); ++k)
      if (static_cast<index_t>(out.alternatives[k].parameters.at(0)) == r.selected)
        out.preferred = static_cast<index_t>(k);
    if (options_.start_from_matcher_selection && out.preferred != no_index) out.initial = out.preferred;
    return out;
  }

  static void check_geodesic_samples(const shape_record& rs, const shape_record& rt, index_t source) {
    if (rs.sample_vertex.empty() || rs.sample_vertex[0] == no_index || rt.sample_geodesics.size() == 0)
      throw invalid_input(input_error::unsupported_topology, source,
                          "intrinsic_aligner: shapes '" + rs.name + "' and '" + rt.name +
                              "' need geodesic samples (closed genus-0 surfaces); use the extrinsic mode");
  }

  /// One map's alternative: a(p_i, p_j) = c_m(p_i) exp(-d_geo(m(p_i), p_j)^2 / sigma^2) * B.
  alignment_alternative alternative_of(const entry& a, const entry& b, const shape_record& rs, const shape_record& rt,
                                       const surface_map<double>& map) const {
    const double sigma = options_.sigma_fraction * std::sqrt(rt.area);
    const std::vector<double> c = detail::map_area_confidence(a.mesh, b.mesh, map, rs.sample_vertex);
    double B = 0;
    for (const double x : c) B += x;
    B /= double(c.size());
    const index_t K = rs.sample_count(), L = rt.sample_count();
    Eigen::MatrixXf dense(K, L);
    for (index_t i = 0; i < K; ++i) {
      const index_t v = map.target_vertex(rs.sample_vertex[std::size_t(i)]);
      const index_t s = v == no_index ? 0 : rt.vertex_sample[std::size_t(v)];
      for (index_t j = 0; j < L; ++j) {
        const double d = rt.sample_geodesics(s, j);
        dense(i, j) = static_cast<float>(c[std::size_t(i)] * std::exp(-d * d / (sigma * sigma)) * B);
      }
    }
    alignment_alternative alt;
    alt.scores = detail::sparsify_rows(dense, options_.max_entries_per_row, options_.keep_fraction);
    alt.global_score = B;
    return alt;
  }

  std::shared_ptr<const entry> prepared(index_t k) const {
    {
      std::unique_lock lock(mutex_);
      // One preparation per shape at a time: a thread that needs a shape another is preparing waits for it.
      prepared_elsewhere_.wait(lock, [&] { return !preparing_.contains(k); });
      const auto it = cache_.find(k);
      if (it != cache_.end()) {
        lru_.remove(k);
        lru_.push_front(k);
        return it->second;
      }
      // Dropped from the cache but still held by a pair in progress: take it back rather than prepare it again.
      if (const auto held = evicted_.find(k); held != evicted_.end()) {
        std::shared_ptr<const entry> e = held->second.lock();
        evicted_.erase(held);
        if (e) return keep(k, std::move(e));
      }
      preparing_.insert(k);
    }
    struct done_preparing {  // also when loading or preparing throws
      const intrinsic_aligner& self;
      index_t k;
      ~done_preparing() {
        {
          std::lock_guard lock(self.mutex_);
          self.preparing_.erase(k);
        }
        self.prepared_elsewhere_.notify_all();
      }
    } guard{*this, k};
    auto e = std::make_shared<entry>();
    e->mesh = load_(k);
    auto so = options_.matcher.shape;
    so.threads = 1;
    e->shape = make_blended_shape(e->mesh, so);
    e->bytes = sizeof(entry) + heap_bytes(e->mesh) + e->shape.heap_bytes();
    std::lock_guard lock(mutex_);
    ++preparations_;
    return keep(k, std::move(e));
  }

  /// Puts shape k first in the cache and drops the least recently used beyond the budget. Under mutex_.
  std::shared_ptr<const entry> keep(index_t k, std::shared_ptr<const entry> e) const {
    cache_.emplace(k, e);
    cached_bytes_ += e->bytes;
    lru_.push_front(k);
    // The newest always stays: a pair in progress holds its shapes anyway (shared_ptr), whatever the budget.
    while (lru_.size() > 1 && (static_cast<index_t>(lru_.size()) > options_.cache_shapes ||
                               cached_bytes_ > options_.cache_bytes)) {
      const auto old = cache_.find(lru_.back());
      cached_bytes_ -= old->second->bytes;
      std::erase_if(evicted_, [](const auto& held) { return held.second.expired(); });
      evicted_[old->first] = old->second;
      cache_.erase(old);
      lru_.pop_back();
    }
    return e;
  }

  const std::vector<shape_record>* records_;
  loader load_;
  intrinsic_alignment_options options_;
  mutable std::mutex mutex_;
  mutable std::condition_variable prepared_elsewhere_;
  mutable std::set<index_t> preparing_;  ///< shapes being prepared by some thread now
  mutable std::map<index_t, std::shared_ptr<const entry>> cache_;
  mutable std::list<index_t> lru_;
  mutable std::map<index_t, std::weak_ptr<const entry>> evicted_;  ///< dropped shapes, alive while a pair holds them
  mutable std::size_t cached_bytes_ = 0;
  mutable std::size_t preparations_ = 0;
};

}  // namespace shapestruct
