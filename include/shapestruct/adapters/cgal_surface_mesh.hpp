// SPDX-License-Identifier: MIT
// CGAL::Surface_mesh as a SurfaceMesh model. Optional: include only if you use CGAL.
#pragma once

#include <array>
#include <type_traits>

#include <CGAL/Surface_mesh.h>

#include "shapestruct/core/concepts/surface_mesh.hpp"

namespace shapestruct {

/// A triangulated CGAL::Surface_mesh is a SurfaceMesh. Indices are Surface_mesh's vertex/face indices, which
/// are contiguous only when the mesh has no removed elements: call `mesh.collect_garbage()` after removing.
/// The scalar is the kernel's FT converted to double (exact kernels are converted with CGAL::to_double).
template <class Point>
struct surface_traits<CGAL::Surface_mesh<Point>> {
  using mesh = CGAL::Surface_mesh<Point>;
  using scalar_type = double;
  static index_t num_vertices(const mesh& m) { return static_cast<index_t>(m.number_of_vertices()); }
  static index_t num_faces(const mesh& m) { return static_cast<index_t>(m.number_of_faces()); }
  static std::array<double, 3> position(const mesh& m, index_t i) {
    const auto& p = m.point(typename mesh::Vertex_index(static_cast<typename mesh::size_type>(i)));
    return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
  }
  static std::array<index_t, 3> face(const mesh& m, index_t f) {
    std::array<index_t, 3> out{no_index, no_index, no_index};
    const auto fi = typename mesh::Face_index(static_cast<typename mesh::size_type>(f));
    int k = 0;
    for (auto v : m.vertices_around_face(m.halfedge(fi))) {
      if (k == 3) break;
      out[static_cast<std::size_t>(k++)] = static_cast<index_t>(static_cast<typename mesh::size_type>(v));
    }
    return out;
  }
};

}  // namespace shapestruct
