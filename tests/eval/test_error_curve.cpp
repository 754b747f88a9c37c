// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "shapestruct/eval/error_curve.hpp"

using namespace shapestruct;

TEST_CASE("error_curve counts errors within each threshold, inclusive") {
  const auto c = error_curve({0.3, 0.0, 0.1, 0.2}, {0.0, 0.05, 0.1, 0.25, 1.0});
  REQUIRE(c.size() == 5);
  CHECK(c[0] == doctest::Approx(0.25));  // only the exact 0
  CHECK(c[1] == doctest::Approx(0.25));
  CHECK(c[2] == doctest::Approx(0.5));   // 0.1 is within 0.1
  CHECK(c[3] == doctest::Approx(0.75));
  CHECK(c[4] == doctest::Approx(1.0));
}

TEST_CASE("error_curve is non-decreasing in D and matches a direct count on random data") {
  std::mt19937_64 rng(3);
  std::exponential_distribution<double> ex(20);
  std::vector<double> e(500);
  for (auto& x : e) x = ex(rng);
  std::vector<double> D;
  for (int i = 0; i <= 50; ++i) D.push_back(0.005 * i);
  const auto c = error_curve(e, D);
  for (std::size_t i = 0; i < D.size(); ++i) {
    double n = 0;
    for (const double x : e) n += x <= D[i] ? 1 : 0;
    CHECK(c[i] == doctest::Approx(n / 500.0));
    if (i > 0) CHECK(c[i] >= c[i - 1]);
  }
}

TEST_CASE("error_curve rejects empty input and bad values, naming the index") {
  CHECK_THROWS_AS((void)error_curve({}, {0.1}), invalid_input);
  try {
    (void)error_curve({0.1, std::numeric_limits<double>::quiet_NaN()}, {0.1});
    FAIL("no throw");
  } catch (const invalid_input& e) {
    CHECK(e.element() == 1);
  }
  CHECK_THROWS_AS((void)error_curve({0.1}, {-1.0}), invalid_input);
}
