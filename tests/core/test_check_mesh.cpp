// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <array>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>

#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/geometry/connected_components.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

/// Runs `check` on the report of both mesh models (triangle_mesh<double> and the float legacy_mesh).
template <class Fn>
void on_both_models(const triangle_mesh<double>& m, Fn&& check) {
  {
    INFO("model: triangle_mesh<double>");
    check(check_mesh(m));
  }
  {
    INFO("model: legacy_mesh (float, int indices)");
    check(check_mesh(test::to_legacy(m)));
  }
}

/// Tetrahedron plus a face whose third corner is the midpoint of its first two (zero area) and a face that
/// repeats a vertex: faces 4 and 5 are degenerate.
triangle_mesh<double> with_degenerate_faces() {
  auto m = test::tetrahedron();
  m.V.conservativeResize(5, 3);
  m.V.row(4) = 0.5 * (m.V.row(0) + m.V.row(1));
  m.F.conservativeResize(6, 3);
  m.F.row(4) << 0, 1, 4;
  m.F.row(5) << 2, 2, 3;
  return m;
}

/// Octahedron plus vertex 6 at exactly the position of vertex 1, used by no face.
triangle_mesh<double> with_duplicate_vertex() {
  auto m = test::octahedron();
  m.V.conservativeResize(7, 3);
  m.V.row(6) = m.V.row(1);
  return m;
}

/// Octahedron with face 0 listed clockwise.
triangle_mesh<double> with_flipped_face() {
  auto m = test::octahedron();
  std::swap(m.F(0, 1), m.F(0, 2));
  return m;
}

/// A Moebius strip: a band of n quads whose ends are glued with a half twist (non-orientable, 1 boundary loop).
triangle_mesh<double> moebius_strip(int n) {
  triangle_mesh<double> m;
  m.V.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const double u = 2.0 * 3.141592653589793 * i / n;
    for (int s = 0; s < 2; ++s) {
      const double t = s == 0 ? -0.3 : 0.3;
      m.V.row(2 * i + s) << (1 + t * std::cos(u / 2)) * std::cos(u), (1 + t * std::cos(u / 2)) * std::sin(u),
          t * std::sin(u / 2);
    }
  }
  m.F.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const index_t a = 2 * i, b = 2 * i + 1;
    // the last quad connects to the first one with sides swapped: the half twist
    const index_t c = (i + 1 < n) ? 2 * (i + 1) : 1, d = (i + 1 < n) ? 2 * (i + 1) + 1 : 0;
    m.F.row(2 * i) << a, c, b;
    m.F.row(2 * i + 1) << b, c, d;
  }
  return m;
}

}  // namespace

TEST_CASE("check_mesh: closed genus-0 fixtures") {
  struct expect {
    triangle_mesh<double> mesh;
    index_t v, f, e;
  };
  const expect cases[] = {
      {test::tetrahedron(), 4, 4, 6}, {test::octahedron(), 6, 8, 12}, {make_icosphere(2), 162, 320, 480}};
  for (const auto& c : cases) {
    on_both_models(c.mesh, [&](const mesh_report& r) {
      CHECK(r.num_vertices == c.v);
      CHECK(r.num_faces == c.f);
      CHECK(r.num_edges == c.e);
      CHECK(r.euler_characteristic == 2);
      CHECK(r.genus == 0);
      CHECK(r.num_components == 1);
      CHECK(r.num_boundary_edges == 0);
      CHECK(r.num_boundary_loops == 0);
      CHECK(r.num_non_manifold_edges == 0);
      CHECK(r.num_non_manifold_vertices == 0);
      CHECK(r.num_inconsistent_edges == 0);
      CHECK(r.num_degenerate_faces == 0);
      CHECK(r.num_duplicate_vertices == 0);
      CHECK(r.orientable);
      CHECK(r.is_valid());
      CHECK(r.is_closed_manifold());
      CHECK(r.is_closed_genus0_manifold());
      REQUIRE(r.components.size() == 1);
      CHECK(r.components[0].genus == 0);
      CHECK(r.components[0].area > 0);
    });
  }
}

