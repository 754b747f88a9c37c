// SPDX-License-Identifier: MIT
// alpha_expansion: multi-label Potts labeling by graph cuts (Boykov, Veksler, Zabih 2001) on Boost.Graph's
// Boykov-Kolmogorov max-flow.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
// Boost.Graph's edge iterators trip GCC 12's -Wmaybe-uninitialized (a false positive inside boost::optional);
// GCC attributes the warning to the header's lines, so silencing it around the includes is enough.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/graph/graph_traits.hpp>
#include <boost/iterator/counting_iterator.hpp>
#include <boost/iterator/transform_iterator.hpp>
#include <boost/property_map/function_property_map.hpp>
#include <boost/property_map/property_map.hpp>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// A weighted undirected edge of the labeling graph: cutting it (different labels at a and b) costs `weight`.
struct potts_edge {
  index_t a = 0, b = 0;
  double weight = 0;
};

namespace detail {

/// An arc of a flow_network: its tail and its position in the network's arc arrays.
struct flow_arc {
  std::size_t tail = 0, index = 0;
  friend bool operator==(const flow_arc&, const flow_arc&) = default;
};

/// The s-t network of one expansion move in compressed sparse row form, as a graph Boost's Boykov-Kolmogorov
/// max-flow runs on (VertexList, EdgeList and Incidence graph). Flat arrays reused from move to move, because
/// allocating per arc or per move cost more than the max-flows (docs/part_templates.md).
class flow_network {
 public:
  struct arc_at {  // position -> arc
    const std::vector<std::size_t>* tails = nullptr;
    flow_arc operator()(std::size_t k) const { return {(*tails)[k], k}; }
  };
  using vertex_descriptor = std::size_t;
  using edge_descriptor = flow_arc;
  using directed_category = boost::directed_tag;
  using edge_parallel_category = boost::allow_parallel_edge_tag;
  struct traversal_category : boost::vertex_list_graph_tag, boost::edge_list_graph_tag, boost::incidence_graph_tag {};
  using vertices_size_type = std::size_t;
  using edges_size_type = std::size_t;
  using degree_size_type = std::size_t;
  using vertex_iterator = boost::counting_iterator<std::size_t>;
  using edge_iterator = boost::transform_iterator<arc_at, boost::counting_iterator<std::size_t>, flow_arc, flow_arc>;
  using out_edge_iterator = edge_iterator;
  using adjacency_iterator = void;
  using in_edge_iterator = void;
  static vertex_descriptor null_vertex() { return std::numeric_limits<std::size_t>::max(); }

