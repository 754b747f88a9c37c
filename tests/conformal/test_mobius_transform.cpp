// SPDX-License-Identifier: MIT
#include <complex>
#include <random>

#include <doctest/doctest.h>

#include "shapestruct/conformal/mobius_transform.hpp"

using namespace shapestruct;
using cplx = std::complex<double>;

TEST_CASE("mobius_transform interpolates its triplets exactly") {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int trial = 0; trial < 200; ++trial) {
    const cplx z[3] = {{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}};
    const cplx w[3] = {{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}};
    const auto T = mobius_transform<double>::from_triplets(z, w);
    REQUIRE(T.has_value());
    for (int k = 0; k < 3; ++k) CHECK(std::abs((*T)(z[k]) - w[k]) < 1e-9 * (1 + std::abs(w[k])));
    // ad - bc = 1 after normalisation
    CHECK(std::abs(T->a * T->d - T->b * T->c - cplx(1)) < 1e-9);
    // inverse and composition
    const auto I = T->inverse().compose(*T);
    const cplx p(u(rng), u(rng));
    CHECK(std::abs(I(p) - p) < 1e-8 * (1 + std::abs(p)));
    for (int k = 0; k < 3; ++k) CHECK(std::abs(T->inverse()(w[k]) - z[k]) < 1e-8 * (1 + std::abs(z[k])));
  }
}

TEST_CASE("mobius_transform area scale is |T'|^2") {
  const cplx z[3] = {{0, 0}, {1, 0}, {0, 1}};
  const cplx w[3] = {{0.5, 0.2}, {-1, 0.3}, {0.1, -2}};
  const auto T = *mobius_transform<double>::from_triplets(z, w);
  const cplx p(0.3, 0.4);
  const double h = 1e-6;
  const cplx deriv = (T(p + h) - T(p - h)) / (2 * h);
  CHECK(T.area_scale(p) == doctest::Approx(std::norm(deriv)).epsilon(1e-5));
}

TEST_CASE("mobius_transform rejects coincident triplet points") {
  const cplx z[3] = {{0, 0}, {0, 0}, {0, 1}};
  const cplx w[3] = {{0, 0}, {1, 0}, {0, 1}};
  CHECK_FALSE(mobius_transform<double>::from_triplets(z, w).has_value());
  CHECK_FALSE(mobius_transform<double>::from_triplets(w, z).has_value());
}

TEST_CASE("mobius_transform never returns NaN at its pole") {
  const cplx z[3] = {{0, 0}, {1, 0}, {0, 1}};
  const cplx w[3] = {{0, 0}, {1, 0}, {2, 1}};
  const auto T = *mobius_transform<double>::from_triplets(z, w);
  const cplx pole = -T.d / T.c;
  const cplx v = T(pole);
  CHECK(std::isfinite(v.real()));
  CHECK(std::isfinite(v.imag()));
}
