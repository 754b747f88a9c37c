// SPDX-License-Identifier: MIT
// planar_triangle_locator: which triangle of a planar triangulation contains (or is nearest to) a query point.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/heap_bytes.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/sorted_half_edges.hpp"

namespace shapestruct {

/// A bounding-volume hierarchy over the triangles of a planar triangulation. Conformal flattenings shrink
/// extremities by many orders of magnitude, so a uniform grid would either be huge or put thousands of
/// triangles in a cell; an AABB tree adapts to that scale range and answers in O(log n) on average.
template <class Scalar = double>
class planar_triangle_locator {
 public:
  using complex = std::complex<Scalar>;

  /// Result of a query: the triangle and the barycentric weights of the (clamped) point in it.
  struct hit {
    index_t triangle = no_index;
    Eigen::Matrix<Scalar, 3, 1> bary = Eigen::Matrix<Scalar, 3, 1>::Zero();
    Scalar distance = std::numeric_limits<Scalar>::infinity();  ///< 0 when the point is inside the triangle
  };

  planar_triangle_locator() = default;

  /// Builds the tree. O(T log T).
  /// \param points  #P planar points, \param tris  #T x 3 indices into points.
  /// \throws invalid_input (empty) when there are no triangles.
  planar_triangle_locator(std::vector<complex> points, Eigen::Matrix<index_t, Eigen::Dynamic, 3> tris)
      : pts_(std::move(points)), tris_(std::move(tris)) {
    if (tris_.rows() == 0)
      throw invalid_input(input_error::empty, no_index, "planar_triangle_locator: no triangles to index");
    const index_t n = tris_.rows();
    order_.resize(static_cast<std::size_t>(n));
    std::iota(order_.begin(), order_.end(), index_t(0));
    boxes_.resize(static_cast<std::size_t>(n));
    centers_.resize(static_cast<std::size_t>(n));
    for (index_t t = 0; t < n; ++t) {
      box b;
      for (int k = 0; k < 3; ++k) b.grow(pts_[static_cast<std::size_t>(tris_(t, k))]);
      boxes_[static_cast<std::size_t>(t)] = b;
      centers_[static_cast<std::size_t>(t)] = complex((b.lo[0] + b.hi[0]) / 2, (b.lo[1] + b.hi[1]) / 2);
    }
    // Triangles whose box covers a sizeable part of the whole domain (the neighbourhood of the cut, i.e. of
    // infinity, and vertices whose fan wraps around it) would inflate the boxes of every ancestor in the tree and
    // make each query visit hundreds of nodes; they are kept in a short list tested linearly instead.
    box all;
    for (const auto& b : boxes_) all.grow(b);
    const Scalar big_area = Scalar(1e-1) * (all.hi[0] - all.lo[0]) * (all.hi[1] - all.lo[1]);
    std::vector<index_t> small;
    for (index_t t : order_) {
      const box& b = boxes_[static_cast<std::size_t>(t)];
      if ((b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1]) > big_area) big_.push_back(t);
      else small.push_back(t);
    }
    if (small.empty()) {  // degenerate case: everything is big; index it all
      small.swap(big_);
    }
    order_ = std::move(small);
    nodes_.reserve(2 * order_.size() / leaf_size + 2);
    build(0, order_.size());
    build_walk();
  }

  [[nodiscard]] index_t num_triangles() const noexcept { return tris_.rows(); }
  /// Bytes held on the heap (core/heap_bytes.hpp).
  [[nodiscard]] std::size_t heap_bytes() const noexcept {
    using shapestruct::heap_bytes;
    return heap_bytes(pts_) + heap_bytes(tris_) + heap_bytes(order_) + heap_bytes(big_) + heap_bytes(boxes_) +
           heap_bytes(centers_) + heap_bytes(nodes_) + heap_bytes(neighbours_) + heap_bytes(walkable_);
  }
  /// Whether locate_from may answer from its walk at triangle t (see there).
  [[nodiscard]] bool walkable(index_t t) const { return walkable_[static_cast<std::size_t>(t)] != 0; }

