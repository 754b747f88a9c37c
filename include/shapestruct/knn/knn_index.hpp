// SPDX-License-Identifier: MIT
// knn_index: exact k-nearest-neighbour and radius queries over a fixed point set (a nanoflann kd-tree).
//
// This is the ONLY header of shapestruct that includes <nanoflann.hpp>. nanoflann 1.5 renamed SearchParams to
// SearchParameters and changed radiusSearch's result type; the version switch below and our own result sets
// (which only rely on the addPoint / worstDist / full protocol shared by 1.4 and 1.5) keep both compiling.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nanoflann.hpp>

#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/heap_bytes.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/knn/detail/morton_order.hpp"

namespace shapestruct {

namespace detail {
#if defined(NANOFLANN_VERSION) && NANOFLANN_VERSION >= 0x150
using nanoflann_search_params = nanoflann::SearchParameters;
#else
using nanoflann_search_params = nanoflann::SearchParams;
#endif
}  // namespace detail

/// Neighbours of one query: point indices and squared Euclidean distances, both sorted by increasing
/// distance (ties by increasing index).
template <class Scalar = double>
struct knn_result {
  std::vector<index_t> indices;
  std::vector<Scalar> sq_distances;

  [[nodiscard]] index_t size() const noexcept { return static_cast<index_t>(indices.size()); }
};

/// Neighbours of a batch of queries: row q holds the neighbours of query q, sorted by increasing distance.
///   indices       (#Q x k') point indices
///   sq_distances  (#Q x k') squared Euclidean distances
/// with k' = min(k, number of indexed points).
template <class Scalar = double>
struct knn_batch_result {
  Eigen::Matrix<index_t, Eigen::Dynamic, Eigen::Dynamic> indices;
  matrix_x<Scalar> sq_distances;
};

/// The nearest indexed point to a query: its index and squared distance (index == no_index for an empty index).
template <class Scalar = double>
struct nearest_neighbor {
  index_t index = no_index;
  Scalar sq_distance = std::numeric_limits<Scalar>::infinity();
};

/// Build options of knn_index.
struct knn_index_options {
  /// Points per kd-tree leaf. nanoflann's default of 10 is close to the optimum for k = 1..16 queries in 3-D
  /// (smaller leaves deepen the tree, larger ones scan more points per leaf). Must be >= 1.
  index_t leaf_size = 10;
  /// Store the points in Morton (Z-order) order of their first min(Dim, 3) coordinates, so that each kd-tree
  /// leaf's points are contiguous in memory. Answers are identical either way (indices always refer to the
  /// input order); it only changes speed, mostly for sets larger than the CPU caches.
  bool spatial_sort = true;
};

/// Exact Euclidean k-nearest-neighbour and radius search over a fixed set of Dim-dimensional points,
/// a kd-tree built with nanoflann (O(P log P) build; memory: the copied coordinates, plus three 32-bit ids per
/// point for nanoflann's permutation and the Morton-order maps).
///
/// Lifetime: the index OWNS a copy of the points, so the source may be modified or destroyed after
/// construction. The index is move-only (the kd-tree refers to the copied points; moving keeps them in place).
///
/// Thread safety: all const member functions (knn, radius, nearest, knn_batch) may run concurrently on the
/// same index from any number of threads; nanoflann's search is read-only on a built tree.
///
/// Empty sets: an index over zero points is valid; every query on it returns an empty result (nearest()
/// returns index no_index). k larger than the number of points returns all points.
/// \tparam Scalar float or double (coordinates and squared distances)
/// \tparam Dim    compile-time dimension, >= 1
template <class Scalar = double, int Dim = 3>
class knn_index {
  static_assert(std::is_floating_point_v<Scalar>, "shapestruct: knn_index needs a floating-point scalar");
  static_assert(Dim >= 1, "shapestruct: knn_index needs a compile-time dimension >= 1");

 public:
  using scalar_type = Scalar;
  static constexpr int dimension = Dim;
  /// One point as a column vector.
  using point_type = Eigen::Matrix<Scalar, Dim, 1>;
  /// `#P x Dim` points, one per row.
  using points_matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Dim>;

  /// An index over zero points.
  knn_index() : impl_(std::make_unique<impl>()) {}

