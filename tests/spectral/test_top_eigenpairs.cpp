// SPDX-License-Identifier: MIT
#include <random>

#include <doctest/doctest.h>

#include "shapestruct/spectral/top_eigenpairs.hpp"

using namespace shapestruct;

namespace {
Eigen::SparseMatrix<double> random_sparse_symmetric(index_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Triplet<double, index_t>> t;
  for (index_t i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2 + u(rng));
    for (int k = 0; k < 3; ++k) {
      const index_t j = static_cast<index_t>(rng() % static_cast<std::uint64_t>(n));
      if (j == i) continue;
      const double v = u(rng);
      t.emplace_back(i, j, v);
      t.emplace_back(j, i, v);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}
}  // namespace

TEST_CASE("top_eigenpairs: Spectra and the dense path agree with the full eigen-decomposition") {
  for (index_t n : {50, 900}) {
    const auto A = random_sparse_symmetric(n, 3);
    const auto r = top_eigenpairs(A, 4);
    REQUIRE(r.info == status::ok);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(A)};
    for (int k = 0; k < 4; ++k) {
      CHECK(r.values[k] == doctest::Approx(es.eigenvalues()[n - 1 - k]).epsilon(1e-8));
      const Eigen::VectorXd v = r.vectors.col(k);
      CHECK((Eigen::MatrixXd(A) * v - r.values[k] * v).norm() < 1e-6);
    }
    for (int k = 1; k < 4; ++k) CHECK(r.values[k - 1] >= r.values[k]);
  }
}

TEST_CASE("top_eigenpairs rejects bad input") {
  Eigen::SparseMatrix<double> rect(3, 4);
  CHECK_THROWS_AS((void)top_eigenpairs(rect, 1), invalid_input);
  Eigen::SparseMatrix<double> empty(0, 0);
  CHECK_THROWS_AS((void)top_eigenpairs(empty, 1), invalid_input);
  const auto A = random_sparse_symmetric(10, 1);
  CHECK_THROWS_AS((void)top_eigenpairs(A, 0), invalid_input);
}
