// SPDX-License-Identifier: MIT
// closest_point_query: exact closest point on a triangle mesh or soup to query points, through an AABB tree.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/heap_bytes.hpp"
#include "shapestruct/core/surface_point.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/knn/detail/morton_order.hpp"

namespace shapestruct {

/// The closest point of a triangle to a query: the point, its barycentric weights (a, b, c) and the squared
/// distance.
template <class Scalar = double>
struct triangle_closest_point {
  vec3<Scalar> point;
  vec3<Scalar> bary;
  Scalar sq_distance;
};

namespace detail {

/// Closest point on segment [x, y] to p as the weight t of y (x + t (y - x)); a zero-length segment gives 0.
template <class Scalar>
Scalar segment_parameter(const vec3<Scalar>& p, const vec3<Scalar>& x, const vec3<Scalar>& y) {
  const vec3<Scalar> e = y - x;
  const Scalar ee = e.squaredNorm();
  if (!(ee > Scalar(0))) return Scalar(0);
  return std::clamp((p - x).dot(e) / ee, Scalar(0), Scalar(1));
}

}  // namespace detail

/// Exact closest point of triangle (a, b, c) to p: Ericson's Voronoi-region test ("Real-Time Collision
/// Detection", 5.1.5), which decides the region (vertex, edge or face) with dot products and divides only once.
/// Degenerate triangles (|ab x ac| below 64 machine epsilons of the longest squared edge, i.e. collinear or
/// coincident corners) have no face region and would divide 0 by 0 there; they are handled as the union of
/// their three edges, so the result is always finite. O(1).
/// \returns the point, barycentric weights summing to 1, and the squared distance.
template <class Scalar>
[[nodiscard]] triangle_closest_point<Scalar> closest_point_on_triangle(const vec3<Scalar>& p, const vec3<Scalar>& a,
                                                                       const vec3<Scalar>& b, const vec3<Scalar>& c) {
  const vec3<Scalar> ab = b - a, ac = c - a, bc = c - b;
  const Scalar longest = std::max({ab.squaredNorm(), ac.squaredNorm(), bc.squaredNorm()});
  const Scalar tol = Scalar(64) * std::numeric_limits<Scalar>::epsilon() * longest;
  triangle_closest_point<Scalar> out;
  auto finish = [&](Scalar wa, Scalar wb, Scalar wc) {
    out.bary = vec3<Scalar>(wa, wb, wc);
    out.point = wa * a + wb * b + wc * c;
    out.sq_distance = (p - out.point).squaredNorm();
    return out;
  };
  if (!(ab.cross(ac).norm() > tol)) {
    // Degenerate: best of the three edges (each a clamped projection, safe for zero-length edges).
    const Scalar t_ab = detail::segment_parameter(p, a, b), t_ac = detail::segment_parameter(p, a, c),
                 t_bc = detail::segment_parameter(p, b, c);
    const Scalar d_ab = (p - (a + t_ab * ab)).squaredNorm(), d_ac = (p - (a + t_ac * ac)).squaredNorm(),
                 d_bc = (p - (b + t_bc * bc)).squaredNorm();
    if (d_ab <= d_ac && d_ab <= d_bc) return finish(Scalar(1) - t_ab, t_ab, Scalar(0));
    if (d_ac <= d_bc) return finish(Scalar(1) - t_ac, Scalar(0), t_ac);
    return finish(Scalar(0), Scalar(1) - t_bc, t_bc);
  }
  const vec3<Scalar> ap = p - a;
  const Scalar d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return finish(1, 0, 0);  // vertex region a
  const vec3<Scalar> bp = p - b;
  const Scalar d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return finish(0, 1, 0);  // vertex region b
  const Scalar vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {  // edge region ab; d1 - d3 = |ab|^2 > 0 here
    const Scalar v = d1 / (d1 - d3);
    return finish(Scalar(1) - v, v, 0);
  }
  const vec3<Scalar> cp = p - c;
  const Scalar d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return finish(0, 0, 1);  // vertex region c
  const Scalar vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {  // edge region ac; d2 - d6 = |ac|^2 > 0
    const Scalar w = d2 / (d2 - d6);
    return finish(Scalar(1) - w, 0, w);
  }
  const Scalar va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {  // edge region bc; the sum is |bc|^2 > 0
    const Scalar w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return finish(0, Scalar(1) - w, w);
  }
  // Face region: va + vb + vc = |ab x ac|^2 > 0 for a non-degenerate triangle.
  const Scalar denom = Scalar(1) / (va + vb + vc);
  const Scalar v = vb * denom, w = vc * denom;
  return finish(Scalar(1) - v - w, v, w);
}

/// One closest-point answer: where on the mesh (face + barycentric), the point itself and its squared distance
/// to the query.
template <class Scalar = double>
struct closest_point_result {
  surface_point<Scalar> location;
  vec3<Scalar> point = vec3<Scalar>::Zero();
  Scalar sq_distance = std::numeric_limits<Scalar>::infinity();
};

/// Closest points of a batch of queries (row q answers query q).
///   faces         (#Q)     face index of each closest point
///   bary          (#Q x 3) barycentric weights in that face (rows sum to 1)
///   points        (#Q x 3) closest points
///   sq_distances  (#Q)     squared distances query-closest point
template <class Scalar = double>
struct closest_point_batch {
  Eigen::Matrix<index_t, Eigen::Dynamic, 1> faces;
  matrix_x3<Scalar> bary;
  matrix_x3<Scalar> points;
  vector_x<Scalar> sq_distances;