  /// Indexes the rows of P (O(P log P)).
  /// \param P  (#P x Dim) points, one per row; may be empty
  /// \throws invalid_input non_finite (row index) if a coordinate is NaN/Inf; bad_parameter if leaf_size < 1 or
  ///         #P >= 2^32 (nanoflann's 32-bit point ids).
  explicit knn_index(const Eigen::Ref<const points_matrix>& P, const knn_index_options& options = {})
      : impl_(std::make_unique<impl>()) {
    const index_t n = P.rows();
    impl_->adaptor.data.resize(static_cast<std::size_t>(n) * Dim);
    for (index_t i = 0; i < n; ++i)
      for (int d = 0; d < Dim; ++d) impl_->adaptor.data[static_cast<std::size_t>(i * Dim + d)] = P(i, d);
    build(options);
  }

  /// Indexes any PointSet of the same dimension (coordinates converted to Scalar; O(P log P)).
  /// \throws as the matrix constructor.
  template <PointSet Points>
    requires(point_set_traits_t<Points>::dimension == Dim)
  explicit knn_index(const Points& points, const knn_index_options& options = {})
      : impl_(std::make_unique<impl>()) {
    using traits = point_set_traits_t<Points>;
    const index_t n = static_cast<index_t>(traits::num_points(points));
    impl_->adaptor.data.resize(static_cast<std::size_t>(n) * Dim);
    for (index_t i = 0; i < n; ++i)
      for (int d = 0; d < Dim; ++d)
        impl_->adaptor.data[static_cast<std::size_t>(i * Dim + d)] = static_cast<Scalar>(traits::coord(points, i, d));
    build(options);
  }

  knn_index(knn_index&&) noexcept = default;
  knn_index& operator=(knn_index&&) noexcept = default;
  knn_index(const knn_index&) = delete;
  knn_index& operator=(const knn_index&) = delete;
  ~knn_index() = default;

  /// Number of indexed points. A moved-from index behaves as an empty one.
  [[nodiscard]] index_t size() const noexcept {
    return impl_ ? static_cast<index_t>(impl_->adaptor.data.size() / Dim) : 0;
  }
  [[nodiscard]] bool empty() const noexcept { return size() == 0; }
  /// Bytes held on the heap (core/heap_bytes.hpp): the point copy, the id maps and nanoflann's tree.
  [[nodiscard]] std::size_t heap_bytes() const noexcept {
    if (!impl_) return 0;
    using shapestruct::heap_bytes;
    std::size_t n = sizeof(impl) + heap_bytes(impl_->adaptor.data) + heap_bytes(impl_->to_input) +
                    heap_bytes(impl_->to_internal);
    if (impl_->tree) n += sizeof(tree_type) + impl_->tree->usedMemory(*impl_->tree);
    return n;
  }

  /// Point i of the indexed copy, i in [0, size()) (unchecked, like Eigen's operator()).
  [[nodiscard]] Eigen::Map<const point_type> point(index_t i) const {
    const auto& to_internal = impl_->to_internal;
    const index_t internal = to_internal.empty() ? i : static_cast<index_t>(to_internal[static_cast<std::size_t>(i)]);
    return Eigen::Map<const point_type>(impl_->adaptor.data.data() + internal * Dim);
  }

  /// The k nearest indexed points to q, sorted by increasing squared distance (O(k log P) expected).
  /// \param q any Dim-vector expression (row or column)
  /// \param k number of neighbours, >= 1; min(k, size()) are returned
  /// \throws invalid_input bad_parameter (k < 1, q of the wrong size), non_finite (q has a NaN/Inf)
  template <class Derived>
  [[nodiscard]] knn_result<Scalar> knn(const Eigen::MatrixBase<Derived>& q, index_t k) const {
    const point_type p = to_point(q, "knn_index::knn", no_index);
    check_k(k, "knn_index::knn");
    knn_result<Scalar> out;
    const index_t kk = std::min(k, size());
    if (kk == 0) return out;
    with_buffers(kk, [&](std::uint32_t* ids, Scalar* d) {
      const index_t found = knn_raw(p, kk, ids, d);
      out.indices.assign(ids, ids + found);
      out.sq_distances.assign(d, d + found);
    });
    return out;
  }

