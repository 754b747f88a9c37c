// SPDX-License-Identifier: MIT
// MapRefiner: improves a dense map between two meshes (the optional last stage of a pairwise matcher).
#pragma once

#include <concepts>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/maps/surface_map.hpp"

namespace shapestruct {

/// A refiner takes a map from the vertices of `a` to the surface of `b` (both in the meshes' own numbering,
/// `nearest` filled) and returns a map of the same size, using `threads` std::threads (0 = all cores).
/// Models: zoomout_refiner (refine/), no_refinement (refine/), and any user type with a conforming `refine`.
template <class R, class Scalar = double>
concept MapRefiner = requires(const R& r, const triangle_mesh<Scalar>& a, const triangle_mesh<Scalar>& b,
                              const surface_map<Scalar>& map, int threads) {
  { r.refine(a, b, map, threads) } -> std::same_as<surface_map<Scalar>>;
};

}  // namespace shapestruct
