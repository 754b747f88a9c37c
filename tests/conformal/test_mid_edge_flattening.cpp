// SPDX-License-Identifier: MIT
#include <optional>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "../blended/blended_fixtures.hpp"
#include "shapestruct/conformal/mid_edge_flattening.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {
void check_flattening(const triangle_mesh<double>& m, const mid_edge_flattening<double>& fl) {
  CHECK(fl.info() == status::ok);
  CHECK(fl.count_foldovers() == 0);
  // Vertices and face points map back to themselves through point location. The mid-edge map is
  // non-conforming: near the cut the corner triangles of a vertex may overlap a neighbour's, so a few points come
  // back elsewhere, but never farther than one ring.
  const double ring = 2 * mean_edge_length<double>(m.V, m.F) * 3;
  index_t exact = 0, total = 0;
  for (index_t v = 0; v < m.V.rows(); ++v) {
    const auto p = fl.locate(fl.coordinate(v));
    REQUIRE(p.valid());
    const double err = (p.position(m.V, m.F) - m.V.row(v).transpose()).norm();
    CHECK(err < ring);
    exact += err < 1e-9;
    ++total;
  }
  for (index_t f = 0; f < m.F.rows(); ++f) {
    if (f == fl.cut_face()) continue;
    surface_point<double> sp;
    sp.face = f;
    sp.bary << 0.2, 0.3, 0.5;
    const auto back = fl.locate(fl.coordinate(sp));
    const double err = (back.position(m.V, m.F) - sp.position(m.V, m.F)).norm();
    CHECK(err < ring);
    exact += err < 1e-9;
    ++total;
  }
  CHECK(double(exact) >= 0.97 * double(total));
  for (index_t v = 0; v < fl.vertex_density().size(); ++v) {
    CHECK(std::isfinite(fl.vertex_density()[v]));
    CHECK(fl.vertex_density()[v] > 0);
  }
}
}  // namespace

TEST_CASE("mid_edge_flattening maps closed genus-0 meshes without fold-overs (triangle_mesh)") {
  for (const auto& m : {make_icosphere<double>(3), test::armed_sphere(3), test::octahedron<double>()}) {
    const mid_edge_flattening<double> fl(m.V, m.F);
    check_flattening(m, fl);
  }
}

TEST_CASE("mid_edge_flattening on a second mesh model (legacy_mesh)") {
  const auto m = test::armed_sphere(3);
  const auto legacy = test::to_legacy(m);
  const auto fl = flatten_mid_edge(legacy);
  const auto back = to_triangle_mesh<double>(legacy);
  check_flattening(back, fl);
}

TEST_CASE("mid_edge_flattening is conformal: a sphere's Möbius-invariant cross-ratios are preserved") {
  // On the round sphere the flattening is (close to) a Möbius image of stereographic projection, so the
  // cross-ratio of four vertices equals the cross-ratio of their stereographic images.
  const auto m = make_icosphere<double>(4);
  const mid_edge_flattening<double> fl(m.V, m.F);
  auto stereo = [&](index_t v) {
    const Eigen::Vector3d p = m.V.row(v).transpose().normalized();
    return std::complex<double>(p.x(), p.y()) / (1.0 - p.z());
  };
  auto cross_ratio = [](std::complex<double> a, std::complex<double> b, std::complex<double> c, std::complex<double> d) {
    return (a - c) * (b - d) / ((a - d) * (b - c));
  };
  // vertices far from the cut and from the pole of the projection
  const index_t ids[4] = {3, 17, 101, 250};
  const auto cr_plane = cross_ratio(fl.coordinate(ids[0]), fl.coordinate(ids[1]), fl.coordinate(ids[2]), fl.coordinate(ids[3]));
  const auto cr_sphere = cross_ratio(stereo(ids[0]), stereo(ids[1]), stereo(ids[2]), stereo(ids[3]));
  // A Möbius map preserves the cross-ratio; the flattening may also be orientation-reversing (conjugate).
  const double err = std::min(std::abs(cr_plane - cr_sphere), std::abs(cr_plane - std::conj(cr_sphere)));
  CHECK(err < 0.05 * std::abs(cr_sphere));
}

