// SPDX-License-Identifier: MIT
// Test shapes for blended intrinsic maps: a sphere with arms of different lengths (distinct AGD maxima, no
// intrinsic symmetry), rigid motions and vertex permutations.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

namespace shapestruct::test {

/// An icosphere with `arms` smooth protrusions of different lengths in irregular directions: a closed genus-0
/// "creature" whose AGD maxima are the arm tips.
inline triangle_mesh<double> armed_sphere(int level = 4, int arms = 5) {
  auto m = make_icosphere<double>(level);
  const double dirs[6][3] = {{1, 0.1, 0.05}, {-0.3, 1, 0.2}, {-0.2, -0.4, 1}, {0.1, -1, -0.3}, {-1, 0.2, -0.6}, {0.4, 0.5, -1}};
  const double lens[6] = {1.6, 1.1, 0.8, 1.35, 0.95, 1.2};
  const double cos_cap = 0.88;
  for (index_t v = 0; v < m.V.rows(); ++v) {
    const Eigen::Vector3d p = m.V.row(v).transpose().normalized();
    double r = 1;
    for (int k = 0; k < arms; ++k) {
      const Eigen::Vector3d d = Eigen::Vector3d(dirs[k][0], dirs[k][1], dirs[k][2]).normalized();
      const double t = std::max(0.0, (p.dot(d) - cos_cap) / (1 - cos_cap));
      r += lens[k] * t * t;
    }
    m.V.row(v) = (r * p).transpose();
  }
  return m;
}

/// The five-armed creature with three small bumps side by side on its body (as a dog's eyes and mouth on its
/// head): the highest is an AGD maximum of low persistence, the others are suppressed beside it.
inline triangle_mesh<double> bumpy_creature() {
  auto m = test::armed_sphere(4, 5);
  const Eigen::Vector3d centres[3] = {Eigen::Vector3d(0.3, 0.6, 0.75).normalized(),
                                      Eigen::Vector3d(0.6, 0.3, 0.75).normalized(),
                                      Eigen::Vector3d(0.45, 0.45, 0.78).normalized()};
  for (index_t v = 0; v < m.V.rows(); ++v) {
    const Eigen::Vector3d p = m.V.row(v).transpose();
    const Eigen::Vector3d n = p.normalized();
    double bump = 0;
    for (const auto& c : centres) {
      const double angle = std::acos(std::min(1.0, n.dot(c)));
      bump += 0.3 * std::exp(-angle * angle / (2 * 0.08 * 0.08));
    }
    m.V.row(v) = ((p.norm() + bump) * n).transpose();
  }
  return m;
}

/// A creature with an intrinsic 180-degree symmetry that is not an extrinsic one: a sphere with two equal arms
/// along +-x and two unequal ones along +-z, a dome at +y and, at -y, the same cap reflected through the plane of
/// its rim (a dimple). Reflecting a cap through its rim plane is an isometry, so the rotation (x, y, z) ->
/// (-x, -y, z) is an intrinsic symmetry (front to back, the x arms swapped) that only extrinsic cues break:
/// exactly the situation of a human's front and back.
inline triangle_mesh<double> front_back_creature(int level = 4) {
  auto m = make_icosphere<double>(level);
  const double dirs[4][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
  const double lens[4] = {1.2, 1.2, 1.5, 0.8};
  const double cos_cap = 0.88;
  for (index_t v = 0; v < m.V.rows(); ++v) {
    const Eigen::Vector3d p = m.V.row(v).transpose().normalized();
    double r = 1;
    for (int k = 0; k < 4; ++k) {
      const double t = std::max(0.0, (p.dot(Eigen::Vector3d(dirs[k][0], dirs[k][1], dirs[k][2])) - cos_cap) / (1 - cos_cap));
      r += lens[k] * t * t;
    }
    Eigen::Vector3d q = r * p;
    const double rim = 0.8;  // the caps |y| > rim lie on the unit sphere (the arms are far from them)
    if (q.y() < -rim) q.y() = -2 * rim - q.y();
    m.V.row(v) = q.transpose();
  }
  return m;
}

/// The mesh rotated, translated and with its vertices renumbered by a seeded random permutation.
/// perm[old] = new index.
inline triangle_mesh<double> moved_and_permuted(const triangle_mesh<double>& m, std::vector<index_t>& perm,
                                                std::uint64_t seed = 7) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const Eigen::Vector3d t(3, -1, 2);
  perm.resize(static_cast<std::size_t>(m.V.rows()));
  std::iota(perm.begin(), perm.end(), index_t(0));
  std::mt19937_64 rng(seed);
  for (std::size_t i = perm.size() - 1; i > 0; --i) std::swap(perm[i], perm[static_cast<std::size_t>(rng() % (i + 1))]);
  triangle_mesh<double> out;
  out.V.resize(m.V.rows(), 3);
  out.F.resize(m.F.rows(), 3);
  for (index_t v = 0; v < m.V.rows(); ++v)
    out.V.row(perm[static_cast<std::size_t>(v)]) = (R * m.V.row(v).transpose() + t).transpose();
  for (index_t f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.F(f, k) = perm[static_cast<std::size_t>(m.F(f, k))];
  return out;
}

/// Two disjoint copies of a mesh (several components).
inline triangle_mesh<double> two_copies(const triangle_mesh<double>& m, double shift = 5) {
  triangle_mesh<double> out;
  out.V.resize(2 * m.V.rows(), 3);
  out.F.resize(2 * m.F.rows(), 3);
  out.V.topRows(m.V.rows()) = m.V;
  out.V.bottomRows(m.V.rows()) = m.V.rowwise() + Eigen::RowVector3d(shift, 0, 0);
  out.F.topRows(m.F.rows()) = m.F;
  out.F.bottomRows(m.F.rows()) = m.F.array() + m.V.rows();
  return out;
}

/// A sphere whose vertex b is identified with vertex a (faces around b now use a): one sphere pinched at a
/// non-manifold vertex joining two face fans (b becomes unreferenced), the situation of SCAPE's vertex 419.
inline triangle_mesh<double> pinched_sphere(const triangle_mesh<double>& m, index_t a, index_t b) {
  triangle_mesh<double> out = m;
  for (index_t f = 0; f < out.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (out.F(f, k) == b) out.F(f, k) = a;
  return out;
}

}  // namespace shapestruct::test
