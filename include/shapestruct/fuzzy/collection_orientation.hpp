// SPDX-License-Identifier: MIT
// collection_orientation: which shapes sit in a collection's f the mirror way round, voted by the aligner's own choices.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"

namespace shapestruct {

/// One edge's say on the relative orientation of shapes a and b in f: +1 the aligner's own choice for the pair
/// agrees with the collection's, -1 the collection clearly overrules it (for a shape with a left-right symmetry,
/// most often because one of the two sits in f mirrored).
struct orientation_vote {
  index_t a = no_index;
  index_t b = no_index;
  int sign = 1;
  double weight = 1;
};

/// Orientation of every shape, +1 or -1, agreeing with as much of the votes' weight as it can (Z2
/// synchronisation: maximise sum weight * sign * x_a * x_b). An intrinsic collection whose shapes share a
/// symmetry cannot tell a map from its flip (the whole collection agrees with either), so a shape can settle in f
/// mirrored against the rest; each edge's aligner, judging its pair alone, is right more often than not, and the
/// votes of all of a shape's edges outweigh the few wrong ones.
/// The leading eigenvector of the signed adjacency (power iteration from all +1) gives the start, single-shape
/// flips that gain are then made until none does. Within each connected component of the votes the sign is the one
/// that leaves most shapes at +1 (the collection's own orientation; a tie keeps the lowest-indexed shape at +1);
/// shapes without votes are +1. Deterministic.
/// \throws invalid_input (bad_parameter) for a vote naming a shape outside [0, N), joining a shape to itself, with
///         a sign other than +1 / -1 or a negative or non-finite weight.
[[nodiscard]] inline std::vector<std::int8_t> orient_collection(index_t N, std::span<const orientation_vote> votes) {
  for (const auto& v : votes)
    if (v.a < 0 || v.a >= N || v.b < 0 || v.b >= N || v.a == v.b || (v.sign != 1 && v.sign != -1) ||
        !(v.weight >= 0) || !std::isfinite(v.weight))
      throw invalid_input(input_error::bad_parameter, v.a,
                          "orient_collection: a vote must join two different shapes of " + std::to_string(N) +
                              " with sign +1 or -1 and a finite weight >= 0 (got " + std::to_string(v.a) + " - " +
                              std::to_string(v.b) + ", sign " + std::to_string(v.sign) + ")");
  const auto n = static_cast<std::size_t>(N);
  std::vector<std::int8_t> x(n, 1);
  if (votes.empty() || N < 2) return x;
  std::vector<double> degree(n, 0.0);
  for (const auto& v : votes) degree[std::size_t(v.a)] += v.weight, degree[std::size_t(v.b)] += v.weight;
  double shift = 0;
  for (const double d : degree) shift = std::max(shift, d);
  // Power iteration on A + shift I (positive semi-definite, so it finds A's largest eigenvalue, not its largest magnitude).
  std::vector<double> u(n, 1.0), w(n);
  for (int iteration = 0; iteration < 1000; ++iteration) {
    for (std::size_t k = 0; k < n; ++k) w[k] = shift * u[k];
    for (const auto& v : votes) {
      w[std::size_t(v.a)] += v.weight * v.sign * u[std::size_t(v.b)];
      w[std::size_t(v.b)] += v.weight * v.sign * u[std::size_t(v.a)];
    }
    double norm = 0;
    for (const double c : w) norm += c * c;
    norm = std::sqrt(norm);
    if (!(norm > 0)) break;
    double change = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const double c = w[k] / norm;
      change = std::max(change, std::abs(c - u[k]));
      u[k] = c;
    }
    if (change < 1e-12) break;
  }
  for (std::size_t k = 0; k < n; ++k) x[k] = u[k] < 0 ? -1 : 1;
  // Local repair: flip a shape while its votes, weighed with the current labels, say it sits the other way.
  std::vector<std::vector<std::size_t>> at(n);
  for (std::size_t e = 0; e < votes.size(); ++e) at[std::size_t(votes[e].a)].push_back(e), at[std::size_t(votes[e].b)].push_back(e);
  for (std::size_t pass = 0; pass < n + 1; ++pass) {
    bool flipped = false;
    for (std::size_t k = 0; k < n; ++k) {
      double agreement = 0;
      for (const auto e : at[k]) {
        const auto& v = votes[e];
        const std::size_t other = std::size_t(v.a) == k ? std::size_t(v.b) : std::size_t(v.a);
        agreement += v.weight * v.sign * x[k] * x[other];
      }
      if (agreement < -1e-12) x[k] = std::int8_t(-x[k]), flipped = true;
    }
    if (!flipped) break;
  }
  // The sign of each component of the votes is free: keep its majority at +1.
  detail::disjoint_sets components(N);
  for (const auto& v : votes)
    if (v.weight > 0) components.unite(v.a, v.b);
  std::vector<index_t> balance(n, 0), first(n, no_index);
  for (index_t k = 0; k < N; ++k) {
    const auto c = std::size_t(components.find(k));
    balance[c] += x[std::size_t(k)];
    if (first[c] == no_index) first[c] = k;
  }
  std::vector<bool> flip(n, false);
  for (std::size_t c = 0; c < n; ++c)
    flip[c] = first[c] != no_index && (balance[c] < 0 || (balance[c] == 0 && x[std::size_t(first[c])] < 0));
  for (index_t k = 0; k < N; ++k)
    if (flip[std::size_t(components.find(k))]) x[std::size_t(k)] = std::int8_t(-x[std::size_t(k)]);
  return x;
}

}  // namespace shapestruct