TEST_CASE("check_mesh: torus has genus 1") {
  on_both_models(make_torus(1.0, 0.3, 12, 8), [](const mesh_report& r) {
    CHECK(r.num_vertices == 96);
    CHECK(r.num_faces == 192);
    CHECK(r.num_edges == 288);
    CHECK(r.euler_characteristic == 0);
    CHECK(r.genus == 1);
    CHECK(r.is_closed_manifold());
    CHECK_FALSE(r.is_closed_genus0_manifold());
  });
}

TEST_CASE("check_mesh: disk has one boundary loop") {
  on_both_models(make_disk(3, 8), [](const mesh_report& r) {
    CHECK(r.num_vertices == 25);
    CHECK(r.num_faces == 40);
    CHECK(r.num_edges == 64);
    CHECK(r.num_boundary_edges == 8);
    CHECK(r.num_boundary_loops == 1);
    CHECK(r.euler_characteristic == 1);
    CHECK(r.genus == 0);
    CHECK(r.is_manifold());
    CHECK_FALSE(r.is_closed());
    REQUIRE(r.boundary_edge_examples.size() == 8);
    // every listed boundary edge joins two vertices of the outer ring (indices 17..24)
    for (const auto& e : r.boundary_edge_examples) {
      CHECK(e[0] >= 17);
      CHECK(e[1] >= 17);
    }
  });
}

TEST_CASE("check_mesh: bowtie vertex is non-manifold") {
  on_both_models(test::bowtie(), [](const mesh_report& r) {
    CHECK(r.num_non_manifold_vertices == 1);
    REQUIRE(r.non_manifold_vertex_examples.size() == 1);
    CHECK(r.non_manifold_vertex_examples[0] == 0);
    CHECK(r.num_non_manifold_edges == 0);
    CHECK(r.num_boundary_edges == 6);
    CHECK(r.genus == -1);  // undefined on a non-manifold component
    CHECK(r.is_valid());
    CHECK_FALSE(r.is_manifold());
  });
}

TEST_CASE("check_mesh: fin edge is non-manifold") {
  on_both_models(test::fin(), [](const mesh_report& r) {
    CHECK(r.num_non_manifold_edges == 1);
    REQUIRE(r.non_manifold_edge_examples.size() == 1);
    CHECK(r.non_manifold_edge_examples[0] == std::array<index_t, 2>{0, 1});
    CHECK(r.num_non_manifold_vertices == 0);
    CHECK(r.num_edges == 7);
    CHECK(r.num_boundary_edges == 6);
    CHECK_FALSE(r.is_manifold());
  });
}

