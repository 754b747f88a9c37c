// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "shapestruct/eval/best_label_matching.hpp"
#include "shapestruct/eval/labeling_accuracy.hpp"
#include "shapestruct/eval/rand_index.hpp"

using namespace shapestruct;

TEST_CASE("best_label_matching equals brute force over permutations") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 10);
  for (int trial = 0; trial < 30; ++trial) {
    const int rows = 1 + trial % 5, cols = 1 + (trial / 5) % 5;
    Eigen::MatrixXd W(rows, cols);
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) W(i, j) = u(rng);
    const auto m = best_label_matching(W);
    // brute force: permute the larger side
    const int n = std::max(rows, cols);
    std::vector<int> perm(static_cast<std::size_t>(n));
    std::iota(perm.begin(), perm.end(), 0);
    double best = 0;
    do {
      double s = 0;
      for (int i = 0; i < rows; ++i)
        if (perm[static_cast<std::size_t>(i)] < cols) s += W(i, perm[static_cast<std::size_t>(i)]);
      best = std::max(best, s);
    } while (std::next_permutation(perm.begin(), perm.end()));
    CHECK(m.score == doctest::Approx(best));
    std::vector<index_t> used;
    for (auto t : m.to_truth)
      if (t != no_index) used.push_back(t);
    std::sort(used.begin(), used.end());
    CHECK(std::adjacent_find(used.begin(), used.end()) == used.end());
  }
}

TEST_CASE("best_label_matching rejects NaN") {
  Eigen::MatrixXd W = Eigen::MatrixXd::Ones(2, 2);
  W(1, 0) = std::nan("");
  CHECK_THROWS_AS(best_label_matching(W), invalid_input);
}

TEST_CASE("labeling_accuracy is invariant to renaming labels and weights by area") {
  labeled_shape s;
  s.truth = {0, 0, 1, 1, 2};
  s.predicted = {2, 2, 0, 0, 1};  // a permutation: perfect
  s.weight = {1, 1, 1, 1, 1};
  CHECK(labeling_accuracy({s}).accuracy == doctest::Approx(1.0));
  s.predicted = {2, 2, 0, 2, 1};  // face 3 wrong, weight 3 of 7
  s.weight = {1, 1, 1, 3, 1};
  CHECK(labeling_accuracy({s}).accuracy == doctest::Approx(4.0 / 7.0));
  s.predicted = {-1, 2, 0, 0, 1};  // unlabeled face counts as wrong
  s.weight = {1, 1, 1, 1, 1};
  CHECK(labeling_accuracy({s}).accuracy == doctest::Approx(0.8));
}

TEST_CASE("labeling_accuracy bad input") {
  labeled_shape s{{0, 1}, {0}, {1, 1}};
  CHECK_THROWS_AS(labeling_accuracy({s}), invalid_input);
  labeled_shape t{{0}, {0}, {-1}};
  CHECK_THROWS_AS(labeling_accuracy({t}), invalid_input);
  labeled_shape z{{0}, {0}, {0}};
  CHECK_THROWS_AS(labeling_accuracy({z}), invalid_input);
}

TEST_CASE("rand_index matches pair counting") {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> lab(0, 3);
  std::uniform_real_distribution<double> w(0.1, 2.0);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<index_t> a(12), b(12);
    std::vector<double> ws(12);
    for (int i = 0; i < 12; ++i) {
      a[static_cast<std::size_t>(i)] = lab(rng);
      b[static_cast<std::size_t>(i)] = lab(rng);
      ws[static_cast<std::size_t>(i)] = w(rng);
    }
    double agree = 0, all = 0;
    for (std::size_t i = 0; i < 12; ++i)
      for (std::size_t j = i + 1; j < 12; ++j) {
        const double ww = ws[i] * ws[j];
        all += ww;
        if ((a[i] == a[j]) == (b[i] == b[j])) agree += ww;
      }
    CHECK(rand_index(a, b, ws) == doctest::Approx(agree / all));
  }
  CHECK(rand_index({0, 0, 1}, {5, 5, 7}) == doctest::Approx(1.0));
  CHECK_THROWS_AS(rand_index({0, 1}, {0}), invalid_input);
  CHECK_THROWS_AS(rand_index({}, {}), invalid_input);
  CHECK_THROWS_AS(rand_index({0, 1}, {0, 1}, {1.0, -1.0}), invalid_input);
}