  /// locate(q), started from the triangle `hint` (a previous answer; no_index or out of range: none) and set to the
  /// answer. Consecutive queries that lie close together (the images of one point under similar maps, neighbouring
  /// points) then cost a few steps of a walk across edges instead of a tree search. The walk answers only where q
  /// lies clearly inside a walkable triangle, one whose box meets no degenerate, inverted or folded triangle's, so
  /// that no other triangle can hold q. Elsewhere (outside the image, within a tolerance band of an edge, around a
  /// fold-over, after max_walk_steps) it falls back to locate(q), so it returns what locate returns.
  [[nodiscard]] hit locate_from(complex q, index_t& hint) const {
    hit h;
    if (hint >= 0 && hint < tris_.rows() && std::isfinite(q.real()) && std::isfinite(q.imag())) {
      // locate() tries the big triangles first, and they may overlap others: it answers with them, so does this.
      if (!in_big_triangle(q, h)) h = walk_or_search(q, hint);
    } else {
      h = locate(q);
    }
    hint = h.triangle;
    return h;
  }

  [[nodiscard]] const std::vector<complex>& points() const noexcept { return pts_; }
  [[nodiscard]] const Eigen::Matrix<index_t, Eigen::Dynamic, 3>& triangles() const noexcept { return tris_; }

  /// The triangle containing q, or, when q lies outside the triangulation, the nearest triangle with q clamped
  /// onto it. O(log T) for points inside; the fallback is a branch-and-bound nearest search.
  [[nodiscard]] hit locate(complex q) const {
    hit best;
    if (nodes_.empty() || !std::isfinite(q.real()) || !std::isfinite(q.imag())) {
      // A non-finite query (a Möbius pole) is "at infinity": clamp to the triangle farthest out.
      q = complex(far_value(), far_value());
    }
    // Phase 1: containment. Only boxes that contain q are opened, so an inside point costs O(depth + overlap).
    if (in_big_triangle(q, best)) return best;
    return search_after_big(q);
  }

 private:
  /// Whether q lies in one of the big triangles (tried first: their boxes would make every tree node large), the
  /// first such in `out`.
  bool in_big_triangle(complex q, hit& out) const {
    for (index_t t : big_) {
      if (!boxes_[static_cast<std::size_t>(t)].contains(q)) continue;
      hit h = test(t, q);
      if (h.distance == Scalar(0)) {
        out = h;
        return true;
      }
    }
    return false;
  }

  /// locate_from once the big triangles are ruled out: the walk from `hint`, else the tree.
  hit walk_or_search(complex q, index_t hint) const {
    index_t t = hint;
    for (int step = 0; step < max_walk_steps && t != no_index && walkable(t); ++step) {
      Scalar l[3];
      barycentric(t, q, l);
      const int k = static_cast<int>(std::min_element(l, l + 3) - l);
      if (l[k] >= walk_margin) return inside(t, l);
      if (l[k] >= -walk_margin) break;  // on or near an edge: the tree decides, as it always has
      t = neighbours_(t, k);
    }
    return search_after_big(q);
  }

