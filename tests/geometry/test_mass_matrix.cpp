// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/geometry/mass_matrix.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

TEST_CASE("mass matrices are diagonal, non-negative and sum to the area, on both mesh models") {
  const auto ico = test::jittered_icosphere(3, 11);
  const auto legacy = test::to_legacy(ico);
  const double area = total_area(ico);
  for (const auto type : {mass_type::barycentric, mass_type::voronoi}) {
    const auto M = mass_matrix(ico, type);
    const auto Mf = mass_matrix(legacy, type);
    CHECK(M.nonZeros() == ico.V.rows());
    CHECK(Eigen::MatrixXd(M).isDiagonal());
    CHECK(M.diagonal().minCoeff() > 0);
    CHECK(M.diagonal().sum() == doctest::Approx(area).epsilon(1e-10));
    CHECK(double(Mf.diagonal().sum()) == doctest::Approx(area).epsilon(1e-5));
  }
  CHECK((mass_matrix(ico).diagonal() - vertex_areas(ico)).cwiseAbs().maxCoeff() < 1e-14);
}

TEST_CASE("Voronoi mass: circumcentric cells on an acute triangle, obtuse rule otherwise") {
  // Right isosceles triangle (legs 1): circumcentre on the hypotenuse midpoint. The right-angle corner gets
  // half the area (it is not obtuse, so the cot formula applies): (1 * cot45 + 1 * cot45) / 8 = 1/4.
  triangle_mesh<double> m;
  m.V.resize(3, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  m.F.resize(1, 3);
  m.F << 0, 1, 2;
  const Eigen::VectorXd d = mass_matrix(m.V, m.F, mass_type::voronoi).diagonal();
  CHECK(d[0] == doctest::Approx(0.25));
  CHECK(d[1] == doctest::Approx(0.125));
  CHECK(d[2] == doctest::Approx(0.125));
  // Obtuse at vertex 0: half of the area to it, a quarter to each other corner.
  m.V << 0, 0, 0, 1, 0.1, 0, -1, 0.1, 0;
  const double A = 0.1;
  const Eigen::VectorXd o = mass_matrix(m.V, m.F, mass_type::voronoi).diagonal();
  CHECK(o[0] == doctest::Approx(A / 2));
  CHECK(o[1] == doctest::Approx(A / 4));
  CHECK(o[2] == doctest::Approx(A / 4));
}

TEST_CASE("mass matrix on degenerate faces is finite") {
  const auto m = test::degenerate_grid();
  for (const auto type : {mass_type::barycentric, mass_type::voronoi}) {
    const Eigen::VectorXd d = mass_matrix(m.V, m.F, type).diagonal();
    CHECK(d.allFinite());
    CHECK(d.minCoeff() >= 0);
    CHECK(d.sum() == doctest::Approx(16.0));
  }
}

TEST_CASE("mass matrix: one test per invalid_input reason") {
  triangle_mesh<double> empty;
  const auto nan = test::with_nan_vertex();
  const auto bad = test::with_bad_index();
  test::expect_invalid([&] { (void)mass_matrix(empty.V, empty.F); }, input_error::empty, no_index);
  test::expect_invalid([&] { (void)mass_matrix(nan, mass_type::voronoi); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)mass_matrix(test::to_legacy(bad)); }, input_error::bad_face, 3);
}