  /// Query q's answer as a surface_point.
  [[nodiscard]] surface_point<Scalar> location(index_t q) const {
    return surface_point<Scalar>{faces[q], bary.row(q).transpose()};
  }
};

/// Options of closest_point_query.
struct closest_point_query_options {
  /// Triangles per leaf of the AABB tree. 4 balances box tests against triangle tests (each triangle test
  /// costs about as much as two box tests). Must be >= 1.
  index_t leaf_size = 4;
  /// validation_level::trust skips validate_mesh for callers that already checked the mesh.
  validation_level validation = validation_level::full;
};

/// Exact closest point on a triangle mesh (or polygon soup: faces need not share vertices) to query points.
/// Builds a bounding-volume hierarchy of axis-aligned boxes once (median split along the widest centroid axis,
/// O(F log F) time, O(F) memory), then answers each query by best-first descent with box-distance pruning
/// (O(log F) expected for queries near the surface) and Ericson's exact point-triangle test.
///
/// Ties: among faces at exactly the same computed distance the lowest face index wins, so the answer is
/// unique and independent of tree layout and thread count. Degenerate (zero-area) faces are kept and treated
/// as segments or points; they never produce NaN.
///
/// Lifetime and threads: the query owns copies of V and F (the source may be destroyed); all const member
/// functions may run concurrently.
/// \tparam Scalar float or double
template <class Scalar = double>
class closest_point_query {
  static_assert(std::is_floating_point_v<Scalar>, "shapestruct: closest_point_query needs a floating-point scalar");

 public:
  using scalar_type = Scalar;

  /// Builds the tree over (V, F).
  /// \param V (#V x 3) vertex positions
  /// \param F (#F x 3) triangles (indices into V)
  /// \throws invalid_input empty (no vertices or faces), non_finite (vertex), bad_face (face index out of range
  ///         or repeated vertex), bad_parameter (leaf_size < 1)
  closest_point_query(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                      const closest_point_query_options& options = {})
      : V_(V), F_(F) {
    build(options);
  }

  /// Builds the tree over any SurfaceMesh, gathered into triangle_mesh<Scalar> first (O(V + F)).
  /// \throws as the (V, F) constructor.
  template <SurfaceMesh Mesh>
  explicit closest_point_query(const Mesh& mesh, const closest_point_query_options& options = {}) {
    auto m = to_triangle_mesh<Scalar>(mesh);
    V_ = std::move(m.V);
    F_ = std::move(m.F);
    build(options);
  }