  /// Every indexed point within distance r of q (inclusive: |p - q| <= r), sorted by increasing squared
  /// distance, ties by index. Cost O(log P + result size) expected.
  /// \param r radius, finite and >= 0 (the radius itself, not its square)
  /// \throws invalid_input bad_parameter (r negative or non-finite, q of the wrong size), non_finite (q)
  template <class Derived>
  [[nodiscard]] knn_result<Scalar> radius(const Eigen::MatrixBase<Derived>& q, Scalar r) const {
    const point_type p = to_point(q, "knn_index::radius", no_index);
    if (!(r >= Scalar(0)) || !std::isfinite(r))
      throw invalid_input(input_error::bad_parameter, no_index,
                          "knn_index::radius: the radius must be finite and >= 0, got " + std::to_string(r));
    knn_result<Scalar> out;
    if (empty()) return out;
    std::vector<std::pair<std::uint32_t, Scalar>> hits;
    radius_raw(p, r * r, hits);
    out.indices.reserve(hits.size());
    out.sq_distances.reserve(hits.size());
    for (const auto& h : hits) {
      out.indices.push_back(static_cast<index_t>(h.first));
      out.sq_distances.push_back(h.second);
    }
    return out;
  }

  /// Same as radius() but writes into caller-owned buffers (cleared first), to avoid an allocation per query
  /// in hot loops. `hits` holds (index, squared distance) pairs sorted like radius().
  template <class Derived>
  void radius_into(const Eigen::MatrixBase<Derived>& q, Scalar r,
                   std::vector<std::pair<std::uint32_t, Scalar>>& hits) const {
    const point_type p = to_point(q, "knn_index::radius_into", no_index);
    if (!(r >= Scalar(0)) || !std::isfinite(r))
      throw invalid_input(input_error::bad_parameter, no_index,
                          "knn_index::radius_into: the radius must be finite and >= 0, got " + std::to_string(r));
    hits.clear();
    if (!empty()) radius_raw(p, r * r, hits);
  }

  /// The nearest indexed point to q (index no_index and infinite distance if the index is empty).
  /// \throws invalid_input bad_parameter (q of the wrong size), non_finite (q)
  template <class Derived>
  [[nodiscard]] nearest_neighbor<Scalar> nearest(const Eigen::MatrixBase<Derived>& q) const {
    const point_type p = to_point(q, "knn_index::nearest", no_index);
    nearest_neighbor<Scalar> out;
    if (empty()) return out;
    std::uint32_t id = 0;
    Scalar d = 0;
    if (knn_raw(p, 1, &id, &d) == 1) {
      out.index = static_cast<index_t>(id);
      out.sq_distance = d;
    }
    return out;
  }

  /// k nearest neighbours of every row of Q, in parallel. Row q of the result equals knn(Q.row(q), k) for any
  /// thread count (each query is independent and writes only its own row). O(#Q k log P / threads).
  /// \param Q       (#Q x Dim) queries, one per row
  /// \param k       >= 1; the result has min(k, size()) columns
  /// \param threads worker threads, 0 = all cores
  /// \throws invalid_input bad_parameter (k < 1, threads < 0), non_finite (row index of the offending query)
  [[nodiscard]] knn_batch_result<Scalar> knn_batch(const Eigen::Ref<const points_matrix>& Q, index_t k,
                                                   int threads = 0) const {
    check_k(k, "knn_index::knn_batch");
    const unsigned workers = detail::resolve_threads(threads, "knn_index::knn_batch");
    if (!Q.allFinite())
      for (index_t i = 0; i < Q.rows(); ++i)
        if (!Q.row(i).allFinite())
          throw invalid_input(input_error::non_finite, i,
                              "knn_index::knn_batch: query " + std::to_string(i) + " has a non-finite coordinate");
    const index_t kk = std::min(k, size());
    knn_batch_result<Scalar> out;
    out.indices.setConstant(Q.rows(), kk, no_index);
    out.sq_distances.setConstant(Q.rows(), kk, std::numeric_limits<Scalar>::infinity());
    if (kk == 0) return out;
    // Answer the queries in Morton order: consecutive queries then walk the same tree branches and leaves,
    // which stay in cache. Each answer still goes to its own row, so the result is unchanged.
    std::vector<std::uint32_t> order;
    if (Q.rows() >= 1024)
      order = detail::morton_order<Dim>(static_cast<std::size_t>(Q.rows()),
                           [&](std::size_t i, int d) { return Q(static_cast<index_t>(i), d); });
    detail::parallel_for(Q.rows(), workers, [&](index_t j) {
      const index_t i = order.empty() ? j : static_cast<index_t>(order[static_cast<std::size_t>(j)]);
      const point_type p = Q.row(i).transpose();
      with_buffers(kk, [&](std::uint32_t* ids, Scalar* d) {
        const index_t found = knn_raw(p, kk, ids, d);
        for (index_t j = 0; j < found; ++j) {
          out.indices(i, j) = static_cast<index_t>(ids[j]);
          out.sq_distances(i, j) = d[j];
        }
      });
    });
    return out;
  }