  /// locate() for a finite q in none of the big triangles: containment through the tree, then the nearest triangle.
  hit search_after_big(complex q) const {
    hit best;
    {
      std::array<std::size_t, 128> stack{};
      std::size_t top = 0;
      stack[top++] = 0;
      while (top > 0) {
        const node& nd = nodes_[stack[--top]];
        if (!nd.bounds.contains(q)) continue;
        if (nd.count > 0) {
          for (std::size_t i = nd.first; i < nd.first + nd.count; ++i) {
            const index_t t = order_[i];
            if (!boxes_[static_cast<std::size_t>(t)].contains(q)) continue;
            hit h = test(t, q);
            if (h.distance == Scalar(0)) return h;
          }
        } else if (top + 2 <= stack.size()) {
          stack[top++] = nd.right;
          stack[top++] = nd.left;
        }
      }
    }
    // Phase 2: q is in no triangle (outside the image, or in a crack left by a fold-over): nearest triangle by
    // branch and bound.
    for (index_t t : big_) {
      if (boxes_[static_cast<std::size_t>(t)].distance(q) >= best.distance) continue;
      hit h = test(t, q);
      if (h.distance < best.distance) best = h;
    }
    std::array<std::size_t, 128> stack{};
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const node& nd = nodes_[stack[--top]];
      if (nd.bounds.distance(q) >= best.distance) continue;
      if (nd.count > 0) {
        for (std::size_t i = nd.first; i < nd.first + nd.count; ++i) {
          const index_t t = order_[i];
          if (boxes_[static_cast<std::size_t>(t)].distance(q) >= best.distance) continue;
          hit h = test(t, q);
          if (h.distance < best.distance) best = h;
          if (best.distance == Scalar(0)) return best;
        }
      } else {
        // Visit the nearer child first so that the bound tightens quickly.
        const Scalar dl = nodes_[nd.left].bounds.distance(q), dr = nodes_[nd.right].bounds.distance(q);
        if (top + 2 > stack.size()) continue;  // depth is O(log T); this guards a pathological tree
        if (dl <= dr) {
          stack[top++] = nd.right;
          stack[top++] = nd.left;
        } else {
          stack[top++] = nd.left;
          stack[top++] = nd.right;
        }
      }
    }
    return best;
  }

  static constexpr std::size_t leaf_size = 4;

  struct box {
    Scalar lo[2] = {std::numeric_limits<Scalar>::infinity(), std::numeric_limits<Scalar>::infinity()};
    Scalar hi[2] = {-std::numeric_limits<Scalar>::infinity(), -std::numeric_limits<Scalar>::infinity()};
    void grow(complex p) {
      lo[0] = std::min(lo[0], p.real());
      lo[1] = std::min(lo[1], p.imag());
      hi[0] = std::max(hi[0], p.real());
      hi[1] = std::max(hi[1], p.imag());
    }
    void grow(const box& b) {
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], b.lo[k]);
        hi[k] = std::max(hi[k], b.hi[k]);
      }
    }
    [[nodiscard]] bool contains(complex p) const {
      return p.real() >= lo[0] && p.real() <= hi[0] && p.imag() >= lo[1] && p.imag() <= hi[1];
    }
    [[nodiscard]] Scalar distance(complex p) const {
      const Scalar dx = std::max({lo[0] - p.real(), Scalar(0), p.real() - hi[0]});
      const Scalar dy = std::max({lo[1] - p.imag(), Scalar(0), p.imag() - hi[1]});
      return std::sqrt(dx * dx + dy * dy);
    }
  };

  struct node {
    box bounds;
    std::size_t left = 0, right = 0;  // children (inner nodes)
    std::size_t first = 0, count = 0;  // range in order_ (leaves: count > 0)
  };

  static constexpr int max_walk_steps = 32;
  // Far outside test()'s tolerance (1e-10), so that a point the walk accepts is in no neighbour's tolerance band.
  static constexpr Scalar walk_margin = Scalar(1e-6);

  /// A triangle too thin to hold a point (test()'s rule), or so small against its distance from the origin that its
  /// corners differ only in the last digits: there barycentric coordinates are rounding noise.
  [[nodiscard]] bool degenerate(index_t t) const {
    const complex p0 = pts_[static_cast<std::size_t>(tris_(t, 0))], p1 = pts_[static_cast<std::size_t>(tris_(t, 1))],
                  p2 = pts_[static_cast<std::size_t>(tris_(t, 2))];
    const Scalar area = cross(p1 - p0, p2 - p0);
    const Scalar scale = std::norm(p1 - p0) + std::norm(p2 - p0) + std::norm(p2 - p1);
    const Scalar reach = std::max({std::norm(p0), std::norm(p1), std::norm(p2)});
    return !(std::abs(area) > Scalar(1e-14) * scale && scale > Scalar(1e-16) * reach);
  }

  /// The hit at barycentric coordinates l (at least -1e-10 each) of triangle t: clamped to 0 and renormalised.
  static hit inside(index_t t, const Scalar* l) {
    hit h;
    h.triangle = t;
    h.bary << std::max(l[0], Scalar(0)), std::max(l[1], Scalar(0)), std::max(l[2], Scalar(0));
    h.bary /= h.bary.sum();
    h.distance = 0;
    return h;
  }

  /// Barycentric coordinates of q in triangle t (not degenerate), as test() computes them.
  void barycentric(index_t t, complex q, Scalar* l) const {
    const complex p0 = pts_[static_cast<std::size_t>(tris_(t, 0))], p1 = pts_[static_cast<std::size_t>(tris_(t, 1))],
                  p2 = pts_[static_cast<std::size_t>(tris_(t, 2))];
    const Scalar area = cross(p1 - p0, p2 - p0);
    l[0] = cross(p1 - q, p2 - q) / area;
    l[1] = cross(p2 - q, p0 - q) / area;
    l[2] = Scalar(1) - l[0] - l[1];
  }

  /// The walk's tables: the neighbour across the edge opposite each corner (no_index on the boundary or where more
  /// than two triangles share the edge), and which triangles the walk may answer in.
  void build_walk() {
    const index_t n = tris_.rows();
    neighbours_.setConstant(n, 3, no_index);
    const std::vector<detail::half_edge> halves = detail::sorted_half_edges(tris_);
    // Triangles that may overlap others: degenerate ones, the two of an edge lying on the same side of it (a fold),
    // and inverted ones (their orientation against the majority, once each triangle's corner order is made
    // consistent with its neighbours'). The big triangles are not counted: the walk tests them first, as locate does.
    std::vector<char> suspect(static_cast<std::size_t>(n), 0);
    std::vector<signed char> order_sign(static_cast<std::size_t>(n), 0);  // +1: corner order kept, -1: reversed
    for (index_t t = 0; t < n; ++t) suspect[static_cast<std::size_t>(t)] = degenerate(t);
    for (std::size_t i = 0; i < halves.size();) {
      std::size_t j = i + 1;
      while (j < halves.size() && halves[j].lo == halves[i].lo && halves[j].hi == halves[i].hi) ++j;
      if (j == i + 2) {
        const detail::half_edge &x = halves[i], &y = halves[i + 1];
        neighbours_(x.face, x.corner) = y.face;
        neighbours_(y.face, y.corner) = x.face;
        const complex p = pts_[static_cast<std::size_t>(x.lo)], d = pts_[static_cast<std::size_t>(x.hi)] - p;
        const Scalar side_x = cross(d, pts_[static_cast<std::size_t>(tris_(x.face, x.corner))] - p);
        const Scalar side_y = cross(d, pts_[static_cast<std::size_t>(tris_(y.face, y.corner))] - p);
        if (!(side_x * side_y < 0)) {
          suspect[static_cast<std::size_t>(x.face)] = 1;
          suspect[static_cast<std::size_t>(y.face)] = 1;
        }
      } else if (j > i + 2) {
        for (std::size_t h = i; h < j; ++h) suspect[static_cast<std::size_t>(halves[h].face)] = 1;
      }
      i = j;
    }
    // Corner orders made consistent breadth first: neighbours run along their shared edge in opposite directions.
    const auto runs_forward = [&](index_t t, int corner) {  // the edge opposite `corner`, from its lower point up
      return tris_(t, (corner + 1) % 3) < tris_(t, (corner + 2) % 3);
    };
    index_t agree = 0, disagree = 0;
    std::vector<signed char> geometric(static_cast<std::size_t>(n), 0);
    for (index_t t = 0; t < n; ++t) {
      const complex p0 = pts_[static_cast<std::size_t>(tris_(t, 0))];
      const Scalar area =
          cross(pts_[static_cast<std::size_t>(tris_(t, 1))] - p0, pts_[static_cast<std::size_t>(tris_(t, 2))] - p0);
      geometric[static_cast<std::size_t>(t)] = area > 0 ? 1 : (area < 0 ? -1 : 0);
    }
    std::vector<index_t> queue;
    for (index_t root = 0; root < n; ++root) {
      if (order_sign[static_cast<std::size_t>(root)] != 0) continue;
      order_sign[static_cast<std::size_t>(root)] = 1;
      queue.assign(1, root);
      for (std::size_t head = 0; head < queue.size(); ++head) {
        const index_t t = queue[head];
        for (int k = 0; k < 3; ++k) {
          const index_t u = neighbours_(t, k);
          if (u == no_index || order_sign[static_cast<std::size_t>(u)] != 0) continue;
          int ku = 0;
          while (ku < 3 && neighbours_(u, ku) != t) ++ku;
          const bool opposite = runs_forward(t, k) != runs_forward(u, ku);
          const signed char parent = order_sign[static_cast<std::size_t>(t)];
          order_sign[static_cast<std::size_t>(u)] = static_cast<signed char>(opposite ? parent : -parent);
          queue.push_back(u);
        }
      }
    }
    for (index_t t = 0; t < n; ++t) {
      const int s = geometric[static_cast<std::size_t>(t)] * order_sign[static_cast<std::size_t>(t)];
      (s > 0 ? agree : disagree) += s != 0;
    }
    const int majority = agree >= disagree ? 1 : -1;
    for (index_t t = 0; t < n; ++t)
      if (geometric[static_cast<std::size_t>(t)] * order_sign[static_cast<std::size_t>(t)] != majority)
        suspect[static_cast<std::size_t>(t)] = 1;
    for (index_t t : big_) suspect[static_cast<std::size_t>(t)] = 0;
    // Overlapping triangles have overlapping boxes: every triangle whose box meets a suspect's is left to the tree.
    std::vector<char> near_fold(static_cast<std::size_t>(n), 0);
    for (index_t t = 0; t < n; ++t)
      if (suspect[static_cast<std::size_t>(t)]) {
        near_fold[static_cast<std::size_t>(t)] = 1;  // even when its box is not a box (non-finite corners)
        mark_boxes_meeting(boxes_[static_cast<std::size_t>(t)], near_fold);
      }
    walkable_.assign(static_cast<std::size_t>(n), 0);
    for (index_t t = 0; t < n; ++t) walkable_[static_cast<std::size_t>(t)] = !near_fold[static_cast<std::size_t>(t)];
  }

  /// Sets marks[t] for every indexed triangle (the tree's and the big ones) whose box meets `b`.
  void mark_boxes_meeting(const box& b, std::vector<char>& marks) const {
    const auto meets = [&](const box& c) {
      return c.lo[0] <= b.hi[0] && b.lo[0] <= c.hi[0] && c.lo[1] <= b.hi[1] && b.lo[1] <= c.hi[1];
    };
    for (index_t t : big_)
      if (meets(boxes_[static_cast<std::size_t>(t)])) marks[static_cast<std::size_t>(t)] = 1;
    if (nodes_.empty()) return;
    std::vector<std::size_t> stack{0};
    while (!stack.empty()) {
      const node& nd = nodes_[stack.back()];
      stack.pop_back();
      if (!meets(nd.bounds)) continue;
      if (nd.count > 0) {
        for (std::size_t i = nd.first; i < nd.first + nd.count; ++i)
          if (meets(boxes_[static_cast<std::size_t>(order_[i])])) marks[static_cast<std::size_t>(order_[i])] = 1;
      } else {
        stack.push_back(nd.left);
        stack.push_back(nd.right);
      }
    }
  }

  Scalar far_value() const {
    const box& b = nodes_.empty() ? box{} : nodes_[0].bounds;
    return std::max(std::abs(b.hi[0]), std::abs(b.lo[0])) * Scalar(4) + Scalar(1);
  }

  std::size_t build(std::size_t first, std::size_t last) {
    const std::size_t id = nodes_.size();
    nodes_.push_back({});
    box b, cb;
    for (std::size_t i = first; i < last; ++i) {
      b.grow(boxes_[static_cast<std::size_t>(order_[i])]);
      cb.grow(centers_[static_cast<std::size_t>(order_[i])]);
    }
    nodes_[id].bounds = b;
    if (last - first <= leaf_size) {
      nodes_[id].first = first;
      nodes_[id].count = last - first;
      return id;
    }
    // Median split of the centres along the longer axis: balanced depth whatever the scale range.
    const int axis = (cb.hi[0] - cb.lo[0]) >= (cb.hi[1] - cb.lo[1]) ? 0 : 1;
    const std::size_t mid = first + (last - first) / 2;
    std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(first),
                     order_.begin() + static_cast<std::ptrdiff_t>(mid), order_.begin() + static_cast<std::ptrdiff_t>(last),
                     [&](index_t x, index_t y) {
                       const complex cx = centers_[static_cast<std::size_t>(x)], cy = centers_[static_cast<std::size_t>(y)];
                       return axis == 0 ? cx.real() < cy.real() : cx.imag() < cy.imag();
                     });
    const std::size_t l = build(first, mid);
    const std::size_t r = build(mid, last);
    nodes_[id].left = l;
    nodes_[id].right = r;
    return id;
  }

  static Scalar cross(complex u, complex v) { return u.real() * v.imag() - u.imag() * v.real(); }

  /// Distance from q to triangle t (0 inside) and the barycentric weights of the closest point.
  hit test(index_t t, complex q) const {
    const complex p0 = pts_[static_cast<std::size_t>(tris_(t, 0))], p1 = pts_[static_cast<std::size_t>(tris_(t, 1))],
                  p2 = pts_[static_cast<std::size_t>(tris_(t, 2))];
    hit h;
    h.triangle = t;
    const Scalar area = cross(p1 - p0, p2 - p0);
    const Scalar scale = std::norm(p1 - p0) + std::norm(p2 - p0) + std::norm(p2 - p1);
    if (std::abs(area) > Scalar(1e-14) * scale && scale > Scalar(0)) {
      Scalar l[3];
      barycentric(t, q, l);
      const Scalar tol = Scalar(-1e-10);
      if (l[0] >= tol && l[1] >= tol && l[2] >= tol) return inside(t, l);
    }
    // Outside (or degenerate): closest point on the three edges.
    const complex P[3] = {p0, p1, p2};
    for (int e = 0; e < 3; ++e) {
      const complex a = P[e], b = P[(e + 1) % 3];
      const Scalar len2 = std::norm(b - a);
      Scalar s = len2 > Scalar(0) ? ((q - a) * std::conj(b - a)).real() / len2 : Scalar(0);
      s = std::clamp(s, Scalar(0), Scalar(1));
      const Scalar dist = std::abs(q - (a + s * (b - a)));
      if (dist < h.distance) {
        h.distance = dist;
        h.bary.setZero();
        h.bary[e] = Scalar(1) - s;
        h.bary[(e + 1) % 3] = s;
      }
    }
    return h;
  }

  std::vector<complex> pts_;
  Eigen::Matrix<index_t, Eigen::Dynamic, 3> tris_;
  std::vector<index_t> order_;
  std::vector<index_t> big_;
  std::vector<box> boxes_;
  std::vector<complex> centers_;
  std::vector<node> nodes_;
  Eigen::Matrix<index_t, Eigen::Dynamic, 3> neighbours_;
  std::vector<char> walkable_;
};

}  // namespace shapestruct
