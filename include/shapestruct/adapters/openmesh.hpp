// SPDX-License-Identifier: MIT
// OpenMesh triangle meshes (TriMesh_ArrayKernelT) as SurfaceMesh models. Optional: include only if you use OpenMesh.
#pragma once

#include <array>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "shapestruct/core/concepts/surface_mesh.hpp"

namespace shapestruct {

/// An OpenMesh TriMesh is a SurfaceMesh. Vertex and face indices are OpenMesh's handle indices, which are
/// contiguous only when the mesh holds no deleted elements: call `mesh.garbage_collection()` after deleting.
/// face() walks the face's three halfedges: O(1).
template <class Traits>
struct surface_traits<OpenMesh::TriMesh_ArrayKernelT<Traits>> {
  using mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;
  using scalar_type = typename mesh::Point::value_type;
  static index_t num_vertices(const mesh& m) { return static_cast<index_t>(m.n_vertices()); }
  static index_t num_faces(const mesh& m) { return static_cast<index_t>(m.n_faces()); }
  static std::array<scalar_type, 3> position(const mesh& m, index_t i) {
    const auto& p = m.point(typename mesh::VertexHandle(static_cast<int>(i)));
    return {p[0], p[1], p[2]};
  }
  static std::array<index_t, 3> face(const mesh& m, index_t f) {
    std::array<index_t, 3> out{no_index, no_index, no_index};
    int k = 0;
    for (auto v : m.fv_range(typename mesh::FaceHandle(static_cast<int>(f)))) {
      if (k == 3) break;  // a polygon in a TriMesh cannot happen; guard anyway
      out[static_cast<std::size_t>(k++)] = v.idx();
    }
    return out;
  }
};

}  // namespace shapestruct
