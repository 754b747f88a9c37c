// SPDX-License-Identifier: MIT
// assembly_generator: determinism, labels, part boxes, landmarks, class mixing, option checks.
#include <doctest/doctest.h>

#include <set>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/generate/assembly_generator.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

/// Distance from p to triangle (a, b, c), by projecting on the plane and falling back to the edges.
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  if (n.squaredNorm() > 0) {
    const Eigen::Vector3d q = p - n.dot(p - a) / n.squaredNorm() * n;
    const double w0 = (c - b).cross(q - b).dot(n), w1 = (a - c).cross(q - c).dot(n), w2 = (b - a).cross(q - a).dot(n);
    if (w0 >= 0 && w1 >= 0 && w2 >= 0) return (p - q).norm();
  }
  const auto seg = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
    const double t = std::clamp((p - x).dot(y - x) / std::max((y - x).squaredNorm(), 1e-300), 0.0, 1.0);
    return (p - (x + t * (y - x))).norm();
  };
  return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

/// Distance from p to the nearest face of any SurfaceMesh (gathered; brute force).
template <SurfaceMesh Mesh>
double distance_to_surface(const Mesh& mesh, const Eigen::Vector3d& p) {
  const auto m = to_triangle_mesh<double>(mesh);
  double best = 1e300;
  for (index_t f = 0; f < m.num_faces(); ++f)
    best = std::min(best, point_triangle_distance(p, m.V.row(m.F(f, 0)), m.V.row(m.F(f, 1)), m.V.row(m.F(f, 2))));
  return best;
}

}  // namespace

TEST_CASE("assemblies are deterministic per (class, seed, index)") {
  for (const auto k : {assembly_kind::chair, assembly_kind::table, assembly_kind::airplane}) {
    CAPTURE(to_string(k));
    const assembly_generator<double> g(k, 12), same(k, 12), other(k, 13);
    const auto a = g.generate(4), b = same.generate(4), c = other.generate(4);
    CHECK(a.mesh.V == b.mesh.V);
    CHECK(a.mesh.F == b.mesh.F);
    CHECK(a.face_labels == b.face_labels);
    const bool differs = a.mesh.V.rows() != c.mesh.V.rows() || a.mesh.V != c.mesh.V;
    CHECK(differs);
    const auto one = g.generate_range(3, 3, 1), two = g.generate_range(3, 3, 2);
    for (std::size_t i = 0; i < 3; ++i) CHECK(one[i].mesh.V == two[i].mesh.V);
    CHECK(one[1].mesh.V == a.mesh.V);
  }
}

TEST_CASE("a mixed collection reproduces each class's own shapes and mixes all three") {
  const assembly_generator<double> mixed(std::nullopt, 6);
  std::set<int> kinds;
  for (std::uint64_t i = 0; i < 30; ++i) {
    const auto k = mixed.kind_of(i);
    kinds.insert(static_cast<int>(k));
    if (i < 6) {
      const auto a = mixed.generate(i), b = assembly_generator<double>(k, 6).generate(i);
      CHECK(a.kind == k);
      CHECK(a.mesh.V == b.mesh.V);
    }
  }
  CHECK(kinds.size() == 3);
}

TEST_CASE("labels cover every face and each part's faces lie in its declared box") {
  for (const auto k : {assembly_kind::chair, assembly_kind::table, assembly_kind::airplane}) {
    const assembly_generator<double> g(k, 2);
    const auto names = assembly_label_names(k);
    std::set<int> seen;
    std::set<std::size_t> part_counts;
    for (std::uint64_t i = 0; i < 25; ++i) {
      CAPTURE(to_string(k));
      CAPTURE(i);
      const auto a = g.generate(i);
      CHECK_NOTHROW(validate_mesh(a.mesh.V, a.mesh.F, "test"));
      REQUIRE(a.face_labels.size() == static_cast<std::size_t>(a.mesh.num_faces()));
      REQUIRE(a.face_part.size() == a.face_labels.size());
      part_counts.insert(a.parts.size());
      std::vector<bool> part_used(a.parts.size(), false);
      index_t outside = 0, mislabelled = 0;
      for (index_t f = 0; f < a.mesh.num_faces(); ++f) {
        const int l = a.face_labels[static_cast<std::size_t>(f)];
        CHECK(l >= 0);
        CHECK(l < static_cast<int>(names.size()));
        seen.insert(l);
        const auto p = a.face_part[static_cast<std::size_t>(f)];
        REQUIRE(p >= 0);
        REQUIRE(p < static_cast<index_t>(a.parts.size()));
        part_used[static_cast<std::size_t>(p)] = true;
        const auto& part = a.parts[static_cast<std::size_t>(p)];
        if (part.label != l) ++mislabelled;
        for (int c = 0; c < 3; ++c)
          if (!part.contains(a.mesh.V.row(a.mesh.F(f, c)).transpose())) ++outside;
      }
      CHECK(mislabelled == 0);
      CHECK(outside == 0);
      for (const bool u : part_used) CHECK(u);
      // Boxes are tight: each part box's extreme corners are reached by its own vertices (per axis).
      for (std::size_t p = 0; p < a.parts.size(); ++p) {
        const auto& part = a.parts[p];
        Eigen::Vector3d reach = Eigen::Vector3d::Zero();
        for (index_t f = 0; f < a.mesh.num_faces(); ++f)
          if (a.face_part[static_cast<std::size_t>(f)] == static_cast<index_t>(p))
            for (int c = 0; c < 3; ++c)
              reach = reach.cwiseMax((part.axes.transpose() * (a.mesh.V.row(a.mesh.F(f, c)).transpose() - part.center)).cwiseAbs());
        CHECK((reach - part.half_extents).cwiseAbs().maxCoeff() < 1e-9);
      }
    }
    CHECK(seen.size() == names.size());  // every label occurs somewhere in 25 shapes
    CHECK(part_counts.size() >= 3);      // optional parts and multiplicities vary
  }
}

