// SPDX-License-Identifier: MIT
// A "legacy" user mesh struct adapted in ~10 lines: the second SurfaceMesh model every algorithm is tested on.
#pragma once

#include <array>
#include <vector>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"

namespace shapestruct::test {

struct legacy_vertex {
  float x, y, z;
};
struct legacy_triangle {
  int a, b, c;
};
/// A user's own mesh type: array-of-structs, float coordinates, int indices.
struct legacy_mesh {
  std::vector<legacy_vertex> verts;
  std::vector<legacy_triangle> tris;
};

/// Converts a triangle_mesh into the legacy form (for running the same test on both models).
template <class Scalar>
legacy_mesh to_legacy(const triangle_mesh<Scalar>& m) {
  legacy_mesh out;
  for (index_t i = 0; i < m.V.rows(); ++i)
    out.verts.push_back({float(m.V(i, 0)), float(m.V(i, 1)), float(m.V(i, 2))});
  for (index_t f = 0; f < m.F.rows(); ++f) out.tris.push_back({int(m.F(f, 0)), int(m.F(f, 1)), int(m.F(f, 2))});
  return out;
}

}  // namespace shapestruct::test

template <>
struct shapestruct::surface_traits<shapestruct::test::legacy_mesh> {
  using mesh = shapestruct::test::legacy_mesh;
  using scalar_type = float;
  static index_t num_vertices(const mesh& m) { return static_cast<index_t>(m.verts.size()); }
  static index_t num_faces(const mesh& m) { return static_cast<index_t>(m.tris.size()); }
  static std::array<float, 3> position(const mesh& m, index_t i) {
    const auto& v = m.verts[static_cast<std::size_t>(i)];
    return {v.x, v.y, v.z};
  }
  static std::array<index_t, 3> face(const mesh& m, index_t f) {
    const auto& t = m.tris[static_cast<std::size_t>(f)];
    return {t.a, t.b, t.c};
  }
};
