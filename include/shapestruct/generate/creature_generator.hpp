// SPDX-License-Identifier: MIT
// creature_generator: procedural genus-0 articulated creatures with dense ground truth between any two.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shapestruct/config.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/generate/catmull_clark_patches.hpp"
#include "shapestruct/generate/creature.hpp"
#include "shapestruct/generate/creature_locator.hpp"
#include "shapestruct/generate/shape_rng.hpp"

namespace shapestruct {

/// Options of creature_generator. Ranges are inclusive; every option is validated by the constructor.
struct creature_options {
  int min_leg_pairs = 1;             ///< legs come in left/right pairs; 1..3 pairs (2, 4 or 6 legs)
  int max_leg_pairs = 3;
  double arm_probability = 0.3;      ///< chance of a pair of arms at the front of the torso
  double tail_probability = 0.6;     ///< chance of a tail
  int min_resolution = 3;            ///< grid cells per patch side (triangulation density), 2..16
  int max_resolution = 5;
  double jitter = 0.25;              ///< tangential vertex jitter, as a fraction of a grid cell, in [0, 0.4]
  double flip_fraction = 0.15;       ///< fraction of patch-interior edges randomly flipped, in [0, 1]
  double pose_variation = 1.0;       ///< scales joint-angle deviation from the rest pose, in [0, 1.5]; above 1
                                     ///< rare self-intersections occur (3 in 400 creatures at 1.5)
  int subdivision_levels = 3;        ///< Catmull-Clark levels of the reference surface, 1..5
  unsigned threads = 0;              ///< for generate_range: 0 = all cores
};

namespace detail::creature_impl {

inline constexpr int nx = 3, ny = 2, nz = 5;  // torso cage cells along x (width), y (height), z (length)
inline constexpr int rings = 4;               // cross-section rings per limb
inline constexpr int patches_per_slot = 4 * rings + 1;

/// The full creature template: the torso box cage plus all ten limb extrusions, with fixed ids.
struct cage_template {
  int torso_vertices = 0;
  int torso_patches = 0;
  std::vector<std::array<index_t, 4>> quads;  // every patch of the full template, ccw from outside
  std::vector<int> part;                      // creature_part per patch
  std::vector<int> slot;                      // owning slot, -1 for plain torso patches
  std::vector<bool> is_base;                  // torso quad that a present limb replaces
  std::array<index_t, creature_slot_count> base{};
  std::vector<Eigen::Vector3i> lattice;       // lattice coordinates of torso vertices
  int vertex_count = 0;

