// SPDX-License-Identifier: MIT
// error_curve: cumulative error curve (fraction of errors within each threshold), the usual way to report
// correspondence / landmark errors (dissertation 3.5, 5.4.5).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Fraction of `errors` that are <= each threshold.
/// \param errors     non-negative finite errors (e.g. Euclidean landmark error / bounding-box diagonal)
/// \param thresholds the thresholds D (any order)
/// \throws invalid_input empty when there are no errors, bad_parameter (index of the value) when an error or a
///         threshold is negative or not finite.
/// \returns one fraction in [0, 1] per threshold, in the order given. O((E + T) log E).
inline std::vector<double> error_curve(std::vector<double> errors, const std::vector<double>& thresholds) {
  if (errors.empty()) throw invalid_input(input_error::empty, no_index, "error_curve: no errors");
  for (std::size_t i = 0; i < errors.size(); ++i)
    if (!(errors[i] >= 0) || !std::isfinite(errors[i]))
      throw invalid_input(input_error::bad_parameter, static_cast<index_t>(i),
                          "error_curve: error " + std::to_string(i) + " is negative or not finite");
  for (std::size_t i = 0; i < thresholds.size(); ++i)
    if (!(thresholds[i] >= 0) || !std::isfinite(thresholds[i]))
      throw invalid_input(input_error::bad_parameter, static_cast<index_t>(i),
                          "error_curve: threshold " + std::to_string(i) + " is negative or not finite");
  std::sort(errors.begin(), errors.end());
  std::vector<double> out;
  out.reserve(thresholds.size());
  for (const double d : thresholds) {
    const auto n = std::upper_bound(errors.begin(), errors.end(), d) - errors.begin();
    out.push_back(static_cast<double>(n) / static_cast<double>(errors.size()));
  }
  return out;
}

}  // namespace shapestruct
