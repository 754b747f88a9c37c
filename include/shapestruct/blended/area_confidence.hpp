// SPDX-License-Identifier: MIT
// area_confidence: c_i(p), how well candidate map i preserves area at the even samples (eq. 3.2).
#pragma once

#include <cmath>
#include <vector>

#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/blended/triplet_candidates.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// The confidence policy of blended_matcher: c_i(p) = 2 / (r + 1/r), r = area(m_i(N_p)) / area(N_p), at every
/// even sample p of the source. For a conformal map r is analytic: r = |T'(z)|^2 rho_2(T(z)) / rho_1(z), with rho
/// the flattenings' area densities (3-D area per planar area over a two-ring neighbourhood), so one nearest-vertex
/// query in the target plane per (map, sample) suffices (the density is smooth over two rings). Returns a (#maps x #samples) matrix in [0, 1].
/// Complexity O(K S log F / threads); deterministic for any thread count.
struct area_confidence {
  template <class Scalar>
  [[nodiscard]] matrix_x<Scalar> operator()(const blended_shape<Scalar>& a, const blended_shape<Scalar>& b,
                                            const std::vector<candidate_map<Scalar>>& maps, int threads) const {
    const auto& samples = a.samples();
    const index_t S = static_cast<index_t>(samples.size()), K = static_cast<index_t>(maps.size());
    matrix_x<Scalar> C(K, S);
    const auto& fa = a.flattening();
    const auto& fb = b.flattening();
    detail::parallel_for(K, detail::resolve_threads(threads, "blended intrinsic maps"), [&](index_t i) {
      const auto& T = maps[static_cast<std::size_t>(i)].transform;
      for (index_t s = 0; s < S; ++s) {
        const index_t v = samples[static_cast<std::size_t>(s)];
        const auto z = fa.coordinate(v);
        const index_t u = fb.nearest_vertex(T(z));
        const Scalar r = T.area_scale(z) * fb.vertex_density()[u] / fa.vertex_density()[v];
        C(i, s) = (std::isfinite(r) && r > 0) ? Scalar(2) / (r + Scalar(1) / r) : Scalar(0);
      }
    });
    return C;
  }
};

}  // namespace shapestruct
