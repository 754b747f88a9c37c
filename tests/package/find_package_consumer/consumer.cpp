// SPDX-License-Identifier: MIT
// Uses the installed package: the version header, the built-in mesh, a generator and validation.
#include <cstdio>

#include "shapestruct/core/validate.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/shapestruct.hpp"

int main() {
  const auto mesh = shapestruct::make_icosphere(1);
  shapestruct::validate_mesh(mesh.V, mesh.F, "consumer");
  static_assert(shapestruct::SurfaceMesh<shapestruct::triangle_mesh<double>>);
  std::printf("shapestruct %s: icosphere with %ld vertices\n", SHAPESTRUCT_VERSION_STRING,
              static_cast<long>(mesh.num_vertices()));
  return mesh.num_vertices() == 42 ? 0 : 1;
}
