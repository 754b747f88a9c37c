// SPDX-License-Identifier: MIT
// geodesic_consistency: the blending matrix S~ of eq. 3.6 with the precomputed-distance consistency of eq. 3.5.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <vector>

#include <Eigen/SparseCore>

#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/blended/triplet_candidates.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Options of geodesic_consistency.
struct geodesic_consistency_options {
  double sigma = 0.5;  ///< S_ij(p) = exp(-d / sigma^2), d in units of sqrt(area) (ch. 3.3.4: sigma = 0.5)
  /// Samples where c_i(p) c_j(p) is below this add (at most) this much to S~_ij and are skipped: it saves most
  /// point locations, since a wrong map has low confidence almost everywhere.
  double min_confidence_product = 1e-3;
  /// Pairs involving a map whose integrated squared confidence sum_p c_i(p)^2 is below this fraction of the best
  /// map's are not evaluated (the map keeps only its diagonal entry): such a map (a wrong generating triplet)
  /// distorts area almost everywhere, and its entries in the top eigenvectors are negligible anyway. 0 keeps all.
  double min_relative_self_confidence = 0.05;
  /// Only the this-many maps with the largest sum_p c_i(p)^2 are paired (ties by index); the others keep their
  /// diagonal entry. The filled pairs grow with the square of the bucket sizes, so shapes with many features
  /// (cats, centaurs: 8-10 AGD maxima, 28,000+ triplet maps pruned to 10,000) would otherwise spend most of the
  /// time on maps that cannot reach the top eigenvectors. 0 = no limit.
  index_t max_paired_maps = 2000;
};

/// The consistency policy of blended_matcher. S~_ij = sum_p c_i(p) c_j(p) S_ij(p) A_p over the even samples,
/// with S_ij(p) = exp(-d_M1(p, m_j^-1(m_i(p))) / sigma^2) (eq. 3.5: the distance is measured on the SOURCE, from
/// the sample p, so it is a lookup in the precomputed distance table). Only pairs of maps that share two
/// generating correspondences and do not conflict are filled (the matrix is sparse, ch. 3.3.4); the diagonal is
/// sum_p c_i(p)^2 A_p. A_p = 1 / #samples (unit area).
/// Complexity O(pairs * S log F / threads); deterministic for any thread count.
struct geodesic_consistency {
  geodesic_consistency_options options{};

  template <class Scalar>
  [[nodiscard]] Eigen::SparseMatrix<Scalar> operator()(const blended_shape<Scalar>& a, const blended_shape<Scalar>&,
                                                       const std::vector<candidate_map<Scalar>>& maps,
                                                       const matrix_x<Scalar>& confidence, int threads) const {
    const index_t K = static_cast<index_t>(maps.size());
    const auto& samples = a.samples();
    const index_t S = static_cast<index_t>(samples.size());
    const Scalar area_unit = Scalar(1) / Scalar(S);
    const Scalar inv_sigma2 = Scalar(1) / Scalar(options.sigma * options.sigma);
    // Bucket maps by each of their three pairs of generating correspondences.
    std::map<std::array<index_t, 4>, std::vector<index_t>> buckets;
    for (index_t i = 0; i < K; ++i) {
      const auto& m = maps[static_cast<std::size_t>(i)];
      for (int drop = 0; drop < 3; ++drop) {
        std::array<std::array<index_t, 2>, 2> pr;
        int n = 0;
        for (int k = 0; k < 3; ++k)
          if (k != drop) pr[static_cast<std::size_t>(n++)] = {m.source[static_cast<std::size_t>(k)], m.target[static_cast<std::size_t>(k)]};
        if (pr[1] < pr[0]) std::swap(pr[0], pr[1]);
        buckets[{pr[0][0], pr[0][1], pr[1][0], pr[1][1]}].push_back(i);
      }
    }
    std::vector<std::pair<index_t, index_t>> pairs;
    for (const auto& [key, list] : buckets)
      for (std::size_t x = 0; x < list.size(); ++x)
        for (std::size_t y = x + 1; y < list.size(); ++y) {
          const index_t i = std::min(list[x], list[y]), j = std::max(list[x], list[y]);
          if (i == j || maps[static_cast<std::size_t>(i)].conflicts_with(maps[static_cast<std::size_t>(j)])) continue;
          pairs.emplace_back(i, j);
        }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    vector_x<Scalar> self(K);
    for (index_t i = 0; i < K; ++i) self[i] = confidence.row(i).squaredNorm();
    const Scalar self_min = K > 0 ? Scalar(options.min_relative_self_confidence) * self.maxCoeff() : Scalar(0);
    std::vector<char> paired(static_cast<std::size_t>(K), 1);
    if (options.max_paired_maps > 0 && K > options.max_paired_maps) {
      std::vector<index_t> order(static_cast<std::size_t>(K));
      std::iota(order.begin(), order.end(), index_t(0));
      std::stable_sort(order.begin(), order.end(), [&](index_t x, index_t y) { return self[x] > self[y]; });
      std::fill(paired.begin(), paired.end(), 0);
      for (index_t k = 0; k < options.max_paired_maps; ++k) paired[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] = 1;
    }
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                               [&](const std::pair<index_t, index_t>& p) {
                                 return self[p.first] < self_min || self[p.second] < self_min ||
                                        !paired[static_cast<std::size_t>(p.first)] ||
                                        !paired[static_cast<std::size_t>(p.second)];
                               }),
                pairs.end());
    std::vector<Scalar> values(pairs.size(), 0);
    const auto& fa = a.flattening();
    std::vector<std::complex<Scalar>> zs(static_cast<std::size_t>(S));
    for (index_t s = 0; s < S; ++s) zs[static_cast<std::size_t>(s)] = fa.coordinate(samples[static_cast<std::size_t>(s)]);
    detail::parallel_for(static_cast<index_t>(pairs.size()), detail::resolve_threads(threads, "blended intrinsic maps"), [&](index_t pi) {
      const auto [i, j] = pairs[static_cast<std::size_t>(pi)];
      // m_j^-1 o m_i is one Möbius transform of the source plane.
      const auto R = maps[static_cast<std::size_t>(j)].transform.inverse().compose(maps[static_cast<std::size_t>(i)].transform);
      Scalar sum = 0;
      for (index_t s = 0; s < S; ++s) {
        const Scalar cc = confidence(i, s) * confidence(j, s);
        if (cc < options.min_confidence_product) continue;
        // Vertex accuracy is ample here: sigma^2 = 0.25 is hundreds of edge lengths on a unit-area mesh.
        const index_t q = fa.nearest_vertex(R(zs[static_cast<std::size_t>(s)]));
        sum += cc * std::exp(-a.sample_distances()(q, s) * inv_sigma2);
      }
      values[static_cast<std::size_t>(pi)] = sum * area_unit;
    });
    std::vector<Eigen::Triplet<Scalar, index_t>> trip;
    trip.reserve(2 * pairs.size() + static_cast<std::size_t>(K));
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      if (values[p] <= 0) continue;
      trip.emplace_back(pairs[p].first, pairs[p].second, values[p]);
      trip.emplace_back(pairs[p].second, pairs[p].first, values[p]);
    }
    for (index_t i = 0; i < K; ++i) trip.emplace_back(i, i, confidence.row(i).squaredNorm() * area_unit);
    Eigen::SparseMatrix<Scalar> M(K, K);
    M.setFromTriplets(trip.begin(), trip.end());
    return M;
  }
};

}  // namespace shapestruct