  void reset(std::size_t vertices) {
    vertices_ = vertices;
    tail_.clear();
    head_.clear();
    capacity_in_order_.clear();
  }
  /// Arc u -> v of capacity c and its reverse v -> u of capacity 0. Each vertex's out-arcs keep the order they
  /// were added in, so the flow (and which of several minimum cuts is returned) does not depend on the storage.
  void add_arc(std::size_t u, std::size_t v, double c) {
    tail_.push_back(u), head_.push_back(v), capacity_in_order_.push_back(c);
    tail_.push_back(v), head_.push_back(u), capacity_in_order_.push_back(0.0);
  }
  /// Max-flow from `source` to `sink`; afterwards on_source_side(v) says which side of the minimum cut v is on.
  void solve(std::size_t source, std::size_t sink) {
    const std::size_t m = tail_.size();
    // Stable counting sort of the arcs by tail.
    row_start_.assign(vertices_ + 1, 0);
    for (const auto u : tail_) ++row_start_[u + 1];
    for (std::size_t v = 0; v < vertices_; ++v) row_start_[v + 1] += row_start_[v];
    next_.assign(row_start_.begin(), row_start_.end() - 1);
    position_.resize(m);
    for (std::size_t k = 0; k < m; ++k) position_[k] = next_[tail_[k]]++;
    sorted_tail_.resize(m);
    sorted_head_.resize(m);
    capacity_.resize(m);
    residual_.resize(m);
    reverse_.resize(m);
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t at = position_[k], twin = position_[k ^ 1];  // arcs were added in pairs
      sorted_tail_[at] = tail_[k];
      sorted_head_[at] = head_[k];
      capacity_[at] = capacity_in_order_[k];
      reverse_[at] = {head_[k], twin};
    }
    predecessor_.assign(vertices_, flow_arc{});
    color_.assign(vertices_, boost::white_color);
    distance_.assign(vertices_, 0);
    const auto arc_id = boost::make_function_property_map<flow_arc>([](const flow_arc& a) { return a.index; });
    const boost::typed_identity_property_map<std::size_t> vertex_id;
    boost::boykov_kolmogorov_max_flow(*this, boost::make_iterator_property_map(capacity_.begin(), arc_id),
                                      boost::make_iterator_property_map(residual_.begin(), arc_id),
                                      boost::make_iterator_property_map(reverse_.begin(), arc_id),
                                      boost::make_iterator_property_map(predecessor_.begin(), vertex_id),
                                      boost::make_iterator_property_map(color_.begin(), vertex_id),
                                      boost::make_iterator_property_map(distance_.begin(), vertex_id), vertex_id,
                                      source, sink);
    source_color_ = color_[source];
  }
  [[nodiscard]] bool on_source_side(std::size_t v) const { return color_[v] == source_color_; }

  // The Boost graph interface (found by argument-dependent lookup).
  friend std::size_t num_vertices(const flow_network& g) { return g.vertices_; }
  friend std::pair<vertex_iterator, vertex_iterator> vertices(const flow_network& g) {
    return {vertex_iterator(0), vertex_iterator(g.vertices_)};
  }
  friend std::size_t num_edges(const flow_network& g) { return g.sorted_tail_.size(); }
  friend std::pair<edge_iterator, edge_iterator> edges(const flow_network& g) { return g.arcs(0, g.sorted_tail_.size()); }
  friend std::pair<out_edge_iterator, out_edge_iterator> out_edges(std::size_t v, const flow_network& g) {
    return g.arcs(g.row_start_[v], g.row_start_[v + 1]);
  }
  friend std::size_t out_degree(std::size_t v, const flow_network& g) { return g.row_start_[v + 1] - g.row_start_[v]; }
  friend std::size_t source(const flow_arc& a, const flow_network&) { return a.tail; }
  friend std::size_t target(const flow_arc& a, const flow_network& g) { return g.sorted_head_[a.index]; }

 private:
  [[nodiscard]] std::pair<edge_iterator, edge_iterator> arcs(std::size_t from, std::size_t to) const {
    const arc_at at{&sorted_tail_};
    return {edge_iterator(boost::counting_iterator<std::size_t>(from), at),
            edge_iterator(boost::counting_iterator<std::size_t>(to), at)};
  }

  std::size_t vertices_ = 0;
  std::vector<std::size_t> tail_, head_, row_start_, next_, position_, sorted_tail_, sorted_head_;
  std::vector<double> capacity_in_order_, capacity_, residual_;
  std::vector<flow_arc> reverse_, predecessor_;
  std::vector<boost::default_color_type> color_;
  std::vector<long> distance_;
  boost::default_color_type source_color_ = boost::black_color;
};

}  // namespace detail

/// Options of alpha_expansion.
struct alpha_expansion_options {
  int max_sweeps = 20;  ///< a sweep tries every label once; stops earlier when a sweep changes nothing
};

/// Labels, their energy, and whether the sweeps converged (a sweep without improvement).
struct alpha_expansion_result {
  std::vector<index_t> labels;
  double energy = 0;
  int sweeps = 0;
  status info = status::ok;
};

