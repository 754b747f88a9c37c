// SPDX-License-Identifier: MIT
// How to plug your own mesh type into shapestruct: one surface_traits specialization (~10 lines), after which
// every algorithm accepts it. Run: example_plug_in_your_mesh
#include <array>
#include <cstdio>
#include <vector>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/shapestruct.hpp"

// Your existing mesh type, which you cannot or do not want to change.
namespace legacy {
struct vertex { float x, y, z; };
struct triangle { unsigned a, b, c; };
struct mesh {
  std::vector<vertex> verts;
  std::vector<triangle> tris;
};
}  // namespace legacy

// The whole adapter.
template <>
struct shapestruct::surface_traits<legacy::mesh> {
  using scalar_type = float;
  static index_t num_vertices(const legacy::mesh& m) { return static_cast<index_t>(m.verts.size()); }
  static index_t num_faces(const legacy::mesh& m) { return static_cast<index_t>(m.tris.size()); }
  static std::array<float, 3> position(const legacy::mesh& m, index_t i) {
    const auto& v = m.verts[static_cast<std::size_t>(i)];
    return {v.x, v.y, v.z};
  }
  static std::array<index_t, 3> face(const legacy::mesh& m, index_t f) {
    const auto& t = m.tris[static_cast<std::size_t>(f)];
    return {t.a, t.b, t.c};
  }
};

static_assert(shapestruct::SurfaceMesh<legacy::mesh>, "the adapter above makes legacy::mesh a SurfaceMesh");

int main() {
  // Build a legacy mesh from an icosphere, as if it came from your own code.
  const auto sphere = shapestruct::make_icosphere(3);
  legacy::mesh mine;
  for (shapestruct::index_t i = 0; i < sphere.V.rows(); ++i)
    mine.verts.push_back({float(sphere.V(i, 0)), float(sphere.V(i, 1)), float(sphere.V(i, 2))});
  for (shapestruct::index_t f = 0; f < sphere.F.rows(); ++f)
    mine.tris.push_back({unsigned(sphere.F(f, 0)), unsigned(sphere.F(f, 1)), unsigned(sphere.F(f, 2))});

  // Any shapestruct entry point now takes it; here, the gather into canonical form and validation.
  const auto canonical = shapestruct::to_triangle_mesh(mine);
  shapestruct::validate_mesh(canonical.V, canonical.F, "plug_in_your_mesh");
  std::printf("legacy mesh adapted: %ld vertices, %ld faces\n", static_cast<long>(canonical.num_vertices()),
              static_cast<long>(canonical.num_faces()));
  return 0;
}
