// SPDX-License-Identifier: MIT
// map_creatures: the exact dense ground-truth map between two creatures of one generator.
#pragma once

#include <string>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/surface_point.hpp"
#include "shapestruct/generate/creature.hpp"
#include "shapestruct/generate/creature_locator.hpp"

namespace shapestruct {

/// A dense vertex-to-surface map from a source creature to a target creature.
template <class Scalar = double>
struct creature_map {
  std::vector<surface_point<Scalar>> points;  ///< per source vertex: target face + barycentric, or invalid
  std::vector<index_t> nearest_vertex;        ///< per source vertex: target vertex nearest the image, or -1
  index_t unmapped = 0;                       ///< source vertices on body parts the target lacks
};

/// The ground-truth map from `source` to `target` (two creatures of the same creature_generator): each
/// source vertex goes to the target point with the same common-domain coordinates (patch, u, v). Source
/// vertices on a patch the target does not have (a limb it lacks, or the torso spot where the target has a
/// limb) map to an invalid surface_point and nearest_vertex -1.
/// \param source, target creatures from the same generator (same template); any seeds, poses, triangulations
/// \throws invalid_input (size_mismatch) if a creature's ground-truth arrays do not match its mesh.
/// \returns the map; O(V_source * faces per patch of the target).
template <class Scalar>
[[nodiscard]] creature_map<Scalar> map_creatures(const creature<Scalar>& source, const creature<Scalar>& target) {
  if (static_cast<index_t>(source.canonical.size()) != source.mesh.num_vertices())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "map_creatures: the source's canonical coordinates must have one entry per vertex (" +
                            std::to_string(source.mesh.num_vertices()) + ")");
  const creature_locator<Scalar> loc(target);
  creature_map<Scalar> out;
  out.points.reserve(source.canonical.size());
  out.nearest_vertex.reserve(source.canonical.size());
  for (const auto& cp : source.canonical) {
    const auto sp = loc.locate(cp);
    out.points.push_back(sp);
    out.nearest_vertex.push_back(sp.valid() ? sp.nearest_corner(target.mesh.F) : no_index);
    if (!sp.valid()) ++out.unmapped;
  }
  return out;
}

}  // namespace shapestruct
