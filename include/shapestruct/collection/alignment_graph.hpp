// SPDX-License-Identifier: MIT
// alignment_graph: which pairs of shapes get aligned (ch. 4.3.2), and the initial graph G_0 built from
// descriptor distances: minimum spanning tree plus the candidate edges of highest edge rank.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
// Boost.Graph's headers trip GCC 12's -Wmaybe-uninitialized (a false positive inside boost::optional, see
// alpha_expansion.hpp); GCC attributes the warning to the header's lines, so silencing it around the includes
// is enough.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/kruskal_min_spanning_tree.hpp>
#include <boost/property_map/function_property_map.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "shapestruct/collection/edge_rank.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// An undirected graph over the shapes of a collection: an edge (i, j) means "align shape i with shape j".
/// Invariant (kept by make_alignment_graph and initial_alignment_graph; has_edge relies on it): every edge has
/// 0 <= i < j < nodes, and `edges` is sorted without duplicates.
struct alignment_graph {
  index_t nodes = 0;
  std::vector<std::pair<index_t, index_t>> edges;

  [[nodiscard]] index_t edge_count() const noexcept { return static_cast<index_t>(edges.size()); }

  /// Whether {a, b} is an edge (either order). O(log E).
  [[nodiscard]] bool has_edge(index_t a, index_t b) const {
    return std::binary_search(edges.begin(), edges.end(), std::pair<index_t, index_t>(std::min(a, b), std::max(a, b)));
  }

  /// The neighbours of `node`, ascending. O(E): for many nodes build adjacency_lists() once instead.
  [[nodiscard]] std::vector<index_t> neighbours(index_t node) const {
    std::vector<index_t> out;
    for (const auto& [a, b] : edges) {
      if (a == node) out.push_back(b);
      else if (b == node) out.push_back(a);
    }
    std::sort(out.begin(), out.end());
    return out;
  }
};

namespace detail {

inline void check_alignment_graph(const char* who, const alignment_graph& g) {
  if (g.nodes < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": the graph has a negative node count (" + std::to_string(g.nodes) + ")");
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    const auto [a, b] = g.edges[e];
    if (a < 0 || b >= g.nodes || a >= b)
      throw invalid_input(input_error::bad_face, static_cast<index_t>(e),
                          std::string(who) + ": edge " + std::to_string(e) + " = (" + std::to_string(a) + ", " +
                              std::to_string(b) + ") is not 0 <= i < j < " + std::to_string(g.nodes) +
                              "; build graphs with make_alignment_graph()");
  }
}

}  // namespace detail

/// An alignment_graph from any list of pairs: each pair is ordered (i < j), then the list is sorted and
/// deduplicated.
/// \throws invalid_input bad_parameter (nodes < 0), bad_face (an endpoint outside [0, nodes) or a self-loop;
///         element = the pair's position in `edges`). Complexity O(E log E).
[[nodiscard]] inline alignment_graph make_alignment_graph(index_t nodes,
                                                          std::vector<std::pair<index_t, index_t>> edges) {
  // Copies, not std::minmax: that returns references into the pair being overwritten.
  for (auto& e : edges)
    if (e.first > e.second) std::swap(e.first, e.second);
  alignment_graph g{.nodes = nodes, .edges = std::move(edges)};
  detail::check_alignment_graph("make_alignment_graph", g);
  std::sort(g.edges.begin(), g.edges.end());
  g.edges.erase(std::unique(g.edges.begin(), g.edges.end()), g.edges.end());
  return g;
}

/// Neighbour lists of every node (each ascending). \throws invalid_input as check of make_alignment_graph
/// (bad_parameter, bad_face). Complexity O(N + E).
[[nodiscard]] inline std::vector<std::vector<index_t>> adjacency_lists(const alignment_graph& g) {
  detail::check_alignment_graph("adjacency_lists", g);
  std::vector<std::vector<index_t>> adj(static_cast<std::size_t>(g.nodes));
  // Sorted edges (i, j) list each node's larger neighbours in order, and its smaller ones in order too, but
  // interleaved with them; one sort per list restores the order whatever the edge order was.
  for (const auto& [a, b] : g.edges) {
    adj[static_cast<std::size_t>(a)].push_back(b);
    adj[static_cast<std::size_t>(b)].push_back(a);
  }
  for (auto& l : adj) std::sort(l.begin(), l.end());
  return adj;
}