TEST_CASE("check_mesh: defective input is reported, not thrown") {
  SUBCASE("NaN vertex") {
    on_both_models(test::with_nan_vertex(), [](const mesh_report& r) {
      CHECK(r.num_non_finite_vertices == 1);
      REQUIRE(r.non_finite_vertex_examples.size() == 1);
      CHECK(r.non_finite_vertex_examples[0] == 2);
      CHECK(std::isfinite(r.bbox_diagonal));
      CHECK(r.num_edges == 12);  // topology does not depend on coordinates
      CHECK_FALSE(r.is_valid());
      CHECK(r.to_json().find("nan") == std::string::npos);
    });
  }
  SUBCASE("index out of range") {
    on_both_models(test::with_bad_index(), [](const mesh_report& r) {
      CHECK(r.num_out_of_range_faces == 1);
      REQUIRE(r.out_of_range_face_examples.size() == 1);
      CHECK(r.out_of_range_face_examples[0] == 3);
      CHECK(r.num_faces == 8);
      CHECK(r.num_boundary_edges == 3);  // the hole left by the ignored face
      CHECK(r.num_boundary_loops == 1);
      CHECK_FALSE(r.is_valid());
    });
  }
  SUBCASE("negative index") {
    auto m = test::tetrahedron();
    m.F(2, 0) = -7;
    const auto r = check_mesh(m);
    CHECK(r.num_out_of_range_faces == 1);
    CHECK(r.out_of_range_face_examples.at(0) == 2);
  }
  SUBCASE("degenerate faces") {
    on_both_models(with_degenerate_faces(), [](const mesh_report& r) {
      CHECK(r.num_degenerate_faces == 2);
      CHECK(r.degenerate_face_examples == std::vector<index_t>{4, 5});
      CHECK(r.num_repeated_index_faces == 1);
      CHECK_FALSE(r.is_valid());  // validate_mesh rejects the repeated index
    });
  }
  SUBCASE("duplicate vertex") {
    on_both_models(with_duplicate_vertex(), [](const mesh_report& r) {
      CHECK(r.num_duplicate_vertices == 1);
      CHECK(r.duplicate_vertex_examples == std::vector<index_t>{6});
      CHECK(r.num_unreferenced_vertices == 1);
      CHECK(r.unreferenced_vertex_examples == std::vector<index_t>{6});
      CHECK(r.num_components == 2);  // the stray vertex is its own component
      CHECK(r.components.size() == 1);
      CHECK(r.genus == 0);
      CHECK(r.euler_characteristic == 3);
      CHECK_FALSE(r.is_closed_genus0_manifold());
    });
  }
  SUBCASE("empty") {
    const triangle_mesh<double> m;
    const auto r = check_mesh(m);
    CHECK(r.num_vertices == 0);
    CHECK(r.num_faces == 0);
    CHECK(r.num_components == 0);
    CHECK_FALSE(r.is_valid());
    CHECK_FALSE(r.to_string().empty());
    const auto r2 = check_mesh(test::to_legacy(m));
    CHECK(r2.num_edges == 0);
  }
  SUBCASE("vertices but no faces") {
    triangle_mesh<double> m;
    m.V = Eigen::MatrixX3d::Random(5, 3);
    const auto r = check_mesh(m);
    CHECK(r.num_components == 5);
    CHECK(r.num_unreferenced_vertices == 5);
    CHECK_FALSE(r.is_valid());
  }
  SUBCASE("wrong matrix shape") {
    const Eigen::MatrixXd V = Eigen::MatrixXd::Zero(4, 2);
    const Eigen::MatrixXi F = Eigen::MatrixXi::Zero(1, 3);
    const auto r = check_mesh(V, F);
    CHECK_FALSE(r.shape_problem.empty());
    CHECK_FALSE(r.is_valid());
    CHECK(r.to_string().find("3 columns") != std::string::npos);
  }
}

TEST_CASE("check_mesh: orientation") {
  SUBCASE("one flipped face: inconsistent but orientable") {
    on_both_models(with_flipped_face(), [](const mesh_report& r) {
      CHECK(r.num_inconsistent_edges == 3);
      CHECK(r.orientable);
      CHECK(r.genus == 0);
      CHECK(r.is_closed_manifold());
    });
  }
  SUBCASE("Moebius strip: non-orientable") {
    on_both_models(moebius_strip(12), [](const mesh_report& r) {
      CHECK_FALSE(r.orientable);
      CHECK(r.num_boundary_loops == 1);
      CHECK(r.euler_characteristic == 0);
      CHECK(r.genus == -1);
      CHECK(r.is_manifold());
      CHECK(r.num_inconsistent_edges >= 1);
    });
  }
}

TEST_CASE("check_mesh: several components, each with its own genus") {
  // a torus and a shifted icosphere in one mesh: genus 1 + 0
  const auto t = make_torus(1.0, 0.3, 10, 6);
  const auto s = make_icosphere(1);
  triangle_mesh<double> m;
  m.V.resize(t.V.rows() + s.V.rows(), 3);
  m.V << t.V, (s.V.rowwise() + Eigen::RowVector3d(5, 0, 0));
  m.F.resize(t.F.rows() + s.F.rows(), 3);
  m.F << t.F, (s.F.array() + t.V.rows()).matrix();
  on_both_models(m, [&](const mesh_report& r) {
    CHECK(r.num_components == 2);
    REQUIRE(r.components.size() == 2);
    CHECK(r.components[0].genus == 1);
    CHECK(r.components[0].num_vertices == t.V.rows());
    CHECK(r.components[1].genus == 0);
    CHECK(r.components[1].first_vertex == t.V.rows());
    CHECK(r.genus == 1);
    CHECK(r.euler_characteristic == 2);
    CHECK(r.components[1].area == doctest::Approx(4 * 3.14159).epsilon(0.1));
  });
}

