// SPDX-License-Identifier: MIT
// sample_variance: where a collection varies (ch. 4.5.1): the spread of each sample's fuzzy neighbourhood.
#pragma once
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <Eigen/Core>
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/nearest_fraction.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/fuzzy/diffusion_embedding.hpp"

namespace shapestruct {

/// Options of sample_variance.
struct sample_variance_options {
  double fraction = 0.15;  ///< the neighbourhood: this fraction of the nearest points of other shapes (ch. 4.5.1)
  /// Reference points the neighbourhood is drawn from (all up to this many, else a seeded subset), as for tau.
  index_t reference_points = 4096;
  std::uint64_t seed = 1;
  int threads = 0;  ///< 0 = all cores; the result does not depend on it
};

/// The variance of every embedded point (ch. 4.5.1): its mean diffusion distance to the given fraction of its
/// nearest points on the other shapes, divided by the largest such mean within its own shape, so every shape's
/// values lie in [0, 1] and 1 marks where that shape differs most from the rest of the collection. Points of other
/// shapes only: a shape's own nearby samples say nothing about the collection. A shape whose means are all zero
/// (identical copies) gets zeros. O(NK R d) for R reference points.
/// \throws invalid_input (bad_parameter) for a fraction outside (0, 1] or reference_points < 1.
[[nodiscard]] inline Eigen::VectorXf sample_variance(const diffusion_embedding& e,
                                                     const sample_variance_options& options = {}) {
  const char* who = "sample_variance";
  if (!(options.fraction > 0 && options.fraction <= 1))
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": fraction must be in (0, 1]");
  if (options.reference_points < 1)
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": reference_points must be >= 1");
  Eigen::VectorXf mean = Eigen::VectorXf::Zero(e.points());
  detail::for_each_nearest_fraction(e.coordinates, e.offsets, options.fraction, options.reference_points,
                                    options.seed, detail::resolve_threads(options.threads, who),
                                    [&mean](index_t p, std::span<const float> nearest) {
                                      double sum = 0;
                                      for (const float d2 : nearest) sum += std::sqrt(double(d2));
                                      if (!nearest.empty()) mean[p] = float(sum / double(nearest.size()));
                                    });
  for (index_t k = 0; k < e.shapes(); ++k) {
    auto shape = mean.segment(e.offset(k), e.samples_of(k));
    const float top = shape.size() > 0 ? shape.maxCoeff() : 0.0f;
    if (top > 0) shape /= top;
  }
  return mean;
}

}  // namespace shapestruct
