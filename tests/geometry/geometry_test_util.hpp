// SPDX-License-Identifier: MIT
// Shared helpers for the geometry tests: error-reason checks and small procedural meshes with known answers.
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

namespace shapestruct::test {

/// Runs fn and checks that it throws invalid_input with the given reason (and element, unless element is
/// left at its default sentinel -2 meaning "any").
template <class Fn>
void expect_invalid(Fn&& fn, input_error reason, index_t element = -2) {
  bool thrown = false;
  try {
    fn();
  } catch (const invalid_input& e) {
    thrown = true;
    INFO("message: " << e.what());
    CHECK(e.reason() == reason);
    if (element != -2) CHECK(e.element() == element);
    CHECK(std::string(e.what()).size() > 10);
  }
  CHECK_MESSAGE(thrown, "expected invalid_input(" << to_string(reason) << ")");
}

/// Planar (nx+1) x (ny+1) grid in z = 0 with spacing h; every square is split along the (+1, +1) diagonal, so
/// edge-graph distances from the origin corner to (a, b) are h * (|a - b| + sqrt(2) min(a, b)).
/// Vertex (i, j) has index j * (nx + 1) + i.
template <class Scalar = double>
triangle_mesh<Scalar> grid_mesh(int nx, int ny, double h = 1.0) {
  triangle_mesh<Scalar> m;
  m.V.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.V.row(j * (nx + 1) + i) << Scalar(i * h), Scalar(j * h), Scalar(0);
  m.F.resize(2 * nx * ny, 3);
  index_t f = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const index_t a = j * (nx + 1) + i, b = a + 1, c = a + (nx + 1) + 1, d = a + (nx + 1);
      m.F.row(f++) << a, b, c;
      m.F.row(f++) << a, c, d;
    }
  return m;
}

/// Icosphere with every vertex moved by a seeded random amount (so edge lengths are all different).
template <class Scalar = double>
triangle_mesh<Scalar> jittered_icosphere(int level, std::uint64_t seed, double amount = 0.05) {
  auto m = make_icosphere<Scalar>(level);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (index_t i = 0; i < m.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) m.V(i, c) += Scalar(u(rng));
  return m;
}

/// The unit icosphere stretched by `factor` along x: an elongated closed surface with two ends at x = +-factor.
template <class Scalar = double>
triangle_mesh<Scalar> elongated_ellipsoid(int level, double factor) {
  auto m = make_icosphere<Scalar>(level);
  m.V.col(0) *= Scalar(factor);
  return m;
}

/// A 4 x 4 grid with defects: vertex 6 moved onto the segment between 5 and 7 (zero-area faces) and vertex 12
/// placed exactly on vertex 11 (a zero-length edge). Valid for validate_mesh, numerically nasty.
template <class Scalar = double>
triangle_mesh<Scalar> degenerate_grid() {
  auto m = grid_mesh<Scalar>(4, 4);
  m.V.row(6) = (m.V.row(5) + m.V.row(7)) / Scalar(2);
  m.V.row(12) = m.V.row(11);
  return m;
}

}  // namespace shapestruct::test
