// SPDX-License-Identifier: MIT
// sample_map_measures: measures of maps between two prepared shapes, taken at the source's even samples.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/maps/surface_map.hpp"

namespace shapestruct {

/// Geodesic distortion: the mean over pairs of even samples (s, t) of a of |d_a(s, t) - d_b(f(s), f(t))| in
/// unit-area units (lower is better). `image` holds f(s) for every even sample as an internal vertex of b
/// (no_index where unmapped); d_b is read from b's sample table through the sample nearest to f(t), so it carries
/// an error up to the sampling's covering radius, the same for every map of the pair.
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

/// The image of every even sample of a, as an internal vertex of b, under a map in the INPUT numbering of both
/// shapes (as blended_match_result and every map of the library hand it out): the map's nearest target vertex.
/// Samples on vertices a repair added, and images a repair dropped, are unmapped (no_index).
[[nodiscard]] inline std::vector<index_t> input_map_sample_images(const blended_shape<double>& a,
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
  return image;
}

/// geodesic_distortion of a map in the input numbering.
[[nodiscard]] inline double input_map_geodesic_distortion(const blended_shape<double>& a,
                                                          const blended_shape<double>& b,
                                                          const surface_map<double>& map) {
  return geodesic_distortion(a, b, input_map_sample_images(a, b, map));
}

/// How far apart two maps of a onto b (input numbering) send the even samples of a: the mean geodesic distance on
/// b, in unit-area units, between the two images of each sample both map (d_b read through the sample nearest to
/// the second image, so up to the covering radius). Near 0 where the maps are one map up to local precision; about
/// the shape's size where one is the other's flip.
[[nodiscard]] inline double mean_image_distance(const blended_shape<double>& a, const blended_shape<double>& b,
                                                const surface_map<double>& first, const surface_map<double>& second) {
  const std::vector<index_t> x = input_map_sample_images(a, b, first);
  const std::vector<index_t> y = input_map_sample_images(a, b, second);
  const auto& Tb = b.sample_distances();
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t s = 0; s < x.size(); ++s) {
    if (x[s] == no_index || y[s] == no_index) continue;
    index_t nearest = 0;
    Tb.row(y[s]).minCoeff(&nearest);
    sum += Tb(x[s], nearest);
    ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace shapestruct