 private:
  // nanoflann's dataset protocol over our flat row-major copy.
  struct adaptor_type {
    std::vector<Scalar> data;
    [[nodiscard]] std::size_t kdtree_get_point_count() const { return data.size() / Dim; }
    [[nodiscard]] Scalar kdtree_get_pt(std::size_t i, std::size_t d) const { return data[i * Dim + d]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const {
      return false;  // let nanoflann compute the bounding box
    }
  };
  // L2_Simple sums all coordinates; L2 terminates early against the current worst distance, which only pays
  // off in higher dimensions.
  using metric = std::conditional_t<(Dim <= 4), nanoflann::L2_Simple_Adaptor<Scalar, adaptor_type, Scalar, std::uint32_t>,
                                    nanoflann::L2_Adaptor<Scalar, adaptor_type, Scalar, std::uint32_t>>;
  using tree_type = nanoflann::KDTreeSingleIndexAdaptor<metric, adaptor_type, Dim, std::uint32_t>;

  // The tree keeps a reference to the adaptor: both live together on the heap so moving the index is safe.
  struct impl {
    adaptor_type adaptor;
    std::unique_ptr<tree_type> tree;
    // With spatial_sort: to_input[internal id] = input index, to_internal[input index] = internal id.
    // Empty when the points are stored in input order.
    std::vector<std::uint32_t> to_input, to_internal;
  };

  // k best candidates ordered by (distance, index), the protocol nanoflann 1.4 and 1.5 both call.
  // Ids are mapped back to input indices as they arrive (to_input, or nullptr for identity), so ties are
  // broken by input index whatever the storage order.
  struct knn_set {
    std::uint32_t* ids;
    Scalar* dists;
    std::size_t capacity;
    const std::uint32_t* to_input;
    std::size_t count = 0;
    Scalar worst = std::numeric_limits<Scalar>::max();
    bool addPoint(Scalar d, std::uint32_t internal) {
      const std::uint32_t id = to_input ? to_input[internal] : internal;
      std::size_t i = count;
      while (i > 0 && (dists[i - 1] > d || (dists[i - 1] == d && ids[i - 1] > id))) {
        if (i < capacity) {
          dists[i] = dists[i - 1];
          ids[i] = ids[i - 1];
        }
        --i;
      }
      if (i < capacity) {
        dists[i] = d;
        ids[i] = id;
      }
      if (count < capacity) ++count;
      // nanoflann offers a leaf point only if its distance is < worstDist(). Reporting the next float above
      // the current k-th distance lets points at exactly that distance through, so addPoint can break ties by
      // index and the result is the unique k smallest (distance, index) pairs. Cached rather than read as
      // dists[capacity - 1], which GCC 12 cannot prove in bounds.
      if (count == capacity) worst = std::nextafter(dists[count - 1], std::numeric_limits<Scalar>::infinity());
      return true;
    }
    [[nodiscard]] Scalar worstDist() const { return worst; }
    [[nodiscard]] bool full() const { return count == capacity; }
    [[nodiscard]] std::size_t size() const { return count; }
  };

  // All points with squared distance <= r2. nanoflann adds a leaf point only if dist < worstDist(), so the
  // bound is the next float above r2: the radius is inclusive, as documented.
  struct radius_set {
    Scalar r2;
    Scalar bound;
    std::vector<std::pair<std::uint32_t, Scalar>>* hits;
    const std::uint32_t* to_input;
    bool addPoint(Scalar d, std::uint32_t internal) {
      if (d <= r2) hits->emplace_back(to_input ? to_input[internal] : internal, d);
      return true;
    }
    [[nodiscard]] Scalar worstDist() const { return bound; }
    [[nodiscard]] bool full() const { return true; }
    [[nodiscard]] std::size_t size() const { return hits->size(); }
  };

