// SPDX-License-Identifier: MIT
// creature_generator: determinism, topology, ground-truth maps, symmetry, landmarks, option checks.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include <Eigen/Geometry>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/generate/creature_generator.hpp"
#include "shapestruct/generate/creature_map.hpp"
#include "shapestruct/geometry/mesh_topology.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

struct topology_report {
  index_t vertices = 0, edges = 0, faces = 0, components = 0;
  index_t bad_edges = 0;        // edges not in exactly two faces
  index_t misoriented = 0;      // interior edges traversed in the same direction by both faces
  index_t unreferenced = 0;
  double min_area_ratio = 0;    // smallest face area / mean face area
};

/// Independent topology check on any SurfaceMesh (gathered, so both models run the same code).
template <SurfaceMesh Mesh>
topology_report topology(const Mesh& mesh) {
  const auto m = to_triangle_mesh<double>(mesh);
  topology_report r;
  r.vertices = m.num_vertices();
  r.faces = m.num_faces();
  std::map<std::pair<index_t, index_t>, std::pair<int, int>> edges;  // undirected -> (count, direction sum)
  std::vector<index_t> parent(static_cast<std::size_t>(r.vertices));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](index_t x) {
    while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  std::vector<bool> used(static_cast<std::size_t>(r.vertices), false);
  double total = 0, min_area = 1e300;
  for (index_t f = 0; f < r.faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      const index_t a = m.F(f, k), b = m.F(f, (k + 1) % 3);
      auto& e = edges[std::minmax(a, b)];
      ++e.first;
      e.second += a < b ? 1 : -1;
      parent[static_cast<std::size_t>(find(a))] = find(b);
      used[static_cast<std::size_t>(a)] = true;
    }
    const Eigen::Vector3d p0 = m.V.row(m.F(f, 0)), p1 = m.V.row(m.F(f, 1)), p2 = m.V.row(m.F(f, 2));
    const double area = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    total += area;
    min_area = std::min(min_area, area);
  }
  r.edges = static_cast<index_t>(edges.size());
  for (const auto& [k, e] : edges) {
    if (e.first != 2) ++r.bad_edges;
    else if (e.second != 0) ++r.misoriented;
  }
  for (index_t v = 0; v < r.vertices; ++v) {
    if (!used[static_cast<std::size_t>(v)]) ++r.unreferenced;
    if (find(v) == v) ++r.components;
  }
  r.min_area_ratio = min_area / (total / static_cast<double>(r.faces));
  return r;
}

Eigen::Vector3d point_on(const creature<double>& c, const surface_point<double>& s, bool rest = false) {
  return rest ? s.position(c.rest_positions, c.mesh.F) : s.position(c.mesh.V, c.mesh.F);
}

/// Longest edge of face f: the scale of the chordal error of a point located in that face.
double face_size(const triangle_mesh<double>& m, index_t f) {
  double e = 0;
  for (int k = 0; k < 3; ++k) e = std::max(e, (m.V.row(m.F(f, k)) - m.V.row(m.F(f, (k + 1) % 3))).norm());
  return e;
}

double mean_edge_length(const triangle_mesh<double>& m) {
  double sum = 0;
  for (index_t f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) sum += (m.V.row(m.F(f, k)) - m.V.row(m.F(f, (k + 1) % 3))).norm();
  return sum / (3.0 * static_cast<double>(m.num_faces()));
}

/// True if segment [p, q] crosses triangle (a, b, c) (Moller-Trumbore, with the segment's end points and the
/// triangle's border excluded by a small margin so that touching at a shared vertex is not reported).
bool segment_hits_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d d = q - p, e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-18) return false;
  const Eigen::Vector3d s = p - a;
  const double u = s.dot(h) / det;
  if (u < 1e-9 || u > 1 - 1e-9) return false;
  const Eigen::Vector3d qv = s.cross(e1);
  const double v = d.dot(qv) / det;
  if (v < 1e-9 || u + v > 1 - 1e-9) return false;
  const double t = e2.dot(qv) / det;
  return t > 1e-9 && t < 1 - 1e-9;
}