  [[nodiscard]] index_t ring_vertex(int s, int r, int k) const {  // r in 1..rings, k in 0..3
    return torso_vertices + s * 4 * rings + (r - 1) * 4 + k;
  }
  [[nodiscard]] index_t limb_patch(int s, int r, int e) const {  // side quad between ring r-1 and r
    return torso_patches + s * patches_per_slot + (r - 1) * 4 + e;
  }
  [[nodiscard]] index_t cap_patch(int s) const { return torso_patches + s * patches_per_slot + 4 * rings; }
};

inline int slot_part(int s) {
  if (s == 0) return static_cast<int>(creature_part::head);
  if (s == 1) return static_cast<int>(creature_part::tail);
  if (s >= 8) return static_cast<int>(creature_part::arm);
  return static_cast<int>(creature_part::leg);
}

inline cage_template make_template() {
  cage_template t;
  std::map<std::array<int, 3>, index_t> id;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        if (i == 0 || i == nx || j == 0 || j == ny || k == 0 || k == nz) {
          id[{i, j, k}] = static_cast<index_t>(t.lattice.size());
          t.lattice.emplace_back(i, j, k);
        }
  t.torso_vertices = static_cast<int>(t.lattice.size());
  // side_quads[{axis, at_max, b, c}] = patch id, b/c the cell indices along the two other axes (cyclic order).
  std::map<std::array<int, 4>, index_t> side_quad;
  const int n[3] = {nx, ny, nz};
  for (int axis = 0; axis < 3; ++axis) {
    const int ab = (axis + 1) % 3, ac = (axis + 2) % 3;  // e_ab x e_ac = +e_axis
    for (int at_max = 0; at_max < 2; ++at_max)
      for (int c = 0; c < n[ac]; ++c)
        for (int b = 0; b < n[ab]; ++b) {
          std::array<index_t, 4> q{};
          const int corner[4][2] = {{b, c}, {b + 1, c}, {b + 1, c + 1}, {b, c + 1}};
          for (int m = 0; m < 4; ++m) {
            std::array<int, 3> l{};
            l[static_cast<std::size_t>(axis)] = at_max ? n[axis] : 0;
            l[static_cast<std::size_t>(ab)] = corner[m][0];
            l[static_cast<std::size_t>(ac)] = corner[m][1];
            q[static_cast<std::size_t>(m)] = id.at(l);
          }
          if (!at_max) std::swap(q[1], q[3]);  // outward is -e_axis: reverse, keeping corner 0
          side_quad[{axis, at_max, b, c}] = static_cast<index_t>(t.quads.size());
          t.quads.push_back(q);
          t.part.push_back(static_cast<int>(creature_part::torso));
          t.slot.push_back(-1);
          t.is_base.push_back(false);
        }
  }
  t.torso_patches = static_cast<int>(t.quads.size());
  // Base quads. Axis 2 (z) side cells are (x, y); axis 1 (y) cells are (z, x); axis 0 (x) cells are (y, z).
  t.base[0] = side_quad.at({2, 0, 1, 1});  // head: front (-z), middle column, upper row
  t.base[1] = side_quad.at({2, 1, 1, 1});  // tail: back (+z), middle column, upper row
  const int leg_rows[3] = {0, 2, 4};
  for (int p = 0; p < 3; ++p) {
    t.base[static_cast<std::size_t>(2 + 2 * p)] = side_quad.at({1, 0, leg_rows[p], 0});       // left: x cell 0
    t.base[static_cast<std::size_t>(3 + 2 * p)] = side_quad.at({1, 0, leg_rows[p], nx - 1});  // right
  }
  t.base[8] = side_quad.at({0, 0, 1, 0});  // left arm: -x side, upper row, front cell
  t.base[9] = side_quad.at({0, 1, 1, 0});  // right arm
  for (int s = 0; s < creature_slot_count; ++s) {
    const auto b = static_cast<std::size_t>(t.base[static_cast<std::size_t>(s)]);
    t.is_base[b] = true;
    t.slot[b] = s;
  }
  for (int s = 0; s < creature_slot_count; ++s) {
    // A copy, not a reference: the push_backs below reallocate t.quads.
    const std::array<index_t, 4> bq = t.quads[static_cast<std::size_t>(t.base[static_cast<std::size_t>(s)])];
    for (int r = 1; r <= rings; ++r)
      for (int e = 0; e < 4; ++e) {
        const auto lo = [&](int k) { return r == 1 ? bq[static_cast<std::size_t>(k)] : t.ring_vertex(s, r - 1, k); };
        const int e1 = (e + 1) % 4;
        t.quads.push_back({lo(e), lo(e1), t.ring_vertex(s, r, e1), t.ring_vertex(s, r, e)});
        t.part.push_back(slot_part(s));
        t.slot.push_back(s);
        t.is_base.push_back(false);
      }
    t.quads.push_back({t.ring_vertex(s, rings, 0), t.ring_vertex(s, rings, 1), t.ring_vertex(s, rings, 2),
                       t.ring_vertex(s, rings, 3)});
    t.part.push_back(slot_part(s));
    t.slot.push_back(s);
    t.is_base.push_back(false);
  }
  t.vertex_count = t.torso_vertices + creature_slot_count * 4 * rings;
  return t;
}

/// Size and shape of one limb (shared by a left/right pair so that the rest pose is symmetric).
struct limb_shape {
  double l1 = 0, l2 = 0;              // upper / lower segment (head: neck length / head radius)
  std::array<double, rings> radius{};  // cross-section "radius" (centre to cage corner) per ring
};
/// Joint angles of one limb (radians).
struct limb_pose {
  double swing = 0, bend = 0, yaw = 0;
};

/// Everything that defines a creature's geometry.
struct body {
  double width = 0.42, height = 0.34, length = 1.05, splay = 0.15;
  double taper_width = 0, taper_height = 0;  // relative change of width / height from the middle to the back
  std::array<bool, creature_slot_count> present{};
  std::array<limb_shape, creature_slot_count> shape{};
  std::array<limb_pose, creature_slot_count> rest{}, pose{};
};

inline Eigen::Matrix3d rot(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// The smallest rotation taking unit vector a to unit vector b (limbs never point back into the torso, so
/// the antiparallel case only needs to be well defined, not smooth).
inline Eigen::Matrix3d min_rotation(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d axis = a.cross(b);
  const double s = axis.norm(), c = a.dot(b);
  if (s < 1e-12) {
    if (c > 0) return Eigen::Matrix3d::Identity();
    const Eigen::Vector3d perp = std::abs(a.x()) < 0.9 ? a.cross(Eigen::Vector3d::UnitX()) : a.cross(Eigen::Vector3d::UnitY());
    return rot(perp, std::acos(-1.0));
  }
  return rot(axis, std::atan2(s, c));
}

/// Cage vertex positions of `b` in its rest pose or its actual pose. Left limbs are built as the mirror
/// image of a right limb with the same parameters, so equal parameters give an exactly symmetric pair.
inline std::vector<Eigen::Vector3d> cage_positions(const cage_template& t, const body& b, bool rest_pose) {
  std::vector<Eigen::Vector3d> X(static_cast<std::size_t>(t.vertex_count), Eigen::Vector3d::Zero());
  for (int v = 0; v < t.torso_vertices; ++v) {
    const Eigen::Vector3i& l = t.lattice[static_cast<std::size_t>(v)];
    const Eigen::Vector3d box(2.0 * l.x() / nx - 1.0, 2.0 * l.y() / ny - 1.0, 2.0 * l.z() / nz - 1.0);
    // Halfway between the box and its projection on the sphere: a rounded box, so that Catmull-Clark gives
    // an egg-shaped torso with flat-enough quads for the limbs to attach to.
    const Eigen::Vector3d p = 0.55 * box + 0.45 * box.normalized();
    // Tapering scales x and y by a function of z only, so the torso stays mirror-symmetric in x.
    const double zn = box.z();
    X[static_cast<std::size_t>(v)] = Eigen::Vector3d(b.width * (1 + b.taper_width * zn) * p.x(),
                                                     b.height * (1 + b.taper_height * zn) * p.y(), b.length * p.z());
  }
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ey = Eigen::Vector3d::UnitY();
  const Eigen::Matrix3d M = Eigen::Vector3d(-1, 1, 1).asDiagonal();
  for (int s = 0; s < creature_slot_count; ++s) {
    if (!b.present[static_cast<std::size_t>(s)]) continue;
    const bool left = (s >= 2 && s % 2 == 0);  // legs 2, 4, 6 and arm 8 are left
    const Eigen::Matrix3d F = left ? M : Eigen::Matrix3d::Identity();  // into / out of the right-side frame
    const auto& bq = t.quads[static_cast<std::size_t>(t.base[static_cast<std::size_t>(s)])];
    Eigen::Vector3d q[4];
    for (int k = 0; k < 4; ++k) q[k] = F * X[static_cast<std::size_t>(bq[static_cast<std::size_t>(k)])];
    const Eigen::Vector3d c0 = 0.25 * (q[0] + q[1] + q[2] + q[3]);
    // Mirroring reverses orientation, so the outward normal of the mirrored quad is minus the cross product.
    Eigen::Vector3d n0 = (q[2] - q[0]).cross(q[3] - q[1]).normalized();
    if (left) n0 = -n0;
    Eigen::Vector3d dir[4];
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d d = q[k] - c0;
      dir[k] = (d - d.dot(n0) * n0).normalized();
    }
    const limb_shape& sh = b.shape[static_cast<std::size_t>(s)];
    const limb_pose& po = rest_pose ? b.rest[static_cast<std::size_t>(s)] : b.pose[static_cast<std::size_t>(s)];
    std::array<Eigen::Vector3d, rings> P, T;
    if (s == 0) {  // head: neck, then a round head pitched by `bend`
      const Eigen::Vector3d d0 = Eigen::Vector3d(0, 0.6, -1).normalized();
      const Eigen::Vector3d d1 = rot(ey, po.yaw) * rot(ex, po.swing) * d0;
      const Eigen::Vector3d d2 = rot(rot(ey, po.yaw) * ex, po.bend) * d1;
      P[0] = c0 + 0.4 * sh.l1 * d1;
      P[1] = c0 + sh.l1 * d1;
      P[2] = P[1] + 1.0 * sh.l2 * d2;
      P[3] = P[1] + 2.1 * sh.l2 * d2;
      T = {d1, (d1 + d2).normalized(), d2, d2};
    } else if (s == 1) {  // tail: four segments curling by bend/4 (pitch) and yaw/4 each
      Eigen::Vector3d d = rot(ex, po.swing) * Eigen::Vector3d(0, 0.35, 1).normalized();
      Eigen::Vector3d p = c0;
      for (int r = 0; r < rings; ++r) {
        p += 0.25 * sh.l1 * d;
        P[static_cast<std::size_t>(r)] = p;
        T[static_cast<std::size_t>(r)] = d;
        d = rot(ey, 0.25 * po.yaw) * rot(ex, 0.25 * po.bend) * d;
      }
    } else {  // legs and arms: two segments with a knee / elbow
      const bool arm = s >= 8;
      const Eigen::Vector3d d0 =
          arm ? Eigen::Vector3d(1, -0.7, -0.3).normalized() : Eigen::Vector3d(b.splay, -1, 0).normalized();
      const Eigen::Vector3d axis = arm ? d0.cross(ey).normalized() : ex;
      const Eigen::Vector3d d1 = rot(axis, po.swing) * d0;
      const Eigen::Vector3d d2 = rot(axis, po.bend) * d1;
      const Eigen::Vector3d knee = c0 + sh.l1 * d1;
      P = {c0 + 0.3 * sh.l1 * d1, knee, knee + 0.55 * sh.l2 * d2, knee + sh.l2 * d2};
      T = {d1, (d1 + d2).normalized(), d2, d2};
    }
    for (int r = 0; r < rings; ++r) {
      const Eigen::Matrix3d R = min_rotation(n0, T[static_cast<std::size_t>(r)]);
      for (int k = 0; k < 4; ++k)
        X[static_cast<std::size_t>(t.ring_vertex(s, r + 1, k))] =
            F * (P[static_cast<std::size_t>(r)] + sh.radius[static_cast<std::size_t>(r)] * (R * dir[k]));
    }
  }
  return X;
}

/// Samples a body from the shape stream. Pairs share shape and rest pose; each limb gets its own pose.
inline body sample_body(shape_rng& rng, const creature_options& o) {
  body b;
  b.width = rng.uniform(0.36, 0.5);
  b.height = rng.uniform(0.28, 0.4);
  const int pairs = rng.integer(o.min_leg_pairs, o.max_leg_pairs);
  // Six legs need a longer torso so that swung legs of neighbouring rows cannot touch.
  b.length = pairs == 3 ? rng.uniform(1.05, 1.35) : rng.uniform(0.85, 1.3);
  b.splay = rng.uniform(0.05, 0.3);
  b.taper_width = rng.uniform(-0.2, 0.2);
  b.taper_height = rng.uniform(-0.2, 0.2);
  b.present[0] = true;
  b.present[1] = rng.chance(o.tail_probability);
  const bool rows[3] = {pairs >= 2, pairs != 2, pairs >= 2};  // 1 pair: middle; 2: front+back; 3: all
  for (int p = 0; p < 3; ++p) b.present[static_cast<std::size_t>(2 + 2 * p)] = b.present[static_cast<std::size_t>(3 + 2 * p)] = rows[p];
  b.present[8] = b.present[9] = rng.chance(o.arm_probability);
  const double v = o.pose_variation;
  // Head.
  {
    limb_shape& h = b.shape[0];
    h.l1 = rng.uniform(0.15, 0.3);
    h.l2 = rng.uniform(0.14, 0.22);
    const double neck = rng.uniform(0.08, 0.11);
    h.radius = {neck, 0.9 * neck, 1.25 * h.l2, 0.7 * h.l2};
    // Pitch limits keep the head bulb off the chest: a short neck and a head bent down by more than about
    // 0.7 rad made the head touch the torso (1 creature in 400 before these bounds).
    b.rest[0] = {0.0, rng.uniform(-0.4, -0.05), 0.0};
    b.pose[0] = {v * rng.uniform(-0.25, 0.25), b.rest[0].bend + v * rng.uniform(-0.25, 0.25), v * rng.uniform(-0.5, 0.5)};
  }
  // Tail.
  {
    limb_shape& tl = b.shape[1];
    tl.l1 = rng.uniform(0.4, 0.85);
    const double r0 = rng.uniform(0.08, 0.12);
    tl.radius = {r0, 0.75 * r0, 0.55 * r0, 0.4 * r0};
    b.rest[1] = {0.0, rng.uniform(-0.6, 0.3), 0.0};
    b.pose[1] = {v * rng.uniform(-0.3, 0.3), b.rest[1].bend + v * rng.uniform(-0.6, 0.6), v * rng.uniform(-0.8, 0.8)};
  }
  // Legs and arms, by pairs.
  for (int s = 2; s < creature_slot_count; s += 2) {
    const bool arm = s >= 8;
    limb_shape sh;
    sh.l1 = arm ? rng.uniform(0.2, 0.32) : rng.uniform(0.3, 0.5);
    sh.l2 = arm ? rng.uniform(0.2, 0.32) : rng.uniform(0.3, 0.5);
    const double r0 = arm ? rng.uniform(0.06, 0.085) : rng.uniform(0.085, 0.12);
    sh.radius = {r0, 0.8 * r0, 0.72 * r0, 0.62 * r0};
    const double rest_bend = arm ? rng.uniform(0.2, 0.7) : rng.uniform(-0.45, -0.1);
    for (int side = 0; side < 2; ++side) {
      const auto i = static_cast<std::size_t>(s + side);
      b.shape[i] = sh;
      b.rest[i] = {0.0, rest_bend, 0.0};
      const double swing = arm ? 0.4 : 0.25, bend = arm ? 0.5 : 0.35;
      b.pose[i] = {v * rng.uniform(-swing, swing), rest_bend + v * rng.uniform(-bend, bend), 0.0};
    }
  }
  return b;
}

/// The mean body with every limb: the canonical creature.
inline body canonical_body() {
  body b;
  b.present.fill(true);
  b.shape[0].l1 = 0.21;
  b.shape[0].l2 = 0.18;
  b.shape[0].radius = {0.095, 0.0855, 0.225, 0.126};
  b.rest[0] = {0.0, -0.3, 0.0};
  b.shape[1].l1 = 0.62;
  b.shape[1].radius = {0.1, 0.075, 0.055, 0.04};
  b.rest[1] = {0.0, -0.15, 0.0};
  for (int s = 2; s < creature_slot_count; ++s) {
    const bool arm = s >= 8;
    b.shape[static_cast<std::size_t>(s)].l1 = b.shape[static_cast<std::size_t>(s)].l2 = arm ? 0.26 : 0.4;
    const double r0 = arm ? 0.0725 : 0.1;
    b.shape[static_cast<std::size_t>(s)].radius = {r0, 0.8 * r0, 0.72 * r0, 0.62 * r0};
    b.rest[static_cast<std::size_t>(s)] = {0.0, arm ? 0.45 : -0.27, 0.0};
  }
  b.length = 1.2;  // long enough for six legs
  b.pose = b.rest;
  return b;
}

}  // namespace detail::creature_impl

/// Generates genus-0 articulated creatures (torso, head, 2/4/6 legs, optional arms and tail) with varied
/// proportions, pose and triangulation, and their exact ground truth.
///
/// Construction: every creature is a subset of one quad *template* (a 3x2x5 torso box cage and ten limb
/// extrusions of 4 rings each, one per slot); absent limbs keep their torso base quad. The cage of a creature
/// is placed by its body parameters (limbs skinned along a two-segment skeleton with joint angles), and
/// Catmull-Clark subdivided; each template quad ("patch") thereby becomes a smooth bilinear grid, the
/// reference surface. The output mesh samples each patch on an n x n grid (n random per creature), jitters
/// the samples in (u, v), splits cells along random diagonals and flips random edges inside patches.
/// Every vertex keeps its (patch, u, v), so ground truth between any two creatures is point location in
/// the shared domain (map_creatures), and the left-right symmetry is a fixed patch permutation.
///
/// Shape i depends only on (seed, i): body parameters and triangulation use separate streams, and
/// `triangulation_variant` re-triangulates the same body.
template <class Scalar = double>
class creature_generator {
 public:
  /// \throws invalid_input (bad_parameter) naming the option if an option is out of its documented range.
  explicit creature_generator(std::uint64_t seed, creature_options options = {})
      : seed_(seed), o_(options), t_(detail::creature_impl::make_template()) {
    const auto bad = [](const char* what) {
      throw invalid_input(input_error::bad_parameter, no_index, std::string("creature_generator: ") + what);
    };
    if (o_.min_leg_pairs < 1 || o_.max_leg_pairs > 3 || o_.min_leg_pairs > o_.max_leg_pairs)
      bad("need 1 <= min_leg_pairs <= max_leg_pairs <= 3");
    if (!(o_.arm_probability >= 0 && o_.arm_probability <= 1)) bad("arm_probability must be in [0, 1]");
    if (!(o_.tail_probability >= 0 && o_.tail_probability <= 1)) bad("tail_probability must be in [0, 1]");
    if (o_.min_resolution < 2 || o_.max_resolution > 16 || o_.min_resolution > o_.max_resolution)
      bad("need 2 <= min_resolution <= max_resolution <= 16");
    if (!(o_.jitter >= 0 && o_.jitter <= 0.4)) bad("jitter must be in [0, 0.4] (larger could fold cells)");
    if (!(o_.flip_fraction >= 0 && o_.flip_fraction <= 1)) bad("flip_fraction must be in [0, 1]");
    if (!(o_.pose_variation >= 0 && o_.pose_variation <= 1.5))
      bad("pose_variation must be in [0, 1.5] (larger poses can self-intersect)");
    if (o_.subdivision_levels < 1 || o_.subdivision_levels > 5) bad("subdivision_levels must be in [1, 5]");
    build_mirror();
  }

