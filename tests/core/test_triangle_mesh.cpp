// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include "shapestruct/adapters/eigen_vf.hpp"
#include "shapestruct/adapters/std_arrays.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/validate.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

TEST_CASE("to_triangle_mesh gathers every model identically") {
  const auto ico = make_icosphere(2);
  const auto legacy = test::to_legacy(ico);
  Eigen::MatrixXd V = ico.V;
  Eigen::MatrixXi F = ico.F.cast<int>();
  const eigen_mesh_view view(V, F);
  std::vector<std::array<double, 3>> pos;
  std::vector<std::array<int, 3>> tri;
  for (index_t i = 0; i < ico.V.rows(); ++i) pos.push_back({ico.V(i, 0), ico.V(i, 1), ico.V(i, 2)});
  for (index_t f = 0; f < ico.F.rows(); ++f) tri.push_back({int(ico.F(f, 0)), int(ico.F(f, 1)), int(ico.F(f, 2))});
  const std_array_mesh_view soup(pos, tri);

  const auto a = to_triangle_mesh(legacy);
  const auto b = to_triangle_mesh(view);
  const auto c = to_triangle_mesh(soup);
  CHECK(a.F == ico.F);
  CHECK(b.F == ico.F);
  CHECK(c.F == ico.F);
  CHECK((a.V - ico.V).cwiseAbs().maxCoeff() < 1e-6);
  CHECK(b.V == ico.V);
  CHECK(c.V == ico.V);
  CHECK(ico.V.rows() == 162);
  CHECK(ico.F.rows() == 320);
}

TEST_CASE("validate_mesh rejects each kind of bad input with the offending element") {
  SUBCASE("empty") {
    triangle_mesh<double> m;
    try {
      validate_mesh(m.V, m.F, "test");
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::empty);
    }
  }
  SUBCASE("non-finite vertex") {
    const auto m = test::with_nan_vertex();
    try {
      validate_mesh(m.V, m.F, "test");
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::non_finite);
      CHECK(e.element() == 2);
    }
  }
  SUBCASE("index out of range") {
    const auto m = test::with_bad_index();
    try {
      validate_mesh(m.V, m.F, "test");
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::bad_face);
      CHECK(e.element() == 3);
    }
  }
  SUBCASE("repeated vertex") {
    auto m = test::octahedron();
    m.F(5, 2) = m.F(5, 0);
    try {
      validate_mesh(m.V, m.F, "test");
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::bad_face);
      CHECK(e.element() == 5);
    }
  }
  SUBCASE("valid meshes pass") {
    for (const auto& m : test::closed_genus0_meshes()) CHECK_NOTHROW(validate_mesh(m.V, m.F, "test"));
  }
}
