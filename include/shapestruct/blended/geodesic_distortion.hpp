// SPDX-License-Identifier: MIT
// geodesic_distortion: how far a map between two prepared shapes is from an isometry, at the source's even samples.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/maps/surface_map.hpp"

namespace shapestruct {

/// Mean over pairs of even samples (s, t) of a of |d_a(s, t) - d_b(f(s), f(t))| in unit-area units (lower is
/// better). `image` holds f(s) for every even sample as an internal vertex of b (no_index where unmapped);
/// d_b is read from b's sample table through the sample nearest to f(t), so it carries an error up to the
/// sampling's covering radius, the same for every map of the pair.
[[nodiscard]] inline double geodesic_distortion(const blended_shape<double>& a, const blended_shape<double>& b,
                                                const std::vector<index_t>& image) {
  const auto& samples = a.samples();
  const index_t ns = static_cast<index_t>(samples.size());
  const auto& Ta = a.sample_distances();
  const auto& Tb = b.sample_distances();
  std::vector<index_t> image_sample(static_cast<std::size_t>(ns), 0);
  for (index_t s = 0; s < ns; ++s)
    if (image[static_cast<std::size_t>(s)] != no_index)
      Tb.row(image[static_cast<std::size_t>(s)]).minCoeff(&image_sample[static_cast<std::size_t>(s)]);
  double sum = 0;
  std::size_t count = 0;
  for (index_t s = 0; s < ns; ++s) {
    const index_t vs = image[static_cast<std::size_t>(s)];
    if (vs == no_index) continue;
    for (index_t t = 0; t < ns; ++t) {
      if (t == s || image[static_cast<std::size_t>(t)] == no_index) continue;
      sum += std::abs(Ta(samples[static_cast<std::size_t>(s)], t) - Tb(vs, image_sample[static_cast<std::size_t>(t)]));
      ++count;
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

/// The same measure for a map in the INPUT numbering of both shapes (as blended_match_result and every map of
/// the library hand it out): each even sample's image is the map's nearest target vertex. Samples on vertices a
/// repair added, and images a repair dropped, count as unmapped.
[[nodiscard]] inline double input_map_geodesic_distortion(const blended_shape<double>& a,
                                                          const blended_shape<double>& b,
                                                          const surface_map<double>& map) {
  const auto& samples = a.samples();
  std::vector<index_t> image(samples.size(), no_index);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const index_t v = a.original_vertex(samples[s]);
    if (v == no_index || static_cast<std::size_t>(v) >= map.nearest.size()) continue;
    const index_t w = map.nearest[static_cast<std::size_t>(v)];
    if (w != no_index && w < b.original_size()) image[s] = b.internal_vertex(w);
  }
  return geodesic_distortion(a, b, image);
}

}  // namespace shapestruct
