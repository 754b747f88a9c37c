// SPDX-License-Identifier: MIT
// co_alignment: every shape of a collection brought into one frame through its fuzzy correspondences (ch. 4.5.2).
#pragma once
#include <numeric>
#include <span>
#include <vector>
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/explore/affine_alignment.hpp"
#include "shapestruct/explore/region_query.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"

namespace shapestruct {

/// The shape the canonical view is that of: the one whose samples have the smallest mean width tau, i.e. whose
/// points sit where the collection's fuzzy correspondences are densest, the most typical shape.
[[nodiscard]] inline index_t canonical_reference(const fuzzy_correspondence& f) {
  index_t best = 0;
  double best_mean = 0;
  for (index_t k = 0; k < f.shapes(); ++k) {
    const index_t m = f.embedding().samples_of(k);
    if (m == 0) continue;
    const double mean = double(f.tau().segment(f.embedding().offset(k), m).mean());
    if (k == 0 || mean < best_mean) best = k, best_mean = mean;
  }
  return best;
}

/// The canonical view (ch. 4.5.2, Fig. 4.19b): for every shape the affine map into the reference shape's frame
/// that aligns its fuzzy correspondences with all of the reference's samples (T_R with R = the whole reference).
/// The reference gets the identity. O(N K^2 d / threads).
/// \throws invalid_input as region_query.
[[nodiscard]] inline std::vector<affine_transform> canonical_alignment(const fuzzy_correspondence& f,
                                                                       std::span<const shape_record> records,
                                                                       index_t reference, int threads = 0) {
  region whole{reference, {}};
  if (reference >= 0 && reference < f.shapes()) {
    whole.samples.resize(std::size_t(f.embedding().samples_of(reference)));
    std::iota(whole.samples.begin(), whole.samples.end(), index_t{0});
  }
  const region_query query(f, records, whole);
  std::vector<affine_transform> out(static_cast<std::size_t>(f.shapes()));
  detail::parallel_for(f.shapes(), detail::resolve_threads(threads, "canonical_alignment"),
                       [&](index_t j) { out[std::size_t(j)] = query.match(j).transform; });
  return out;
}

}  // namespace shapestruct
