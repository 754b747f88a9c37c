// SPDX-License-Identifier: MIT
// Procedural test meshes, tagged by property: valid closed genus-0, other topologies, and defective ones.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

namespace shapestruct::test {

/// Every face with its own three vertices (as an STL file or a polygon soup stores it): no shared edges.
template <class Scalar>
triangle_mesh<Scalar> as_soup(const triangle_mesh<Scalar>& m) {
  triangle_mesh<Scalar> out;
  out.V.resize(3 * m.F.rows(), 3);
  out.F.resize(m.F.rows(), 3);
  for (index_t f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      out.V.row(3 * f + k) = m.V.row(m.F(f, k));
      out.F(f, k) = 3 * f + k;
    }
  return out;
}

template <class Scalar = double>
triangle_mesh<Scalar> tetrahedron() {
  triangle_mesh<Scalar> m;
  m.V.resize(4, 3);
  m.V << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  m.F.resize(4, 3);
  m.F << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  return m;
}

template <class Scalar = double>
triangle_mesh<Scalar> octahedron() {
  triangle_mesh<Scalar> m;
  m.V.resize(6, 3);
  m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

/// Two triangles sharing only vertex 0: a non-manifold ("bowtie") vertex.
template <class Scalar = double>
triangle_mesh<Scalar> bowtie() {
  triangle_mesh<Scalar> m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 3, 4;
  return m;
}

/// Three triangles sharing edge (0, 1): a non-manifold ("fin") edge.
template <class Scalar = double>
triangle_mesh<Scalar> fin() {
  triangle_mesh<Scalar> m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1;
  m.F.resize(3, 3);
  m.F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  return m;
}

/// An octahedron whose vertex 2 is NaN.
template <class Scalar = double>
triangle_mesh<Scalar> with_nan_vertex() {
  auto m = octahedron<Scalar>();
  m.V(2, 1) = std::numeric_limits<Scalar>::quiet_NaN();
  return m;
}

/// An octahedron whose face 3 refers to vertex 6 (out of range).
template <class Scalar = double>
triangle_mesh<Scalar> with_bad_index() {
  auto m = octahedron<Scalar>();
  m.F(3, 1) = 6;
  return m;
}

/// Closed genus-0 meshes for algorithms that need a sphere.
template <class Scalar = double>
std::vector<triangle_mesh<Scalar>> closed_genus0_meshes() {
  return {tetrahedron<Scalar>(), octahedron<Scalar>(), make_icosphere<Scalar>(2)};
}

/// The mesh without the listed faces (vertices kept): holes built to order.
inline triangle_mesh<double> without_faces(const triangle_mesh<double>& m, const std::vector<index_t>& drop) {
  triangle_mesh<double> out;
  out.V = m.V;
  out.F.resize(m.F.rows() - static_cast<index_t>(drop.size()), 3);
  index_t g = 0;
  for (index_t f = 0; f < m.F.rows(); ++f)
    if (std::find(drop.begin(), drop.end(), f) == drop.end()) out.F.row(g++) = m.F.row(f);
  return out;
}

}  // namespace shapestruct::test
