// SPDX-License-Identifier: MIT
// assembly_generator: procedural chairs, tables and airplanes as labelled polygon soups with landmarks.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/generate/assembly.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/generate/shape_rng.hpp"

namespace shapestruct {

/// Options of assembly_generator.
struct assembly_options {
  int round_segments = 16;   ///< sides of round parts (legs, columns, fuselage, engines), 6..64
  double tilt = 0.03;        ///< max random tilt of each part about its centre (radians, in [0, 0.1]): variation
  unsigned threads = 0;      ///< for generate_range: 0 = all cores
};

namespace detail::assembly_impl {

using mat3 = Eigen::Matrix3d;
using vec = Eigen::Vector3d;

inline mat3 rot(const vec& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

/// Accumulates parts into one soup (in double; cast at the end).
struct soup {
  std::vector<vec> V;
  std::vector<std::array<index_t, 3>> F;
  std::vector<int> labels;
  std::vector<index_t> face_part;
  std::vector<assembly_part<double>> parts;
  std::vector<feature_point<double>> features;
  shape_rng* rng = nullptr;
  double tilt = 0;

  /// Random small rotation: shapes of one class are never exact copies of each other's parts.
  mat3 jitter() {
    if (tilt <= 0) return mat3::Identity();
    const vec axis(rng->uniform(-1, 1), rng->uniform(-1, 1), rng->uniform(-1, 1));
    if (axis.norm() < 1e-6) return mat3::Identity();
    return rot(axis, rng->uniform(-tilt, tilt));
  }

  /// Adds a primitive (local coordinates) placed by rotation R about its local origin and translation t;
  /// returns the index of its first vertex.
  index_t add(const triangle_mesh<double>& m, const mat3& R, const vec& t, int label, const vec& local_center,
              const vec& half) {
    const index_t base = static_cast<index_t>(V.size());
    for (index_t i = 0; i < m.num_vertices(); ++i) V.push_back(R * m.V.row(i).transpose() + t);
    const index_t part = static_cast<index_t>(parts.size());
    for (index_t f = 0; f < m.num_faces(); ++f) {
      F.push_back({base + m.F(f, 0), base + m.F(f, 1), base + m.F(f, 2)});
      labels.push_back(label);
      face_part.push_back(part);
    }
    parts.push_back({label, R * local_center + t, R, half});
    return base;
  }

  /// Box with centre c, half extents h, orientation R (columns = box axes). Returns the first vertex; corner
  /// k of make_box is base + k.
  index_t box(const vec& c, const vec& h, const mat3& R, int label) {
    const mat3 Rj = R * jitter();
    return add(make_box<double>(h.x(), h.y(), h.z()), Rj, c, label, vec::Zero(), h);
  }

  /// Cylinder (frustum) from p0 (radius r0) to p1 (radius r1). Vertex base is the centre of the p0 cap,
  /// base + 1 that of the p1 cap. `phase` turns the rim (4 segments at pi/4 give a square leg).
  index_t cylinder(const vec& p0, const vec& p1, double r0, double r1, int segments, int label, double phase = 0) {
    const vec axis = p1 - p0;
    const double len = axis.norm();
    const vec y = axis / len;
    // A frame with local +y along the axis; x picked away from y so it is well defined.
    const vec helper = std::abs(y.z()) < 0.9 ? vec::UnitZ() : vec::UnitX();
    const vec x = helper.cross(y).normalized(), z = x.cross(y);
    mat3 R;
    R.col(0) = x;
    R.col(1) = y;
    R.col(2) = z;
    R = R * rot(vec::UnitY(), phase);
    const double r = std::max(r0, r1);
    // The rim polygon is inscribed in the circle: the box of the circle contains it.
    return add(make_cylinder<double>(r0, r1, len, segments), R, p0, label, vec(0, 0.5 * len, 0), vec(r, 0.5 * len, r));
  }

  void feature(const std::string& name, index_t v) { features.push_back({name, V[static_cast<std::size_t>(v)], v}); }
  /// The vertex among [first, first + count) that maximises dot(position, direction): named corners.
  index_t extreme(index_t first, index_t count, const vec& direction) const {
    index_t best = first;
    for (index_t v = first; v < first + count; ++v)
      if (V[static_cast<std::size_t>(v)].dot(direction) > V[static_cast<std::size_t>(best)].dot(direction)) best = v;
    return best;
  }
};

inline const char* side_name(int s) { return s < 0 ? "left" : "right"; }

inline void make_chair(soup& S, shape_rng& r, int segs) {
  const double w = r.uniform(0.4, 0.56), d = r.uniform(0.38, 0.52), t = r.uniform(0.03, 0.07);
  const double seat_y = r.uniform(0.4, 0.5);
  const mat3 I = mat3::Identity();
  const index_t seat = S.box(vec(0, seat_y + 0.5 * t, 0), vec(0.5 * w, 0.5 * t, 0.5 * d), I, 0);
  for (const int sz : {-1, 1})
    for (const int sx : {-1, 1})
      S.feature(std::string("seat_") + (sz < 0 ? "front_" : "back_") + side_name(sx),
                S.extreme(seat, 8, vec(sx, 1, sz)));
  // Back: reclined by `recline` about the seat's back edge.
  const double bw = w * r.uniform(0.8, 1.0), bh = r.uniform(0.35, 0.6), bt = r.uniform(0.025, 0.05);
  const double recline = r.uniform(0.0, 0.28);
  const mat3 Rb = rot(vec::UnitX(), recline);  // +y tilts towards +z (backwards)
  const vec back_base(0, seat_y + t, 0.5 * d - 0.5 * bt);
  const index_t back = S.box(back_base + Rb * vec(0, 0.5 * bh, 0), vec(0.5 * bw, 0.5 * bh, 0.5 * bt), Rb, 1);
  for (const int sx : {-1, 1}) S.feature(std::string("back_top_") + side_name(sx), S.extreme(back, 8, Rb * vec(sx, 4, 1)));
  const bool pedestal = r.chance(0.3);
  if (!pedestal) {
    const bool square = r.chance(0.5);
    const double lr = r.uniform(0.015, 0.028), inset = r.uniform(0.03, 0.06);
    const int ls = square ? 4 : segs;
    const double splay = r.uniform(0.0, 0.04);
    std::array<vec, 4> tops, feet;
    int k = 0;
    for (const int sz : {-1, 1})
      for (const int sx : {-1, 1}) {
        tops[static_cast<std::size_t>(k)] = vec(sx * (0.5 * w - inset), seat_y, sz * (0.5 * d - inset));
        feet[static_cast<std::size_t>(k)] = tops[static_cast<std::size_t>(k)] + vec(sx * splay, -seat_y, sz * splay);
        const index_t leg = S.cylinder(feet[static_cast<std::size_t>(k)], tops[static_cast<std::size_t>(k)], lr, lr, ls, 2,
                                       square ? std::numbers::pi / 4 : 0.0);
        S.feature(std::string("leg_") + (sz < 0 ? "front_" : "back_") + side_name(sx) + "_tip", leg);
        ++k;
      }
    if (r.chance(0.4)) {  // side stretchers between front and back legs, and one across the front
      const double h = r.uniform(0.12, 0.22) / seat_y, sr = 0.6 * lr;
      const auto at = [&](int i) { return feet[static_cast<std::size_t>(i)] + h * (tops[static_cast<std::size_t>(i)] - feet[static_cast<std::size_t>(i)]); };
      S.cylinder(at(0), at(2), sr, sr, ls, 4);
      S.cylinder(at(1), at(3), sr, sr, ls, 4);
      if (r.chance(0.5)) S.cylinder(at(0), at(1), sr, sr, ls, 4);
    }
  } else {
    const double cr = r.uniform(0.025, 0.045), foot_h = r.uniform(0.04, 0.08);
    S.cylinder(vec(0, foot_h, 0), vec(0, seat_y, 0), cr, cr, segs, 5);
    const int n_feet = r.chance(0.7) ? 5 : 4;
    const double reach = r.uniform(0.25, 0.33), phase = r.uniform(0, 2 * std::numbers::pi / n_feet);
    for (int f = 0; f < n_feet; ++f) {
      const double a = phase + 2 * std::numbers::pi * f / n_feet;
      const vec dir(std::cos(a), 0, std::sin(a));
      const mat3 R = rot(vec::UnitY(), -a);  // box x axis along dir
      const index_t foot = S.box(0.5 * reach * dir + vec(0, 0.5 * foot_h, 0), vec(0.5 * reach, 0.5 * foot_h, 0.025), R, 6);
      S.feature("base_foot_" + std::to_string(f), S.extreme(foot, 8, dir - 0.5 * vec::UnitY()));
    }
  }
  if (r.chance(0.35)) {  // arms: a rest above each side of the seat and a post holding its front
    const double ah = r.uniform(0.18, 0.26), aw = r.uniform(0.03, 0.06), al = d * r.uniform(0.7, 0.95);
    for (const int sx : {-1, 1}) {
      const double x = sx * (0.5 * w + 0.5 * aw);
      const index_t rest = S.box(vec(x, seat_y + t + ah, 0.5 * d - 0.5 * al), vec(0.5 * aw, 0.015, 0.5 * al), I, 3);
      S.feature(std::string("arm_front_") + side_name(sx), S.extreme(rest, 8, vec(sx, 1, -4)));
      const double z = 0.5 * d - al + 0.04;
      S.cylinder(vec(x, seat_y + 0.5 * t, z), vec(x, seat_y + t + ah, z), 0.015, 0.015, 8, 3);
    }
  }
}

inline void make_table(soup& S, shape_rng& r, int segs) {
  const double h = r.uniform(0.65, 0.8), t = r.uniform(0.02, 0.05);
  const double support = r.uniform();
  const int kind = support < 0.55 ? 0 : support < 0.8 ? 1 : 2;  // legs, pedestal, side panels
  const bool round = kind == 1 && r.chance(0.6);
  const double w = round ? r.uniform(0.7, 1.1) : r.uniform(0.7, 1.8);
  const double d = round ? w : r.uniform(0.6, 1.0);
  const mat3 I = mat3::Identity();
  if (round) {
    const index_t top = S.cylinder(vec(0, h - t, 0), vec(0, h, 0), 0.5 * w, 0.5 * w, 2 * segs, 0);
    S.feature("top_center", top + 1);
    S.feature("top_front", S.extreme(top, 2 + 4 * segs, vec(0, 1, -1)));
  } else {
    const index_t top = S.box(vec(0, h - 0.5 * t, 0), vec(0.5 * w, 0.5 * t, 0.5 * d), I, 0);
    for (const int sz : {-1, 1})
      for (const int sx : {-1, 1})
        S.feature(std::string("top_") + (sz < 0 ? "front_" : "back_") + side_name(sx), S.extreme(top, 8, vec(sx, 1, sz)));
  }
  const double under = h - t;
  if (kind == 0) {
    const bool square = r.chance(0.5);
    const double lr = r.uniform(0.02, 0.04), inset = r.uniform(0.04, 0.1);
    for (const int sz : {-1, 1})
      for (const int sx : {-1, 1}) {
        const vec top(sx * (0.5 * w - inset), under, sz * (0.5 * d - inset));
        const index_t leg = S.cylinder(vec(top.x(), 0, top.z()), top, lr, lr, square ? 4 : segs, 1, square ? std::numbers::pi / 4 : 0.0);
        S.feature(std::string("leg_") + (sz < 0 ? "front_" : "back_") + side_name(sx) + "_tip", leg);
      }
    if (r.chance(0.5)) {  // aprons: boards under the top between the legs
      const double ah = r.uniform(0.06, 0.12), at = 0.015;
      const double ix = 0.5 * w - inset, iz = 0.5 * d - inset;
      for (const int sz : {-1, 1}) S.box(vec(0, under - 0.5 * ah, sz * iz), vec(ix - lr, 0.5 * ah, at), I, 2);
      for (const int sx : {-1, 1}) S.box(vec(sx * ix, under - 0.5 * ah, 0), vec(at, 0.5 * ah, iz - lr), I, 2);
    }
  } else if (kind == 1) {
    const double cr = r.uniform(0.04, 0.08), bh = r.uniform(0.03, 0.06);
    S.cylinder(vec(0, bh, 0), vec(0, under, 0), cr, cr, segs, 3);
    if (r.chance(0.5)) {
      const index_t base = S.cylinder(vec(0, 0, 0), vec(0, bh, 0), r.uniform(0.2, 0.3), r.uniform(0.15, 0.25), segs, 4);
      S.feature("base_center", base);
    } else {  // a cross of two feet
      const double reach = r.uniform(0.22, 0.32);
      for (int f = 0; f < 2; ++f) {
        const mat3 R = rot(vec::UnitY(), f * std::numbers::pi / 2);
        const index_t foot = S.box(vec(0, 0.5 * bh, 0), vec(reach, 0.5 * bh, 0.03), R, 4);
        S.feature("base_foot_" + std::to_string(2 * f), S.extreme(foot, 8, R * vec(1, -0.1, 0)));
        S.feature("base_foot_" + std::to_string(2 * f + 1), S.extreme(foot, 8, R * vec(-1, -0.1, 0)));
      }
    }
  } else {
    const double pt = r.uniform(0.02, 0.05), inset = r.uniform(0.0, 0.15);
    for (const int sx : {-1, 1}) {
      const index_t panel = S.box(vec(sx * (0.5 * w - inset - 0.5 * pt), 0.5 * under, 0), vec(0.5 * pt, 0.5 * under, 0.45 * d), I, 5);
      S.feature(std::string("panel_front_") + side_name(sx) + "_foot", S.extreme(panel, 8, vec(sx, -1, -1)));
    }
    if (r.chance(0.6)) {
      const double sy = r.uniform(0.1, 0.4) * under;
      S.box(vec(0, sy, 0), vec(0.5 * w - inset - pt, 0.03, 0.02), I, 6);
    }
  }
}

inline void make_airplane(soup& S, shape_rng& r, int segs) {
  const double L = r.uniform(0.9, 1.2), R = L * r.uniform(0.045, 0.075);
  const double nose = L * r.uniform(0.1, 0.16), tail = L * r.uniform(0.18, 0.26);
  const double z0 = -0.5 * L, z1 = z0 + nose, z3 = 0.5 * L, z2 = z3 - tail;
  const double tail_rise = R * r.uniform(0.2, 0.6);
  S.cylinder(vec(0, 0, z1), vec(0, 0, z2), R, R, segs, 0);
  const index_t nose_cone = S.cylinder(vec(0, 0, z1), vec(0, -0.2 * R, z0), R, 0.12 * R, segs, 0);
  S.feature("nose", nose_cone + 1);
  const index_t tail_cone = S.cylinder(vec(0, 0, z2), vec(0, tail_rise, z3), R, 0.3 * R, segs, 0);
  S.feature("tail_end", tail_cone + 1);
  // Wings: boxes from the fuselage axis outwards, swept back and with dihedral.
  const double span = L * r.uniform(0.4, 0.6), chord = L * r.uniform(0.1, 0.18), wt = 0.012 * L;
  const double sweep = r.uniform(0.0, 0.55), dihedral = r.uniform(0.0, 0.1);
  const double wz = z0 + L * r.uniform(0.38, 0.5), wy = -R * r.uniform(0.0, 0.5);
  const auto wing_frame = [&](int s, double sw, double dh) {  // columns: span direction, up, chord direction
    return mat3(rot(vec::UnitY(), -s * sw) * rot(vec::UnitZ(), s * dh));  // tips back (+z) and up
  };
  std::array<mat3, 2> wing_R;
  for (const int s : {-1, 1}) {
    const mat3 Rw = wing_frame(s, sweep, dihedral);
    wing_R[static_cast<std::size_t>(s > 0)] = Rw;
    const vec root(0, wy, wz);
    const index_t wing = S.box(root + Rw * vec(s * 0.5 * span, 0, 0), vec(0.5 * span, 0.5 * wt, 0.5 * chord), Rw, 1);
    S.feature(std::string("wing_tip_") + side_name(s), S.extreme(wing, 8, Rw * vec(s * 4, 0, -1)));
  }
  // Engines: 0, 2 or 4 nacelles hanging under the wings (intersecting them: it is a soup).
  const double e = r.uniform();
  const int per_side = e < 0.3 ? 0 : e < 0.75 ? 1 : 2;
  const double er = L * r.uniform(0.025, 0.04), el = L * r.uniform(0.14, 0.22);
  for (const int s : {-1, 1})
    for (int k = 0; k < per_side; ++k) {
      const double f = per_side == 1 ? r.uniform(0.3, 0.45) : (k == 0 ? 0.3 : 0.62);
      const mat3& Rw = wing_R[static_cast<std::size_t>(s > 0)];
      const vec at = vec(0, wy, wz) + Rw * vec(s * f * span, 0, -0.5 * chord);
      const vec front = at + vec(0, -0.9 * er, -0.35 * el), back = front + vec(0, 0, el);
      const index_t eng = S.cylinder(front, back, er, 0.85 * er, segs, 4);
      S.feature(std::string("engine_") + side_name(s) + "_" + std::to_string(k) + "_front", eng);
    }
  // Tail: horizontal stabilisers and a fin, near the tail end.
  const double hspan = span * r.uniform(0.28, 0.42), hchord = chord * r.uniform(0.5, 0.75);
  const double hz = z3 - 0.6 * hchord, hy = tail_rise * 0.7;
  for (const int s : {-1, 1}) {
    const mat3 Rh = wing_frame(s, sweep * 1.1, 0.0);
    const index_t h = S.box(vec(0, hy, hz) + Rh * vec(s * 0.5 * hspan, 0, 0), vec(0.5 * hspan, 0.4 * wt, 0.5 * hchord), Rh, 2);
    S.feature(std::string("horizontal_tail_tip_") + side_name(s), S.extreme(h, 8, Rh * vec(s * 4, 0, -1)));
  }
  const double vh = L * r.uniform(0.1, 0.18), vchord = hchord * r.uniform(1.0, 1.4), vsweep = r.uniform(0.3, 0.7);
  const mat3 Rv = rot(vec::UnitX(), vsweep);  // box +y leans towards +z (back)
  const index_t fin = S.box(vec(0, tail_rise * 0.5, z3 - 0.55 * vchord) + Rv * vec(0, 0.5 * vh + 0.5 * R, 0),
                            vec(0.4 * wt, 0.5 * vh + 0.5 * R, 0.5 * vchord), Rv, 3);
  S.feature("vertical_tail_tip", S.extreme(fin, 8, Rv * vec(0, 4, -1)));
}

}  // namespace detail::assembly_impl

/// Generates man-made assemblies: chairs (seat, back, 4 legs or a pedestal with 4-5 feet, optional arms and
/// stretchers), tables (rectangular or round top; 4 legs with optional aprons, a pedestal with a disc or
/// cross base, or 2 side panels with an optional stretcher) and airplanes (fuselage with nose and tail
/// cones, swept wings, horizontal and vertical tail, 0/2/4 engines). Parts are boxes and cylinders kept as
/// separate intersecting pieces (a polygon soup), each face labelled with its part class, each part with
/// its exact oriented box, and named landmarks snapped to vertices. +Y is up, the front faces -Z, left is -X.
///
/// Shape i depends only on (class, seed, i); a mixed generator (no fixed class) draws the class of shape i
/// from (seed, i) and then builds exactly the shape the class's own generator would build for i.
template <class Scalar = double>
class assembly_generator {
 public:
  /// \param kind the class to generate, or nullopt for a mix of all three
  /// \throws invalid_input (bad_parameter) naming the option if an option is out of range.
  explicit assembly_generator(std::optional<assembly_kind> kind, std::uint64_t seed, assembly_options options = {})
      : kind_(kind), seed_(seed), o_(options) {
    if (o_.round_segments < 6 || o_.round_segments > 64)
      throw invalid_input(input_error::bad_parameter, no_index, "assembly_generator: round_segments must be in [6, 64]");
    if (!(o_.tilt >= 0 && o_.tilt <= 0.1))
      throw invalid_input(input_error::bad_parameter, no_index, "assembly_generator: tilt must be in [0, 0.1] radians");
  }

