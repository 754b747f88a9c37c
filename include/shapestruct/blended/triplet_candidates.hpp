// SPDX-License-Identifier: MIT
// triplet_candidates: candidate conformal maps from all triplets of feature correspondences (ch. 3.3.2).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/conformal/mobius_transform.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// One candidate conformal map: the Möbius transform between the two flattenings that sends source feature
/// source[k] to target feature target[k] (indices into blended_shape::features()), k = 0, 1, 2.
template <class Scalar = double>
struct candidate_map {
  mobius_transform<Scalar> transform;
  std::array<index_t, 3> source{};  ///< feature indices on the source, in increasing order
  std::array<index_t, 3> target{};  ///< the corresponding feature indices on the target (any order)

  /// True if the two maps' generating correspondences conflict: one feature matched to two different ones.
  [[nodiscard]] bool conflicts_with(const candidate_map& o) const noexcept {
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if ((source[a] == o.source[b]) != (target[a] == o.target[b])) return true;
    return false;
  }
};

/// How triplet_candidates removes the maps beyond triplet_candidates_options::max_maps.
enum class triplet_pruning {
  /// Seeded random choice (the chapter prunes without a criterion, and says the bias this introduces can cost
  /// the true map, ch. 3.4).
  random,
  /// Keep the maps whose generating triplets preserve the geodesic distances between the three features best:
  /// sum over the triplet's three pairs of |d_source(s_k, s_l) - d_target(t_k, t_l)| (unit-area units), lowest
  /// first, ties by enumeration order. A near-isometry's triplets preserve them, so its maps survive: on TOSCA
  /// david6->david12 (10 x 10 features, 86,400 maps) random pruning to 30,000 keeps 29 of the 84 true triplet
  /// maps and selects a flip; this keeps all 84 (errors: docs/blended_maps.md, data test tosca_pruning).
  feature_distances,
};

/// Options of triplet_candidates.
struct triplet_candidates_options {
  /// Cap on the number of enumerated candidate maps; the excess is removed as `pruning` says, the survivors kept
  /// in enumeration order. blended_matcher then keeps the blended_matcher_options::max_maps (ch. 3.3.4: "at most
  /// 10,000") most confident of them, so this cap only bounds the confidence stage's work (10 x 10 features
  /// enumerate 86,400 maps).
  index_t max_maps = 30000;
  triplet_pruning pruning = triplet_pruning::feature_distances;
  std::uint64_t seed = 1;  ///< of triplet_pruning::random
};

/// The candidate generator policy of blended_matcher: every unordered source triplet x every unordered target
/// triplet x the 3! = 6 assignments between them, K = C(|P1|,3) C(|P2|,3) 6 maps (ch. 3.3.2); Möbius transforms
/// are orientation-preserving, so the six assignments give six genuinely different maps.
/// Complexity O(K) (plus O(K_all) for the enumeration before pruning).
struct triplet_candidates {
  triplet_candidates_options options{};

  template <class Scalar>
  [[nodiscard]] std::vector<candidate_map<Scalar>> operator()(const blended_shape<Scalar>& a,
                                                              const blended_shape<Scalar>& b) const {
    using complex = std::complex<Scalar>;
    const auto& fa = a.features();
    const auto& fb = b.features();
    const index_t na = static_cast<index_t>(fa.size()), nb = static_cast<index_t>(fb.size());
    std::vector<std::array<index_t, 3>> ta, tb;
    for (index_t i = 0; i < na; ++i)
      for (index_t j = i + 1; j < na; ++j)
        for (index_t k = j + 1; k < na; ++k) ta.push_back({i, j, k});
    for (index_t i = 0; i < nb; ++i)
      for (index_t j = i + 1; j < nb; ++j)
        for (index_t k = j + 1; k < nb; ++k) tb.push_back({i, j, k});
    static constexpr int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    const std::size_t total = ta.size() * tb.size() * 6;
    std::vector<std::size_t> keep(total);
    std::iota(keep.begin(), keep.end(), std::size_t(0));
    if (options.max_maps >= 0 && total > static_cast<std::size_t>(options.max_maps) &&
        options.pruning == triplet_pruning::feature_distances) {
      const auto& da = a.feature_distances();
      const auto& db = b.feature_distances();
      std::vector<Scalar> distortion(total);
      for (std::size_t id = 0; id < total; ++id) {
        const std::size_t p = id % 6, t = (id / 6) % tb.size(), s = id / 6 / tb.size();
        Scalar sum = 0;
        for (int k = 0; k < 3; ++k)
          for (int l = k + 1; l < 3; ++l) {
            const index_t sk = ta[s][static_cast<std::size_t>(k)], sl = ta[s][static_cast<std::size_t>(l)];
            const index_t tk = tb[t][static_cast<std::size_t>(perms[p][k])], tl = tb[t][static_cast<std::size_t>(perms[p][l])];
            sum += std::abs(da(fa[static_cast<std::size_t>(sk)], sl) - db(fb[static_cast<std::size_t>(tk)], tl));
          }
        distortion[id] = sum;
      }
      const std::size_t m = static_cast<std::size_t>(options.max_maps);
      std::nth_element(keep.begin(), keep.begin() + static_cast<std::ptrdiff_t>(m), keep.end(), [&](std::size_t x, std::size_t y) {
        return distortion[x] < distortion[y] || (distortion[x] == distortion[y] && x < y);
      });
      keep.resize(m);
      std::sort(keep.begin(), keep.end());
    } else if (options.max_maps >= 0 && total > static_cast<std::size_t>(options.max_maps)) {
      // Partial Fisher-Yates with an explicit uniform draw (std::uniform_int_distribution is not specified
      // identically across standard libraries; this keeps the same seed -> same maps everywhere).
      std::mt19937_64 rng(options.seed);
      const std::size_t m = static_cast<std::size_t>(options.max_maps);
      for (std::size_t i = 0; i < m; ++i) {
        const std::size_t j = i + static_cast<std::size_t>(rng() % (total - i));
        std::swap(keep[i], keep[j]);
      }
      keep.resize(m);
      std::sort(keep.begin(), keep.end());
    }
    std::vector<candidate_map<Scalar>> out;
    out.reserve(keep.size());
    const auto& flat_a = a.flattening();
    const auto& flat_b = b.flattening();
    for (std::size_t id : keep) {
      const std::size_t p = id % 6, t = (id / 6) % tb.size(), s = id / 6 / tb.size();
      candidate_map<Scalar> c;
      c.source = ta[s];
      for (int k = 0; k < 3; ++k) c.target[static_cast<std::size_t>(k)] = tb[t][static_cast<std::size_t>(perms[p][k])];
      complex z[3], w[3];
      for (int k = 0; k < 3; ++k) {
        z[k] = flat_a.coordinate(fa[static_cast<std::size_t>(c.source[static_cast<std::size_t>(k)])]);
        w[k] = flat_b.coordinate(fb[static_cast<std::size_t>(c.target[static_cast<std::size_t>(k)])]);
      }
      const auto T = mobius_transform<Scalar>::from_triplets(z, w);
      if (!T) continue;  // coincident images (e.g. features merged by the flattening): no map
      c.transform = *T;
      out.push_back(c);
    }
    return out;
  }
};

}  // namespace shapestruct
