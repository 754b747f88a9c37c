// SPDX-License-Identifier: MIT
// energy_sum: a compile-time sum of EnergyTerm policies; the fitting energy of eq. 5.1 is one instance.
#pragma once

#include <array>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/concepts/energy_term.hpp"
#include "shapestruct/templates/fit_energy_terms.hpp"

namespace shapestruct {

/// Sum of energy terms, each an EnergyTerm<fit_state>. Besides value(), a term may provide any of
///   accumulate_unary(state, U)         adds per-point label costs (#P x (K+1), last column = null label)
///   accumulate_pairwise(state, edges)  appends Potts edges for the graph cut
///   accumulate_regression(state, sys)  adds rows to the per-part, per-axis 2x2 normal equations
/// and energy_sum forwards each call to the terms that have it, so a user term plugs into the labeling, the
/// regression, or both. Reweight a term through its `weight` member (terms()), replace one by building another
/// energy_sum, extend by adding a type.
template <class... Terms>
  requires(EnergyTerm<Terms, fit_state> && ...)
class energy_sum {
 public:
  using scalar_type = double;

  energy_sum() = default;
  explicit energy_sum(Terms... terms) : terms_(std::move(terms)...) {}

  [[nodiscard]] double value(const fit_state& x) const {
    return std::apply([&](const auto&... t) { return (0.0 + ... + static_cast<double>(t.value(x))); }, terms_);
  }
  void accumulate_unary(const fit_state& x, Eigen::MatrixXd& U) const {
    std::apply([&](const auto&... t) { (unary_one(t, x, U), ...); }, terms_);
  }
  void accumulate_pairwise(const fit_state& x, std::vector<potts_edge>& edges) const {
    std::apply([&](const auto&... t) { (pairwise_one(t, x, edges), ...); }, terms_);
  }
  void accumulate_regression(const fit_state& x, std::vector<std::array<part_axis_system, 3>>& sys) const {
    std::apply([&](const auto&... t) { (regression_one(t, x, sys), ...); }, terms_);
  }
  /// Term values separately (for reports), in declaration order.
  [[nodiscard]] std::array<double, sizeof...(Terms)> values(const fit_state& x) const {
    return std::apply([&](const auto&... t) { return std::array<double, sizeof...(Terms)>{t.value(x)...}; }, terms_);
  }
  [[nodiscard]] std::tuple<Terms...>& terms() noexcept { return terms_; }
  [[nodiscard]] const std::tuple<Terms...>& terms() const noexcept { return terms_; }

 private:
  template <class T>
  static void unary_one(const T& t, const fit_state& x, Eigen::MatrixXd& U) {
    if constexpr (requires { t.accumulate_unary(x, U); }) t.accumulate_unary(x, U);
  }
  template <class T>
  static void pairwise_one(const T& t, const fit_state& x, std::vector<potts_edge>& e) {
    if constexpr (requires { t.accumulate_pairwise(x, e); }) t.accumulate_pairwise(x, e);
  }
  template <class T>
  static void regression_one(const T& t, const fit_state& x, std::vector<std::array<part_axis_system, 3>>& s) {
    if constexpr (requires { t.accumulate_regression(x, s); }) t.accumulate_regression(x, s);
  }
  std::tuple<Terms...> terms_;
};

/// The chapter's energy (eq. 5.1): E_data (distance + gamma feature) + alpha E_deform + beta E_smooth with
/// alpha = 0.5, beta = 2, gamma = 2.
using chapter5_energy = energy_sum<distance_term, feature_term, deformation_term, smoothness_term>;

/// chapter5_energy with the chapter's weights.
inline chapter5_energy make_chapter5_energy(double alpha = 0.5, double beta = 2, double gamma = 2) {
  return chapter5_energy(distance_term{1.0, 0.1}, feature_term{gamma, 1.0}, deformation_term{alpha},
                         smoothness_term{beta});
}

}  // namespace shapestruct
