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
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
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

  using traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
  using graph = boost::adjacency_list<
      boost::vecS, boost::vecS, boost::directedS,
      boost::property<boost::vertex_index_t, long,
                      boost::property<boost::vertex_color_t, boost::default_color_type,
                                      boost::property<boost::vertex_distance_t, long,
                                                      boost::property<boost::vertex_predecessor_t,
                                                                      traits::edge_descriptor>>>>,
      boost::property<boost::edge_capacity_t, double,
                      boost::property<boost::edge_residual_capacity_t, double,
                                      boost::property<boost::edge_reverse_t, traits::edge_descriptor>>>>;

  alpha_expansion_result res;
  double energy = potts_energy(unary, edges, lab);
  std::vector<double> d(static_cast<std::size_t>(n));  // unary difference cost(x=1) - cost(x=0) per node
  res.info = status::not_converged;
  for (int sweep = 0; sweep < opt.max_sweeps; ++sweep) {
    bool improved = false;
    for (index_t alpha = 0; alpha < L; ++alpha) {
      // Binary move: x_i = 0 keeps l_i, x_i = 1 takes alpha. Nodes already labeled alpha stay (x_i = 0 = 1).
      graph g(static_cast<std::size_t>(n + 2));
      const auto src = static_cast<std::size_t>(n), snk = static_cast<std::size_t>(n + 1);
      auto cap = boost::get(boost::edge_capacity, g);
      auto rev = boost::get(boost::edge_reverse, g);
      auto add_arc = [&](std::size_t u, std::size_t v, double c) {
        const auto e1 = boost::add_edge(u, v, g).first;
        const auto e2 = boost::add_edge(v, u, g).first;
        cap[e1] = c;
        cap[e2] = 0;
        rev[e1] = e2;
        rev[e2] = e1;
      };
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
        if (pair > 0) add_arc(static_cast<std::size_t>(e.a), static_cast<std::size_t>(e.b), pair);
      }
      for (index_t i = 0; i < n; ++i) {
        if (lab[static_cast<std::size_t>(i)] == alpha) continue;
        const double di = d[static_cast<std::size_t>(i)];
        if (di > 0) add_arc(src, static_cast<std::size_t>(i), di);   // paying di when x_i = 1 (sink side)
        else if (di < 0) add_arc(static_cast<std::size_t>(i), snk, -di);  // paying -di when x_i = 0
      }
      boost::boykov_kolmogorov_max_flow(g, src, snk);
      auto color = boost::get(boost::vertex_color, g);
      const auto src_color = boost::get(color, src);
      std::vector<index_t> cand = lab;
      for (index_t i = 0; i < n; ++i)
        if (cand[static_cast<std::size_t>(i)] != alpha && boost::get(color, static_cast<std::size_t>(i)) != src_color)
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
