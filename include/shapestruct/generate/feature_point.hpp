// SPDX-License-Identifier: MIT
// feature_point: a named landmark of a synthetic shape (a leg tip, a wing tip, the nose), snapped to a vertex.
#pragma once

#include <string>

#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// A named landmark on a generated shape. `position` lies on the surface and equals the position of
/// `vertex` (generators snap landmarks to a mesh vertex so that vertex-based methods can use them directly).
template <class Scalar = double>
struct feature_point {
  std::string name;                                  ///< e.g. "nose", "foot_front_left", "seat_front_left"
  vec3<Scalar> position = vec3<Scalar>::Zero();      ///< on the surface
  index_t vertex = no_index;                         ///< the mesh vertex at `position`
};

}  // namespace shapestruct
