// SPDX-License-Identifier: MIT
// Private helpers shared by the geometry kernels: clamped cotangents and dense-type helpers. No stability promise.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"

namespace shapestruct::detail {

/// Largest |cot| the cotangent kernels produce. A triangle angle of 1e-5 rad (5.7e-4 degrees) already has
/// cot = 1e5; scanned meshes (SCAPE) contain slivers and zero-area faces whose exact cotangents are huge or
/// 0/0. Unclamped they put Inf/NaN into the Laplacian or make it so ill-conditioned (condition number ~ cot)
/// that the LDLT solve loses all digits. No angle of a usable triangle comes near the bound, so clamping
/// changes nothing on good meshes and keeps every entry finite on bad ones.
inline constexpr double max_abs_cot = 1e5;

/// cot of the angle between a and b, computed as dot / |cross| and clamped to [-limit, limit]. A zero-length
/// edge (dot = 0, cross = 0) gives 0: such a corner contributes no weight.
template <class Scalar>
Scalar clamped_cot(const vec3<Scalar>& a, const vec3<Scalar>& b, double limit = max_abs_cot) {
  const Scalar d = a.dot(b);
  const Scalar c = a.cross(b).norm();
  const Scalar lim = static_cast<Scalar>(limit);
  if (!(c > Scalar(0))) return d > 0 ? lim : (d < 0 ? -lim : Scalar(0));
  const Scalar r = d / c;
  if (!std::isfinite(r)) return d > 0 ? lim : -lim;  // c subnormal: d / c overflows
  return std::clamp(r, -lim, lim);
}

/// Triangle f's corners as vec3.
template <class Scalar, class DV, class DF>
inline void geometry_corners(const DV& V, const DF& F, index_t f, vec3<Scalar>& a, vec3<Scalar>& b, vec3<Scalar>& c) {
  a = V.row(F(f, 0)).transpose();
  b = V.row(F(f, 1)).transpose();
  c = V.row(F(f, 2)).transpose();
}

/// Throws invalid_input(bad_parameter) naming the vertex if v is not in [0, n).
inline void geometry_check_vertex(index_t v, index_t n, const char* who, const char* what) {
  if (v < 0 || v >= n)
    throw invalid_input(input_error::bad_parameter, v,
                        std::string(who) + ": " + what + " " + std::to_string(v) + " is not a vertex index in [0, " +
                            std::to_string(n) + ")");
}

}  // namespace shapestruct::detail
