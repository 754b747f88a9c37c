// SPDX-License-Identifier: MIT
// matcher_aligner: any PairwiseMatcher with its AlignmentScore as the pairwise alignments of a collection.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/concepts/alignment_score.hpp"
#include "shapestruct/core/concepts/pairwise_matcher.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/fuzzy/intrinsic_alignment.hpp"

namespace shapestruct {

/// Options of matcher_aligner.
struct matcher_aligner_options {
  /// Width of the local term relative to the target's scale: sqrt(area) on records with sample geodesics (as
  /// eq. 4.4's 0.3 sqrt(area)), else Diam(S) (as eq. 4.2's Diam / 5 = 0.2 Diam).
  double sigma_fraction = 0.3;
  index_t max_entries_per_row = 16;
  float keep_fraction = 1e-3f;
};

/// ShapeAligner from a user's PairwiseMatcher (match(a, b) -> a map of a's vertices onto b) and AlignmentScore
/// (lower is better; an empty optional rejects the map). One alternative per pair: the matcher's map, with
/// a(p_i, p_j) = exp(-d(m(p_i), p_j)^2 / sigma^2) * B, where d is the target's sample geodesic (or Euclidean)
/// distance from the sample nearest to m(p_i), and B = 1 / (1 + score) turns the score into eq. 4.1's global
/// term in (0, 1]. A rejected map leaves the pair without alternatives: the collection drops that edge.
/// Meshes come from `load(index)`; the matcher is called concurrently for different pairs (it must allow that).
template <class Matcher, class Score>
class matcher_aligner {
 public:
  using loader = std::function<triangle_mesh<double>(index_t)>;

  matcher_aligner(const std::vector<shape_record>& records, loader load, Matcher matcher, Score score,
                  matcher_aligner_options options = {})
      : records_(&records), load_(std::move(load)), matcher_(std::move(matcher)), score_(std::move(score)),
        options_(options) {
    if (!(options_.sigma_fraction > 0) || options_.max_entries_per_row < 1)
      throw invalid_input(input_error::bad_parameter, no_index,
                          "matcher_aligner: need sigma_fraction > 0 and max_entries_per_row >= 1");
  }

  [[nodiscard]] pair_alignment align(index_t source, index_t target) const
    requires PairwiseMatcher<const Matcher, triangle_mesh<double>, triangle_mesh<double>>
  {
    const triangle_mesh<double> a = load_(source), b = load_(target);
    const auto result = matcher_.match(a, b);
    using map_type = std::remove_cvref_t<decltype(result.map)>;
    static_assert(AlignmentScore<Score, map_type, triangle_mesh<double>, triangle_mesh<double>>,
                  "matcher_aligner: Score must be an AlignmentScore of the matcher's map");
    pair_alignment out;
    out.source = source;
    out.target = target;
    const auto score = score_(result.map, a, b);
    if (!score) return out;
    const shape_record& rs = (*records_)[std::size_t(source)];
    const shape_record& rt = (*records_)[std::size_t(target)];
    const bool geodesic = rt.sample_geodesics.size() > 0;
    const double sigma = options_.sigma_fraction * (geodesic ? std::sqrt(rt.area) : rt.diameter);
    const double B = 1.0 / (1.0 + std::max(0.0, double(*score)));
    const index_t K = rs.sample_count(), L = rt.sample_count();
    Eigen::MatrixXf dense(K, L);
    for (index_t i = 0; i < K; ++i) {
      // The vertex nearest to sample i stands for it: samples of soups are surface points.
      const index_t v = rs.sample_vertex[std::size_t(i)] != no_index ? rs.sample_vertex[std::size_t(i)] : nearest_vertex(a, rs, i);
      const index_t w = result.map.target_vertex(v);
      for (index_t j = 0; j < L; ++j) {
        double d = std::numeric_limits<double>::infinity();
        if (w != no_index) {
          const index_t s = rt.vertex_sample[std::size_t(w)];
          d = geodesic ? double(rt.sample_geodesics(s, j)) : (b.V.row(w) - rt.samples.row(j)).norm();
        }
        dense(i, j) = static_cast<float>(std::exp(-d * d / (sigma * sigma)) * B);
      }
    }
    alignment_alternative alt;
    alt.scores = detail::sparsify_rows(dense, options_.max_entries_per_row, options_.keep_fraction);
    alt.global_score = B;
    out.alternatives.push_back(std::move(alt));
    return out;
  }

 private:
  static index_t nearest_vertex(const triangle_mesh<double>& m, const shape_record& r, index_t i) {
    index_t best = 0;
    (m.V.rowwise() - r.samples.row(i)).rowwise().squaredNorm().minCoeff(&best);
    return best;
  }

  const std::vector<shape_record>* records_;
  loader load_;
  Matcher matcher_;
  Score score_;
  matcher_aligner_options options_;
};

}  // namespace shapestruct