/// Energy E(l) = sum_i U(i, l_i) + sum_edges w_ab [l_a != l_b] of a labeling. O(n + #edges).
inline double potts_energy(const Eigen::Ref<const Eigen::MatrixXd>& unary, const std::vector<potts_edge>& edges,
                           const std::vector<index_t>& labels) {
  double e = 0;
  for (index_t i = 0; i < unary.rows(); ++i) e += unary(i, labels[static_cast<std::size_t>(i)]);
  for (const auto& ed : edges)
    if (labels[static_cast<std::size_t>(ed.a)] != labels[static_cast<std::size_t>(ed.b)]) e += ed.weight;
  return e;
}

/// Minimizes the Potts energy above by alpha-expansion: each move solves "keep your label or switch to alpha"
/// exactly as an s-t min cut (the Potts model is a metric, so every move is submodular); the result is within
/// a factor 2 of the global optimum (Boykov et al. 2001) and is a local minimum under all expansion moves.
/// \param unary    n x L costs, finite (a very large finite value forbids a label)
/// \param edges    pairs in [0, n) with finite non-negative weights; a == b is ignored
/// \param initial  starting labels in [0, L) (empty: argmin of unary per node)
/// \throws invalid_input empty (no nodes or labels), non_finite (node of a NaN/inf unary), bad_face (edge index
///         out of range), bad_parameter (negative or non-finite edge weight; initial label out of range),
///         size_mismatch (initial has the wrong length).
/// \returns the labeling, its energy; info = not_converged when max_sweeps ran out while still improving.
/// Complexity: sweeps x L max-flows on n + 2 vertices and n + #edges arcs.
inline alpha_expansion_result alpha_expansion(const Eigen::Ref<const Eigen::MatrixXd>& unary,
                                              const std::vector<potts_edge>& edges,
                                              std::vector<index_t> initial = {},
                                              const alpha_expansion_options& opt = {}) {
  const index_t n = unary.rows(), L = unary.cols();
  if (n == 0 || L == 0)
    throw invalid_input(input_error::empty, no_index,
                        "alpha_expansion: unary is " + std::to_string(n) + " x " + std::to_string(L) +
                            "; it needs at least one node and one label");
  for (index_t i = 0; i < n; ++i)
    if (!unary.row(i).allFinite())
      throw invalid_input(input_error::non_finite, i,
                          "alpha_expansion: node " + std::to_string(i) + " has a non-finite unary cost");
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const auto& e = edges[k];
    if (e.a < 0 || e.b < 0 || e.a >= n || e.b >= n)
      throw invalid_input(input_error::bad_face, static_cast<index_t>(k),
                          "alpha_expansion: edge " + std::to_string(k) + " joins a node outside [0, " +
                              std::to_string(n) + ")");
    if (!(e.weight >= 0) || !std::isfinite(e.weight))
      throw invalid_input(input_error::bad_parameter, static_cast<index_t>(k),
                          "alpha_expansion: edge " + std::to_string(k) + " has a negative or non-finite weight");
  }
  std::vector<index_t> lab = std::move(initial);
  if (lab.empty()) {
    lab.resize(static_cast<std::size_t>(n));
    for (index_t i = 0; i < n; ++i) unary.row(i).minCoeff(&lab[static_cast<std::size_t>(i)]);
  }
  if (static_cast<index_t>(lab.size()) != n)
    throw invalid_input(input_error::size_mismatch, no_index,
                        "alpha_expansion: initial has " + std::to_string(lab.size()) + " labels for " +
                            std::to_string(n) + " nodes");
  for (index_t i = 0; i < n; ++i)
    if (lab[static_cast<std::size_t>(i)] < 0 || lab[static_cast<std::size_t>(i)] >= L)
      throw invalid_input(input_error::bad_parameter, i,
                          "alpha_expansion: initial label of node " + std::to_string(i) + " is outside [0, " +
                              std::to_string(L) + ")");

  // One network per thread, reused by every call (the fitter makes thousands): fresh arrays per call had the
  // allocator return memory to the kernel and fault it back in, at a cost above that of the max-flows. It keeps
  // the largest network a thread has solved: about 80 bytes per arc and 50 per node.
  thread_local detail::flow_network net;
  alpha_expansion_result res;
  double energy = potts_energy(unary, edges, lab);
  std::vector<double> d(static_cast<std::size_t>(n));  // unary difference cost(x=1) - cost(x=0) per node
  std::vector<index_t> cand;
  res.info = status::not_converged;
  for (int sweep = 0; sweep < opt.max_sweeps; ++sweep) {
    bool improved = false;
    for (index_t alpha = 0; alpha < L; ++alpha) {
      // Binary move: x_i = 0 keeps l_i, x_i = 1 takes alpha. Nodes already labeled alpha stay (x_i = 0 = 1).
      const auto src = static_cast<std::size_t>(n), snk = static_cast<std::size_t>(n + 1);
      net.reset(static_cast<std::size_t>(n + 2));
      for (index_t i = 0; i < n; ++i) {
        const auto l = lab[static_cast<std::size_t>(i)];
        d[static_cast<std::size_t>(i)] = (l == alpha) ? 0.0 : unary(i, alpha) - unary(i, l);
      }
      // Pairwise Potts term A = E00, B = E01, C = E10, D = E11 (Kolmogorov-Zabih decomposition):
      // E = A + (C - A) x_a + (D - C) x_b + (B + C - A - D)(1 - x_a) x_b, with B + C - A - D >= 0.
      for (const auto& e : edges) {
        if (e.a == e.b || e.weight == 0) continue;
        const auto la = lab[static_cast<std::size_t>(e.a)], lb = lab[static_cast<std::size_t>(e.b)];
        const bool fa = la == alpha, fb = lb == alpha;  // fixed nodes: x is irrelevant, treat as constant 0
        const double A = la != lb ? e.weight : 0.0;
        const double B = la != alpha ? e.weight : 0.0;  // a keeps la, b takes alpha
        const double C = alpha != lb ? e.weight : 0.0;  // a takes alpha, b keeps lb
        if (fa && fb) continue;
        if (fa) {  // x_a == 0 always: E = A + (B - A) x_b
          d[static_cast<std::size_t>(e.b)] += B - A;
          continue;
        }
        if (fb) {  // x_b == 0 always: E = A + (C - A) x_a
          d[static_cast<std::size_t>(e.a)] += C - A;
          continue;
        }
        d[static_cast<std::size_t>(e.a)] += C - A;
        d[static_cast<std::size_t>(e.b)] += 0.0 - C;  // D = 0
        const double pair = B + C - A;
        if (pair > 0) net.add_arc(static_cast<std::size_t>(e.a), static_cast<std::size_t>(e.b), pair);
      }
      for (index_t i = 0; i < n; ++i) {
        if (lab[static_cast<std::size_t>(i)] == alpha) continue;
        const double di = d[static_cast<std::size_t>(i)];
        if (di > 0) net.add_arc(src, static_cast<std::size_t>(i), di);   // paying di when x_i = 1 (sink side)
        else if (di < 0) net.add_arc(static_cast<std::size_t>(i), snk, -di);  // paying -di when x_i = 0
      }
      net.solve(src, snk);
      cand = lab;
      for (index_t i = 0; i < n; ++i)
        if (cand[static_cast<std::size_t>(i)] != alpha && !net.on_source_side(static_cast<std::size_t>(i)))
          cand[static_cast<std::size_t>(i)] = alpha;
      const double e_new = potts_energy(unary, edges, cand);
      // Accept strict improvements only (relative tolerance absorbs floating-point noise in the flow).
      if (e_new < energy - 1e-12 * (1.0 + std::abs(energy))) {
        lab.swap(cand);
        energy = e_new;
        improved = true;
      }
    }
    res.sweeps = sweep + 1;
    if (!improved) {
      res.info = status::ok;
      break;
    }
  }
  res.labels = std::move(lab);
  res.energy = energy;
  return res;
}

}  // namespace shapestruct