TEST_CASE("assembly landmarks are named vertices on the surface, on both mesh models") {
  for (const auto k : {assembly_kind::chair, assembly_kind::table, assembly_kind::airplane}) {
    const assembly_generator<double> g(k, 8);
    for (std::uint64_t i = 0; i < 6; ++i) {
      const auto a = g.generate(i);
      const auto legacy = test::to_legacy(a.mesh);
      REQUIRE(!a.features.empty());
      std::set<std::string> names;
      for (const auto& f : a.features) {
        CAPTURE(f.name);
        names.insert(f.name);
        REQUIRE(f.vertex >= 0);
        REQUIRE(f.vertex < a.mesh.num_vertices());
        CHECK((a.mesh.V.row(f.vertex).transpose() - f.position).norm() == 0.0);
        CHECK(distance_to_surface(a.mesh, f.position) < 1e-12);
        CHECK(distance_to_surface(legacy, f.position) < 1e-5);  // float model
      }
      CHECK(names.size() == a.features.size());  // names are unique within a shape
    }
  }
  // Conventions: chairs and tables stand on y = 0 with +Y up; airplanes point their nose to -Z.
  const auto chair = assembly_generator<double>(assembly_kind::chair, 1).generate(0);
  CHECK(std::abs(chair.mesh.V.col(1).minCoeff()) < 0.01);
  const auto plane = assembly_generator<double>(assembly_kind::airplane, 1).generate(0);
  for (const auto& f : plane.features)
    if (f.name == "nose") CHECK(f.position.z() < plane.mesh.V.col(2).minCoeff() + 0.01);  // cap centre of a tilted cone
  for (const auto& f : plane.features)
    if (f.name == "wing_tip_left") CHECK(f.position.x() < -0.2);
}

TEST_CASE("assembly_generator and the new primitives reject bad parameters") {
  CHECK_THROWS_AS(assembly_generator<double>(assembly_kind::chair, 1, {.round_segments = 3}), invalid_input);
  CHECK_THROWS_AS(assembly_generator<double>(assembly_kind::chair, 1, {.tilt = 1.0}), invalid_input);
  try {
    (void)make_box<double>(1, 0, 1);
    FAIL("expected invalid_input");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == input_error::bad_parameter);
  }
  CHECK_THROWS_AS((void)make_cylinder<double>(1, 1, 1, 2), invalid_input);
  CHECK_THROWS_AS((void)make_cylinder<double>(0, 0, 1, 8), invalid_input);
}

TEST_CASE("make_box and make_cylinder are closed and outward-oriented") {
  const auto volume = [](const triangle_mesh<double>& m) {
    double v = 0;
    for (index_t f = 0; f < m.num_faces(); ++f)
      v += m.V.row(m.F(f, 0)).dot(m.V.row(m.F(f, 1)).cross(m.V.row(m.F(f, 2)))) / 6;
    return v;
  };
  CHECK(volume(make_box<double>(1, 2, 3)) == doctest::Approx(48.0));
  CHECK(make_box<double>(1, 2, 3).V.row(5) == Eigen::RowVector3d(1, -2, 3));
  const int n = 256;
  const double pi = std::numbers::pi;
  // A fine regular prism approaches the cylinder's volume pi r^2 h from below.
  CHECK(volume(make_cylinder<double>(1, 1, 2, n)) == doctest::Approx(2 * pi).epsilon(1e-3));
  CHECK(volume(make_cylinder<double>(1, 0.5, 3, n)) == doctest::Approx(pi * 3 * (1 + 0.5 + 0.25) / 3).epsilon(1e-3));
  const auto c = make_cylinder<double>(0.5, 0.5, 1, 8);
  CHECK(c.V.row(0) == Eigen::RowVector3d(0, 0, 0));
  CHECK(c.V.row(1) == Eigen::RowVector3d(0, 1, 0));
  CHECK(c.num_faces() == 32);
}
