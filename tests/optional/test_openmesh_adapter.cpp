// SPDX-License-Identifier: MIT
// The OpenMesh adapter: gathers the same mesh as the built-in type and works in validation.
#include <doctest/doctest.h>

#include "shapestruct/adapters/openmesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

using namespace shapestruct;
using om_mesh = OpenMesh::TriMesh_ArrayKernelT<>;
static_assert(SurfaceMesh<om_mesh>);

TEST_CASE("OpenMesh TriMesh gathers to the same (V, F)") {
  const auto ico = make_icosphere(2);
  om_mesh om;
  std::vector<om_mesh::VertexHandle> handles;
  for (index_t i = 0; i < ico.V.rows(); ++i)
    handles.push_back(om.add_vertex(om_mesh::Point(float(ico.V(i, 0)), float(ico.V(i, 1)), float(ico.V(i, 2)))));
  for (index_t f = 0; f < ico.F.rows(); ++f)
    om.add_face(handles[std::size_t(ico.F(f, 0))], handles[std::size_t(ico.F(f, 1))], handles[std::size_t(ico.F(f, 2))]);
  const auto gathered = to_triangle_mesh(om);
  CHECK(gathered.F == ico.F);
  CHECK((gathered.V - ico.V).cwiseAbs().maxCoeff() < 1e-6);
  CHECK_NOTHROW(validate_mesh(gathered.V, gathered.F, "test"));
}
