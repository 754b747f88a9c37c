// SPDX-License-Identifier: MIT
// EnergyTerm: one additive term of an objective, composed at compile time (energy_sum in templates/).
#pragma once

#include <concepts>

#include <Eigen/Core>

namespace shapestruct {

/// e.value(x) evaluates the term at state x; deterministic, no side effects.
template <class E, class State>
concept EnergyTerm = requires(const E& e, const State& x) {
  typename E::scalar_type;
  { e.value(x) } -> std::convertible_to<typename E::scalar_type>;
};

/// A term with a gradient: accumulate_gradient ADDS dE/dx to g (never assigns), so terms can share g.
template <class E, class State>
concept DifferentiableEnergyTerm =
    EnergyTerm<E, State> &&
    requires(const E& e, const State& x, Eigen::Matrix<typename E::scalar_type, Eigen::Dynamic, 1>& g) {
      e.accumulate_gradient(x, g);
    };

}  // namespace shapestruct
