// SPDX-License-Identifier: MIT
// nearest_fraction: for every embedded point, its squared distances to the nearest fraction of the points of
// other shapes (the statistic behind both the fuzzy widths tau and the explorer's variance).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <span>
#include <vector>
#include <Eigen/Core>
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"

namespace shapestruct::detail {

/// Calls visit(p, nearest) for every row p of X (rows offsets[k] .. offsets[k+1]-1 belong to shape k), where
/// `nearest` holds p's squared distances to its ceil(fraction * R) nearest reference points of other shapes,
/// unordered; the R reference points are every row up to `reference_points`, beyond that a seeded subset of that
/// size (the same on every platform), which keeps the cost O(NK R d) instead of O((NK)^2 d). `nearest` is empty
/// when no reference point lies on another shape. visit runs concurrently for different p.
template <class Visit>
void for_each_nearest_fraction(const Eigen::MatrixXf& X, const std::vector<index_t>& offsets, double fraction,
                               index_t reference_points, std::uint64_t seed, unsigned workers, Visit&& visit) {
  const index_t n = X.rows();
  std::vector<index_t> shape_of(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k + 1 < offsets.size(); ++k)
    for (index_t p = offsets[k]; p < offsets[k + 1]; ++p) shape_of[std::size_t(p)] = index_t(k);
  std::vector<index_t> ref(static_cast<std::size_t>(n));
  std::iota(ref.begin(), ref.end(), index_t{0});
  if (n > reference_points) {
    std::mt19937_64 rng(seed);
    for (index_t i = n - 1; i > 0; --i) {  // Fisher-Yates with raw engine output: the same on every platform
      const index_t j = static_cast<index_t>(rng() % static_cast<std::uint64_t>(i + 1));
      std::swap(ref[std::size_t(i)], ref[std::size_t(j)]);
    }
    ref.resize(static_cast<std::size_t>(reference_points));
    std::sort(ref.begin(), ref.end());
  }
  const index_t R = static_cast<index_t>(ref.size());
  Eigen::MatrixXf Y(R, X.cols());
  for (index_t r = 0; r < R; ++r) Y.row(r) = X.row(ref[std::size_t(r)]);
  const Eigen::VectorXf y2 = Y.rowwise().squaredNorm();
  constexpr index_t block = 256;
  const index_t blocks = (n + block - 1) / block;
  parallel_for(blocks, workers, [&](index_t b) {
    const index_t p0 = b * block, m = std::min(block, n - p0);
    const Eigen::MatrixXf Xb = X.middleRows(p0, m);
    Eigen::MatrixXf D2 = (-2.0f * Xb * Y.transpose()).eval();
    D2.colwise() += Xb.rowwise().squaredNorm();
    D2.rowwise() += y2.transpose();
    std::vector<float> d;
    d.reserve(static_cast<std::size_t>(R));
    for (index_t i = 0; i < m; ++i) {
      d.clear();
      const index_t own = shape_of[std::size_t(p0 + i)];
      for (index_t r = 0; r < R; ++r)
        if (shape_of[std::size_t(ref[std::size_t(r)])] != own) d.push_back(std::max(0.0f, D2(i, r)));
      if (d.empty()) {
        visit(p0 + i, std::span<const float>());
        continue;
      }
      const auto rank = static_cast<std::size_t>(
          std::clamp<double>(std::ceil(fraction * double(d.size())), 1.0, double(d.size())));
      std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(rank - 1), d.end());
      visit(p0 + i, std::span<const float>(d.data(), rank));
    }
  });
}

}  // namespace shapestruct::detail