/// Number of pairs of faces that share no vertex and intersect (uniform-grid broad phase).
index_t self_intersections(const triangle_mesh<double>& m) {
  const double cell = 2.0 * mean_edge_length(m);
  std::map<std::array<long, 3>, std::vector<index_t>> grid;
  std::vector<Eigen::AlignedBox3d> boxes(static_cast<std::size_t>(m.num_faces()));
  for (index_t f = 0; f < m.num_faces(); ++f) {
    auto& bx = boxes[static_cast<std::size_t>(f)];
    for (int k = 0; k < 3; ++k) bx.extend(m.V.row(m.F(f, k)).transpose());
    const Eigen::Vector3d lo = bx.min() / cell, hi = bx.max() / cell;
    for (long x = long(std::floor(lo.x())); x <= long(std::floor(hi.x())); ++x)
      for (long y = long(std::floor(lo.y())); y <= long(std::floor(hi.y())); ++y)
        for (long z = long(std::floor(lo.z())); z <= long(std::floor(hi.z())); ++z) grid[{x, y, z}].push_back(f);
  }
  std::set<std::pair<index_t, index_t>> hits;
  for (const auto& [key, faces] : grid)
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (std::size_t j = i + 1; j < faces.size(); ++j) {
        const index_t f = faces[i], g = faces[j];
        if (!boxes[static_cast<std::size_t>(f)].intersects(boxes[static_cast<std::size_t>(g)])) continue;
        bool shared = false;
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) shared |= m.F(f, a) == m.F(g, b);
        if (shared) continue;
        const auto P = [&](index_t face, int k) -> Eigen::Vector3d { return m.V.row(m.F(face, k % 3)).transpose(); };
        bool cross = false;
        for (int k = 0; k < 3 && !cross; ++k)
          cross = segment_hits_triangle(P(f, k), P(f, k + 1), P(g, 0), P(g, 1), P(g, 2)) ||
                  segment_hits_triangle(P(g, k), P(g, k + 1), P(f, 0), P(f, 1), P(f, 2));
        if (cross) hits.insert(std::minmax(f, g));
      }
  return static_cast<index_t>(hits.size());
}

}  // namespace

TEST_CASE("creatures do not self-intersect in their generated poses") {
  // The coarsest triangulation keeps the brute-force check fast; the pose and proportions do not depend on it.
  const creature_generator<double> g(17, {.min_resolution = 3, .max_resolution = 3});
  for (std::uint64_t i = 0; i < 60; ++i) {
    CAPTURE(i);
    const auto c = g.generate(i);
    CHECK(self_intersections(c.mesh) == 0);
    triangle_mesh<double> rest{c.rest_positions, c.mesh.F};
    CHECK(self_intersections(rest) == 0);
  }
  // The check can fail: two copies of a creature shifted into each other intersect.
  const auto c = g.generate(0);
  triangle_mesh<double> both;
  both.V.resize(2 * c.mesh.num_vertices(), 3);
  both.V << c.mesh.V, c.mesh.V.rowwise() + Eigen::RowVector3d(0.05, 0.02, 0.01);
  both.F.resize(2 * c.mesh.num_faces(), 3);
  both.F << c.mesh.F, c.mesh.F.array() + c.mesh.num_vertices();
  CHECK(self_intersections(both) > 0);
}

