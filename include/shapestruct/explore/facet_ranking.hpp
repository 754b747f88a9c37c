// SPDX-License-Identifier: MIT
// facet_ranking: several regions of interest (facets) combined into one ordering of the collection.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
#include <string>
#include <vector>
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// The collection sorted by similarity to the query.
struct collection_ranking {
  std::vector<index_t> order;     ///< shape indices, most similar first (the example shapes first)
  std::vector<double> distance;   ///< (N) the combined distance of every shape (index = shape)
};

/// Combines the distances D_R of several facets (one vector of N per region) into one ranking. Each facet's
/// distances are divided by their median over the shapes that are not examples, and the facets' normalised
/// distances averaged: D_R is in the units of its example shape, and a small region sees smaller distances than a
/// large one, so without the normalisation the largest facet would decide the order alone; the median, unlike
/// the mean or the maximum, is not moved by the few shapes that have no correspondence (+infinity). The example
/// shapes come first (distance 0), then the rest by combined distance, ties by index; a shape with no
/// correspondence to some facet (+infinity) comes last.
/// \throws invalid_input (empty) for no facets, (size_mismatch) for facets of different lengths, (bad_parameter)
///         for a negative or NaN distance or an example index out of range.
[[nodiscard]] inline collection_ranking rank_by_facets(std::span<const std::vector<double>> facet_distances,
                                                       std::span<const index_t> examples) {
  const char* who = "rank_by_facets";
  if (facet_distances.empty()) throw invalid_input(input_error::empty, no_index, std::string(who) + ": no facets");
  const std::size_t n = facet_distances.front().size();
  std::vector<char> is_example(n, 0);
  for (const index_t e : examples) {
    if (e < 0 || std::size_t(e) >= n)
      throw invalid_input(input_error::bad_parameter, e, std::string(who) + ": example shape " + std::to_string(e) + " out of range");
    is_example[std::size_t(e)] = 1;
  }
  collection_ranking out;
  out.distance.assign(n, 0.0);
  for (std::size_t f = 0; f < facet_distances.size(); ++f) {
    const auto& d = facet_distances[f];
    if (d.size() != n)
      throw invalid_input(input_error::size_mismatch, index_t(f),
                          std::string(who) + ": facet " + std::to_string(f) + " has " + std::to_string(d.size()) +
                              " distances, facet 0 has " + std::to_string(n));
    std::vector<double> finite;
    for (std::size_t j = 0; j < n; ++j) {
      if (std::isnan(d[j]) || d[j] < 0)
        throw invalid_input(input_error::bad_parameter, index_t(j),
                            std::string(who) + ": facet " + std::to_string(f) + " has distance " + std::to_string(d[j]) +
                                " for shape " + std::to_string(j));
      if (!is_example[j] && std::isfinite(d[j])) finite.push_back(d[j]);
    }
    double median = 0;
    if (!finite.empty()) {
      const auto mid = finite.begin() + std::ptrdiff_t(finite.size() / 2);
      std::nth_element(finite.begin(), mid, finite.end());
      median = *mid;
    }
    const double scale = median > 0 ? 1.0 / median : 1.0;
    for (std::size_t j = 0; j < n; ++j)
      if (!is_example[j]) out.distance[j] += d[j] * scale / double(facet_distances.size());
  }
  out.order.resize(n);
  std::iota(out.order.begin(), out.order.end(), index_t{0});
  std::stable_sort(out.order.begin(), out.order.end(), [&](index_t a, index_t b) {
    if (is_example[std::size_t(a)] != is_example[std::size_t(b)]) return is_example[std::size_t(a)] > is_example[std::size_t(b)];
    return out.distance[std::size_t(a)] < out.distance[std::size_t(b)];
  });
  return out;
}

}  // namespace shapestruct
