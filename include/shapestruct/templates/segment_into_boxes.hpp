// SPDX-License-Identifier: MIT
// segment_into_boxes: a segmentation of a sampled shape into cells that boxes abstract well, for the candidate
// templates of the automatic initialisation (dissertation 5.3.4).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/geometry/principal_frame.hpp"
#include "shapestruct/templates/shape_samples.hpp"

namespace shapestruct {

namespace detail {

/// The box that abstracts a point set as the template does (5.3.1): PCA axes (rows, right-handed), centre and
/// side lengths from the extent of the points along each axis.
struct cell_box {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

inline cell_box fit_cell_box(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 3>>& P,
                             const std::vector<index_t>& mem) {
  cell_box b;
  const principal_frame frame = principal_frame_of(P, mem);
  const Eigen::Vector3d& mu = frame.mean;
  b.axes = frame.axes;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto i : mem) {
    const Eigen::Vector3d l = b.axes * (P.row(i).transpose() - mu);
    lo = lo.cwiseMin(l);
    hi = hi.cwiseMax(l);
  }
  if (mem.empty()) lo = hi = Eigen::Vector3d::Zero();
  b.center = mu + b.axes.transpose() * (0.5 * (lo + hi));
  b.size = hi - lo;
  return b;
}

/// Squared distance from x to the surface of box b (a point inside is pushed to the nearest face: the template's
/// boxes are surfaces, not solids).
inline double box_surface_distance2(const cell_box& b, const Eigen::Vector3d& x) {
  const Eigen::Vector3d h = 0.5 * b.size;
  const Eigen::Vector3d l = b.axes * (x - b.center);
  const double out = (l.cwiseAbs() - h).cwiseMax(0.0).squaredNorm();
  return out > 0 ? out : std::pow((h - l.cwiseAbs()).minCoeff(), 2);
}

/// How badly a box abstracts a point set, in the two directions of E_data (eq. 5.3): the sum over the points of
/// the squared distance to the box surface, plus |cell| times the area-weighted mean squared distance from the
/// box surface (a 5 x 5 grid per face) to the nearest point. A cell that is one part (a slab, a leg) lies on its
/// box and covers it; the union of two parts leaves points inside the box or faces uncovered. O(|cell|).
inline double cell_box_error(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 3>>& P,
                             const std::vector<index_t>& mem) {
  if (mem.empty()) return 0;
  const cell_box b = fit_cell_box(P, mem);
  double s2t = 0;
  for (const auto i : mem) s2t += box_surface_distance2(b, P.row(i).transpose());
  // Box-surface samples: a g x g grid on each of the 6 faces, weighted by the face's area.
  constexpr int g = 5;
  double t2s = 0, wsum = 0;
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const double area = b.size[u] * b.size[v];
    for (const double side : {-0.5, 0.5})
      for (int iu = 0; iu < g; ++iu)
        for (int iv = 0; iv < g; ++iv) {
          Eigen::Vector3d l;
          l[a] = side * b.size[a];
          l[u] = ((iu + 0.5) / g - 0.5) * b.size[u];
          l[v] = ((iv + 0.5) / g - 0.5) * b.size[v];
          const Eigen::Vector3d x = b.center + b.axes.transpose() * l;
          double best = std::numeric_limits<double>::infinity();
          for (const auto i : mem) best = std::min(best, (P.row(i).transpose() - x).squaredNorm());
          t2s += area * best;
          wsum += area;
        }
  }
  if (wsum > 0) t2s /= wsum;
  return s2t + static_cast<double>(mem.size()) * t2s;
}

/// Extents of a box along the up axis and (sorted, larger first) its two horizontal extents: what two copies of
/// a part (four legs, two arms) share whatever their position or rotation about the up axis.
inline Eigen::Vector3d upright_extents(const cell_box& b, int up_axis) {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  for (int w = 0; w < 3; ++w)
    for (int j = 0; j < 3; ++j) e[w] += std::abs(b.axes(j, w)) * b.size[j];  // axis-aligned extent, world axis w
  const double h1 = e[(up_axis + 1) % 3], h2 = e[(up_axis + 2) % 3];
  return {e[up_axis], std::max(h1, h2), std::min(h1, h2)};
}

/// Whether two cells' boxes are copies of one part: every upright extent agrees within 30 % of the larger one
/// plus 0.02 (about the sample spacing of 1,500 samples in the canonical frame, so thin sides of a few samples
/// still agree).
inline bool congruent_boxes(const Eigen::Vector3d& ea, const Eigen::Vector3d& eb) {
  for (int j = 0; j < 3; ++j)
    if (std::abs(ea[j] - eb[j]) > 0.3 * std::max(ea[j], eb[j]) + 0.02) return false;
  return true;
}

/// Groups the live cells whose boxes are congruent (transitively); returns the group of every cell (no_index for
/// dead cells, else a group number in order of the cells) and the number of groups.
inline std::pair<std::vector<index_t>, index_t> congruent_groups(
    const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 3>>& P, const std::vector<std::vector<index_t>>& mem,
    int up_axis) {
  const std::size_t M = mem.size();
  std::vector<Eigen::Vector3d> ext(M);
  std::vector<std::size_t> root(M);
  std::iota(root.begin(), root.end(), std::size_t{0});
  const auto find = [&](std::size_t x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  for (std::size_t k = 0; k < M; ++k)
    if (!mem[k].empty()) ext[k] = upright_extents(fit_cell_box(P, mem[k]), up_axis);
  for (std::size_t a = 0; a < M; ++a)
    for (std::size_t b = a + 1; b < M; ++b)
      if (!mem[a].empty() && !mem[b].empty() && congruent_boxes(ext[a], ext[b])) root[find(b)] = find(a);
  std::vector<index_t> group(M, no_index), id(M, no_index);
  index_t count = 0;
  for (std::size_t k = 0; k < M; ++k)
    if (!mem[k].empty()) {
      auto& g = id[find(k)];
      if (g == no_index) g = count++;
      group[k] = g;
    }
  return {group, count};
}

}  // namespace detail

/// A segmentation of a shape's samples into cells, and the output label of every cell (copies of one part, such
/// as the legs of a chair, share a label).
struct box_segmentation {
  std::vector<index_t> cell;        ///< per sample: its cell, in [0, #cells)
  std::vector<index_t> cell_label;  ///< per cell: its label, in [0, #labels)
  [[nodiscard]] index_t num_cells() const noexcept { return static_cast<index_t>(cell_label.size()); }
};

/// Segments a sampled shape into `parts` cells that follow its structure, for the candidate templates of 5.3.4.
/// `oversegment` farthest-point seeds (the first is the sample farthest from the centroid) grow cells along the
/// neighbourhood graph (geodesic Voronoi: multi-source Dijkstra over the kNN edges with Euclidean lengths; samples
/// the graph does not reach take the Euclidean-nearest seed), so a cell does not jump across a gap between parts.
/// Adjacent cells are then merged greedily, always the pair whose union adds the least box-abstraction error
/// (detail::cell_box_error: the template's own E_data measure). Small cells inside one part (a seat, a leg) merge
/// at almost no cost, a merge across parts (seat + back, seat + legs) leaves points inside the union's box or box
/// faces uncovered and is postponed. Cells whose boxes are congruent (same upright extents, detail::congruent_boxes)
/// form one group, as the legs of a chair do; merging stops when at most `parts` groups remain, and every group
/// becomes one output label. (Counting cells instead would force a chair's four separate legs into its seat.)
/// With oversegment <= parts this is the chapter's plain Voronoi diagram of `parts` farthest points
/// (Euclidean), one label per cell.
/// \param s       sampled shape (points #P x 3 and the kNN edges are read)
/// \param parts   number of groups (labels) K >= 1
/// \param oversegment initial cells M (clamped to [K, #P])
/// \param up_axis the canonical up axis (0, 1, 2), for the upright extents that decide congruence
/// \returns the cells (merged cells are numbered by their smallest sample index) and their labels.
/// \throws invalid_input bad_parameter (parts < 1), empty (fewer samples than parts).
/// Complexity: O(M #P) for the seeds, O(E log #P) for the growth, O(M^2 #P) for the merging (M^2 candidate
/// evaluations are bounded by the adjacent pairs, each linear in the two cells' sizes).
inline box_segmentation segment_into_boxes(const shape_samples& s, int parts, int oversegment, int up_axis = 1,
                                           double merge_tolerance = 0.03) {
  if (parts < 1 || up_axis < 0 || up_axis > 2 || !(merge_tolerance >= 0))
    throw invalid_input(input_error::bad_parameter, no_index,
                        "segment_into_boxes: parts must be >= 1, up_axis in {0, 1, 2}, merge_tolerance >= 0");
  const index_t n = s.size();
  if (n < parts)
    throw invalid_input(
        input_error::empty, no_index,
        "segment_into_boxes: " + std::to_string(n) + " samples are fewer than " + std::to_string(parts) + " parts");
  const bool plain = oversegment <= parts;
  const index_t M = plain ? parts : std::min<index_t>(oversegment, n);
  // Farthest-point seeds.
  const Eigen::RowVector3d centroid = s.points.colwise().mean();
  std::vector<index_t> seeds;
  index_t first = 0;
  (s.points.rowwise() - centroid).rowwise().squaredNorm().maxCoeff(&first);
  seeds.push_back(first);
  Eigen::VectorXd dist = (s.points.rowwise() - s.points.row(first)).rowwise().squaredNorm();
  while (static_cast<index_t>(seeds.size()) < M) {
    index_t next = 0;
    dist.maxCoeff(&next);
    seeds.push_back(next);
    dist = dist.cwiseMin((s.points.rowwise() - s.points.row(next)).rowwise().squaredNorm());
  }
  std::vector<index_t> cell(static_cast<std::size_t>(n), no_index);
  box_segmentation out;
  if (!plain) {
    // Geodesic Voronoi cells over the kNN graph.
    std::vector<std::vector<std::pair<index_t, double>>> adj(static_cast<std::size_t>(n));
    for (const auto& e : s.edges) {
      // Crossing a crease (normals apart) costs up to 5x the distance, so cells stop at the edges between parts.
      const double c = std::min(1.0, std::abs(s.normals.row(e.a).dot(s.normals.row(e.b))) /
                                         std::max(1e-300, s.normals.row(e.a).norm() * s.normals.row(e.b).norm()));
      const double len = (s.points.row(e.a) - s.points.row(e.b)).norm() * (1.0 + 4.0 * (1.0 - c));
      adj[static_cast<std::size_t>(e.a)].push_back({e.b, len});
      adj[static_cast<std::size_t>(e.b)].push_back({e.a, len});
    }
    std::vector<double> gd(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
    using item = std::pair<double, index_t>;
    std::priority_queue<item, std::vector<item>, std::greater<>> pq;
    for (std::size_t k = 0; k < seeds.size(); ++k) {
      gd[static_cast<std::size_t>(seeds[k])] = 0;
      cell[static_cast<std::size_t>(seeds[k])] = static_cast<index_t>(k);
      pq.push({0.0, seeds[k]});
    }
    while (!pq.empty()) {
      const auto [d, i] = pq.top();
      pq.pop();
      if (d > gd[static_cast<std::size_t>(i)]) continue;
      for (const auto& [j, len] : adj[static_cast<std::size_t>(i)])
        if (d + len < gd[static_cast<std::size_t>(j)]) {
          gd[static_cast<std::size_t>(j)] = d + len;
          cell[static_cast<std::size_t>(j)] = cell[static_cast<std::size_t>(i)];
          pq.push({d + len, j});
        }
    }
  }
  for (index_t i = 0; i < n; ++i) {
    if (cell[static_cast<std::size_t>(i)] != no_index) continue;
    double best = std::numeric_limits<double>::infinity();
    for (index_t k = 0; k < M; ++k) {
      const double d = (s.points.row(i) - s.points.row(seeds[static_cast<std::size_t>(k)])).squaredNorm();
      if (d < best) {
        best = d;
        cell[static_cast<std::size_t>(i)] = k;
      }
    }
  }
  if (!plain) {
    // Greedy merging of adjacent cells by the least added box-abstraction error.
    std::vector<std::vector<index_t>> mem(static_cast<std::size_t>(M));
    for (index_t i = 0; i < n; ++i) mem[static_cast<std::size_t>(cell[static_cast<std::size_t>(i)])].push_back(i);
    std::vector<double> err(static_cast<std::size_t>(M));
    for (index_t k = 0; k < M; ++k)
      err[static_cast<std::size_t>(k)] = detail::cell_box_error(s.points, mem[static_cast<std::size_t>(k)]);
    std::vector<std::vector<char>> adjacent(static_cast<std::size_t>(M),
                                            std::vector<char>(static_cast<std::size_t>(M), 0));
    for (const auto& e : s.edges) {
      const index_t a = cell[static_cast<std::size_t>(e.a)], b = cell[static_cast<std::size_t>(e.b)];
      if (a != b)
        adjacent[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] =
            adjacent[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)] = 1;
    }
    std::vector<char> alive(static_cast<std::size_t>(M), 1);
    std::map<std::pair<index_t, index_t>, double> cost;  // ordered: ties break on the smaller pair, deterministically
    const auto union_cost = [&](index_t a, index_t b) {
      std::vector<index_t> u = mem[static_cast<std::size_t>(a)];
      u.insert(u.end(), mem[static_cast<std::size_t>(b)].begin(), mem[static_cast<std::size_t>(b)].end());
      return (detail::cell_box_error(s.points, u) - err[static_cast<std::size_t>(a)] -
              err[static_cast<std::size_t>(b)]) /
             static_cast<double>(u.size());
    };
    for (index_t a = 0; a < M; ++a)
      for (index_t b = a + 1; b < M; ++b)
        if (adjacent[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)]) cost[{a, b}] = union_cost(a, b);
    const double tol2 = merge_tolerance * merge_tolerance;
    const auto cheapest = [&] {
      return std::min_element(cost.begin(), cost.end(),
                              [](const auto& x, const auto& y) { return x.second < y.second; });
    };
    for (index_t live = M; live > parts;) {
      // Merges within a part (added error below the tolerance) always go ahead; beyond it, only while there are
      // more groups of congruent cells than `parts`.
      if ((cost.empty() || cheapest()->second > tol2) &&
          detail::congruent_groups(s.points, mem, up_axis).second <= parts)
        break;
      if (cost.empty()) {
        // The graph is disconnected into more than `parts` pieces: merge the two closest cells (by centroid).
        std::pair<index_t, index_t> bestp{no_index, no_index};
        double best = std::numeric_limits<double>::infinity();
        std::vector<Eigen::Vector3d> cen(static_cast<std::size_t>(M), Eigen::Vector3d::Zero());
        for (index_t k = 0; k < M; ++k)
          if (alive[static_cast<std::size_t>(k)]) {
            for (const auto i : mem[static_cast<std::size_t>(k)])
              cen[static_cast<std::size_t>(k)] += s.points.row(i).transpose();
            cen[static_cast<std::size_t>(k)] /= static_cast<double>(mem[static_cast<std::size_t>(k)].size());
          }
        for (index_t a = 0; a < M; ++a)
          for (index_t b = a + 1; b < M; ++b)
            if (alive[static_cast<std::size_t>(a)] && alive[static_cast<std::size_t>(b)]) {
              const double d = (cen[static_cast<std::size_t>(a)] - cen[static_cast<std::size_t>(b)]).squaredNorm();
              if (d < best) {
                best = d;
                bestp = {a, b};
              }
            }
        adjacent[static_cast<std::size_t>(bestp.first)][static_cast<std::size_t>(bestp.second)] =
            adjacent[static_cast<std::size_t>(bestp.second)][static_cast<std::size_t>(bestp.first)] = 1;
        cost[bestp] = union_cost(bestp.first, bestp.second);
      }
      const auto [a, b] = cheapest()->first;
      // b joins a.
      auto& ma = mem[static_cast<std::size_t>(a)];
      ma.insert(ma.end(), mem[static_cast<std::size_t>(b)].begin(), mem[static_cast<std::size_t>(b)].end());
      std::sort(ma.begin(), ma.end());
      mem[static_cast<std::size_t>(b)].clear();
      alive[static_cast<std::size_t>(b)] = 0;
      err[static_cast<std::size_t>(a)] = detail::cell_box_error(s.points, ma);
      for (index_t k = 0; k < M; ++k) {
        adjacent[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] |=
            adjacent[static_cast<std::size_t>(b)][static_cast<std::size_t>(k)];
        adjacent[static_cast<std::size_t>(k)][static_cast<std::size_t>(a)] =
            adjacent[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)];
        adjacent[static_cast<std::size_t>(b)][static_cast<std::size_t>(k)] =
            adjacent[static_cast<std::size_t>(k)][static_cast<std::size_t>(b)] = 0;
      }
      adjacent[static_cast<std::size_t>(a)][static_cast<std::size_t>(a)] = 0;
      for (auto c = cost.begin(); c != cost.end();)
        c = (c->first.first == a || c->first.second == a || c->first.first == b || c->first.second == b) ? cost.erase(c)
                                                                                                         : std::next(c);
      for (index_t k = 0; k < M; ++k)
        if (k != a && alive[static_cast<std::size_t>(k)] &&
            adjacent[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)])
          cost[{std::min(a, k), std::max(a, k)}] = union_cost(a, k);
      --live;
    }
    const std::vector<index_t> group = detail::congruent_groups(s.points, mem, up_axis).first;
    for (index_t k = 0; k < M; ++k)
      for (const auto i : mem[static_cast<std::size_t>(k)]) cell[static_cast<std::size_t>(i)] = k;
    // Renumber the surviving cells by their smallest sample index, and their groups by first appearance.
    std::vector<index_t> remap(static_cast<std::size_t>(M), no_index), relabel(static_cast<std::size_t>(M), no_index);
    index_t next = 0, next_label = 0;
    for (index_t i = 0; i < n; ++i) {
      const auto c = static_cast<std::size_t>(cell[static_cast<std::size_t>(i)]);
      if (remap[c] == no_index) {
        remap[c] = next++;
        auto& l = relabel[static_cast<std::size_t>(group[c])];
        if (l == no_index) l = next_label++;
        out.cell_label.push_back(l);
      }
      cell[static_cast<std::size_t>(i)] = remap[c];
    }
  } else {  // cells are numbered by seed order, one label each, as before
    out.cell_label.resize(static_cast<std::size_t>(M));
    std::iota(out.cell_label.begin(), out.cell_label.end(), index_t{0});
  }
  out.cell = std::move(cell);
  return out;
}

}  // namespace shapestruct
