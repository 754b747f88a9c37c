// SPDX-License-Identifier: MIT
// no_refinement: the MapRefiner that returns the map it is given.
#pragma once

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/maps/surface_map.hpp"

namespace shapestruct {

/// Leaves the map as it is: plug it into a matcher to switch refinement off at compile time.
struct no_refinement {
  template <class Scalar>
  [[nodiscard]] surface_map<Scalar> refine(const triangle_mesh<Scalar>&, const triangle_mesh<Scalar>&,
                                           const surface_map<Scalar>& map, int /*threads*/) const {
    return map;
  }
};

}  // namespace shapestruct
