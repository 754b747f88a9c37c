// SPDX-License-Identifier: MIT
// Test shapes for extrinsic alignment: unions of boxes, and an upright shape with no symmetry about its up axis.
#pragma once

#include <initializer_list>
#include <utility>

#include <Eigen/Core>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

namespace shapestruct::test {

/// A union of axis-aligned boxes given as (centre, half extents), as one mesh (the boxes overlap; the sampler
/// does not mind).
inline triangle_mesh<double> box_union(std::initializer_list<std::pair<Eigen::Vector3d, Eigen::Vector3d>> boxes) {
  triangle_mesh<double> out;
  out.V.resize(0, 3);
  out.F.resize(0, 3);
  for (const auto& [centre, half] : boxes) {
    const triangle_mesh<double> b = make_box(half.x(), half.y(), half.z());
    const index_t v0 = out.V.rows(), f0 = out.F.rows();
    out.V.conservativeResize(v0 + b.V.rows(), 3);
    out.F.conservativeResize(f0 + b.F.rows(), 3);
    out.V.bottomRows(b.V.rows()) = b.V.rowwise() + centre.transpose();
    out.F.bottomRows(b.F.rows()) = b.F.array() + v0;
  }
  return out;
}

/// An upright (+y) shape with no rotational symmetry about y and no mirror symmetry: a long base slab, a tower
/// at its +x end and an arm sticking out towards +z near its -x end. Its vertices are the boxes' 24 corners, two
/// pairs of which coincide (where the tower stands on the slab's edge).
inline triangle_mesh<double> asymmetric_shape() {
  return box_union({{Eigen::Vector3d(0, 0.1, 0), Eigen::Vector3d(1.0, 0.1, 0.4)},
                    {Eigen::Vector3d(0.8, 0.8, 0), Eigen::Vector3d(0.2, 0.6, 0.4)},
                    {Eigen::Vector3d(-0.7, 0.35, 0.55), Eigen::Vector3d(0.15, 0.15, 0.3)}});
}

}  // namespace shapestruct::test