TEST_CASE("creatures are deterministic per (seed, index) and independent of the thread count") {
  const creature_generator<double> g(7), g_same(7), g_other(8);
  const auto a = g.generate(3), b = g_same.generate(3), c = g_other.generate(3);
  CHECK(a.mesh.F == b.mesh.F);
  CHECK(a.mesh.V == b.mesh.V);
  CHECK(a.face_labels == b.face_labels);
  const bool differs = a.mesh.V.rows() != c.mesh.V.rows() || a.mesh.V != c.mesh.V;
  CHECK(differs);
  // Shape i does not depend on the shapes generated before it or on the threads used.
  const auto one = g.generate_range(2, 4, 1), three = g.generate_range(2, 4, 3);
  REQUIRE(one.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(one[i].mesh.V == three[i].mesh.V);
    CHECK(one[i].mesh.F == three[i].mesh.F);
  }
  CHECK(one[1].mesh.V == a.mesh.V);
  // A different triangulation variant keeps the body (same limbs) but changes the mesh.
  const auto a2 = g.generate(3, 1);
  CHECK(a2.has_slot == a.has_slot);
  const bool retriangulated = a2.mesh.F.rows() != a.mesh.F.rows() || a2.mesh.F != a.mesh.F;
  CHECK(retriangulated);
}

TEST_CASE("creatures are closed genus-0 manifolds without degenerate faces, on both mesh models") {
  const creature_generator<double> g(11);
  std::set<int> leg_counts;
  for (std::uint64_t i = 0; i < 12; ++i) {
    const auto c = g.generate(i);
    for (const auto& r : {topology(c.mesh), topology(test::to_legacy(c.mesh))}) {
      CAPTURE(i);
      CHECK(r.vertices - r.edges + r.faces == 2);
      CHECK(r.components == 1);
      CHECK(r.bad_edges == 0);
      CHECK(r.misoriented == 0);
      CHECK(r.unreferenced == 0);
      CHECK(r.min_area_ratio > 0.01);
    }
    // The precondition check of the blended-intrinsic-maps pipeline accepts it too (both models).
    CHECK_NOTHROW((void)require_closed_genus0_manifold(c.mesh, "test"));
    CHECK_NOTHROW((void)require_closed_genus0_manifold(test::to_legacy(c.mesh), "test"));
    int legs = 0;
    for (int s = 2; s < 8; ++s) legs += c.has_slot[static_cast<std::size_t>(s)];
    leg_counts.insert(legs);
    CHECK(c.has_slot[0]);
    CHECK(static_cast<index_t>(c.face_labels.size()) == c.mesh.num_faces());
    // Outward orientation: positive enclosed volume.
    double volume = 0;
    for (index_t f = 0; f < c.mesh.num_faces(); ++f)
      volume += c.mesh.V.row(c.mesh.F(f, 0)).dot(c.mesh.V.row(c.mesh.F(f, 1)).cross(c.mesh.V.row(c.mesh.F(f, 2)))) / 6;
    CHECK(volume > 0.1);
  }
  CHECK(leg_counts.size() >= 2);  // the collection varies the number of legs
  const auto canon = g.canonical();
  const auto r = topology(canon.mesh);
  CHECK(r.vertices - r.edges + r.faces == 2);
  CHECK(r.bad_edges == 0);
  for (const bool s : canon.has_slot) CHECK(s);
}