  [[nodiscard]] index_t num_faces() const noexcept { return F_.rows(); }
  /// Bytes held on the heap (core/heap_bytes.hpp).
  [[nodiscard]] std::size_t heap_bytes() const noexcept {
    using shapestruct::heap_bytes;
    return heap_bytes(V_) + heap_bytes(F_) + heap_bytes(nodes_) + heap_bytes(order_);
  }
  /// The copied vertices (#V x 3) and faces (#F x 3) the answers refer to.
  [[nodiscard]] const matrix_x3<Scalar>& vertices() const noexcept { return V_; }
  [[nodiscard]] const face_matrix& faces() const noexcept { return F_; }

  /// Closest point on the mesh to q (any 3-vector expression, row or column). O(log F) expected.
  /// \throws invalid_input bad_parameter (q is not a 3-vector), non_finite (q has a NaN/Inf)
  template <class Derived>
  [[nodiscard]] closest_point_result<Scalar> query(const Eigen::MatrixBase<Derived>& q) const {
    if (q.size() != 3)
      throw invalid_input(input_error::bad_parameter, no_index,
                          "closest_point_query::query: the query must have 3 coordinates, got " +
                              std::to_string(q.size()));
    const vec3<Scalar> p(static_cast<Scalar>(q.derived().coeff(0)), static_cast<Scalar>(q.derived().coeff(1)),
                         static_cast<Scalar>(q.derived().coeff(2)));
    if (!p.allFinite())
      throw invalid_input(input_error::non_finite, no_index,
                          "closest_point_query::query: the query point has a non-finite coordinate");
    return query_unchecked(p);
  }

  /// Closest points of all rows of Q, in parallel; row q equals query(Q.row(q)) for any thread count.
  /// O(#Q log F / threads) expected.
  /// \param Q       (#Q x 3) query points
  /// \param threads worker threads, 0 = all cores
  /// \throws invalid_input non_finite (index of the offending query row), bad_parameter (threads < 0)
  [[nodiscard]] closest_point_batch<Scalar> query_batch(const Eigen::Ref<const matrix_x3<Scalar>>& Q,
                                                        int threads = 0) const {
    const unsigned workers = detail::resolve_threads(threads, "closest_point_query::query_batch");
    if (!Q.allFinite())
      for (index_t i = 0; i < Q.rows(); ++i)
        if (!Q.row(i).allFinite())
          throw invalid_input(input_error::non_finite, i,
                              "closest_point_query::query_batch: query " + std::to_string(i) +
                                  " has a non-finite coordinate");
    closest_point_batch<Scalar> out;
    out.faces.resize(Q.rows());
    out.bary.resize(Q.rows(), 3);
    out.points.resize(Q.rows(), 3);
    out.sq_distances.resize(Q.rows());
    // Queries in Morton order share tree paths with their predecessors (cache hits); answers go to their own
    // rows, so the result does not depend on the order.
    std::vector<std::uint32_t> order;
    if (Q.rows() >= 1024)
      order = detail::morton_order<3>(static_cast<std::size_t>(Q.rows()),
                                      [&](std::size_t i, int d) { return Q(static_cast<index_t>(i), d); });
    detail::parallel_for(Q.rows(), workers, [&](index_t j) {
      const index_t i = order.empty() ? j : static_cast<index_t>(order[static_cast<std::size_t>(j)]);
      const auto r = query_unchecked(Q.row(i).transpose());
      out.faces[i] = r.location.face;
      out.bary.row(i) = r.location.bary.transpose();
      out.points.row(i) = r.point.transpose();
      out.sq_distances[i] = r.sq_distance;
    });
    return out;
  }

 private:
  struct node {
    std::array<Scalar, 3> lo, hi;
    // Leaf (count > 0): faces order_[first, first + count). Inner node: children nodes_[first], nodes_[second].
    std::int64_t first = 0, second = 0;
    std::int64_t count = 0;  // > 0 for leaves
  };

