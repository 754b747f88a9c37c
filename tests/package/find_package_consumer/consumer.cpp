// SPDX-License-Identifier: MIT
// Uses the installed package: the version header, the built-in mesh, a generator, validation, and a part template
// through JSON (which needs the package's nlohmann-json dependency to be found).
#include <cstdio>

#include "shapestruct/core/validate.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/shapestruct.hpp"
#include "shapestruct/templates/part_template.hpp"

int main() {
  const auto mesh = shapestruct::make_icosphere(1);
  shapestruct::validate_mesh(mesh.V, mesh.F, "consumer");
  static_assert(shapestruct::SurfaceMesh<shapestruct::triangle_mesh<double>>);
  const auto t = shapestruct::template_from_json(
      shapestruct::parse_json_text(R"({"id": "box", "parts": [{"center": [0, 0, 0], "size": [1, 2, 3]}]})"));
  std::printf("shapestruct %s: icosphere with %ld vertices, template '%s' with %zu part(s)\n",
              SHAPESTRUCT_VERSION_STRING, static_cast<long>(mesh.num_vertices()), t.id.c_str(), t.parts.size());
  return mesh.num_vertices() == 42 && t.parts.size() == 1 && t.parts[0].size[2] == 3 ? 0 : 1;
}