TEST_CASE("ground-truth maps compose to the identity and leave only missing parts unmapped") {
  const creature_generator<double> g(5);
  // Find a pair with different limb sets so that both mapped and unmapped vertices occur.
  auto a = g.generate(0);
  creature<double> b;
  for (std::uint64_t i = 1; i < 40; ++i) {
    b = g.generate(i);
    if (b.has_slot != a.has_slot) break;
  }
  REQUIRE(b.has_slot != a.has_slot);
  const auto ab = map_creatures(a, b), ba = map_creatures(b, a);
  REQUIRE(ab.points.size() == static_cast<std::size_t>(a.mesh.num_vertices()));
  const creature_locator<double> loc_a(a), loc_b(b);
  index_t mapped = 0;
  double worst = 0;
  for (index_t v = 0; v < a.mesh.num_vertices(); ++v) {
    const auto& sp = ab.points[static_cast<std::size_t>(v)];
    const index_t patch = a.canonical[static_cast<std::size_t>(v)].patch;
    CHECK(sp.valid() == loc_b.has_patch(patch));
    CHECK(ab.nearest_vertex[static_cast<std::size_t>(v)] == (sp.valid() ? sp.nearest_corner(b.mesh.F) : no_index));
    if (!sp.valid()) {
      CHECK(g.patch_part(patch) != creature_part::head);  // every creature has a head
      continue;
    }
    ++mapped;
    // Back to A through B's own coordinates of the image point.
    const auto back = loc_a.locate(loc_b.canonical_of(sp));
    REQUIRE(back.valid());
    worst = std::max(worst, (point_on(a, back) - a.mesh.V.row(v).transpose()).norm());
  }
  CHECK(mapped > a.mesh.num_vertices() / 2);
  CHECK(ab.unmapped + mapped == a.mesh.num_vertices());
  CHECK(ab.unmapped > 0);
  CHECK(ba.unmapped > 0);
  CHECK(worst < 1e-9);
  // Semantics: each landmark of A that B also has maps next to B's landmark of the same name.
  index_t shared = 0;
  for (const auto& fa : a.features)
    for (const auto& fb : b.features)
      if (fa.name == fb.name) {
        CAPTURE(fa.name);
        const auto& sp = ab.points[static_cast<std::size_t>(fa.vertex)];
        REQUIRE(sp.valid());
        CHECK((point_on(b, sp) - fb.position).norm() < 2.0 * face_size(b.mesh, sp.face));
        ++shared;
      }
  CHECK(shared >= 2);  // at least the nose and one pair of feet
}

TEST_CASE("a creature mapped to a re-triangulation of itself lands on the same surface point") {
  const creature_generator<double> g(21);
  for (std::uint64_t i = 0; i < 3; ++i) {
    const auto a = g.generate(i), a2 = g.generate(i, 5);
    const auto m = map_creatures(a, a2);
    CHECK(m.unmapped == 0);
    const double h = mean_edge_length(a2.mesh);
    double worst = 0, mean = 0;
    for (index_t v = 0; v < a.mesh.num_vertices(); ++v) {
      const auto& sp = m.points[static_cast<std::size_t>(v)];
      const double d = (point_on(a2, sp) - a.mesh.V.row(v).transpose()).norm();
      worst = std::max(worst, d / face_size(a2.mesh, sp.face));
      mean += d;
    }
    mean /= static_cast<double>(a.mesh.num_vertices());
    CAPTURE(h);
    // Both meshes interpolate the same smooth surface: only the chordal error of a2's triangles remains,
    // a small fraction of the local triangle size (a wrong patch or (u, v) would be off by whole cells).
    CHECK(worst < 0.3);
    CHECK(mean < 0.05 * h);
  }
}