  /// Creature `index` of the collection. O(patches * (4^subdivision_levels + resolution^2)).
  /// \param index                shape number; the result depends only on (seed, index, variant)
  /// \param triangulation_variant 0 for the collection's triangulation; other values give the same body
  ///                             (same reference surface and pose) with a different triangulation
  [[nodiscard]] creature<Scalar> generate(std::uint64_t index, std::uint64_t triangulation_variant = 0) const {
    shape_rng body_rng("creatures", seed_, index, 0);
    const auto b = detail::creature_impl::sample_body(body_rng, o_);
    shape_rng tri_rng("creatures", seed_, index, 1 + triangulation_variant);
    const int n = tri_rng.integer(o_.min_resolution, o_.max_resolution);
    return build(b, tri_rng, n, o_.jitter, o_.flip_fraction);
  }

  /// The canonical creature: mean proportions, all ten limbs, rest pose, regular max_resolution grid.
  /// Its (patch, u, v) coordinates are what `.corr` files refer to.
  [[nodiscard]] creature<Scalar> canonical() const {
    shape_rng rng("creatures-canonical", 0, 0, 0);
    return build(detail::creature_impl::canonical_body(), rng, o_.max_resolution, 0.0, 0.0);
  }

  /// Creatures first .. first+count-1 on `threads` threads (0 = options.threads, whose 0 = all cores).
  /// The result does not depend on the thread count: shape i only depends on (seed, i).
  [[nodiscard]] std::vector<creature<Scalar>> generate_range(std::uint64_t first, std::size_t count,
                                                             unsigned threads = 0) const {
    std::vector<creature<Scalar>> out(count);
    const unsigned nt = threads ? threads : o_.threads ? o_.threads : detail::resolve_threads(0);
    detail::parallel_for(count, nt, [&](std::size_t i) { out[i] = generate(first + i); });
    return out;
  }

