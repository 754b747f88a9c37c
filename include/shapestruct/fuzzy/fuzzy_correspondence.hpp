// SPDX-License-Identifier: MIT
// fuzzy_correspondence: f(p, q) = exp(-D_t(p, q)^2 / tau(p)^2) over a collection's samples (ch. 4.3.6, eq. 4.9).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/nearest_fraction.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/fuzzy/diffusion_embedding.hpp"

namespace shapestruct {

/// Options of make_fuzzy_correspondence (ch. 4.3.6 defaults).
struct fuzzy_correspondence_options {
  /// tau(p) is the distance from p to the farthest of this fraction of its nearest points (points of other
  /// shapes) in the embedding.
  double tau_fraction = 0.15;
  double cutoff = 2.0;  ///< f(p, q) = 0 beyond cutoff * tau(p)
  /// tau is the tau_fraction quantile of p's distances to the other shapes' points. Up to this many points
  /// every point is used (exact); beyond, a fixed seeded subset of this size estimates the quantile, which keeps
  /// the cost O(NK * this) instead of O((NK)^2) on large collections.
  index_t tau_reference_points = 4096;
  std::uint64_t seed = 1;
  int threads = 0;  ///< 0 = all cores; the result does not depend on it
};

/// The fuzzy correspondence function of a collection: its diffusion embedding and the per-point widths tau.
/// f is evaluated on demand from the embedding (NK x d floats plus NK widths), which is what the chapter stores
/// implicitly: with tau set by the 15 % quantile, f is non-zero for a sizeable share of all pairs, so a
/// materialised sparse f would hold O((NK)^2) entries. Queries over one target shape cost O(K d).
class fuzzy_correspondence {
 public:
  fuzzy_correspondence() = default;
  fuzzy_correspondence(diffusion_embedding embedding, Eigen::VectorXf tau, double cutoff)
      : embedding_(std::move(embedding)), tau_(std::move(tau)), cutoff_(cutoff) {}

  [[nodiscard]] const diffusion_embedding& embedding() const noexcept { return embedding_; }
  [[nodiscard]] const Eigen::VectorXf& tau() const noexcept { return tau_; }
  [[nodiscard]] double cutoff() const noexcept { return cutoff_; }
  [[nodiscard]] index_t shapes() const noexcept { return embedding_.shapes(); }
  [[nodiscard]] index_t points() const noexcept { return embedding_.points(); }
  /// Global row of sample i of shape k.
  [[nodiscard]] index_t point(index_t k, index_t i) const { return embedding_.offset(k) + i; }

  /// f(p, q) for global rows p, q (eq. 4.9, zero beyond cutoff * tau(p)).
  [[nodiscard]] double value(index_t p, index_t q) const {
    return from_squared(embedding_.squared_distance(p, q), double(tau_[p]));
  }

  /// Squared diffusion distances from global row p to every sample of shape l.
  [[nodiscard]] Eigen::VectorXf squared_distances_to_shape(index_t p, index_t l) const {
    const auto& X = embedding_.coordinates;
    const index_t o = embedding_.offset(l);
    const index_t m = embedding_.samples_of(l);
    return (X.middleRows(o, m).rowwise() - X.row(p)).rowwise().squaredNorm();
  }

  /// f(p, q) for every sample q of shape l.
  [[nodiscard]] Eigen::VectorXd row(index_t p, index_t l) const {
    const Eigen::VectorXf d2 = squared_distances_to_shape(p, l);
    Eigen::VectorXd f(d2.size());
    for (index_t j = 0; j < d2.size(); ++j) f[j] = from_squared(double(d2[j]), double(tau_[p]));
    return f;
  }

  /// f between every sample of shape k (rows) and every sample of shape l (columns), through one matrix product
  /// of the two shapes' embedded samples. O(K_k K_l d).
  [[nodiscard]] Eigen::MatrixXd block(index_t k, index_t l) const {
    const auto& X = embedding_.coordinates;
    const index_t ok = embedding_.offset(k), ol = embedding_.offset(l);
    const index_t mk = embedding_.samples_of(k), ml = embedding_.samples_of(l);
    const Eigen::MatrixXf A = X.middleRows(ok, mk), B = X.middleRows(ol, ml);
    Eigen::MatrixXf D2 = -2.0f * A * B.transpose();
    D2.colwise() += A.rowwise().squaredNorm();
    D2.rowwise() += B.rowwise().squaredNorm().transpose();
    Eigen::MatrixXd F(mk, ml);
    for (index_t j = 0; j < ml; ++j)
      for (index_t i = 0; i < mk; ++i) F(i, j) = from_squared(std::max(0.0, double(D2(i, j))), double(tau_[ok + i]));
    return F;
  }

