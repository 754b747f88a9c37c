// SPDX-License-Identifier: MIT
// triangulate_polygon: splits one (possibly non-planar, non-convex or degenerate) polygon into triangles.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Ear clipping costs O(n^2) (with the work budget below); above this many corners a non-convex polygon is
/// fanned instead, so that a hostile file with one 10^6-corner polygon cannot stall the reader. Real meshes
/// (CAD n-gons, scanned quads) stay far below it.
inline constexpr std::size_t ear_clipping_max_corners = 256;

/// Triangulates the polygon `corners` (vertex indices into V, in boundary order) and appends the triangles to
/// `out`, each with the polygon's orientation. Convex polygons are fanned from the first corner; non-convex
/// ones are ear-clipped in their best-fit plane (Newell normal), which handles non-planar input. Degenerate
/// input never fails: consecutive repeated corners are dropped, a polygon with fewer than 3 distinct corners
/// yields nothing, and polygons with no usable plane (collinear, zero area) or no ear (self-intersecting) are
/// fanned or clipped anyway, so a polygon with k distinct consecutive corners always yields k - 2 triangles.
/// Triangles (exactly 3 corners) are passed through unchanged, even if degenerate, to stay faithful to the file.
/// \param V `#V x 3` positions; every corner must be a valid row index (callers check, this is not re-checked).
/// \param corners the polygon's vertex indices.
/// \param out receives the triangles.
/// Complexity: O(n) for convex polygons, O(n^2) for non-convex ones (bounded by a work budget; above it, and
/// above ear_clipping_max_corners, the remaining corners are clipped without the ear test).
template <class Derived>
void triangulate_polygon(const Eigen::MatrixBase<Derived>& V, std::span<const index_t> corners,
                         std::vector<std::array<index_t, 3>>& out) {
  if (corners.size() == 3) {
    out.push_back({corners[0], corners[1], corners[2]});
    return;
  }
  // Drop consecutive duplicates (cyclically): "4 0 1 1 2" is a triangle written as a quad.
  std::vector<index_t> poly;
  poly.reserve(corners.size());
  for (index_t c : corners)
    if (poly.empty() || poly.back() != c) poly.push_back(c);
  while (poly.size() > 1 && poly.back() == poly.front()) poly.pop_back();
  const std::size_t n = poly.size();
  if (n < 3) return;
  auto fan = [&] {
    for (std::size_t k = 1; k + 1 < n; ++k) out.push_back({poly[0], poly[k], poly[k + 1]});
  };
  if (n == 3) return fan();

  // Newell's normal: the area-weighted normal of the polygon, well defined even for non-planar polygons.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double extent = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d a = V.row(poly[k]).template cast<double>().transpose();
    const Eigen::Vector3d b = V.row(poly[(k + 1) % n]).template cast<double>().transpose();
    normal.x() += (a.y() - b.y()) * (a.z() + b.z());
    normal.y() += (a.z() - b.z()) * (a.x() + b.x());
    normal.z() += (a.x() - b.x()) * (a.y() + b.y());
    extent = std::max(extent, (b - a).squaredNorm());
  }
  const double nn = normal.norm();
  // Relative threshold: a polygon whose area is ~1e-12 of its squared edge length has no usable plane.
  if (!(nn > 1e-12 * extent) || !std::isfinite(nn)) return fan();
  normal /= nn;
  const Eigen::Vector3d axis_u = normal.unitOrthogonal();
  const Eigen::Vector3d axis_v = normal.cross(axis_u);
  // Projected corners; with this basis the polygon runs counter-clockwise (Newell's normal follows the order).
  std::vector<Eigen::Vector2d> p(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d q = V.row(poly[k]).template cast<double>().transpose();
    p[k] = {q.dot(axis_u), q.dot(axis_v)};
  }
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  bool convex = true;
  for (std::size_t k = 0; k < n && convex; ++k)
    convex = cross(p[(k + n - 1) % n], p[k], p[(k + 1) % n]) >= 0;
  if (convex || n > ear_clipping_max_corners) return fan();

  std::vector<std::size_t> prev(n), next(n);
  for (std::size_t k = 0; k < n; ++k) {
    prev[k] = (k + n - 1) % n;
    next[k] = (k + 1) % n;
  }
  // Work budget: ear clipping is O(n^2) on real polygons but O(n^3) on adversarial ones (ears far apart, or
  // none at all when self-intersecting). Past 4 n^2 containment tests the rest is clipped without testing,
  // so a file of many hostile polygons costs O(n^2) bytes-proportional work each, never a hang.
  const std::size_t budget = 4 * n * n;
  std::size_t work = 0;
  auto is_ear = [&](std::size_t i) {
    const std::size_t a = prev[i], c = next[i];
    if (cross(p[a], p[i], p[c]) <= 0) return false;  // reflex or flat corner
    for (std::size_t j = next[c]; j != a; j = next[j]) {
      ++work;
      const Eigen::Vector2d& q = p[j];
      if (q == p[a] || q == p[i] || q == p[c]) continue;  // touching corners (e.g. a hole bridge) do not block
      if (cross(p[a], p[i], q) >= 0 && cross(p[i], p[c], q) >= 0 && cross(p[c], p[a], q) >= 0) return false;
    }
    return true;
  };
  std::size_t remaining = n, i = 0, misses = 0;
  while (remaining > 3) {
    // After a full lap without an ear the polygon self-intersects: clip the current corner anyway so that
    // the loop always terminates with remaining - 2 triangles.
    if (work > budget || misses >= remaining || is_ear(i)) {
      out.push_back({poly[prev[i]], poly[i], poly[next[i]]});
      next[prev[i]] = next[i];
      prev[next[i]] = prev[i];
      i = prev[i];
      --remaining;
      misses = 0;
    } else {
      i = next[i];
      ++misses;
    }
  }
  out.push_back({poly[prev[i]], poly[i], poly[next[i]]});
}

}  // namespace shapestruct