  void build(const closest_point_query_options& options) {
    if (options.leaf_size < 1)
      throw invalid_input(input_error::bad_parameter, no_index,
                          "closest_point_query: leaf_size must be >= 1, got " + std::to_string(options.leaf_size));
    validate_mesh(V_, F_, "closest_point_query", options.validation);
    const index_t nf = F_.rows();
    // Per-face boxes and centroids, computed once.
    std::vector<std::array<Scalar, 3>> lo(static_cast<std::size_t>(nf)), hi(static_cast<std::size_t>(nf)),
        mid(static_cast<std::size_t>(nf));
    for (index_t f = 0; f < nf; ++f) {
      const auto s = static_cast<std::size_t>(f);
      for (int d = 0; d < 3; ++d) {
        const Scalar a = V_(F_(f, 0), d), b = V_(F_(f, 1), d), c = V_(F_(f, 2), d);
        lo[s][static_cast<std::size_t>(d)] = std::min({a, b, c});
        hi[s][static_cast<std::size_t>(d)] = std::max({a, b, c});
        mid[s][static_cast<std::size_t>(d)] = (a + b + c) / Scalar(3);
      }
    }
    order_.resize(static_cast<std::size_t>(nf));
    for (index_t f = 0; f < nf; ++f) order_[static_cast<std::size_t>(f)] = f;
    nodes_.clear();
    nodes_.reserve(static_cast<std::size_t>(2 * (nf / options.leaf_size) + 2));
    struct task {
      std::size_t node_id;
      std::size_t begin, end;
    };
    nodes_.emplace_back();
    std::vector<task> stack{{0, 0, static_cast<std::size_t>(nf)}};
    while (!stack.empty()) {
      const task t = stack.back();
      stack.pop_back();
      node nd;
      nd.lo.fill(std::numeric_limits<Scalar>::infinity());
      nd.hi.fill(-std::numeric_limits<Scalar>::infinity());
      std::array<Scalar, 3> clo = nd.lo, chi = nd.hi;
      for (std::size_t i = t.begin; i < t.end; ++i) {
        const auto f = static_cast<std::size_t>(order_[i]);
        for (std::size_t d = 0; d < 3; ++d) {
          nd.lo[d] = std::min(nd.lo[d], lo[f][d]);
          nd.hi[d] = std::max(nd.hi[d], hi[f][d]);
          clo[d] = std::min(clo[d], mid[f][d]);
          chi[d] = std::max(chi[d], mid[f][d]);
        }
      }
      const std::size_t n = t.end - t.begin;
      if (n <= static_cast<std::size_t>(options.leaf_size)) {
        nd.first = static_cast<std::int64_t>(t.begin);
        nd.count = static_cast<std::int64_t>(n);
        nodes_[t.node_id] = nd;
        continue;
      }
      std::size_t axis = 0;
      for (std::size_t d = 1; d < 3; ++d)
        if (chi[d] - clo[d] > chi[axis] - clo[axis]) axis = d;
      // Median split (nth_element, O(n)) keeps the tree balanced even when all centroids coincide, so the
      // depth is O(log F) and the build O(F log F). Ties by face index keep the layout deterministic.
      const std::size_t m = t.begin + n / 2;
      std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(t.begin),
                       order_.begin() + static_cast<std::ptrdiff_t>(m),
                       order_.begin() + static_cast<std::ptrdiff_t>(t.end), [&](index_t x, index_t y) {
                         const Scalar cx = mid[static_cast<std::size_t>(x)][axis],
                                      cy = mid[static_cast<std::size_t>(y)][axis];
                         return cx < cy || (cx == cy && x < y);
                       });
      const std::size_t left = nodes_.size();
      nodes_.emplace_back();
      nodes_.emplace_back();
      nd.first = static_cast<std::int64_t>(left);
      nd.second = static_cast<std::int64_t>(left + 1);
      nd.count = 0;
      nodes_[t.node_id] = nd;
      stack.push_back({left, t.begin, m});
      stack.push_back({left + 1, m, t.end});
    }
  }

