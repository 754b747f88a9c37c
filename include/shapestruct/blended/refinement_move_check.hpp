// SPDX-License-Identifier: MIT
// refinement_move_check: where a refinement moved an image far, keep whichever of the two images agrees better
// with the rest of the map.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/maps/surface_map.hpp"

namespace shapestruct {

/// A lower bound of the geodesic distance between every pair of vertices (x[i], y[i]) of `b`, from its sample
/// distance table: max over the samples s of |d(s, x) - d(s, y)| (the triangle inequality). It is tight up to
/// about twice the samples' covering radius, and exact where a sample lies on a shortest path's extension.
/// Pairs with an unmapped end (no_index) get +infinity.
/// Complexity: O(#pairs * #samples), one pass over the table's columns.
[[nodiscard]] inline std::vector<double> sample_distance_lower_bounds(const blended_shape<double>& b,
                                                                      const std::vector<index_t>& x,
                                                                      const std::vector<index_t>& y) {
  const auto& T = b.sample_distances();  // (#V x #samples), one contiguous column per sample
  std::vector<double> bound(x.size(), 0.0);
  for (std::size_t i = 0; i < x.size(); ++i)
    if (x[i] == no_index || y[i] == no_index) bound[i] = std::numeric_limits<double>::infinity();
  for (index_t s = 0; s < T.cols(); ++s) {
    const double* column = T.col(s).data();
    for (std::size_t i = 0; i < x.size(); ++i)
      if (x[i] != no_index && y[i] != no_index) bound[i] = std::max(bound[i], std::abs(column[x[i]] - column[y[i]]));
  }
  return bound;
}

/// Checks a refinement's long moves against the rest of the map. A refinement such as ZoomOut sharpens a map that
/// is right up to a few percent of the shape's size, and it can also repair a region the map had wrong; but now
/// and then its point search jumps to another limb that the map had right (docs/blended_maps.md, "Long moves of
/// the refinement"). Both cases are long moves, so length alone cannot tell them apart; agreement can. At every
/// source vertex v whose refined image lies at least `min_move` (unit-area units; the lower bound above) from its
/// image under `before`, each of the two images y is scored by its geodesic distortion against the source's even
/// samples s, mean over s of |d_a(v, s) - d_b(y, refined(s))| (d_b read through the target sample nearest to
/// refined(s), as geodesic_distortion does), and the image of `before` is put back when the refined one distorts
/// more than `min_ratio` times as much. The ratio leaves alone the differences the samples' spacing can make (on
/// benchmark pairs a right and a wrong image of 0.1-0.2 apart differ by 1.0-1.2 times); jumps to another limb
/// distort 2-9 times as much. Both
/// maps are in the shapes' internal numbering and have a's vertices as source. Returns how many images were put
/// back. Complexity: O(#source vertices * #samples of b + #long moves * #samples of a).
inline index_t check_refinement_moves(const blended_shape<double>& a, const blended_shape<double>& b,
                                      const surface_map<double>& before, surface_map<double>& refined, double min_move,
                                      double min_ratio) {
  const std::size_t n = std::min(before.points.size(), refined.points.size());
  std::vector<index_t> x(n, no_index), y(n, no_index);
  for (std::size_t i = 0; i < n; ++i) {
    if (before.points[i].valid() && i < before.nearest.size()) x[i] = before.nearest[i];
    if (refined.points[i].valid() && i < refined.nearest.size()) y[i] = refined.nearest[i];
  }
  const std::vector<double> moved = sample_distance_lower_bounds(b, x, y);
  // The reference: where the refinement sends a's even samples, each read through b's nearest sample. A wrong
  // jump is a local event, so most samples vouch for the right image; the refined images, rather than `before`'s,
  // so that a region the refinement repaired is judged by the repaired map.
  const auto& samples = a.samples();
  const auto& Ta = a.sample_distances();
  const auto& Tb = b.sample_distances();
  std::vector<index_t> reference;  // a's sample index, then b's sample nearest to its image
  std::vector<index_t> reference_sample;
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const auto v = static_cast<std::size_t>(samples[s]);
    if (v >= n || y[v] == no_index) continue;
    index_t nearest = 0;
    Tb.row(y[v]).minCoeff(&nearest);
    reference.push_back(static_cast<index_t>(s));
    reference_sample.push_back(nearest);
  }
  if (reference.empty()) return 0;
  const auto distortion = [&](index_t v, index_t image) {
    double sum = 0;
    for (std::size_t k = 0; k < reference.size(); ++k)
      sum += std::abs(Ta(v, reference[k]) - Tb(image, reference_sample[k]));
    return sum;
  };
  index_t put_back = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (x[i] == no_index || !(moved[i] >= min_move)) continue;  // nothing to put back, or a local move
    const auto v = static_cast<index_t>(i);
    if (y[i] != no_index && distortion(v, y[i]) <= min_ratio * distortion(v, x[i])) continue;
    refined.points[i] = before.points[i];
    refined.nearest[i] = before.nearest[i];
    ++put_back;
  }
  return put_back;
}

}  // namespace shapestruct
