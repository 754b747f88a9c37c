// SPDX-License-Identifier: MIT
// rand_index: agreement of two segmentations of the same faces (Chen et al. 2009, PSB protocol).
#pragma once

#include <map>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Rand index between two labelings a, b of the same n faces, each face weighted by w (areas; pass an empty w
/// for unit weights): the weighted fraction of face pairs on which the two segmentations agree (both put the
/// pair in one segment, or both split it). Label values need not correspond between a and b. The PSB benchmark
/// reports 1 - RI ("Rand index error"); this returns RI itself, so higher is better.
/// \throws invalid_input size_mismatch when the lengths differ, empty when n = 0, bad_parameter for a negative
///         or non-finite weight (element = face).
/// \returns RI in [0, 1]. O(n log n) via the contingency table (no pair enumeration).
inline double rand_index(const std::vector<index_t>& a, const std::vector<index_t>& b,
                         const std::vector<double>& w = {}) {
  if (a.size() != b.size() || (!w.empty() && w.size() != a.size()))
    throw invalid_input(input_error::size_mismatch, no_index,
                        "rand_index: the labelings have " + std::to_string(a.size()) + " and " +
                            std::to_string(b.size()) + " faces and " + std::to_string(w.size()) +
                            " weights; they must agree");
  if (a.empty()) throw invalid_input(input_error::empty, no_index, "rand_index: no faces");
  std::map<std::pair<index_t, index_t>, double> joint;
  std::map<index_t, double> ma, mb;
  double total = 0, sum_sq = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double wi = w.empty() ? 1.0 : w[i];
    if (!(wi >= 0) || !std::isfinite(wi))
      throw invalid_input(input_error::bad_parameter, static_cast<index_t>(i),
                          "rand_index: face " + std::to_string(i) + " has a negative or non-finite weight");
    joint[{a[i], b[i]}] += wi;
    ma[a[i]] += wi;
    mb[b[i]] += wi;
    total += wi;
    sum_sq += wi * wi;
  }
  if (!(total > 0)) throw invalid_input(input_error::empty, no_index, "rand_index: the weights sum to zero");
  // Weighted pair counts over unordered pairs i != j: sum_{i<j} w_i w_j [same in X] = (sum_g W_g^2 - sum w^2)/2.
  auto pairs = [&](double s2) { return 0.5 * (s2 - sum_sq); };
  double sa = 0, sb = 0, sab = 0;
  for (const auto& [k, v] : ma) sa += v * v;
  for (const auto& [k, v] : mb) sb += v * v;
  for (const auto& [k, v] : joint) sab += v * v;
  const double all_pairs = pairs(total * total);
  if (!(all_pairs > 0)) return 1.0;  // a single face: every (empty) pair set agrees
  // agree = both same + both different = P_ab + (all - P_a - P_b + P_ab).
  const double agree = all_pairs - pairs(sa) - pairs(sb) + 2 * pairs(sab);
  return agree / all_pairs;
}

}  // namespace shapestruct
