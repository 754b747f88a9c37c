// SPDX-License-Identifier: MIT
// creature: a generated genus-0 articulated shape with its exact ground truth (common-domain coordinates,
// part labels, left-right symmetry, landmarks).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "shapestruct/core/surface_point.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/generate/feature_point.hpp"

namespace shapestruct {

/// A point of the creatures' common domain: a *patch* (a quad of the full creature template, see
/// docs/synthetic_collections.md) and bilinear coordinates (u, v) in [0, 1]^2 inside it. Two creatures of
/// one generator that both have the patch describe anatomically the same place at the same (patch, u, v).
struct canonical_point {
  index_t patch = no_index;
  double u = 0.0;
  double v = 0.0;
  [[nodiscard]] bool valid() const noexcept { return patch != no_index; }
};

/// Coarse semantic part of a creature face (the `.seg` labels). Stable ids, names in creature_part_names.
enum class creature_part : int { torso = 0, head = 1, leg = 2, arm = 3, tail = 4 };
inline constexpr std::array<const char*, 5> creature_part_names = {"torso", "head", "leg", "arm", "tail"};

/// Limb slots of the full template. A creature has the head always, legs in left/right pairs (1-3 pairs),
/// arms as a pair or not at all, and a tail or not. Left is -X (the creature faces -Z with +Y up).
enum class creature_slot : int {
  head = 0,
  tail = 1,
  leg_front_left = 2,
  leg_front_right = 3,
  leg_middle_left = 4,
  leg_middle_right = 5,
  leg_back_left = 6,
  leg_back_right = 7,
  arm_left = 8,
  arm_right = 9,
};
inline constexpr int creature_slot_count = 10;
/// Landmark name of each slot's tip (the centre of the limb's end patch).
inline constexpr std::array<const char*, creature_slot_count> creature_slot_tip_names = {
    "nose", "tail_tip", "foot_front_left", "foot_front_right", "foot_middle_left", "foot_middle_right",
    "foot_back_left", "foot_back_right", "hand_left", "hand_right"};

/// A generated creature. All per-vertex arrays have mesh.num_vertices() entries, per-face arrays
/// mesh.num_faces() entries.
template <class Scalar = double>
struct creature {
  triangle_mesh<Scalar> mesh;             ///< posed surface: closed, genus 0, manifold, outward-oriented
  matrix_x3<Scalar> rest_positions;       ///< the same vertices in the symmetric rest pose (same F)
  std::vector<canonical_point> canonical; ///< per vertex: its common-domain coordinates
  std::vector<index_t> face_patch;        ///< per face: the patch containing it
  Eigen::Matrix<double, Eigen::Dynamic, 6> face_uv;  ///< per face: (u, v) of its 3 corners in its patch
  std::vector<int> face_labels;           ///< per face: creature_part id
  std::vector<surface_point<Scalar>> symmetry;  ///< per vertex: its left-right mirror image on this mesh
  std::vector<index_t> symmetry_vertex;   ///< per vertex: the vertex nearest its mirror image
  std::vector<feature_point<Scalar>> features;  ///< limb tips, snapped to vertices
  std::array<bool, creature_slot_count> has_slot{};  ///< which limbs this creature has
  int resolution = 0;                     ///< grid cells per patch side used for the triangulation
};

}  // namespace shapestruct