  void build(const knn_index_options& options) {
    if (options.leaf_size < 1)
      throw invalid_input(input_error::bad_parameter, no_index,
                          "knn_index: leaf_size must be >= 1, got " + std::to_string(options.leaf_size));
    const std::size_t n = impl_->adaptor.kdtree_get_point_count();
    if (n >= std::size_t(std::numeric_limits<std::uint32_t>::max()))
      throw invalid_input(input_error::bad_parameter, no_index,
                          "knn_index: at most 2^32 - 1 points can be indexed, got " + std::to_string(n));
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < Dim; ++d)
        if (!std::isfinite(impl_->adaptor.data[i * Dim + static_cast<std::size_t>(d)]))
          throw invalid_input(input_error::non_finite, static_cast<index_t>(i),
                              "knn_index: point " + std::to_string(i) + " has a non-finite coordinate");
    if (n == 0) return;
    if (options.spatial_sort && n > static_cast<std::size_t>(options.leaf_size)) spatial_sort();
    impl_->tree = std::make_unique<tree_type>(
        Dim, impl_->adaptor,
        nanoflann::KDTreeSingleIndexAdaptorParams(static_cast<std::size_t>(options.leaf_size)));
  }

  // Stores the points in Morton order so each kd-tree leaf's points are contiguous in memory.
  void spatial_sort() {
    auto& data = impl_->adaptor.data;
    const std::size_t n = data.size() / Dim;
    impl_->to_input = detail::morton_order<Dim>(n, [&](std::size_t i, int d) { return data[i * Dim + std::size_t(d)]; });
    std::vector<Scalar> sorted(data.size());
    impl_->to_internal.resize(n);
    for (std::size_t j = 0; j < n; ++j) {
      const std::uint32_t i = impl_->to_input[j];
      impl_->to_internal[i] = static_cast<std::uint32_t>(j);
      std::copy_n(data.begin() + static_cast<std::ptrdiff_t>(std::size_t(i) * Dim), Dim,
                  sorted.begin() + static_cast<std::ptrdiff_t>(j * Dim));
    }
    data.swap(sorted);
  }

  template <class Derived>
  static point_type to_point(const Eigen::MatrixBase<Derived>& q, const char* who, index_t element) {
    if (q.size() != Dim)
      throw invalid_input(input_error::bad_parameter, element,
                          std::string(who) + ": the query has " + std::to_string(q.size()) +
                              " coordinates, the index is " + std::to_string(Dim) + "-dimensional");
    point_type p;
    for (int d = 0; d < Dim; ++d) p[d] = static_cast<Scalar>(q.derived().coeff(d));
    if (!p.allFinite())
      throw invalid_input(input_error::non_finite, element,
                          std::string(who) + ": the query point has a non-finite coordinate");
    return p;
  }

  static void check_k(index_t k, const char* who) {
    if (k < 1)
      throw invalid_input(input_error::bad_parameter, no_index,
                          std::string(who) + ": k must be >= 1, got " + std::to_string(k));
  }

  // Calls f(ids, dists) with scratch buffers of k entries: on the stack for the common small k (a heap
  // allocation per query would cost about as much as the search itself at 10K points).
  template <class F>
  static void with_buffers(index_t k, F&& f) {
    constexpr index_t stack_k = 64;
    if (k <= stack_k) {
      std::array<std::uint32_t, stack_k> ids;
      std::array<Scalar, stack_k> d;
      f(ids.data(), d.data());
    } else {
      std::vector<std::uint32_t> ids(static_cast<std::size_t>(k));
      std::vector<Scalar> d(static_cast<std::size_t>(k));
      f(ids.data(), d.data());
    }
  }

  index_t knn_raw(const point_type& p, index_t k, std::uint32_t* ids, Scalar* d) const {
    knn_set set{ids, d, static_cast<std::size_t>(k), impl_->to_input.empty() ? nullptr : impl_->to_input.data()};
    impl_->tree->findNeighbors(set, p.data(), detail::nanoflann_search_params());
    return static_cast<index_t>(set.size());
  }

  void radius_raw(const point_type& p, Scalar r2, std::vector<std::pair<std::uint32_t, Scalar>>& hits) const {
    radius_set set{r2, std::nextafter(r2, std::numeric_limits<Scalar>::infinity()), &hits,
                   impl_->to_input.empty() ? nullptr : impl_->to_input.data()};
    impl_->tree->findNeighbors(set, p.data(), detail::nanoflann_search_params());
    std::sort(hits.begin(), hits.end(), [](const auto& a, const auto& b) {
      return a.second < b.second || (a.second == b.second && a.first < b.first);
    });
  }

  std::unique_ptr<impl> impl_;
};

}  // namespace shapestruct