  /// Number of patches of the full template (patch ids are in [0, patch_count())).
  [[nodiscard]] index_t patch_count() const noexcept { return static_cast<index_t>(t_.quads.size()); }
  /// creature_part of a patch.
  [[nodiscard]] creature_part patch_part(index_t p) const {
    return static_cast<creature_part>(t_.part.at(static_cast<std::size_t>(p)));
  }
  /// The left-right mirror image of a common-domain point (an involution).
  [[nodiscard]] canonical_point mirror(const canonical_point& c) const {
    if (!c.valid()) return c;
    const auto p = static_cast<std::size_t>(c.patch);
    const double w[4] = {(1 - c.u) * (1 - c.v), c.u * (1 - c.v), c.u * c.v, (1 - c.u) * c.v};
    static constexpr double cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
    canonical_point out{mirror_patch_[p], 0.0, 0.0};
    for (int k = 0; k < 4; ++k) {
      out.u += w[k] * cu[mirror_corner_[p][static_cast<std::size_t>(k)]];
      out.v += w[k] * cv[mirror_corner_[p][static_cast<std::size_t>(k)]];
    }
    return out;
  }
  [[nodiscard]] const creature_options& options() const noexcept { return o_; }
  [[nodiscard]] std::uint64_t seed() const noexcept { return seed_; }

