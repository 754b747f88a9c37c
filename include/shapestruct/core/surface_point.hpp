// SPDX-License-Identifier: MIT
// surface_point: a point on a triangle mesh as a face and barycentric coordinates.
#pragma once

#include <Eigen/Core>

#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// A point on a triangle mesh: face index and barycentric weights of the face's three corners (they sum to 1).
/// `face == no_index` marks "no point" (e.g. an unmapped vertex).
template <class Scalar = double>
struct surface_point {
  index_t face = no_index;
  vec3<Scalar> bary = vec3<Scalar>::Zero();

  [[nodiscard]] bool valid() const noexcept { return face != no_index; }

  /// Position of the point on the mesh (V, F).
  template <class DerivedV, class DerivedF>
  [[nodiscard]] vec3<Scalar> position(const Eigen::MatrixBase<DerivedV>& V, const Eigen::MatrixBase<DerivedF>& F) const {
    vec3<Scalar> p = vec3<Scalar>::Zero();
    for (int k = 0; k < 3; ++k) p += bary[k] * V.row(F(face, k)).transpose().template cast<Scalar>();
    return p;
  }

  /// The corner of the face with the largest barycentric weight: the nearest vertex in the face.
  template <class DerivedF>
  [[nodiscard]] index_t nearest_corner(const Eigen::MatrixBase<DerivedF>& F) const {
    int best = 0;
    for (int k = 1; k < 3; ++k)
      if (bary[k] > bary[best]) best = k;
    return static_cast<index_t>(F(face, best));
  }
};

}  // namespace shapestruct