/// Hop counts from `source` to every node by breadth-first search; no_index for nodes it cannot reach.
/// Algorithm 1 of ch. 4.3.7 draws new candidate edges among pairs more than 3 hops apart.
/// \throws invalid_input bad_parameter (source outside [0, nodes)), and those of adjacency_lists.
/// Complexity O(N + E).
[[nodiscard]] inline std::vector<index_t> shortest_path_lengths(const alignment_graph& g, index_t source) {
  if (source < 0 || source >= g.nodes)
    throw invalid_input(input_error::bad_parameter, source,
                        "shortest_path_lengths: source " + std::to_string(source) + " is outside [0, " +
                            std::to_string(g.nodes) + ")");
  const auto adj = adjacency_lists(g);
  std::vector<index_t> hops(static_cast<std::size_t>(g.nodes), no_index);
  std::vector<index_t> queue{source};
  hops[static_cast<std::size_t>(source)] = 0;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const index_t u = queue[head];
    for (const index_t v : adj[static_cast<std::size_t>(u)])
      if (hops[static_cast<std::size_t>(v)] == no_index) {
        hops[static_cast<std::size_t>(v)] = hops[static_cast<std::size_t>(u)] + 1;
        queue.push_back(v);
      }
  }
  return hops;
}

/// Result of connected_components(const alignment_graph&).
struct graph_components {
  index_t count = 0;           ///< number of components, isolated nodes included
  std::vector<index_t> label;  ///< (nodes) in [0, count), numbered by each component's smallest node
};

/// Connected components of an alignment graph. \throws invalid_input bad_parameter, bad_face (as
/// make_alignment_graph). Complexity O(N + E alpha(N)).
[[nodiscard]] inline graph_components connected_components(const alignment_graph& g) {
  detail::check_alignment_graph("connected_components", g);
  detail::disjoint_sets sets(g.nodes);
  for (const auto& [a, b] : g.edges) sets.unite(a, b);
  graph_components out;
  out.label.resize(static_cast<std::size_t>(g.nodes));
  std::vector<index_t> root_label(static_cast<std::size_t>(g.nodes), no_index);
  for (index_t v = 0; v < g.nodes; ++v) {
    index_t& l = root_label[static_cast<std::size_t>(sets.find(v))];
    if (l == no_index) l = out.count++;
    out.label[static_cast<std::size_t>(v)] = l;
  }
  return out;
}

/// Options of initial_alignment_graph (ch. 4.3.2).
struct initial_graph_options {
  index_t edges_per_shape = 5;   ///< M: N * M edges are added to the spanning tree ("we use M = 5")
  index_t candidate_factor = 3;  ///< each node proposes its candidate_factor * M lowest-weight edges (3M)
  /// Count the tree's edges in the budget: the graph then has about N * M edges in all ("roughly M edges per
  /// shape"), which is what the chapter's reported counts show (SCAPE 355 of 2,485 pairs = 71 * 5, airplanes 430
  /// of 3,655 = 86 * 5). false adds N * M edges to the tree (N - 1 + N * M in all).
  bool tree_in_budget = true;
};

