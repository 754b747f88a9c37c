// SPDX-License-Identifier: MIT
// primitive_meshes: closed and open reference surfaces (icosphere, UV sphere, torus, disk, cylinder, box).
#pragma once

#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/errors.hpp"

namespace shapestruct {

/// Unit icosphere: an icosahedron subdivided `level` times and projected to the sphere.
/// 10 * 4^level + 2 vertices, 20 * 4^level faces; closed, genus 0, outward-oriented.
template <class Scalar = double>
[[nodiscard]] triangle_mesh<Scalar> make_icosphere(int level) {
  if (level < 0 || level > 9)
    throw invalid_input(input_error::bad_parameter, no_index, "make_icosphere: level must be in [0, 9]");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v) p.normalize();
  std::vector<std::array<index_t, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                           {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                           {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                           {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<index_t, index_t>, index_t> midpoint;
    auto mid = [&](index_t a, index_t b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]).normalized());
      const index_t id = static_cast<index_t>(v.size()) - 1;
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<std::array<index_t, 3>> next;
    next.reserve(f.size() * 4);
    for (const auto& tri : f) {
      const index_t a = mid(tri[0], tri[1]), b = mid(tri[1], tri[2]), c = mid(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f.swap(next);
  }
  triangle_mesh<Scalar> m;
  m.V.resize(static_cast<index_t>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.V.row(static_cast<index_t>(i)) = v[i].cast<Scalar>().transpose();
  m.F.resize(static_cast<index_t>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    for (int k = 0; k < 3; ++k) m.F(static_cast<index_t>(i), k) = f[i][static_cast<std::size_t>(k)];
  return m;
}

/// Torus around the z axis with the given radii, `rings` x `sides` grid; closed, genus 1.
template <class Scalar = double>
[[nodiscard]] triangle_mesh<Scalar> make_torus(Scalar major_radius, Scalar minor_radius, int rings, int sides) {
  if (rings < 3 || sides < 3)
    throw invalid_input(input_error::bad_parameter, no_index, "make_torus: rings and sides must be at least 3");
  triangle_mesh<Scalar> m;
  m.V.resize(rings * sides, 3);
  m.F.resize(2 * rings * sides, 3);
  const double two_pi = 2.0 * std::numbers::pi;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sides; ++j) {
      const double u = two_pi * i / rings, w = two_pi * j / sides;
      const double r = major_radius + minor_radius * std::cos(w);
      m.V.row(i * sides + j) << Scalar(r * std::cos(u)), Scalar(r * std::sin(u)), Scalar(minor_radius * std::sin(w));
    }
  index_t f = 0;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sides; ++j) {
      const index_t a = i * sides + j, b = ((i + 1) % rings) * sides + j, c = ((i + 1) % rings) * sides + (j + 1) % sides,
                    d = i * sides + (j + 1) % sides;
      m.F.row(f++) << a, b, c;
      m.F.row(f++) << a, c, d;
    }
  return m;
}

/// Flat unit disk in the z = 0 plane, `rings` concentric rings of `sectors` segments; one boundary loop.
template <class Scalar = double>
[[nodiscard]] triangle_mesh<Scalar> make_disk(int rings, int sectors) {
  if (rings < 1 || sectors < 3)
    throw invalid_input(input_error::bad_parameter, no_index, "make_disk: need rings >= 1 and sectors >= 3");
  triangle_mesh<Scalar> m;
  m.V.resize(1 + rings * sectors, 3);
  m.V.row(0).setZero();
  const double two_pi = 2.0 * std::numbers::pi;
  for (int r = 1; r <= rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      const double rad = double(r) / rings, a = two_pi * s / sectors;
      m.V.row(1 + (r - 1) * sectors + s) << Scalar(rad * std::cos(a)), Scalar(rad * std::sin(a)), Scalar(0);
    }
  std::vector<std::array<index_t, 3>> f;
  for (int s = 0; s < sectors; ++s) f.push_back({0, 1 + s, 1 + (s + 1) % sectors});
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      const index_t a = 1 + (r - 1) * sectors + s, b = 1 + (r - 1) * sectors + (s + 1) % sectors;
      const index_t c = 1 + r * sectors + s, d = 1 + r * sectors + (s + 1) % sectors;
      f.push_back({a, c, d});
      f.push_back({a, d, b});
    }
  m.F.resize(static_cast<index_t>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.F.row(static_cast<index_t>(i)) << f[i][0], f[i][1], f[i][2];
  return m;
}

/// Axis-aligned box centred at the origin with half extents (hx, hy, hz): 8 vertices, 12 outward faces.
/// Vertex k is the corner with x > 0 iff (k & 1), y > 0 iff (k & 2), z > 0 iff (k & 4), so callers can
/// name corners without searching. Closed, genus 0.
/// \throws invalid_input (bad_parameter) unless every half extent is positive and finite.
template <class Scalar = double>
[[nodiscard]] triangle_mesh<Scalar> make_box(Scalar hx, Scalar hy, Scalar hz) {
  if (!(hx > 0 && hy > 0 && hz > 0) || !std::isfinite(double(hx)) || !std::isfinite(double(hy)) || !std::isfinite(double(hz)))
    throw invalid_input(input_error::bad_parameter, no_index, "make_box: half extents must be positive and finite");
  triangle_mesh<Scalar> m;
  m.V.resize(8, 3);
  for (int k = 0; k < 8; ++k)
    m.V.row(k) << ((k & 1) ? hx : -hx), ((k & 2) ? hy : -hy), ((k & 4) ? hz : -hz);
  m.F.resize(12, 3);
  // Two triangles per side, counter-clockwise seen from outside.
  m.F << 0, 2, 3, 0, 3, 1,  // -z
      4, 5, 7, 4, 7, 6,     // +z
      0, 1, 5, 0, 5, 4,     // -y
      2, 6, 7, 2, 7, 3,     // +y
      0, 4, 6, 0, 6, 2,     // -x
      1, 3, 7, 1, 7, 5;     // +x
  return m;
}

/// Closed cylinder (or frustum, or cone when a radius is 0) along +y from y = 0 (radius r0) to y = height
/// (radius r1), with `segments` sides and capped ends. Vertex 0 is the bottom cap centre, vertex 1 the top
/// cap centre, then `segments` bottom and `segments` top rim vertices (rim vertex s at angle 2 pi s /
/// segments, at (r cos a, y, -r sin a)). 2 * segments + 2 vertices, 4 * segments faces
/// (2 * segments for a cone: a zero radius collapses that rim into its cap centre, and the rim vertices
/// of that end stay unreferenced). Closed, genus 0.
/// \throws invalid_input (bad_parameter) for segments < 3, a negative radius, both radii 0, or height <= 0.
template <class Scalar = double>
[[nodiscard]] triangle_mesh<Scalar> make_cylinder(Scalar r0, Scalar r1, Scalar height, int segments) {
  if (segments < 3 || !(r0 >= 0) || !(r1 >= 0) || !(r0 > 0 || r1 > 0) || !(height > 0) || !std::isfinite(double(height)))
    throw invalid_input(input_error::bad_parameter, no_index,
                        "make_cylinder: need segments >= 3, radii >= 0 (not both 0) and a positive height");
  const bool cone0 = r0 == 0, cone1 = r1 == 0;
  triangle_mesh<Scalar> m;
  m.V.resize(2 + 2 * segments, 3);
  m.V.row(0) << 0, 0, 0;
  m.V.row(1) << 0, height, 0;
  const double two_pi = 2.0 * std::numbers::pi;
  for (int s = 0; s < segments; ++s) {
    const double a = two_pi * s / segments, c = std::cos(a), n = -std::sin(a);
    m.V.row(2 + s) << Scalar(r0 * c), Scalar(0), Scalar(r0 * n);
    m.V.row(2 + segments + s) << Scalar(r1 * c), height, Scalar(r1 * n);
  }
  std::vector<std::array<index_t, 3>> f;
  for (int s = 0; s < segments; ++s) {
    const index_t b0 = 2 + s, b1 = 2 + (s + 1) % segments, t0 = b0 + segments, t1 = b1 + segments;
    // Rim angle grows from +x towards -z (counter-clockwise seen from +y): the top cap is (1, t0, t1).
    if (cone0) f.push_back({0, t1, t0});
    else if (cone1) f.push_back({b0, b1, 1});
    else {
      f.push_back({b0, b1, t1});
      f.push_back({b0, t1, t0});
    }
    if (!cone0) f.push_back({0, b1, b0});
    if (!cone1) f.push_back({1, t0, t1});
  }
  m.F.resize(static_cast<index_t>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.F.row(static_cast<index_t>(i)) << f[i][0], f[i][1], f[i][2];
  return m;
}

}  // namespace shapestruct
