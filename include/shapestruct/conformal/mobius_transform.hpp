// SPDX-License-Identifier: MIT
// mobius_transform: a Möbius transformation of the extended complex plane, built from three point pairs.
#pragma once

#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <string>

#include "shapestruct/core/errors.hpp"

namespace shapestruct {

/// T(z) = (a z + b) / (c z + d) with ad - bc = 1 (the normalisation keeps compositions well scaled).
/// The candidate conformal maps of blended intrinsic maps (dissertation ch. 3.3.2) are these transforms between
/// the mid-edge flattenings of two surfaces.
template <class Scalar = double>
struct mobius_transform {
  using complex = std::complex<Scalar>;
  complex a{1}, b{0}, c{0}, d{1};

  /// The identity map.
  [[nodiscard]] static mobius_transform identity() noexcept { return {}; }

  /// The unique Möbius transform with T(z[k]) = w[k], k = 0, 1, 2. O(1).
  /// \param z three distinct source points, \param w three distinct target points.
  /// \returns nullopt when two points of a triplet coincide (to relative precision 1e-12), where no unique
  ///          transform exists.
  [[nodiscard]] static std::optional<mobius_transform> from_triplets(const complex (&z)[3], const complex (&w)[3]) {
    const auto zs = to_zero_one_infinity(z);
    const auto ws = to_zero_one_infinity(w);
    if (!zs || !ws) return std::nullopt;
    // T = W^{-1} o Z, where Z and W send their triplets to (0, 1, infinity).
    return ws->inverse().compose(*zs).normalized();
  }

  /// T(z). Points mapped to infinity come back as a very large finite number (1/epsilon times the scale),
  /// so that downstream point location clamps them to the outer boundary instead of propagating inf/NaN.
  [[nodiscard]] complex operator()(complex z) const noexcept {
    const complex den = c * z + d;
    const complex num = a * z + b;
    if (std::abs(den) <= tiny() * std::abs(num)) return num * huge();
    return num / den;
  }

  /// |T'(z)|^2: the factor by which T scales areas at z (T' = 1 / (cz + d)^2 since ad - bc = 1).
  [[nodiscard]] Scalar area_scale(complex z) const noexcept {
    const Scalar den = std::norm(c * z + d);
    if (!(den > tiny())) return huge();
    return Scalar(1) / (den * den);
  }

  /// The composition (*this) o other, i.e. z -> this(other(z)). O(1).
  [[nodiscard]] mobius_transform compose(const mobius_transform& o) const noexcept {
    return mobius_transform{a * o.a + b * o.c, a * o.b + b * o.d, c * o.a + d * o.c, c * o.b + d * o.d}.normalized();
  }

  /// The inverse transform. O(1).
  [[nodiscard]] mobius_transform inverse() const noexcept { return mobius_transform{d, -b, -c, a}.normalized(); }

  /// Rescales (a, b, c, d) so that ad - bc = 1; the map is unchanged.
  [[nodiscard]] mobius_transform normalized() const noexcept {
    const complex det = a * d - b * c;
    const complex s = std::sqrt(det);
    if (std::abs(s) == Scalar(0)) return *this;
    return mobius_transform{a / s, b / s, c / s, d / s};
  }

 private:
  static constexpr Scalar tiny() noexcept { return std::numeric_limits<Scalar>::epsilon() * Scalar(1e-4); }
  static constexpr Scalar huge() noexcept { return Scalar(1) / (std::numeric_limits<Scalar>::epsilon() * Scalar(1e-4)); }

  static bool coincide(complex p, complex q) {
    const Scalar scale = std::max({std::abs(p), std::abs(q), Scalar(1e-300)});
    return std::abs(p - q) <= Scalar(1e-12) * scale;
  }

  /// Z(p) = ((p - z0)(z1 - z2)) / ((p - z2)(z1 - z0)): z0 -> 0, z1 -> 1, z2 -> infinity.
  static std::optional<mobius_transform> to_zero_one_infinity(const complex (&z)[3]) {
    if (coincide(z[0], z[1]) || coincide(z[1], z[2]) || coincide(z[0], z[2])) return std::nullopt;
    const complex s = z[1] - z[2], t = z[1] - z[0];
    return mobius_transform{s, -z[0] * s, t, -z[2] * t}.normalized();
  }
};

}  // namespace shapestruct