/// Pairwise L2 distances between global shape descriptors: the edge weights of ch. 4.3.2 (N x N, symmetric,
/// exactly 0 on the diagonal). Pairs that must never be aligned (e.g. a shape that failed to load) are
/// excluded afterwards by setting their entries to +infinity before calling initial_alignment_graph.
/// \throws invalid_input empty (a descriptor of length 0; element = shape), size_mismatch (descriptors of
///         different lengths; element = the first shape differing from shape 0), non_finite (a NaN or infinite
///         entry; element = shape).
/// Complexity O(N^2 d) time, O(N^2 + N d) memory.
[[nodiscard]] inline Eigen::MatrixXd descriptor_distance_matrix(const std::vector<Eigen::VectorXd>& descriptors) {
  const auto n = static_cast<index_t>(descriptors.size());
  if (n == 0) return {};
  const index_t d = descriptors[0].size();
  for (index_t i = 0; i < n; ++i) {
    const auto& x = descriptors[static_cast<std::size_t>(i)];
    if (x.size() == 0)
      throw invalid_input(input_error::empty, i,
                          "descriptor_distance_matrix: the descriptor of shape " + std::to_string(i) + " is empty");
    if (x.size() != d)
      throw invalid_input(input_error::size_mismatch, i,
                          "descriptor_distance_matrix: shape " + std::to_string(i) + " has a descriptor of length " +
                              std::to_string(x.size()) + ", shape 0 one of length " + std::to_string(d));
    if (!x.allFinite())
      throw invalid_input(input_error::non_finite, i,
                          "descriptor_distance_matrix: the descriptor of shape " + std::to_string(i) +
                              " has a NaN or infinite entry");
  }
  // Columns of one matrix: the inner loop then streams two contiguous columns.
  Eigen::MatrixXd X(d, n);
  for (index_t i = 0; i < n; ++i) X.col(i) = descriptors[static_cast<std::size_t>(i)];
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(n, n);
  // Direct differences, not the Gram-matrix shortcut |a|^2 + |b|^2 - 2 a.b: that cancels catastrophically for
  // near-identical shapes, exactly the pairs the spanning tree is made of.
  for (index_t j = 0; j < n; ++j)
    for (index_t i = j + 1; i < n; ++i) D(i, j) = D(j, i) = (X.col(i) - X.col(j)).norm();
  return D;
}

namespace detail {

/// Kruskal's priority key: the weight, then the edge's position in the row-major upper triangle, i.e. (w, i, j)
/// in lexicographic order. Every key is distinct, so the spanning tree is unique whatever the queue's order.
struct mst_key {
  double weight;
  std::uint32_t position;
  auto operator<=>(const mst_key&) const = default;
};

/// Checks the distance matrix of initial_alignment_graph: square, no NaN or -inf, no negative entry,
/// symmetric up to a relative 1e-9 (user-built matrices may carry rounding from asymmetric arithmetic).
inline void check_distance_matrix(const Eigen::Ref<const Eigen::MatrixXd>& D) {
  if (D.rows() != D.cols())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "initial_alignment_graph: the distance matrix is " + std::to_string(D.rows()) + " x " +
                            std::to_string(D.cols()) + "; it must be N x N");
  const index_t n = D.rows();
  for (index_t j = 0; j < n; ++j)
    for (index_t i = 0; i < n; ++i) {
      const double x = D(i, j);
      if (std::isnan(x) || x == -std::numeric_limits<double>::infinity())
        throw invalid_input(input_error::non_finite, i,
                            "initial_alignment_graph: distance (" + std::to_string(i) + ", " + std::to_string(j) +
                                ") is NaN or -infinity; use +infinity for pairs that must not be aligned");
      if (i == j) continue;
      if (x < 0)
        throw invalid_input(input_error::bad_parameter, i,
                            "initial_alignment_graph: distance (" + std::to_string(i) + ", " + std::to_string(j) +
                                ") is negative (" + std::to_string(x) + ")");
      const double y = D(j, i);
      const bool same = x == y || std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y));
      if (!same)
        throw invalid_input(input_error::bad_parameter, i,
                            "initial_alignment_graph: the distance matrix is not symmetric: (" + std::to_string(i) +
                                ", " + std::to_string(j) + ") = " + std::to_string(x) + " but (" + std::to_string(j) +
                                ", " + std::to_string(i) + ") = " + std::to_string(y));
    }
}