TEST_CASE("check_mesh: examples are capped, counts are not") {
  const auto disk = make_disk(2, 40);
  const auto r = check_mesh(disk, {.max_examples = 3});
  CHECK(r.num_boundary_edges == 40);
  CHECK(r.boundary_edge_examples.size() == 3);
  CHECK(r.to_string().find("...") != std::string::npos);
}

TEST_CASE("check_mesh: random triangle soups agree with a brute-force count and never throw") {
  std::mt19937_64 rng(20261122);
  for (int trial = 0; trial < 200; ++trial) {
    const index_t n = std::uniform_int_distribution<index_t>(0, 12)(rng);
    const index_t m = std::uniform_int_distribution<index_t>(0, 20)(rng);
    triangle_mesh<double> mesh;
    mesh.V.resize(n, 3);
    // coarse integer coordinates so duplicates and collinear corners occur
    std::uniform_int_distribution<int> coord(0, 2);
    for (index_t i = 0; i < n; ++i) mesh.V.row(i) << coord(rng), coord(rng), coord(rng);
    if (n > 0 && trial % 7 == 0) mesh.V(0, 0) = std::numeric_limits<double>::infinity();
    mesh.F.resize(m, 3);
    std::uniform_int_distribution<index_t> idx(-1, n);  // -1 and n are out of range
    for (index_t f = 0; f < m; ++f) mesh.F.row(f) << idx(rng), idx(rng), idx(rng);

    mesh_report r;
    REQUIRE_NOTHROW(r = check_mesh(mesh));

    std::map<std::pair<index_t, index_t>, int> edge_faces;
    index_t bad = 0, repeated = 0, topo = 0;
    for (index_t f = 0; f < m; ++f) {
      const index_t a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
      if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= n) {
        ++bad;
        continue;
      }
      if (a == b || b == c || a == c) {
        ++repeated;
        continue;
      }
      ++topo;
      for (auto [s, t] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
        ++edge_faces[{std::min(s, t), std::max(s, t)}];
    }
    index_t boundary = 0, nonmanifold = 0;
    for (const auto& [e, k] : edge_faces) {
      boundary += (k == 1);
      nonmanifold += (k > 2);
    }
    CHECK(r.num_out_of_range_faces == bad);
    CHECK(r.num_repeated_index_faces == repeated);
    CHECK(r.num_edges == static_cast<index_t>(edge_faces.size()));
    CHECK(r.num_boundary_edges == boundary);
    CHECK(r.num_non_manifold_edges == nonmanifold);
    CHECK(r.euler_characteristic == n - static_cast<index_t>(edge_faces.size()) + topo);

    // components agree with connected_components on the in-range faces
    face_matrix good(m - bad, 3);
    index_t g = 0;
    for (index_t f = 0; f < m; ++f)
      if (std::min({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)}) >= 0 &&
          std::max({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)}) < n)
        good.row(g++) = mesh.F.row(f);
    CHECK(r.num_components == connected_components(good, n).count);
    CHECK_FALSE(r.to_string().empty());
    CHECK(r.to_json().front() == '{');
  }
}

TEST_CASE("check_mesh: printing") {
  const auto r = check_mesh(make_torus(1.0, 0.3, 12, 8));
  const std::string s = r.to_string();
  CHECK(s.find("genus 1") != std::string::npos);
  CHECK(s.find("vertices 96") != std::string::npos);
  const std::string j = r.to_json();
  CHECK(j.find("\"genus\":1") != std::string::npos);
  CHECK(j.find("\"edges\":288") != std::string::npos);
  CHECK(j.back() == '}');
}