TEST_CASE("mid_edge_flattening rejects invalid input, one test per reason") {
  using test::armed_sphere;
  auto reason = [](auto&& fn) -> std::optional<input_error> {
    try {
      fn();
    } catch (const invalid_input& e) {
      return e.reason();
    }
    return std::nullopt;
  };
  SUBCASE("empty") {
    triangle_mesh<double> m;
    m.V.resize(0, 3);
    m.F.resize(0, 3);
    CHECK(reason([&] { mid_edge_flattening<double>(m.V, m.F); }) == input_error::empty);
  }
  SUBCASE("non_finite") {
    const auto m = test::with_nan_vertex<double>();
    CHECK(reason([&] { mid_edge_flattening<double>(m.V, m.F); }) == input_error::non_finite);
  }
  SUBCASE("bad_face") {
    const auto m = test::with_bad_index<double>();
    CHECK(reason([&] { mid_edge_flattening<double>(m.V, m.F); }) == input_error::bad_face);
  }
  SUBCASE("unsupported_topology: boundary") {
    const auto m = make_disk<double>(3, 8);
    try {
      mid_edge_flattening<double> fl(m.V, m.F);
      FAIL("no exception");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::unsupported_topology);
      CHECK(e.element() >= 0);
      CHECK(std::string(e.what()).find("close_small_holes") != std::string::npos);
    }
  }
  SUBCASE("unsupported_topology: genus") {
    const auto m = make_torus<double>(1.0, 0.3, 12, 8);
    CHECK(reason([&] { mid_edge_flattening<double>(m.V, m.F); }) == input_error::unsupported_topology);
  }
  SUBCASE("unsupported_topology: several components") {
    const auto m = test::two_copies(make_icosphere<double>(1));
    try {
      mid_edge_flattening<double> fl(m.V, m.F);
      FAIL("no exception");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::unsupported_topology);
      CHECK(std::string(e.what()).find("keep_largest_component") != std::string::npos);
    }
  }
  SUBCASE("non_manifold edge") {
    const auto m = test::fin<double>();
    CHECK(reason([&] { mid_edge_flattening<double>(m.V, m.F); }) == input_error::non_manifold);
  }
  SUBCASE("non_manifold vertex when pinches are refused") {
    const auto ico = make_icosphere<double>(2);
    index_t far = 0;
    (ico.V.rowwise() - ico.V.row(0)).rowwise().norm().maxCoeff(&far);
    const auto m = test::pinched_sphere(ico, 0, far);
    mid_edge_flattening_options o;
    o.accept_pinched_vertices = false;
    try {
      mid_edge_flattening<double> fl(m.V, m.F, o);
      FAIL("no exception");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::non_manifold);
      CHECK(e.element() == 0);
    }
    // accepted as a pinch (the default), the surface is still a sphere for the mid-edge construction
    const mid_edge_flattening<double> fl(m.V, m.F);
    CHECK(fl.info() == status::ok);
  }
  SUBCASE("bad_parameter") {
    const auto m = make_icosphere<double>(1);
    mid_edge_flattening_options o;
    o.cut_face = m.F.rows();
    CHECK(reason([&] { mid_edge_flattening<double>(m.V, m.F, o); }) == input_error::bad_parameter);
  }
}

TEST_CASE("mid_edge_flattening survives degenerate faces without NaN") {
  auto m = make_icosphere<double>(2);
  // Collapse one face to a sliver: move a vertex onto the midpoint of its opposite edge in one face.
  const index_t f = 10;
  m.V.row(m.F(f, 0)) = 0.5 * (m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2)));
  const mid_edge_flattening<double> fl(m.V, m.F);
  CHECK(fl.info() == status::ok);
  for (const auto& z : fl.vertex_coordinates()) {
    CHECK(std::isfinite(z.real()));
    CHECK(std::isfinite(z.imag()));
  }
  for (index_t v = 0; v < fl.vertex_density().size(); ++v) CHECK(std::isfinite(fl.vertex_density()[v]));
}
