// SPDX-License-Identifier: MIT
// region: a region of interest painted on one example shape of a collection (ch. 4.5.3).
#pragma once
#include <algorithm>
#include <string>
#include <vector>
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/fuzzy/diffusion_embedding.hpp"

namespace shapestruct {

/// A region of interest R on one shape: the shape's index in the collection and the (local) indices of its
/// selected samples. Several regions, on one or several example shapes, are the facets of one query.
struct region {
  index_t shape = 0;
  std::vector<index_t> samples;
};

/// The region with its samples sorted and duplicates removed, after checking it against the collection.
/// \throws invalid_input: bad_parameter naming the unknown shape (element = shape) or the sample out of range
///         (element = sample); empty for a region with no samples.
[[nodiscard]] inline region checked_region(const diffusion_embedding& e, region r) {
  if (r.shape < 0 || r.shape >= e.shapes())
    throw invalid_input(input_error::bad_parameter, r.shape,
                        "region: shape " + std::to_string(r.shape) + " is not in the collection (it has " +
                            std::to_string(e.shapes()) + " shapes)");
  if (r.samples.empty())
    throw invalid_input(input_error::empty, r.shape,
                        "region: no samples selected on shape " + std::to_string(r.shape));
  const index_t K = e.samples_of(r.shape);
  for (const index_t s : r.samples)
    if (s < 0 || s >= K)
      throw invalid_input(input_error::bad_parameter, s,
                          "region: sample " + std::to_string(s) + " is not a sample of shape " +
                              std::to_string(r.shape) + " (it has " + std::to_string(K) + ")");
  std::sort(r.samples.begin(), r.samples.end());
  r.samples.erase(std::unique(r.samples.begin(), r.samples.end()), r.samples.end());
  return r;
}

}  // namespace shapestruct
