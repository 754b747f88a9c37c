// SPDX-License-Identifier: MIT
// The CGAL Surface_mesh adapter: gathers the same mesh as the built-in type.
#include <doctest/doctest.h>

#include <CGAL/Simple_cartesian.h>

#include "shapestruct/adapters/cgal_surface_mesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

using namespace shapestruct;
using kernel = CGAL::Simple_cartesian<double>;
using cgal_mesh = CGAL::Surface_mesh<kernel::Point_3>;
static_assert(SurfaceMesh<cgal_mesh>);

TEST_CASE("CGAL Surface_mesh gathers to the same (V, F)") {
  const auto ico = make_icosphere(2);
  cgal_mesh sm;
  std::vector<cgal_mesh::Vertex_index> handles;
  for (index_t i = 0; i < ico.V.rows(); ++i)
    handles.push_back(sm.add_vertex(kernel::Point_3(ico.V(i, 0), ico.V(i, 1), ico.V(i, 2))));
  for (index_t f = 0; f < ico.F.rows(); ++f)
    sm.add_face(handles[std::size_t(ico.F(f, 0))], handles[std::size_t(ico.F(f, 1))], handles[std::size_t(ico.F(f, 2))]);
  const auto gathered = to_triangle_mesh(sm);
  CHECK(gathered.F == ico.F);
  CHECK(gathered.V == ico.V);
}