 private:
  using body = detail::creature_impl::body;

  void build_mirror() {
    const auto b = detail::creature_impl::canonical_body();
    const auto X = detail::creature_impl::cage_positions(t_, b, true);
    std::vector<index_t> mv(X.size(), no_index);
    for (std::size_t i = 0; i < X.size(); ++i) {
      const Eigen::Vector3d m(-X[i].x(), X[i].y(), X[i].z());
      double best = 1e300;
      for (std::size_t j = 0; j < X.size(); ++j) {
        const double d = (X[j] - m).squaredNorm();
        if (d < best) best = d, mv[i] = static_cast<index_t>(j);
      }
      SHAPESTRUCT_ASSERT(best < 1e-18, "creature template is not mirror-symmetric");
    }
    std::map<std::array<index_t, 4>, index_t> by_set;
    for (std::size_t p = 0; p < t_.quads.size(); ++p) {
      auto s = t_.quads[p];
      std::sort(s.begin(), s.end());
      by_set[s] = static_cast<index_t>(p);
    }
    mirror_patch_.resize(t_.quads.size());
    mirror_corner_.resize(t_.quads.size());
    for (std::size_t p = 0; p < t_.quads.size(); ++p) {
      std::array<index_t, 4> m{};
      for (int k = 0; k < 4; ++k) m[static_cast<std::size_t>(k)] = mv[static_cast<std::size_t>(t_.quads[p][static_cast<std::size_t>(k)])];
      auto s = m;
      std::sort(s.begin(), s.end());
      const index_t q = by_set.at(s);
      mirror_patch_[p] = q;
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
          if (t_.quads[static_cast<std::size_t>(q)][static_cast<std::size_t>(l)] == m[static_cast<std::size_t>(k)])
            mirror_corner_[p][static_cast<std::size_t>(k)] = l;
    }
  }