  static Scalar box_sq_distance(const node& nd, const vec3<Scalar>& p) {
    Scalar s = 0;
    for (int d = 0; d < 3; ++d) {
      const auto k = static_cast<std::size_t>(d);
      const Scalar e = std::max({nd.lo[k] - p[d], Scalar(0), p[d] - nd.hi[k]});
      s += e * e;
    }
    return s;
  }

  closest_point_result<Scalar> query_unchecked(const vec3<Scalar>& p) const {
    closest_point_result<Scalar> best;
    if (F_.rows() == 0) return best;  // only reachable with validation_level::trust
    // Fixed-capacity stack: the tree depth is at most log2(F) + 1 < 64, and each level pushes one sibling.
    std::array<std::pair<std::size_t, Scalar>, 128> stack;
    std::size_t top = 0;
    stack[top++] = {0, box_sq_distance(nodes_[0], p)};
    while (top > 0) {
      const auto [id, dist] = stack[--top];
      // ">" and not ">=": a box at exactly the best distance may hold a lower-index face at that distance.
      if (dist > best.sq_distance) continue;
      const node& nd = nodes_[id];
      if (nd.count > 0) {
        for (std::int64_t i = nd.first; i < nd.first + nd.count; ++i) {
          const index_t f = order_[static_cast<std::size_t>(i)];
          const auto r = closest_point_on_triangle<Scalar>(p, V_.row(F_(f, 0)).transpose(), V_.row(F_(f, 1)).transpose(),
                                                           V_.row(F_(f, 2)).transpose());
          if (r.sq_distance < best.sq_distance ||
              (r.sq_distance == best.sq_distance && f < best.location.face)) {
            best.sq_distance = r.sq_distance;
            best.point = r.point;
            best.location.face = f;
            best.location.bary = r.bary;
          }
        }
        continue;
      }
      const auto l = static_cast<std::size_t>(nd.first), r = static_cast<std::size_t>(nd.second);
      const Scalar dl = box_sq_distance(nodes_[l], p), dr = box_sq_distance(nodes_[r], p);
      // Push the farther child first so the nearer one is explored first and tightens the bound early.
      if (dl <= dr) {
        if (dr <= best.sq_distance) stack[top++] = {r, dr};
        if (dl <= best.sq_distance) stack[top++] = {l, dl};
      } else {
        if (dl <= best.sq_distance) stack[top++] = {l, dl};
        if (dr <= best.sq_distance) stack[top++] = {r, dr};
      }
    }
    return best;
  }

  matrix_x3<Scalar> V_;
  face_matrix F_;
  std::vector<node> nodes_;
  std::vector<index_t> order_;
};

/// One-off convenience: builds a closest_point_query over `mesh` and answers all rows of Q.
/// \param mesh    any SurfaceMesh (gathered into triangle_mesh<Scalar>)
/// \param Q       (#Q x 3) query points
/// \param threads worker threads, 0 = all cores
/// \throws as closest_point_query's constructor and query_batch; size_mismatch if Q does not have 3 columns.
/// O(F log F + #Q log F).
template <class Scalar = double, SurfaceMesh Mesh, class DerivedQ>
[[nodiscard]] closest_point_batch<Scalar> closest_points(const Mesh& mesh, const Eigen::MatrixBase<DerivedQ>& Q,
                                                         int threads = 0,
                                                         const closest_point_query_options& options = {}) {
  if (Q.cols() != 3)
    throw invalid_input(input_error::size_mismatch, no_index,
                        "closest_points: Q must be #Q x 3, got " + std::to_string(Q.cols()) + " columns");
  const matrix_x3<Scalar> queries = Q.template cast<Scalar>();
  return closest_point_query<Scalar>(mesh, options).query_batch(queries, threads);
}

}  // namespace shapestruct
