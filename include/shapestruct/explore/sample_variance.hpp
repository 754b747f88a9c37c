// SPDX-License-Identifier: MIT
// sample_variance: where a collection varies (ch. 4.5.1): how far each sample's counterparts on the other shapes
// lie in the diffusion embedding.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <string>
#include <vector>
#include <Eigen/Core>
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/fuzzy/diffusion_embedding.hpp"

namespace shapestruct {

/// Options of sample_variance.
struct sample_variance_options {
  double fraction = 0.15;  ///< the neighbourhood: this fraction of the other shapes, the nearest (ch. 4.5.1)
  /// Shapes the neighbours are drawn from: all others up to this many, else a seeded subset of this size (the
  /// same for every shape), which bounds the cost per shape at O(K * this * K d).
  index_t reference_shapes = 64;
  std::uint64_t seed = 1;
  int threads = 0;  ///< 0 = all cores; the result does not depend on it
};

namespace detail {
inline void check_variance_options(const sample_variance_options& o, const char* who) {
  if (!(o.fraction > 0 && o.fraction <= 1))
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": fraction must be in (0, 1]");
  if (o.reference_shapes < 1)
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": reference_shapes must be >= 1");
}

/// The reference shapes (all, or a seeded subset of options.reference_shapes + 1 so that one may be excluded).
inline std::vector<index_t> variance_reference_shapes(index_t shapes, const sample_variance_options& o) {
  std::vector<index_t> ref(static_cast<std::size_t>(shapes));
  std::iota(ref.begin(), ref.end(), index_t{0});
  if (shapes > o.reference_shapes + 1) {
    std::mt19937_64 rng(o.seed);
    for (index_t i = shapes - 1; i > 0; --i) {  // Fisher-Yates with raw engine output: the same on every platform
      const index_t j = static_cast<index_t>(rng() % static_cast<std::uint64_t>(i + 1));
      std::swap(ref[std::size_t(i)], ref[std::size_t(j)]);
    }
    ref.resize(static_cast<std::size_t>(o.reference_shapes + 1));
    std::sort(ref.begin(), ref.end());
  }
  return ref;
}

/// Raw (unnormalised) variance of shape k's samples against the reference shapes.
inline Eigen::VectorXf shape_variance_raw(const diffusion_embedding& e, index_t k, const std::vector<index_t>& ref,
                                          const sample_variance_options& o) {
  const index_t m = e.samples_of(k);
  const Eigen::MatrixXf A = e.coordinates.middleRows(e.offset(k), m);
  const Eigen::VectorXf a2 = A.rowwise().squaredNorm();
  // nearest[l](i): squared distance from sample i of k to its best correspondence on reference shape l
  std::vector<Eigen::VectorXf> nearest;
  for (const index_t l : ref) {
    if (l == k || e.samples_of(l) == 0) continue;
    if (static_cast<index_t>(nearest.size()) == o.reference_shapes) break;
    const Eigen::MatrixXf B = e.coordinates.middleRows(e.offset(l), e.samples_of(l));
    Eigen::MatrixXf D2 = -2.0f * A * B.transpose();
    D2.colwise() += a2;
    D2.rowwise() += B.rowwise().squaredNorm().transpose();
    // The expansion |a|^2 + |b|^2 - 2ab finds the nearest point fast but rounds an exact match to ~1e-7 |a|^2,
    // which the per-shape normalisation would blow up: the distance to the nearest is recomputed directly.
    Eigen::VectorXf best(m);
    for (index_t i = 0; i < m; ++i) {
      index_t j = 0;
      D2.row(i).minCoeff(&j);
      best[i] = (A.row(i) - B.row(j)).squaredNorm();
    }
    nearest.push_back(best);
  }
  Eigen::VectorXf out = Eigen::VectorXf::Zero(m);
  if (nearest.empty()) return out;
  const auto count = static_cast<std::size_t>(
      std::clamp<double>(std::ceil(o.fraction * double(nearest.size())), 1.0, double(nearest.size())));
  std::vector<float> d(nearest.size());
  for (index_t i = 0; i < m; ++i) {
    for (std::size_t l = 0; l < nearest.size(); ++l) d[l] = nearest[l][i];
    std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(count - 1), d.end());
    double sum = 0;
    for (std::size_t c = 0; c < count; ++c) sum += std::sqrt(double(d[c]));
    out[i] = float(sum / double(count));
  }
  return out;
}

inline void normalise_by_max(Eigen::Ref<Eigen::VectorXf> v) {
  const float top = v.size() > 0 ? v.maxCoeff() : 0.0f;
  if (top > 0) v /= top;
}
}  // namespace detail

/// The variance of shape k's samples (ch. 4.5.1): for every sample, its diffusion distance to its counterpart
/// (nearest point) on each other shape, averaged over the given fraction of shapes where it is nearest, then
/// divided by the largest value within shape k, so 1 marks where k differs most from the rest of the collection
/// and a collection of identical shapes has variance 0 everywhere. One neighbour per shape, not the plain 15 %
/// nearest of all points: those would hold about 0.15 K points of every similar shape, and measure how densely the
/// embedding is sampled rather than how far the corresponding points are. O(K R K d) for R reference shapes.
/// \throws invalid_input (bad_parameter) for bad options or an unknown shape.
[[nodiscard]] inline Eigen::VectorXf shape_variance(const diffusion_embedding& e, index_t k,
                                                    const sample_variance_options& options = {}) {
  detail::check_variance_options(options, "shape_variance");
  if (k < 0 || k >= e.shapes())
    throw invalid_input(input_error::bad_parameter, k, "shape_variance: shape " + std::to_string(k) + " is not in the collection");
  Eigen::VectorXf v = detail::shape_variance_raw(e, k, detail::variance_reference_shapes(e.shapes(), options), options);
  detail::normalise_by_max(v);
  return v;
}

/// shape_variance of every shape, as one vector over all embedded points (in parallel over shapes).
[[nodiscard]] inline Eigen::VectorXf sample_variance(const diffusion_embedding& e,
                                                     const sample_variance_options& options = {}) {
  detail::check_variance_options(options, "sample_variance");
  const auto ref = detail::variance_reference_shapes(e.shapes(), options);
  Eigen::VectorXf out = Eigen::VectorXf::Zero(e.points());
  detail::parallel_for(e.shapes(), detail::resolve_threads(options.threads, "sample_variance"), [&](index_t k) {
    Eigen::VectorXf v = detail::shape_variance_raw(e, k, ref, options);
    detail::normalise_by_max(v);
    out.segment(e.offset(k), e.samples_of(k)) = v;
  });
  return out;
}

}  // namespace shapestruct
