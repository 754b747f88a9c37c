// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <random>
#include <thread>
#include <utility>

#include "shapestruct/templates/alpha_expansion.hpp"

using namespace shapestruct;

namespace {
double brute_force(const Eigen::MatrixXd& U, const std::vector<potts_edge>& E) {
  const index_t n = U.rows(), L = U.cols();
  std::vector<index_t> lab(static_cast<std::size_t>(n), 0);
  double best = std::numeric_limits<double>::infinity();
  for (;;) {
    best = std::min(best, potts_energy(U, E, lab));
    index_t i = 0;
    while (i < n && ++lab[static_cast<std::size_t>(i)] == L) lab[static_cast<std::size_t>(i++)] = 0;
    if (i == n) break;
  }
  return best;
}
}  // namespace

TEST_CASE("alpha_expansion: two labels is an exact min cut, equal to brute force") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  for (int trial = 0; trial < 40; ++trial) {
    const index_t n = 7;
    Eigen::MatrixXd U(n, 2);
    for (index_t i = 0; i < n; ++i) U.row(i) << u(rng), u(rng);
    std::vector<potts_edge> E;
    for (index_t i = 0; i < n; ++i)
      for (index_t j = i + 1; j < n; ++j)
        if (u(rng) < 0.4) E.push_back({i, j, 0.5 * u(rng)});
    const auto r = alpha_expansion(U, E);
    CHECK(r.info == status::ok);
    CHECK(r.energy == doctest::Approx(brute_force(U, E)));
    CHECK(r.energy == doctest::Approx(potts_energy(U, E, r.labels)));
  }
}

TEST_CASE("alpha_expansion: three and four labels reach brute-force optimum on small chains, within 2x always") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  int optimal = 0;
  const int trials = 40;
  for (int trial = 0; trial < trials; ++trial) {
    const index_t n = 6, L = 3 + trial % 2;
    Eigen::MatrixXd U(n, L);
    for (index_t i = 0; i < n; ++i)
      for (index_t l = 0; l < L; ++l) U(i, l) = u(rng);
    std::vector<potts_edge> E;
    for (index_t i = 0; i + 1 < n; ++i) E.push_back({i, i + 1, 0.6 * u(rng)});
    E.push_back({0, n - 1, 0.3 * u(rng)});
    const auto r = alpha_expansion(U, E);
    const double opt = brute_force(U, E);
    CHECK(r.energy >= opt - 1e-12);
    CHECK(r.energy <= 2 * opt + 1e-12);
    if (r.energy <= opt + 1e-9) ++optimal;
  }
  // Expansion moves are strong: on these small instances they almost always find the optimum.
  CHECK(optimal >= trials * 9 / 10);
}

TEST_CASE("alpha_expansion: the network reused between calls leaves no trace of an earlier, larger one") {
  // Each thread keeps its max-flow arrays from call to call; a large problem, a small one and the large one again
  // must give what they give alone, on this thread and on a fresh one.
  auto grid = [](index_t side, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Eigen::MatrixXd U(side * side, 4);
    for (index_t i = 0; i < U.rows(); ++i)
      for (index_t l = 0; l < 4; ++l) U(i, l) = u(rng);
    std::vector<potts_edge> E;
    for (index_t r = 0; r < side; ++r)
      for (index_t c = 0; c < side; ++c) {
        if (c + 1 < side) E.push_back({r * side + c, r * side + c + 1, 0.4 * u(rng)});
        if (r + 1 < side) E.push_back({r * side + c, (r + 1) * side + c, 0.4 * u(rng)});
      }
    return std::pair{U, E};
  };
  const auto [U_big, E_big] = grid(30, 1);
  const auto [U_small, E_small] = grid(2, 2);
  const auto first = alpha_expansion(U_big, E_big);
  const auto small = alpha_expansion(U_small, E_small);
  const auto again = alpha_expansion(U_big, E_big);
  CHECK(again.labels == first.labels);
  alpha_expansion_result big_alone, small_alone;
  std::thread([&] { big_alone = alpha_expansion(U_big, E_big); }).join();
  std::thread([&] { small_alone = alpha_expansion(U_small, E_small); }).join();
  CHECK(big_alone.labels == first.labels);
  CHECK(small_alone.labels == small.labels);
  CHECK(first.energy == doctest::Approx(potts_energy(U_big, E_big, first.labels)));
}

TEST_CASE("alpha_expansion: strong smoothness gives one label") {
  Eigen::MatrixXd U(4, 2);
  U << 0, 1, 0, 1, 1, 0, 0, 1;
  std::vector<potts_edge> E{{0, 1, 5}, {1, 2, 5}, {2, 3, 5}};
  const auto r = alpha_expansion(U, E);
  for (auto l : r.labels) CHECK(l == 0);
}

TEST_CASE("alpha_expansion bad input") {
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(3, 2);
  CHECK_THROWS_AS(alpha_expansion(Eigen::MatrixXd(0, 2), {}), invalid_input);
  Eigen::MatrixXd Un = U;
  Un(1, 1) = std::nan("");
  try {
    (void)alpha_expansion(Un, {});
    FAIL("expected throw");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == input_error::non_finite);
    CHECK(e.element() == 1);
  }
  CHECK_THROWS_AS(alpha_expansion(U, {{0, 3, 1.0}}), invalid_input);
  CHECK_THROWS_AS(alpha_expansion(U, {{0, 1, -1.0}}), invalid_input);
  CHECK_THROWS_AS(alpha_expansion(U, {}, {0, 1}), invalid_input);
  CHECK_THROWS_AS(alpha_expansion(U, {}, {0, 1, 2}), invalid_input);
}