TEST_CASE("the symmetry map is an involution and reflects the rest pose") {
  SUBCASE("randomised triangulation: exact in the domain, chordal in space") {
    const creature_generator<double> g(3);
    const auto c = g.generate(4);
    const creature_locator<double> loc(c);
    const double h = mean_edge_length(c.mesh);
    double worst_back = 0, worst_reflect = 0;
    for (index_t v = 0; v < c.mesh.num_vertices(); ++v) {
      const auto& cp = c.canonical[static_cast<std::size_t>(v)];
      const auto mm = g.mirror(g.mirror(cp));
      CHECK(mm.patch == cp.patch);
      CHECK(std::abs(mm.u - cp.u) < 1e-12);
      CHECK(std::abs(mm.v - cp.v) < 1e-12);
      const auto& s = c.symmetry[static_cast<std::size_t>(v)];
      REQUIRE(s.valid());
      const auto back = loc.locate(g.mirror(loc.canonical_of(s)));
      worst_back = std::max(worst_back, (point_on(c, back) - c.mesh.V.row(v).transpose()).norm());
      Eigen::Vector3d reflected = c.rest_positions.row(v).transpose();
      reflected.x() = -reflected.x();
      worst_reflect = std::max(worst_reflect, (point_on(c, s, true) - reflected).norm() / face_size(c.mesh, s.face));
    }
    CHECK(worst_back < 1e-9);
    CHECK(worst_reflect < 0.3);
    (void)h;
  }
  SUBCASE("regular triangulation: the vertex map is an exact involution") {
    const creature_generator<double> g(3, {.jitter = 0.0, .flip_fraction = 0.0});
    const auto c = g.generate(4);
    index_t fixed = 0;
    double worst = 0;
    for (index_t v = 0; v < c.mesh.num_vertices(); ++v) {
      const index_t w = c.symmetry_vertex[static_cast<std::size_t>(v)];
      REQUIRE(w != no_index);
      CHECK(c.symmetry_vertex[static_cast<std::size_t>(w)] == v);
      if (w == v) ++fixed;
      Eigen::Vector3d reflected = c.rest_positions.row(v).transpose();
      reflected.x() = -reflected.x();
      worst = std::max(worst, (c.rest_positions.row(w).transpose() - reflected).norm());
      // Fixed points of the reflection lie on the mid-plane x = 0.
      if (w == v) CHECK(std::abs(c.rest_positions(v, 0)) < 1e-9);
    }
    CHECK(worst < 1e-9);
    CHECK(fixed < c.mesh.num_vertices() / 4);  // only vertices on the mid-plane (none when n is odd)
    // The posed creature is not symmetric (limbs move independently).
    double posed_asym = 0;
    for (index_t v = 0; v < c.mesh.num_vertices(); ++v) {
      Eigen::Vector3d reflected = c.mesh.V.row(v).transpose();
      reflected.x() = -reflected.x();
      posed_asym = std::max(posed_asym, (c.mesh.V.row(c.symmetry_vertex[static_cast<std::size_t>(v)]).transpose() - reflected).norm());
    }
    CHECK(posed_asym > 0.01);
  }
}

TEST_CASE("creature landmarks are mesh vertices at limb tips, one per limb") {
  const creature_generator<double> g(9);
  for (std::uint64_t i = 0; i < 5; ++i) {
    const auto c = g.generate(i);
    int limbs = 0;
    for (const bool s : c.has_slot) limbs += s;
    REQUIRE(static_cast<int>(c.features.size()) == limbs);
    CHECK(c.features.front().name == "nose");
    const Eigen::Vector3d centre = c.mesh.V.colwise().mean();
    for (const auto& f : c.features) {
      REQUIRE(f.vertex >= 0);
      REQUIRE(f.vertex < c.mesh.num_vertices());
      CHECK((c.mesh.V.row(f.vertex).transpose() - f.position).norm() == 0.0);
      CHECK((f.position - centre).norm() > 0.3);  // tips stick out of the torso
    }
  }
}

TEST_CASE("creature_generator rejects out-of-range options with bad_parameter") {
  const auto reason = [](creature_options o) {
    try {
      const creature_generator<double> g(1, o);
    } catch (const invalid_input& e) {
      return e.reason();
    }
    return input_error::empty;
  };
  CHECK(reason({.min_leg_pairs = 0}) == input_error::bad_parameter);
  CHECK(reason({.min_leg_pairs = 3, .max_leg_pairs = 2}) == input_error::bad_parameter);
  CHECK(reason({.arm_probability = 1.5}) == input_error::bad_parameter);
  CHECK(reason({.min_resolution = 1}) == input_error::bad_parameter);
  CHECK(reason({.jitter = 0.6}) == input_error::bad_parameter);
  CHECK(reason({.pose_variation = -1}) == input_error::bad_parameter);
  CHECK(reason({.subdivision_levels = 9}) == input_error::bad_parameter);
  CHECK(reason({}) == input_error::empty);  // defaults are accepted
}

TEST_CASE("creature_locator and map_creatures reject inconsistent ground truth with size_mismatch") {
  const creature_generator<double> g(1);
  auto c = g.generate(0);
  const auto d = c;
  c.face_patch.pop_back();
  CHECK_THROWS_AS(creature_locator<double>{c}, invalid_input);
  auto e = d;
  e.canonical.pop_back();
  try {
    (void)map_creatures(e, d);
    FAIL("expected invalid_input");
  } catch (const invalid_input& ex) {
    CHECK(ex.reason() == input_error::size_mismatch);
  }
}
