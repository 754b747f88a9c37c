// SPDX-License-Identifier: MIT
#include <cmath>

#include <doctest/doctest.h>

#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/spectral/laplace_beltrami_basis.hpp"

using namespace shapestruct;

TEST_CASE("laplace_beltrami_basis: the unit sphere's spectrum is l(l+1) with multiplicity 2l+1") {
  // 2,562 vertices: the Lanczos (shift-and-invert) path, not the dense one.
  const auto s = make_icosphere<double>(4);
  const auto b = compute_laplace_beltrami_basis<double>(s.V, s.F, 16);
  REQUIRE(b.info == status::ok);
  REQUIRE(b.size() == 16);
  CHECK(std::abs(b.values[0]) < 1e-8);
  // l = 1 (3 values of 2), l = 2 (5 of 6), l = 3 (7 of 12): discretisation error below 1 %.
  for (index_t j = 1; j < 16; ++j) {
    const double l = j < 4 ? 1 : j < 9 ? 2 : 3;
    CHECK(b.values[j] == doctest::Approx(l * (l + 1)).epsilon(0.01));
  }
  for (index_t j = 1; j < 16; ++j) CHECK(b.values[j] >= b.values[j - 1]);
  // M-orthonormal, and the first function is constant.
  const Eigen::MatrixXd G = b.vectors.transpose() * b.mass.asDiagonal() * b.vectors;
  CHECK((G - Eigen::MatrixXd::Identity(16, 16)).norm() < 1e-8);
  CHECK(b.vectors.col(0).maxCoeff() - b.vectors.col(0).minCoeff() < 1e-8);
  CHECK(b.mass.sum() == doctest::Approx(4 * M_PI).epsilon(0.01));
}

TEST_CASE("laplace_beltrami_basis: the dense path below 400 vertices agrees with the sphere's spectrum") {
  const auto s = make_icosphere<double>(2);  // 162 vertices
  const auto b = compute_laplace_beltrami_basis<double>(s.V, s.F, 4);
  REQUIRE(b.info == status::ok);
  for (index_t j = 1; j < 4; ++j) CHECK(b.values[j] == doctest::Approx(2.0).epsilon(0.05));
}

TEST_CASE("laplace_beltrami_basis: k out of range is a bad_parameter naming the vertex count") {
  const auto s = make_icosphere<double>(1);
  try {
    (void)compute_laplace_beltrami_basis<double>(s.V, s.F, s.V.rows());
    FAIL("expected invalid_input");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == input_error::bad_parameter);
    CHECK(std::string(e.what()).find("42 vertices") != std::string::npos);
  }
  CHECK_THROWS_AS((void)compute_laplace_beltrami_basis<double>(s.V, s.F, 0), invalid_input);
}
