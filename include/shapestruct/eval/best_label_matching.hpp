// SPDX-License-Identifier: MIT
// best_label_matching: the one-to-one mapping of predicted labels to ground-truth labels maximizing agreement.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Result of best_label_matching: `to_truth[p]` is the ground-truth label matched to predicted label p, or
/// no_index when p is left unmatched (more predicted labels than true ones); `score` is the matched weight.
struct label_matching {
  std::vector<index_t> to_truth;
  double score = 0;
};

/// Maximum-weight one-to-one assignment (Hungarian algorithm, Kuhn-Munkres with potentials) on a weight matrix
/// W (#predicted x #truth, W(p, t) = agreement, e.g. the area labeled p by the method and t by the truth).
/// \param W non-negative finite weights, any shape (rectangular handled by padding with zeros).
/// \throws invalid_input non_finite when an entry is NaN or infinite (element = row-major index).
/// \returns the matching and its total weight. O(n^3), n = max(rows, cols).
inline label_matching best_label_matching(const Eigen::Ref<const Eigen::MatrixXd>& W) {
  const index_t rows = W.rows(), cols = W.cols();
  for (index_t i = 0; i < rows; ++i)
    for (index_t j = 0; j < cols; ++j)
      if (!std::isfinite(W(i, j)))
        throw invalid_input(input_error::non_finite, i * cols + j,
                            "best_label_matching: weight (" + std::to_string(i) + ", " + std::to_string(j) +
                                ") is not finite");
  label_matching out;
  out.to_truth.assign(static_cast<std::size_t>(rows), no_index);
  if (rows == 0 || cols == 0) return out;
  const index_t n = std::max(rows, cols);
  double wmax = 0;
  for (index_t i = 0; i < rows; ++i)
    for (index_t j = 0; j < cols; ++j) wmax = std::max(wmax, W(i, j));
  // Minimization form: cost = wmax - weight; padding cells cost wmax (weight 0).
  auto cost = [&](index_t i, index_t j) { return (i < rows && j < cols) ? wmax - W(i, j) : wmax; };
  const double inf = std::numeric_limits<double>::infinity();
  // 1-based arrays as in the classic O(n^3) formulation: p[j] = row assigned to column j.
  std::vector<double> u(static_cast<std::size_t>(n + 1), 0), v(static_cast<std::size_t>(n + 1), 0);
  std::vector<index_t> p(static_cast<std::size_t>(n + 1), 0), way(static_cast<std::size_t>(n + 1), 0);
  for (index_t i = 1; i <= n; ++i) {
    p[0] = i;
    index_t j0 = 0;
    std::vector<double> minv(static_cast<std::size_t>(n + 1), inf);
    std::vector<char> used(static_cast<std::size_t>(n + 1), 0);
    do {
      used[static_cast<std::size_t>(j0)] = 1;
      const index_t i0 = p[static_cast<std::size_t>(j0)];
      double delta = inf;
      index_t j1 = 0;
      for (index_t j = 1; j <= n; ++j) {
        if (used[static_cast<std::size_t>(j)]) continue;
        const double cur = cost(i0 - 1, j - 1) - u[static_cast<std::size_t>(i0)] - v[static_cast<std::size_t>(j)];
        if (cur < minv[static_cast<std::size_t>(j)]) {
          minv[static_cast<std::size_t>(j)] = cur;
          way[static_cast<std::size_t>(j)] = j0;
        }
        if (minv[static_cast<std::size_t>(j)] < delta) {
          delta = minv[static_cast<std::size_t>(j)];
          j1 = j;
        }
      }
      for (index_t j = 0; j <= n; ++j) {
        if (used[static_cast<std::size_t>(j)]) {
          u[static_cast<std::size_t>(p[static_cast<std::size_t>(j)])] += delta;
          v[static_cast<std::size_t>(j)] -= delta;
        } else {
          minv[static_cast<std::size_t>(j)] -= delta;
        }
      }
      j0 = j1;
    } while (p[static_cast<std::size_t>(j0)] != 0);
    do {
      const index_t j1 = way[static_cast<std::size_t>(j0)];
      p[static_cast<std::size_t>(j0)] = p[static_cast<std::size_t>(j1)];
      j0 = j1;
    } while (j0 != 0);
  }
  for (index_t j = 1; j <= n; ++j) {
    const index_t i = p[static_cast<std::size_t>(j)] - 1;
    if (i >= 0 && i < rows && j - 1 < cols) {
      out.to_truth[static_cast<std::size_t>(i)] = j - 1;
      out.score += W(i, j - 1);
    }
  }
  return out;
}

}  // namespace shapestruct