  /// The sample of shape l closest to global row p in the embedding: the best fuzzy correspondence (ch. 4.4.2).
  [[nodiscard]] index_t best_match(index_t p, index_t l) const {
    index_t best = 0;
    squared_distances_to_shape(p, l).minCoeff(&best);
    return best;
  }

  /// For every sample of shape k, its best fuzzy correspondence on shape l (local sample indices).
  [[nodiscard]] std::vector<index_t> best_matches(index_t k, index_t l) const {
    std::vector<index_t> out(static_cast<std::size_t>(embedding_.samples_of(k)));
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = best_match(point(k, index_t(i)), l);
    return out;
  }

  /// Integrated fuzzy correspondence IFC(S_k, S_l) = sum over p in P_k, q in P_l of f(p, q) (ch. 4.3.7), over
  /// every `stride`-th sample of each shape and scaled by stride^2 (stride 1 = exact). The first farthest-point
  /// samples are spread over the whole shape, so a stride keeps the sum representative.
  [[nodiscard]] double integrated(index_t k, index_t l, index_t stride = 1) const {
    const auto& X = embedding_.coordinates;
    const index_t ok = embedding_.offset(k), ol = embedding_.offset(l);
    const index_t mk = (embedding_.samples_of(k) + stride - 1) / stride, ml = (embedding_.samples_of(l) + stride - 1) / stride;
    Eigen::MatrixXf A(mk, X.cols()), B(ml, X.cols());
    for (index_t i = 0; i < mk; ++i) A.row(i) = X.row(ok + i * stride);
    for (index_t j = 0; j < ml; ++j) B.row(j) = X.row(ol + j * stride);
    Eigen::MatrixXf D2 = -2.0f * A * B.transpose();
    D2.colwise() += A.rowwise().squaredNorm();
    D2.rowwise() += B.rowwise().squaredNorm().transpose();
    double sum = 0;
    for (index_t j = 0; j < ml; ++j)
      for (index_t i = 0; i < mk; ++i) sum += from_squared(std::max(0.0, double(D2(i, j))), double(tau_[ok + i * stride]));
    return sum * double(stride * stride);
  }

 private:
  [[nodiscard]] double from_squared(double d2, double tau) const {
    const double t2 = tau * tau;
    if (d2 > cutoff_ * cutoff_ * t2) return 0.0;
    if (!(t2 > 0)) return d2 > 0 ? 0.0 : 1.0;
    return std::exp(-d2 / t2);
  }

  diffusion_embedding embedding_;
  Eigen::VectorXf tau_;
  double cutoff_ = 2.0;
};

/// tau(p) for every embedded point: the distance to its ceil(tau_fraction * R)-th nearest point among the R
/// reference points on other shapes (all of them up to options.tau_reference_points, else a seeded subset).
/// Complexity O(NK * R * d / threads) through blocked matrix products.
/// \throws invalid_input (bad_parameter) for tau_fraction outside (0, 1] or cutoff <= 0.
[[nodiscard]] inline Eigen::VectorXf fuzzy_widths(const diffusion_embedding& e,
                                                  const fuzzy_correspondence_options& options = {}) {
  const char* who = "fuzzy_widths";
  if (!(options.tau_fraction > 0 && options.tau_fraction <= 1))
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": tau_fraction must be in (0, 1]");
  if (options.tau_reference_points < 1)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": tau_reference_points must be >= 1");
  Eigen::VectorXf tau = Eigen::VectorXf::Zero(e.points());
  detail::for_each_nearest_fraction(
      e.coordinates, e.offsets, options.tau_fraction, options.tau_reference_points, options.seed,
      detail::resolve_threads(options.threads, who), [&tau](index_t p, std::span<const float> nearest) {
        // nth_element put the kth smallest last: tau is its distance
        if (!nearest.empty()) tau[p] = std::sqrt(nearest.back());
      });
  return tau;
}

/// The fuzzy correspondence of an embedding (eq. 4.9 with the widths of fuzzy_widths).
/// \throws invalid_input (bad_parameter) for bad options.
[[nodiscard]] inline fuzzy_correspondence make_fuzzy_correspondence(diffusion_embedding e,
                                                                    const fuzzy_correspondence_options& options = {}) {
  if (!(options.cutoff > 0))
    throw invalid_input(input_error::bad_parameter, no_index, "make_fuzzy_correspondence: cutoff must be > 0");
  Eigen::VectorXf tau = fuzzy_widths(e, options);
  return fuzzy_correspondence(std::move(e), std::move(tau), options.cutoff);
}

}  // namespace shapestruct