/// Minimum spanning forest of the graph whose edges are the finite entries of D's strict upper triangle, by
/// Boost.Graph's Kruskal on a compressed sparse row graph: 4 bytes per edge, 8 for its weight, 8 in Kruskal's
/// queue. 32-bit vertices and edge indices keep the queue's edge descriptors at 8 bytes; they limit N to
/// 92,681, far beyond the N^2 memory this needs anyway.
inline std::vector<std::pair<index_t, index_t>> minimum_spanning_forest(const Eigen::Ref<const Eigen::MatrixXd>& D) {
  using graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, boost::no_property,
                                                   boost::no_property, std::uint32_t, std::uint32_t>;
  using edge = boost::graph_traits<graph>::edge_descriptor;
  const index_t n = D.rows();
  if (n * (n - 1) / 2 > index_t{std::numeric_limits<std::uint32_t>::max()})
    throw invalid_input(input_error::bad_parameter, no_index,
                        "initial_alignment_graph: " + std::to_string(n) +
                            " shapes exceed the 92,681 whose pairs a 32-bit edge index can number");
  std::vector<double> weight;
  graph g;
  {
    // Rows in increasing order with increasing columns: the sorted-edges constructor needs no extra copy, and
    // an edge's index in the graph equals its (i, j) rank, which the key's tie-break uses.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (index_t i = 0; i < n; ++i)
      for (index_t j = i + 1; j < n; ++j)
        if (std::isfinite(D(i, j))) {
          pairs.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
          weight.push_back(D(i, j));
        }
    g = graph(boost::edges_are_sorted, pairs.begin(), pairs.end(), static_cast<std::uint32_t>(n));
  }
  auto key = [&weight](const edge& e) { return mst_key{weight[e.idx], e.idx}; };
  const boost::function_property_map<decltype(key), edge, mst_key> keys(key);
  std::vector<edge> tree;
  // The vertex index map is passed explicitly: Boost 1.74's default for it does not compile on a CSR graph with
  // 32-bit vertices (it expects a 64-bit identity map).
  boost::kruskal_minimum_spanning_tree(g, std::back_inserter(tree),
                                       boost::weight_map(keys).vertex_index_map(boost::get(boost::vertex_index, g)));
  std::vector<std::pair<index_t, index_t>> out;
  out.reserve(tree.size());
  for (const edge& e : tree)
    out.emplace_back(static_cast<index_t>(boost::source(e, g)), static_cast<index_t>(boost::target(e, g)));
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace detail

/// The initial alignment graph G_0 of ch. 4.3.2 (Kim et al., fuzzy correspondences):
///  1. the complete graph weighted by descriptor distance is reduced to its minimum spanning tree (Kruskal,
///     ties broken by (weight, i, j));
///  2. each node proposes its candidate_factor * M lowest-weight edges that are not tree edges (ties by the
///     other endpoint); the union of the proposals, deduplicated, is the candidate set;
///  3. every candidate is ranked by its edge rank (edge_ranks) on the tree, with all edge weights 1: descriptor
///     distances choose the tree and the candidates, connectivity is counted in plain edges;
///  4. the highest-ranking candidates are added until the graph has N * M edges (or N * M are added to the tree
///     with tree_in_budget = false; ties: lower descriptor distance, then (i, j)); when there are fewer
///     candidates all are added.
/// The Fiedler vector is computed once, on the tree, as in the chapter ("for each candidate, we compute its
/// edge rank ... we then add the highest ranking N * M edges"): the ranks are first-order estimates against the
/// tree, not re-evaluated as edges go in. Re-ranking greedily in 2 to 32 batches (recomputing the Fiedler vector
/// of the growing graph before each) raised the final algebraic connectivity by only 2 - 5 % on 500 - 1,000
/// clustered random descriptors, not enough to depart from the chapter.
///
/// Entries of +infinity mark pairs that must never be aligned (e.g. shapes that failed to load): they are
/// neither tree edges nor candidates, so a shape whose row is all +infinity stays isolated and G_0 is then a
/// spanning forest plus edges (the edge rank of a disconnected graph favours joins; see edge_ranks). The
/// diagonal is ignored.
/// \param descriptor_distances N x N, symmetric, >= 0 off the diagonal; +infinity allowed
/// \returns the graph: N nodes, at most max(N - 1, N * M) edges (N - 1 + N * M without tree_in_budget); N = 0 or
///          1 gives no edges.
/// \throws invalid_input size_mismatch (not square), non_finite (NaN or -infinity; element = row),
///         bad_parameter (negative or asymmetric entry, element = row; negative option; N > 92,681).
/// Complexity: O(N^2 log N) time and O(N^2) memory (Kruskal over all N (N - 1) / 2 pairs: about 20 bytes a pair,
/// 10 MB for N = 1,000), plus one Fiedler vector of a tree (sparse, no fill). Measured for N = 1,000: 0.37 s,
/// 0.35 s of it in Kruskal's priority queue. Should the Fiedler solve not converge (possible only above 2,000
/// shapes, see fiedler_vector), its best attempt still ranks the candidates.
[[nodiscard]] inline alignment_graph initial_alignment_graph(
    const Eigen::Ref<const Eigen::MatrixXd>& descriptor_distances, const initial_graph_options& options = {}) {
  if (options.edges_per_shape < 0 || options.candidate_factor < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        "initial_alignment_graph: edges_per_shape (" + std::to_string(options.edges_per_shape) +
                            ") and candidate_factor (" + std::to_string(options.candidate_factor) +
                            ") must be >= 0");
  const auto& D = descriptor_distances;
  detail::check_distance_matrix(D);
  const index_t n = D.rows();
  alignment_graph g{.nodes = n, .edges = {}};
  if (n < 2) return g;

  const auto tree = detail::minimum_spanning_forest(D);
  std::vector<std::vector<index_t>> tree_adj(static_cast<std::size_t>(n));
  for (const auto& [a, b] : tree) {
    tree_adj[static_cast<std::size_t>(a)].push_back(b);
    tree_adj[static_cast<std::size_t>(b)].push_back(a);
  }

  // Step 2: each node's k lowest (distance, other node) among its finite non-tree pairs.
  const index_t k = options.candidate_factor * options.edges_per_shape;
  std::vector<std::pair<index_t, index_t>> candidates;
  if (k > 0) {
    std::vector<std::pair<double, index_t>> row;
    for (index_t i = 0; i < n; ++i) {
      row.clear();
      const auto& tn = tree_adj[static_cast<std::size_t>(i)];
      for (index_t j = 0; j < n; ++j)
        if (j != i && std::isfinite(D(i, j)) && std::find(tn.begin(), tn.end(), j) == tn.end())
          row.emplace_back(D(i, j), j);
      const auto take = static_cast<std::ptrdiff_t>(std::min<std::size_t>(static_cast<std::size_t>(k), row.size()));
      std::nth_element(row.begin(), row.begin() + take, row.end());
      for (std::ptrdiff_t r = 0; r < take; ++r)
        candidates.emplace_back(std::min(i, row[static_cast<std::size_t>(r)].second),
                                std::max(i, row[static_cast<std::size_t>(r)].second));
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  }

  // Steps 3-4.
  const auto budget = static_cast<std::size_t>(std::max<index_t>(
      0, n * options.edges_per_shape - (options.tree_in_budget ? static_cast<index_t>(tree.size()) : 0)));
  std::vector<std::pair<index_t, index_t>> added;
  if (candidates.size() <= budget) {
    added = candidates;
  } else {
    const fiedler_result f = fiedler_vector(n, tree);
    const std::vector<double> rank = edge_ranks(f, candidates);
    std::vector<std::size_t> order(candidates.size());
    for (std::size_t c = 0; c < order.size(); ++c) order[c] = c;
    const auto better = [&](std::size_t a, std::size_t b) {
      if (rank[a] != rank[b]) return rank[a] > rank[b];
      const double da = D(candidates[a].first, candidates[a].second);
      const double db = D(candidates[b].first, candidates[b].second);
      if (da != db) return da < db;
      return candidates[a] < candidates[b];
    };
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(budget), order.end(), better);
    added.reserve(budget);
    for (std::size_t c = 0; c < budget; ++c) added.push_back(candidates[order[c]]);
  }

  g.edges = tree;
  g.edges.insert(g.edges.end(), added.begin(), added.end());
  std::sort(g.edges.begin(), g.edges.end());
  return g;
}

/// initial_alignment_graph on descriptor_distance_matrix(descriptors). \throws invalid_input as both.
[[nodiscard]] inline alignment_graph initial_alignment_graph(const std::vector<Eigen::VectorXd>& descriptors,
                                                             const initial_graph_options& options = {}) {
  return initial_alignment_graph(descriptor_distance_matrix(descriptors), options);
}

}  // namespace shapestruct