  creature<Scalar> build(const body& b, shape_rng& rng, int n, double jitter, double flip_fraction) const {
    namespace ci = detail::creature_impl;
    const std::size_t np = t_.quads.size();
    std::vector<bool> active(np, false);
    for (std::size_t p = 0; p < np; ++p) {
      const int s = t_.slot[p];
      if (s < 0) active[p] = true;
      else if (t_.is_base[p]) active[p] = !b.present[static_cast<std::size_t>(s)];
      else active[p] = b.present[static_cast<std::size_t>(s)];
    }
    const auto posed = catmull_clark_patches(ci::cage_positions(t_, b, false), t_.quads, active, o_.subdivision_levels);
    const auto rest = catmull_clark_patches(ci::cage_positions(t_, b, true), t_.quads, active, o_.subdivision_levels);

    // Patches in priority order: a vertex on a patch boundary takes the coordinates of the first patch that
    // creates it. Plain torso patches go first because every creature has them, so boundary vertices of a
    // limb's root ring get coordinates that exist in every other creature too.
    std::vector<index_t> order;
    for (int pass = 0; pass < 3; ++pass)
      for (std::size_t p = 0; p < np; ++p)
        if (active[p] && (t_.slot[p] < 0 ? 0 : t_.is_base[p] ? 1 : 2) == pass) order.push_back(static_cast<index_t>(p));

    creature<Scalar> c;
    c.resolution = n;
    for (int s = 0; s < creature_slot_count; ++s) c.has_slot[static_cast<std::size_t>(s)] = b.present[static_cast<std::size_t>(s)];
    std::vector<index_t> cage_vertex(static_cast<std::size_t>(t_.vertex_count), no_index);
    struct edge_samples {
      index_t first;               // id of the sample nearest the smaller cage vertex
      std::vector<double> t;       // parameters from the smaller cage vertex, increasing
    };
    std::unordered_map<std::uint64_t, edge_samples> edge_map;
    const double cell = 1.0 / n;
    const auto new_vertex = [&](index_t patch, double u, double v) {
      c.canonical.push_back({patch, u, v});
      return static_cast<index_t>(c.canonical.size()) - 1;
    };
    const auto edge_vertex = [&](index_t a, index_t b2, int k, double& param) {
      // k-th of the n-1 inner samples of cage edge a -> b2 counted from a; param = its parameter from a.
      const bool fwd = a < b2;
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b2)) << 32) | static_cast<std::uint64_t>(std::max(a, b2));
      auto it = edge_map.find(key);
      if (it == edge_map.end()) {
        edge_samples e{static_cast<index_t>(c.canonical.size()), {}};
        for (int m = 1; m < n; ++m) e.t.push_back(m * cell + jitter * cell * rng.uniform(-1, 1));
        it = edge_map.emplace(key, std::move(e)).first;
        for (int m = 1; m < n; ++m) c.canonical.push_back({});  // filled by the caller below
      }
      const int m = fwd ? k : n - k;  // index from the smaller vertex
      param = fwd ? it->second.t[static_cast<std::size_t>(m - 1)] : 1.0 - it->second.t[static_cast<std::size_t>(m - 1)];
      return it->second.first + m - 1;
    };
    std::vector<std::array<index_t, 3>> tris;
    std::vector<index_t> tri_patch;
    std::vector<std::array<double, 6>> tri_uv;
    std::vector<index_t> ids(static_cast<std::size_t>((n + 1) * (n + 1)));
    std::vector<double> us(ids.size()), vs(ids.size());
    for (const index_t p : order) {
      const auto& q = t_.quads[static_cast<std::size_t>(p)];
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
          const auto at = static_cast<std::size_t>(j * (n + 1) + i);
          double u = i * cell, v = j * cell;
          index_t id = no_index;
          const bool bi = (i == 0 || i == n), bj = (j == 0 || j == n);
          if (bi && bj) {
            const index_t cv = q[static_cast<std::size_t>(i == 0 ? (j == 0 ? 0 : 3) : (j == 0 ? 1 : 2))];
            auto& slot = cage_vertex[static_cast<std::size_t>(cv)];
            if (slot == no_index) slot = new_vertex(p, u, v);
            id = slot;
          } else if (bj || bi) {
            double t = 0;
            if (j == 0) id = edge_vertex(q[0], q[1], i, t), u = t;
            else if (j == n) id = edge_vertex(q[3], q[2], i, t), u = t;
            else if (i == 0) id = edge_vertex(q[0], q[3], j, t), v = t;
            else id = edge_vertex(q[1], q[2], j, t), v = t;
            // The first (highest-priority) patch to reach a shared edge sample names its coordinates.
            auto& cp = c.canonical[static_cast<std::size_t>(id)];
            if (!cp.valid()) cp = {p, u, v};
          } else {
            u += jitter * cell * rng.uniform(-1, 1);
            v += jitter * cell * rng.uniform(-1, 1);
            id = new_vertex(p, u, v);
          }
          ids[at] = id;
          us[at] = u;
          vs[at] = v;
        }
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const std::size_t a = static_cast<std::size_t>(j * (n + 1) + i), b1 = a + 1,
                            d = a + static_cast<std::size_t>(n + 1), c2 = d + 1;
          const auto push = [&](std::size_t x, std::size_t y, std::size_t z) {
            tris.push_back({ids[x], ids[y], ids[z]});
            tri_patch.push_back(p);
            tri_uv.push_back({us[x], vs[x], us[y], vs[y], us[z], vs[z]});
          };
          if (rng.chance(0.5)) push(a, b1, c2), push(a, c2, d);
          else push(a, b1, d), push(b1, c2, d);
        }
    }
    const index_t nv = static_cast<index_t>(c.canonical.size());
    c.mesh.V.resize(nv, 3);
    c.rest_positions.resize(nv, 3);
    for (index_t v = 0; v < nv; ++v) {
      const auto& cp = c.canonical[static_cast<std::size_t>(v)];
      c.mesh.V.row(v) = posed.evaluate(cp.patch, cp.u, cp.v).template cast<Scalar>().transpose();
      c.rest_positions.row(v) = rest.evaluate(cp.patch, cp.u, cp.v).template cast<Scalar>().transpose();
    }
    flip_edges(tris, tri_patch, tri_uv, c.mesh.V, c.rest_positions, rng, flip_fraction);

    const index_t nf = static_cast<index_t>(tris.size());
    c.mesh.F.resize(nf, 3);
    c.face_uv.resize(nf, 6);
    c.face_patch = tri_patch;
    c.face_labels.resize(static_cast<std::size_t>(nf));
    for (index_t f = 0; f < nf; ++f) {
      for (int k = 0; k < 3; ++k) c.mesh.F(f, k) = tris[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)];
      for (int k = 0; k < 6; ++k) c.face_uv(f, k) = tri_uv[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)];
      c.face_labels[static_cast<std::size_t>(f)] = t_.part[static_cast<std::size_t>(tri_patch[static_cast<std::size_t>(f)])];
    }

    // Ground truth that needs point location on this creature: symmetry and landmarks.
    const creature_locator<Scalar> loc(c);
    c.symmetry.resize(static_cast<std::size_t>(nv));
    c.symmetry_vertex.resize(static_cast<std::size_t>(nv));
    for (index_t v = 0; v < nv; ++v) {
      const auto sp = loc.locate(mirror(c.canonical[static_cast<std::size_t>(v)]));
      c.symmetry[static_cast<std::size_t>(v)] = sp;
      c.symmetry_vertex[static_cast<std::size_t>(v)] = sp.valid() ? sp.nearest_corner(c.mesh.F) : no_index;
    }
    for (int s = 0; s < creature_slot_count; ++s) {
      if (!b.present[static_cast<std::size_t>(s)]) continue;
      const auto sp = loc.locate({t_.cap_patch(s), 0.5, 0.5});
      const index_t v = sp.nearest_corner(c.mesh.F);
      c.features.push_back({creature_slot_tip_names[static_cast<std::size_t>(s)], c.mesh.V.row(v).transpose(), v});
    }
    return c;
  }

  /// Flips a random subset of the edges whose two triangles lie in one patch, when the quad around the edge
  /// is strictly convex in (u, v) (so the new triangles are proper) and the 3D triangles keep their facing.
  static void flip_edges(std::vector<std::array<index_t, 3>>& tris, const std::vector<index_t>& tri_patch,
                         std::vector<std::array<double, 6>>& tri_uv, const matrix_x3<Scalar>& V,
                         const matrix_x3<Scalar>& V_rest, shape_rng& rng, double fraction) {
    if (fraction <= 0) return;
    const auto key = [](index_t a, index_t b) {
      if (a > b) std::swap(a, b);
      return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
    };
    std::unordered_map<std::uint64_t, std::array<index_t, 2>> edge_faces;
    std::vector<std::uint64_t> keys;
    for (std::size_t f = 0; f < tris.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t e = key(tris[f][static_cast<std::size_t>(k)], tris[f][static_cast<std::size_t>((k + 1) % 3)]);
        auto [it, fresh] = edge_faces.emplace(e, std::array<index_t, 2>{static_cast<index_t>(f), no_index});
        if (!fresh) {
          it->second[1] = static_cast<index_t>(f);
          if (tri_patch[static_cast<std::size_t>(it->second[0])] == tri_patch[f]) keys.push_back(e);
        }
      }
    std::sort(keys.begin(), keys.end());  // hash order is not portable; sorted order is
    for (std::size_t i = keys.size(); i > 1; --i)
      std::swap(keys[i - 1], keys[static_cast<std::size_t>(rng.bits() % i)]);
    const std::size_t todo = static_cast<std::size_t>(fraction * static_cast<double>(keys.size()));
    const auto uv_of = [&](std::size_t f, index_t v) {
      for (int k = 0; k < 3; ++k)
        if (tris[f][static_cast<std::size_t>(k)] == v)
          return Eigen::Vector2d(tri_uv[f][static_cast<std::size_t>(2 * k)], tri_uv[f][static_cast<std::size_t>(2 * k + 1)]);
      return Eigen::Vector2d(0, 0);
    };
    const auto area2 = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
      return (b - a).x() * (c - a).y() - (c - a).x() * (b - a).y();
    };
    const auto normal = [](const matrix_x3<Scalar>& P, index_t a, index_t b, index_t c) -> Eigen::Vector3d {
      const Eigen::Vector3d pa = P.row(a).transpose().template cast<double>(), pb = P.row(b).transpose().template cast<double>(),
                            pc = P.row(c).transpose().template cast<double>();
      return (pb - pa).cross(pc - pa);
    };
    // A flip must keep the facing in the pose *and* in the rest pose (the same connectivity serves both).
    const auto keeps_facing = [&](const matrix_x3<Scalar>& P, index_t a, index_t b, index_t c, index_t d) {
      const Eigen::Vector3d n_old = normal(P, a, b, c) + normal(P, b, a, d);
      return normal(P, c, a, d).dot(n_old) > 0 && normal(P, c, d, b).dot(n_old) > 0;
    };
    for (std::size_t i = 0; i < todo; ++i) {
      const auto it = edge_faces.find(keys[i]);
      if (it == edge_faces.end()) continue;
      const auto f0 = static_cast<std::size_t>(it->second[0]), f1 = static_cast<std::size_t>(it->second[1]);
      // Rotate f0 to (a, b, c) with the edge a -> b; f1 then holds b -> a and the opposite vertex d.
      int k0 = 0;
      while (key(tris[f0][static_cast<std::size_t>(k0)], tris[f0][static_cast<std::size_t>((k0 + 1) % 3)]) != keys[i]) ++k0;
      const index_t a = tris[f0][static_cast<std::size_t>(k0)], b = tris[f0][static_cast<std::size_t>((k0 + 1) % 3)],
                    c = tris[f0][static_cast<std::size_t>((k0 + 2) % 3)];
      index_t d = no_index;
      for (const index_t x : tris[f1])
        if (x != a && x != b) d = x;
      if (edge_faces.count(key(c, d))) continue;
      const Eigen::Vector2d ua = uv_of(f0, a), ub = uv_of(f0, b), uc = uv_of(f0, c), ud = uv_of(f1, d);
      const double old_area = area2(ua, ub, uc) + area2(ub, ua, ud);
      // Both new triangles must keep at least 10% of the quad's area: strictly convex, not nearly degenerate.
      if (area2(uc, ua, ud) < 0.1 * old_area || area2(uc, ud, ub) < 0.1 * old_area) continue;
      if (!keeps_facing(V, a, b, c, d) || !keeps_facing(V_rest, a, b, c, d)) continue;
      tris[f0] = {c, a, d};
      tris[f1] = {c, d, b};
      tri_uv[f0] = {uc.x(), uc.y(), ua.x(), ua.y(), ud.x(), ud.y()};
      tri_uv[f1] = {uc.x(), uc.y(), ud.x(), ud.y(), ub.x(), ub.y()};
      edge_faces.erase(it);
      edge_faces[key(c, d)] = {static_cast<index_t>(f0), static_cast<index_t>(f1)};
      const auto move = [&](index_t x, index_t y, std::size_t from, std::size_t to) {
        auto& e = edge_faces.at(key(x, y));
        for (auto& f : e)
          if (f == static_cast<index_t>(from)) f = static_cast<index_t>(to);
      };
      move(a, d, f1, f0);
      move(b, c, f0, f1);
    }
  }

  std::uint64_t seed_;
  creature_options o_;
  detail::creature_impl::cage_template t_;
  std::vector<index_t> mirror_patch_;
  std::vector<std::array<int, 4>> mirror_corner_;
};

}  // namespace shapestruct
