// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

TEST_CASE("face and vertex areas of a right triangle and a unit square") {
  auto m = test::grid_mesh(1, 1, 2.0);  // two right triangles with legs 2: area 2 each
  const auto A = face_areas(m.V, m.F);
  REQUIRE(A.size() == 2);
  CHECK(A[0] == doctest::Approx(2.0));
  CHECK(A[1] == doctest::Approx(2.0));
  const auto va = vertex_areas(m.V, m.F);
  // vertices 0 and 3 are on the diagonal (two faces), 1 and 2 on one face each
  CHECK(va[0] == doctest::Approx(4.0 / 3));
  CHECK(va[3] == doctest::Approx(4.0 / 3));
  CHECK(va[1] == doctest::Approx(2.0 / 3));
  CHECK(total_area(m.V, m.F) == doctest::Approx(4.0));
  CHECK(bounding_box_diagonal(m.V) == doctest::Approx(std::sqrt(8.0)));
  CHECK(mean_edge_length(m.V, m.F) == doctest::Approx((4 * 2.0 + 2 * std::sqrt(8.0)) / 6));
}

TEST_CASE("areas sum to the total and approach 4 pi on the icosphere, on both mesh models") {
  const auto ico = make_icosphere(4);
  const auto legacy = test::to_legacy(ico);
  const auto fa = face_areas(ico);
  const auto va = vertex_areas(ico);
  const auto fl = face_areas(legacy);
  const auto vl = vertex_areas(legacy);
  CHECK(fa.sum() == doctest::Approx(va.sum()).epsilon(1e-12));
  CHECK(fl.sum() == doctest::Approx(vl.sum()).epsilon(1e-5));
  CHECK(total_area(ico) == doctest::Approx(4 * std::numbers::pi).epsilon(0.01));
  CHECK(double(total_area(legacy)) == doctest::Approx(total_area(ico)).epsilon(1e-5));
  CHECK(fa.minCoeff() > 0);
  CHECK(bounding_box_diagonal(ico) == doctest::Approx(std::sqrt(12.0)).epsilon(1e-9));
  CHECK(double(bounding_box_diagonal(legacy)) == doctest::Approx(std::sqrt(12.0)).epsilon(1e-6));
  CHECK(double(mean_edge_length(legacy)) == doctest::Approx(mean_edge_length(ico)).epsilon(1e-5));
}

TEST_CASE("normals point outward on the sphere and are unit length, on both mesh models") {
  const auto ico = make_icosphere(3);
  const auto legacy = test::to_legacy(ico);
  const auto fn = face_normals(ico);
  const auto vn = vertex_normals(ico);
  const auto vnl = vertex_normals(legacy);
  const auto fnl = face_normals(legacy);
  for (index_t f = 0; f < ico.F.rows(); ++f) {
    const Eigen::RowVector3d c = (ico.V.row(ico.F(f, 0)) + ico.V.row(ico.F(f, 1)) + ico.V.row(ico.F(f, 2))) / 3;
    CHECK(fn.row(f).dot(c.normalized()) > 0.99);
    CHECK(fn.row(f).norm() == doctest::Approx(1.0));
    CHECK(double(fnl.row(f).cast<double>().dot(fn.row(f))) > 0.9999);
  }
  for (index_t v = 0; v < ico.V.rows(); ++v) {
    CHECK(vn.row(v).dot(ico.V.row(v)) > 0.999);  // the sphere's normal is the position
    CHECK(double(vnl.row(v).cast<double>().dot(vn.row(v))) > 0.9999);
  }
}

TEST_CASE("degenerate faces give zero area and zero normal, never NaN") {
  const auto m = test::degenerate_grid();
  const auto A = face_areas(m.V, m.F);
  const auto N = face_normals(m.V, m.F);
  const auto VN = vertex_normals(m.V, m.F);
  CHECK(A.allFinite());
  CHECK(N.allFinite());
  CHECK(VN.allFinite());
  CHECK(A.minCoeff() == 0.0);
  bool zero_normal = false;
  for (index_t f = 0; f < N.rows(); ++f) zero_normal |= N.row(f).isZero(0);
  CHECK(zero_normal);
  CHECK(total_area(m.V, m.F) == doctest::Approx(16.0));  // moving vertices inside the plane keeps the area
}

TEST_CASE("mesh measures: one test per invalid_input reason") {
  const auto nan = test::with_nan_vertex();
  const auto bad = test::with_bad_index();
  triangle_mesh<double> empty;
  test::expect_invalid([&] { (void)face_areas(empty.V, empty.F); }, input_error::empty, no_index);
  test::expect_invalid([&] { (void)vertex_areas(nan); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)face_normals(bad.V, bad.F); }, input_error::bad_face, 3);
  test::expect_invalid([&] { (void)vertex_normals(bad); }, input_error::bad_face, 3);
  test::expect_invalid([&] { (void)total_area(nan.V, nan.F); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)mean_edge_length(nan.V, nan.F); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)bounding_box_diagonal(nan.V); }, input_error::non_finite, 2);
  test::expect_invalid([&] { (void)bounding_box_diagonal(empty.V); }, input_error::empty, no_index);
  auto rep = test::octahedron();
  rep.F(1, 2) = rep.F(1, 0);
  test::expect_invalid([&] { (void)face_areas(rep); }, input_error::bad_face, 1);
}
