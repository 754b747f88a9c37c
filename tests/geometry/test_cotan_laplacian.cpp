// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/geometry/cotan_laplacian.hpp"
#include "shapestruct/geometry/mass_matrix.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {
template <class S>
double asymmetry(const Eigen::SparseMatrix<S>& L) {
  const Eigen::SparseMatrix<S> T = L.transpose();
  return double((L - T).cwiseAbs().sum());
}
}  // namespace

TEST_CASE("cotan Laplacian matches a hand computation on two right triangles") {
  // Vertices 0 (0,0), 1 (1,0), 2 (0,1), 3 (1,1); faces (0,1,3), (0,3,2), split along the diagonal 0-3.
  // Right angles at 1 and 2 (cot 0), 45 degrees at 0 and 3 (cot 1). The four sides are each opposite a
  // 45-degree corner: w = 1/2. The diagonal is opposite the two right angles: w = 0. 1-2 is not an edge.
  const auto m = test::grid_mesh(1, 1);
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotan_laplacian(m.V, m.F));
  Eigen::Matrix4d expected;
  expected << 1, -0.5, -0.5, 0,  //
      -0.5, 1, 0, -0.5,          //
      -0.5, 0, 1, -0.5,          //
      0, -0.5, -0.5, 1;
  CHECK((L - expected).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("cotan Laplacian of an equilateral triangle: every weight cot(60)/2") {
  triangle_mesh<double> m;
  m.V.resize(3, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0;
  m.F.resize(1, 3);
  m.F << 0, 1, 2;
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotan_laplacian(m.V, m.F));
  const double w = 0.5 / std::sqrt(3.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) CHECK(L(i, j) == doctest::Approx(i == j ? 2 * w : -w));
}

TEST_CASE("cotan Laplacian is symmetric, PSD and annihilates constants, on both mesh models") {
  const auto ico = test::jittered_icosphere(3, 7);
  const auto legacy = test::to_legacy(ico);
  const auto L = cotan_laplacian(ico);
  const auto Lf = cotan_laplacian(legacy);
  static_assert(std::is_same_v<decltype(Lf), const Eigen::SparseMatrix<float>>);
  CHECK(asymmetry(L) == 0.0);
  CHECK(asymmetry(Lf) == 0.0);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(ico.V.rows());
  CHECK((L * ones).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((Lf * ones.cast<float>()).cwiseAbs().maxCoeff() < 1e-4f);
  CHECK((Eigen::MatrixXd(L) - Eigen::MatrixXf(Lf).cast<double>()).cwiseAbs().maxCoeff() < 1e-3);
  // The coordinate functions are linear on each triangle, and on a flat triangle sum_c |grad x_c|^2 = 2 (the
  // trace of the tangent-plane projector), so the exact Dirichlet energy tr(V^T L V) is twice the total area.
  const Eigen::MatrixXd LV = L * ico.V;
  double area = 0;
  for (index_t f = 0; f < ico.F.rows(); ++f)
    area += 0.5 * (ico.V.row(ico.F(f, 1)) - ico.V.row(ico.F(f, 0)))
                      .cross(ico.V.row(ico.F(f, 2)) - ico.V.row(ico.F(f, 0)))
                      .norm();
  CHECK((ico.V.transpose() * LV).trace() == doctest::Approx(2 * area).epsilon(1e-10));
  const Eigen::MatrixXd Ld(L);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Ld);
  CHECK(es.eigenvalues().minCoeff() > -1e-10);
  CHECK(std::abs(es.eigenvalues()[0]) < 1e-10);
  CHECK(es.eigenvalues()[1] > 1e-3);  // connected: one-dimensional null space
}

TEST_CASE("cotan Laplacian on degenerate faces is finite and bounded by the clamp") {
  const auto m = test::degenerate_grid();
  const auto L = cotan_laplacian(m.V, m.F);
  const Eigen::MatrixXd D(L);
  CHECK(D.allFinite());
  CHECK(D.cwiseAbs().maxCoeff() <= 6 * 1e5);  // at most 6 clamped half-cotangents per entry
  CHECK(D.cwiseAbs().maxCoeff() > 1e4);       // the clamp was actually hit
  CHECK((L * Eigen::VectorXd::Ones(m.V.rows())).cwiseAbs().maxCoeff() < 1e-9);
  const auto L2 = cotan_laplacian(m.V, m.F, {.max_abs_cot = 10});
  CHECK(Eigen::MatrixXd(L2).cwiseAbs().maxCoeff() <= 6 * 10.0);
}

TEST_CASE("cotan Laplacian: one test per invalid_input reason") {
  const auto nan = test::with_nan_vertex();
  const auto bad = test::with_bad_index();
  triangle_mesh<double> empty;
  test::expect_invalid([&] { (void)cotan_laplacian(empty); }, input_error::empty, no_index);
  test::expect_invalid([&] { (void)cotan_laplacian(nan.V, nan.F); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)cotan_laplacian(test::to_legacy(bad)); }, input_error::bad_face, 3);
  const auto oct = test::octahedron();
  test::expect_invalid([&] { (void)cotan_laplacian(oct, {.max_abs_cot = 0}); }, input_error::bad_parameter);
  test::expect_invalid([&] { (void)cotan_laplacian(oct, {.max_abs_cot = std::nan("")}); }, input_error::bad_parameter);
}
