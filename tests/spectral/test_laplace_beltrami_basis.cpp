// SPDX-License-Identifier: MIT
#include <cmath>

#include <Eigen/SVD>
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

namespace {
laplace_beltrami_options galerkin(index_t coarse, index_t steps) {
  laplace_beltrami_options o;
  o.solver = laplace_beltrami_solver::galerkin;
  o.coarse_functions = coarse;
  o.subspace_iterations = steps;
  return o;
}

// Cosine of the largest principal angle between the spans of two M-orthonormal bases.
double smallest_cosine(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y, const Eigen::VectorXd& mass) {
  const Eigen::MatrixXd P = X.transpose() * mass.asDiagonal() * Y;
  return Eigen::JacobiSVD<Eigen::MatrixXd>(P).singularValues().minCoeff();
}
}  // namespace

TEST_CASE("laplace_beltrami_basis, galerkin: the sphere's spectrum and the same space as Lanczos") {
  const auto s = make_icosphere<double>(4);  // 2,562 vertices; l = 0..3 fill exactly 16 functions
  const auto exact = compute_laplace_beltrami_basis<double>(s.V, s.F, 16);
  for (const index_t steps : {1, 0}) {
    CAPTURE(steps);
    const auto b = compute_laplace_beltrami_basis<double>(s.V, s.F, 16, galerkin(300, steps));
    REQUIRE(b.info == status::ok);
    REQUIRE(b.size() == 16);
    CHECK(std::abs(b.values[0]) < 1e-8);
    // One refinement step: the values of Lanczos on every vertex. The coarse space alone is stiffer: 300 bumps on
    // 2,562 vertices are only about 9 vertices apart, so their piecewise-linear shape is coarse.
    const double tolerance = steps > 0 ? 5e-4 : 0.1;
    for (index_t j = 1; j < 16; ++j) CHECK(b.values[j] == doctest::Approx(exact.values[j]).epsilon(tolerance));
    for (index_t j = 1; j < 16; ++j) CHECK(b.values[j] >= b.values[j - 1]);
    // Rayleigh-Ritz values on a subspace bound the exact ones from above (min-max principle); without the
    // refinement step they are visibly above, which shows the coarse space, not a fallback, was used.
    for (index_t j = 1; j < 16; ++j) CHECK(b.values[j] >= exact.values[j] * (1 - 1e-7));  // Lanczos converged to 1e-8
    if (steps == 0) CHECK(b.values[15] > 1.01 * exact.values[15]);
    const Eigen::MatrixXd G = b.vectors.transpose() * b.mass.asDiagonal() * b.vectors;
    CHECK((G - Eigen::MatrixXd::Identity(16, 16)).norm() < 1e-8);
    CHECK(b.vectors.col(0).maxCoeff() - b.vectors.col(0).minCoeff() < 1e-8);
    CHECK(smallest_cosine(exact.vectors, b.vectors, exact.mass) > (steps > 0 ? 0.9999 : 0.99));
  }
}

TEST_CASE("laplace_beltrami_basis, galerkin: two components give a two-dimensional null space") {
  const auto s = make_icosphere<double>(4);
  Eigen::MatrixX3d V(2 * s.V.rows(), 3);
  V << s.V, s.V.rowwise() + Eigen::RowVector3d(3, 0, 0);
  face_matrix F(2 * s.F.rows(), 3);
  F << s.F, s.F.array() + s.V.rows();
  const auto b = compute_laplace_beltrami_basis<double>(V, F, 8, galerkin(400, 1));
  REQUIRE(b.info == status::ok);
  CHECK(std::abs(b.values[0]) < 1e-8);
  CHECK(std::abs(b.values[1]) < 1e-8);
  for (index_t j = 2; j < 8; ++j) CHECK(b.values[j] == doctest::Approx(2.0).epsilon(0.01));
}

TEST_CASE("laplace_beltrami_basis, galerkin: meshes too small for the coarse space are solved by Lanczos") {
  const auto s = make_icosphere<double>(3);  // 642 vertices, fewer than twice the 600 default bumps
  const auto exact = compute_laplace_beltrami_basis<double>(s.V, s.F, 9);
  laplace_beltrami_options o;
  o.solver = laplace_beltrami_solver::galerkin;
  const auto b = compute_laplace_beltrami_basis<double>(s.V, s.F, 9, o);
  REQUIRE(b.info == status::ok);
  CHECK((b.values - exact.values).norm() < 1e-10);
  // Too few bumps for the pairs asked (about 1.2 k + 5, with room for the Krylov space) also falls back.
  const auto c = compute_laplace_beltrami_basis<double>(s.V, s.F, 9, galerkin(20, 1));
  REQUIRE(c.info == status::ok);
  CHECK((c.values - exact.values).norm() < 1e-10);
}

TEST_CASE("laplace_beltrami_basis, galerkin: options out of range are a bad_parameter") {
  const auto s = make_icosphere<double>(4);
  auto o = galerkin(300, 1);
  o.coarse_support = 0;
  CHECK_THROWS_AS((void)compute_laplace_beltrami_basis<double>(s.V, s.F, 8, o), invalid_input);
  o = galerkin(300, -1);
  CHECK_THROWS_AS((void)compute_laplace_beltrami_basis<double>(s.V, s.F, 8, o), invalid_input);
  o = galerkin(0, 1);
  CHECK_THROWS_AS((void)compute_laplace_beltrami_basis<double>(s.V, s.F, 8, o), invalid_input);
  o = galerkin(300, 1);
  o.oversampling = 0.5;
  CHECK_THROWS_AS((void)compute_laplace_beltrami_basis<double>(s.V, s.F, 8, o), invalid_input);
}