  /// The class of shape `index` (fixed, or drawn from (seed, index) for a mixed generator).
  [[nodiscard]] assembly_kind kind_of(std::uint64_t index) const {
    if (kind_) return *kind_;
    shape_rng r("assemblies", seed_, index);
    return static_cast<assembly_kind>(r.integer(0, 2));
  }

  /// Assembly `index`. O(number of parts * round_segments).
  [[nodiscard]] assembly<Scalar> generate(std::uint64_t index) const {
    namespace ai = detail::assembly_impl;
    const assembly_kind k = kind_of(index);
    shape_rng rng(to_string(k), seed_, index);
    ai::soup S;
    S.rng = &rng;
    S.tilt = o_.tilt;
    switch (k) {
      case assembly_kind::chair: ai::make_chair(S, rng, o_.round_segments); break;
      case assembly_kind::table: ai::make_table(S, rng, o_.round_segments); break;
      case assembly_kind::airplane: ai::make_airplane(S, rng, o_.round_segments); break;
    }
    assembly<Scalar> out;
    out.kind = k;
    out.mesh.V.resize(static_cast<index_t>(S.V.size()), 3);
    for (std::size_t i = 0; i < S.V.size(); ++i) out.mesh.V.row(static_cast<index_t>(i)) = S.V[i].cast<Scalar>().transpose();
    out.mesh.F.resize(static_cast<index_t>(S.F.size()), 3);
    for (std::size_t f = 0; f < S.F.size(); ++f)
      out.mesh.F.row(static_cast<index_t>(f)) << S.F[f][0], S.F[f][1], S.F[f][2];
    out.face_labels = std::move(S.labels);
    out.face_part = std::move(S.face_part);
    for (const auto& p : S.parts)
      out.parts.push_back({p.label, p.center.cast<Scalar>(), p.axes.cast<Scalar>(), p.half_extents.cast<Scalar>()});
    for (const auto& f : S.features) out.features.push_back({f.name, f.position.cast<Scalar>(), f.vertex});
    return out;
  }

  /// Assemblies first .. first+count-1 on `threads` threads (0 = options.threads, whose 0 = all cores);
  /// identical for every thread count.
  [[nodiscard]] std::vector<assembly<Scalar>> generate_range(std::uint64_t first, std::size_t count, unsigned threads = 0) const {
    std::vector<assembly<Scalar>> out(count);
    const unsigned nt = threads ? threads : o_.threads ? o_.threads : detail::resolve_threads(0);
    detail::parallel_for(count, nt, [&](std::size_t i) { out[i] = generate(first + i); });
    return out;
  }

  [[nodiscard]] std::optional<assembly_kind> kind() const noexcept { return kind_; }
  [[nodiscard]] std::uint64_t seed() const noexcept { return seed_; }
  [[nodiscard]] const assembly_options& options() const noexcept { return o_; }

 private:
  std::optional<assembly_kind> kind_;
  std::uint64_t seed_;
  assembly_options o_;
};

}  // namespace shapestruct
