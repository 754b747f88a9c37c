// SPDX-License-Identifier: MIT
// edge_rank: Heath et al.'s first-order estimate of how much an added edge raises a graph's algebraic
// connectivity (the Fiedler value), and the Fiedler vector it needs.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <limits>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"
#include "shapestruct/spectral/top_eigenpairs.hpp"

namespace shapestruct {

/// Options of fiedler_vector.
struct fiedler_options {
  /// Below this many nodes the dense self-adjoint solver is used: exact, and for small graphs faster than
  /// factorising and iterating (the same threshold as top_eigenpairs).
  index_t dense_below = 400;
  /// Above dense_below, shift-invert (a sparse LDL^T factor) is used while the factor has at most this many
  /// nonzeros per nonzero of the Laplacian's lower triangle; a denser factor means an expander-like graph, where
  /// plain Lanczos on c I - L converges in a few restarts while the factorisation would take minutes (a 20,000-
  /// node 6-nearest-neighbour graph: 0.2 s against 157 s). 0 always tries Lanczos first.
  double fill_budget = 50;
  int max_iterations = 1000;  ///< Spectra restarts before giving up (status::not_converged)
  double tolerance = 1e-10;   ///< Spectra's relative eigenvalue tolerance
};

/// The algebraic connectivity of a graph and its eigenvector.
///
/// For a connected graph `value` is lambda_2 of L = D - W and `vector` the unit eigenvector (orthogonal to
/// the constant vector; sign fixed so that its largest-magnitude entry, the first one on exact ties, is
/// positive). When lambda_2 is a multiple eigenvalue (cycles, complete graphs) any unit vector of its
/// eigenspace is a valid answer and the one returned is whatever the solver converged to.
///
/// A disconnected graph (isolated nodes included; only edges of positive weight connect) has `value` = 0
/// exactly and needs no eigensolver: `vector` is then the null vector of L that separates the largest
/// component (the lowest label on ties) from the rest, c_A on it and -c_B elsewhere with c_A = sqrt(n_B / (n
/// n_A)), c_B = sqrt(n_A / (n n_B)): unit, orthogonal to the constant. edge_ranks() reads `components` and
/// `component` instead of the vector in that case (see there).
struct fiedler_result {
  double value = 0;                ///< lambda_2 (0 for a disconnected graph)
  Eigen::VectorXd vector;          ///< (nodes) unit Fiedler vector
  status info = status::ok;        ///< ok unless the eigensolvers failed (see fiedler_vector)
  index_t components = 0;          ///< number of connected components (1: connected)
  std::vector<index_t> component;  ///< (nodes) component label, numbered by each component's smallest node
};

namespace detail {

/// Checks edge endpoints and weights of the graph routines; `who` names the public function.
inline void check_weighted_edges(const char* who, index_t nodes, std::span<const std::pair<index_t, index_t>> edges,
                                 std::span<const double> weights) {
  if (!weights.empty() && weights.size() != edges.size())
    throw invalid_input(input_error::size_mismatch, no_index,
                        std::string(who) + ": " + std::to_string(weights.size()) + " weights for " +
                            std::to_string(edges.size()) + " edges; pass one per edge or none (all 1)");
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    if (a < 0 || a >= nodes || b < 0 || b >= nodes)
      throw invalid_input(input_error::bad_face, static_cast<index_t>(e),
                          std::string(who) + ": edge " + std::to_string(e) + " = (" + std::to_string(a) + ", " +
                              std::to_string(b) + ") has an endpoint outside [0, " + std::to_string(nodes) + ")");
    if (!weights.empty() && !(std::isfinite(weights[e]) && weights[e] >= 0))
      throw invalid_input(input_error::bad_parameter, static_cast<index_t>(e),
                          std::string(who) + ": edge " + std::to_string(e) + " has weight " +
                              std::to_string(weights[e]) + "; weights must be finite and >= 0");
  }
}

inline double edge_weight(std::span<const double> weights, std::size_t e) noexcept {
  return weights.empty() ? 1.0 : weights[e];
}

/// y = P (L + shift I)^{-1} P x with P = I - 1 1^T / n, the projector that removes the constant vector.
/// On the complement of the constants its eigenvalues are 1 / (lambda_k + shift), so the largest is the
/// Fiedler pair and Lanczos converges at the rate of (lambda_2 + shift) / (lambda_3 + shift): shift-invert
/// without the shift having to be tuned to lambda_2. The constant vector (eigenvalue 1 / shift, the largest of
/// the undeflated operator) is projected out on the way in and on the way out of every product.
class deflated_laplacian_inverse {
 public:
  using Scalar = double;

  /// \param shifted_lower lower triangle of L + shift I
  explicit deflated_laplacian_inverse(const Eigen::SparseMatrix<double>& shifted_lower)
      : n_(shifted_lower.rows()), ldlt_(shifted_lower) {}

  [[nodiscard]] index_t rows() const noexcept { return n_; }
  [[nodiscard]] index_t cols() const noexcept { return n_; }
  [[nodiscard]] bool ok() const { return ldlt_.info() == Eigen::Success; }

  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> x(x_in, n_);
    Eigen::Map<Eigen::VectorXd> y(y_out, n_);
    const Eigen::VectorXd b = x.array() - x.mean();
    y = ldlt_.solve(b);
    y.array() -= y.mean();
  }

 private:
  index_t n_;
  // AMD ordering (the default): a tree, the graph the initial alignment graph ranks on, factors without fill.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt_;
};

/// y = P (c I - L) P x: with c >= lambda_max (Gershgorin: twice the largest weighted degree) the operator is
/// positive semi-definite on the complement of the constants, with eigenvalues c - lambda_k, so its largest is
/// the Fiedler pair. Costs one sparse product per application, but converges at the rate of
/// (lambda_3 - lambda_2) / c: fast on well-connected graphs, hopeless on long paths and trees.
class deflated_laplacian_complement {
 public:
  using Scalar = double;

  /// \param shifted_lower lower triangle of L + shift I  \param shift that shift  \param c the bound
  deflated_laplacian_complement(const Eigen::SparseMatrix<double>& shifted_lower, double shift, double c)
      : lower_(shifted_lower), shift_(shift), c_(c) {}

  [[nodiscard]] index_t rows() const noexcept { return lower_.rows(); }
  [[nodiscard]] index_t cols() const noexcept { return lower_.rows(); }

  void perform_op(const double* x_in, double* y_out) const {
    const index_t n = lower_.rows();
    const Eigen::Map<const Eigen::VectorXd> x(x_in, n);
    Eigen::Map<Eigen::VectorXd> y(y_out, n);
    const Eigen::VectorXd b = x.array() - x.mean();
    y = (c_ + shift_) * b;
    y.noalias() -= lower_.selfadjointView<Eigen::Lower>() * b;
    y.array() -= y.mean();
  }

 private:
  const Eigen::SparseMatrix<double>& lower_;
  double shift_, c_;
};

/// Nonzeros of the LDL^T factor (strictly below the diagonal) of the symmetric matrix whose lower triangle is
/// `lower`, under the AMD ordering SimplicialLDLT uses; the count stops as soon as it exceeds `budget`. The
/// symbolic elimination-tree walk of Eigen's analyzePattern, without allocating the factor: O(nnz + min(fill,
/// budget)) after the ordering.
inline double ldlt_fill(const Eigen::SparseMatrix<double>& lower, double budget) {
  const auto n = static_cast<int>(lower.rows());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> pinv;
  {
    const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
    Eigen::AMDOrdering<int> amd;
    amd(full, pinv);
  }
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm = pinv.inverse();
  Eigen::SparseMatrix<double> upper(n, n);
  upper.selfadjointView<Eigen::Upper>() = lower.selfadjointView<Eigen::Lower>().twistedBy(perm);
  std::vector<int> parent(static_cast<std::size_t>(n), -1), tag(static_cast<std::size_t>(n), -1);
  double count = 0;
  for (int k = 0; k < n; ++k) {
    tag[static_cast<std::size_t>(k)] = k;
    for (Eigen::SparseMatrix<double>::InnerIterator it(upper, k); it; ++it)
      for (int i = static_cast<int>(it.index()); i < k && tag[static_cast<std::size_t>(i)] != k;
           i = parent[static_cast<std::size_t>(i)]) {
        if (parent[static_cast<std::size_t>(i)] == -1) parent[static_cast<std::size_t>(i)] = k;
        count += 1;
        tag[static_cast<std::size_t>(i)] = k;
      }
    if (count > budget) return count;
  }
  return count;
}

/// Flips v so that its largest-magnitude entry (the first on exact ties) is positive.
inline void fix_sign(Eigen::VectorXd& v) {
  if (v.size() == 0) return;
  Eigen::Index at = 0;
  v.cwiseAbs().maxCoeff(&at);
  if (v(at) < 0) v = -v;
}

/// Dense path of fiedler_vector on a connected graph: fills out.value, out.vector, out.info.
inline void dense_fiedler(index_t nodes, std::span<const std::pair<index_t, index_t>> edges,
                          std::span<const double> weights, fiedler_result& out) {
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(nodes, nodes);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    if (a == b) continue;
    const double w = edge_weight(weights, e);
    L(a, b) -= w;
    L(b, a) -= w;
    L(a, a) += w;
    L(b, b) += w;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(L);
  if (es.info() != Eigen::Success) {
    out.info = status::numerical_issue;
    out.value = 0;
    out.vector = Eigen::VectorXd::Zero(nodes);
    return;
  }
  out.info = status::ok;
  out.value = es.eigenvalues()(1);
  out.vector = es.eigenvectors().col(1);
  fix_sign(out.vector);
}

}  // namespace detail

/// The Fiedler value and vector of the undirected graph on `nodes` nodes with the given weighted edges
/// (Laplacian L = D - W; repeated edges add their weights, self-loops do not change L).
///
/// Connected graphs below options.dense_below nodes: dense Eigen::SelfAdjointEigenSolver. Above, Spectra's
/// Lanczos (top_eigenpairs_operator) on the Laplacian with the constant vector projected out, either
///  - shift-invert, the largest eigenpair of P (L + s I)^{-1} P (sparse LDL^T, s = 1e-10 x the largest weighted
///    degree), when the factor stays within options.fill_budget: trees, paths, meshes, any sparse graph with
///    small separators, whose tiny and clustered lambda_2 defeat plain Lanczos; or
///  - the largest eigenpair of P (2 d_max I - L) P otherwise (expander-like graphs, well connected, where it
///    converges in a few restarts), falling back to shift-invert if it does not converge.
/// The value is then the Rayleigh quotient v^T L v, and a result is accepted only if ||L v - value v|| <=
/// sqrt(tolerance) x 2 d_max. When neither method gets there, graphs of up to 2,000 nodes fall back to the dense
/// solver; larger ones return the better attempt with info = not_converged. Disconnected graphs: value 0 and
/// the component-separating null vector described at fiedler_result, without a solve.
/// \param weights one per edge, finite and >= 0, or empty for all 1
/// \throws invalid_input empty (nodes < 2: no second eigenvalue), bad_face (edge endpoint outside [0, nodes);
///         element = edge), size_mismatch (weights.size() != edges.size()), bad_parameter (negative or
///         non-finite weight; element = edge).
/// \returns the result; above 2,000 nodes info may be not_converged (the better attempt is returned, or 0
///          and zeros if none produced a vector) or numerical_issue (the factorisation failed and nothing else
///          converged).
/// Complexity: dense O(n^3); sparse: the AMD ordering, then iterations x (ncv n + a solve or a product). The
/// solve costs O(fill) (zero fill on trees), the product O(E). Measured: a 20,000-node 6-nearest-neighbour
/// graph in 0.2 s (Lanczos on 2 d_max I - L), a 1,000-node alignment graph in about 15 ms.
[[nodiscard]] inline fiedler_result fiedler_vector(index_t nodes, std::span<const std::pair<index_t, index_t>> edges,
                                                   std::span<const double> weights = {},
                                                   const fiedler_options& options = {}) {
  if (nodes < 2)
    throw invalid_input(input_error::empty, no_index,
                        "fiedler_vector: the graph has " + std::to_string(nodes) +
                            " nodes; the Fiedler value needs at least 2");
  detail::check_weighted_edges("fiedler_vector", nodes, edges, weights);
  const auto n = static_cast<std::size_t>(nodes);

  fiedler_result out;
  detail::disjoint_sets sets(nodes);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (detail::edge_weight(weights, e) > 0) sets.unite(edges[e].first, edges[e].second);
  out.component.assign(n, no_index);
  {
    std::vector<index_t> root_label(n, no_index);
    for (index_t v = 0; v < nodes; ++v) {
      index_t& l = root_label[static_cast<std::size_t>(sets.find(v))];
      if (l == no_index) l = out.components++;
      out.component[static_cast<std::size_t>(v)] = l;
    }
  }

  if (out.components > 1) {
    std::vector<index_t> size(static_cast<std::size_t>(out.components), 0);
    for (const index_t l : out.component) ++size[static_cast<std::size_t>(l)];
    const auto largest = static_cast<index_t>(std::max_element(size.begin(), size.end()) - size.begin());
    const double na = static_cast<double>(size[static_cast<std::size_t>(largest)]);
    const double nb = static_cast<double>(nodes) - na;
    const double total = static_cast<double>(nodes);
    const double ca = std::sqrt(nb / (total * na)), cb = std::sqrt(na / (total * nb));
    out.vector.resize(nodes);
    for (index_t v = 0; v < nodes; ++v)
      out.vector(v) = out.component[static_cast<std::size_t>(v)] == largest ? ca : -cb;
    out.value = 0;
    return out;
  }

  if (nodes < options.dense_below) {
    detail::dense_fiedler(nodes, edges, weights, out);
    return out;
  }

  // Sparse path. Only the lower triangle is stored: SimplicialLDLT<..., Lower> and selfadjointView<Lower> read
  // no more.
  Eigen::VectorXd degree = Eigen::VectorXd::Zero(nodes);
  std::vector<Eigen::Triplet<double, index_t>> lower;
  lower.reserve(edges.size() + n);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    if (a == b) continue;
    const double w = detail::edge_weight(weights, e);
    degree(a) += w;
    degree(b) += w;
    lower.emplace_back(std::max(a, b), std::min(a, b), -w);
  }
  // The shift only makes L positive definite for the factorisation; 1e-10 of the largest degree stays below
  // lambda_2 of any connected graph short of a 200,000-node path (lambda_2 = pi^2 / n^2 against degree 2), so
  // the shift-invert convergence rate (lambda_2 + s) / (lambda_3 + s) is that of lambda_2 / lambda_3. The
  // resulting condition number (about 1e10) only inflates the solve's error along the constant vector, which is
  // projected out.
  const double max_degree = degree.maxCoeff();
  const double shift = 1e-10 * max_degree;
  for (index_t v = 0; v < nodes; ++v) lower.emplace_back(v, v, degree(v) + shift);
  Eigen::SparseMatrix<double> A(nodes, nodes);
  A.setFromTriplets(lower.begin(), lower.end());
  lower = {};

  const top_eigenpairs_options lanczos{.max_iterations = options.max_iterations, .tolerance = options.tolerance};
  const double c = 2 * max_degree;
  // Spectra's tolerance bounds the residual ||L v - lambda v|| by about tolerance x c for either operator; the
  // square root leaves room for that and still rejects what Spectra may report as converged after a Krylov
  // breakdown (tiny or highly degenerate spectra: e.g. the 4-cycle under Lanczos on c I - L).
  const double accept = std::sqrt(options.tolerance) * c;
  double best_residual = std::numeric_limits<double>::infinity();
  // Runs Lanczos on `op` and keeps its vector in `out` if it beats the previous attempt; true when accepted.
  const auto attempt = [&](auto& op) {
    eigenpairs_result<double> pairs;
    try {
      pairs = top_eigenpairs_operator(op, 1, lanczos);
    } catch (const std::exception&) {  // Spectra throws when its tridiagonal eigensolver breaks down
      return false;
    }
    if (pairs.vectors.cols() != 1) return false;
    Eigen::VectorXd v = pairs.vectors.col(0);
    v.array() -= v.mean();
    const double norm = v.norm();
    if (!(norm > 0) || !v.allFinite()) return false;
    v /= norm;
    const Eigen::VectorXd Lv = Eigen::VectorXd(A.selfadjointView<Eigen::Lower>() * v) - shift * v;
    const double q = v.dot(Lv);  // Rayleigh quotient: exact to the square of the vector's error
    const double residual = (Lv - q * v).norm();
    const bool accepted = pairs.info == status::ok && residual <= accept;
    if (accepted || residual < best_residual) {
      best_residual = residual;
      out.vector = std::move(v);
      out.value = q;
      out.info = accepted ? status::ok : status::not_converged;
    }
    return accepted;
  };

  bool done = false;
  const double budget = options.fill_budget * static_cast<double>(A.nonZeros());
  if (detail::ldlt_fill(A, budget) > budget) {
    detail::deflated_laplacian_complement op(A, shift, c);
    done = attempt(op);
  }
  // Not done: a sparse factor, or a poorly connected graph with a dense one, where shift-invert is slow but sure.
  bool factored = true;
  if (!done) {
    detail::deflated_laplacian_inverse op(A);
    factored = op.ok();
    if (factored) done = attempt(op);
  }
  // Last resort for graphs small enough to afford it (32 MB at the limit): the dense solver is never wrong.
  constexpr index_t dense_fallback_limit = 2000;
  if (!done && nodes <= dense_fallback_limit) {
    detail::dense_fiedler(nodes, edges, weights, out);
    return out;
  }
  if (!done && out.vector.size() == 0) {
    out.info = factored ? status::not_converged : status::numerical_issue;
    out.vector = Eigen::VectorXd::Zero(nodes);
    return out;
  }
  detail::fix_sign(out.vector);
  return out;
}

/// Edge rank (Heath, Gelfand, Ovsjanikov, Aanjaneya, Guibas, "Image webs", CVPR 2010): the first-order
/// increase of the algebraic connectivity when the candidate edge (i, j) of weight w is added,
/// d lambda_2 = w (v_i - v_j)^2 with v the unit Fiedler vector of `fiedler`. Candidates are not added one after
/// the other: every estimate is against the graph of `fiedler`.
///
/// For a disconnected graph (fiedler.components > 1) the estimate is the first-order rise of the zero
/// eigenvalue that the edge lifts: w (1 / n_a + 1 / n_b) for an edge joining components of sizes n_a and n_b,
/// 0 for an edge inside a component (which leaves the graph as disconnected as before). With two components
/// this is exactly w (v_i - v_j)^2 on the null vector of fiedler_result, i.e. the rise of the Fiedler value;
/// with more, lambda_2 stays 0 until the last join, and the rank orders joins by how much they connect.
/// \param weights one per candidate, finite and >= 0, or empty for all 1
/// \throws invalid_input bad_face (candidate endpoint outside [0, fiedler.vector.size()); element = candidate),
///         size_mismatch (weights.size() != candidates.size(), or fiedler.component does not match the vector),
///         bad_parameter (negative or non-finite weight; element = candidate).
/// Complexity: O(candidates + nodes).
[[nodiscard]] inline std::vector<double> edge_ranks(const fiedler_result& fiedler,
                                                    std::span<const std::pair<index_t, index_t>> candidates,
                                                    std::span<const double> weights = {}) {
  const index_t nodes = fiedler.vector.size();
  detail::check_weighted_edges("edge_ranks", nodes, candidates, weights);
  std::vector<double> rank(candidates.size(), 0.0);
  if (fiedler.components > 1) {
    if (fiedler.component.size() != static_cast<std::size_t>(nodes))
      throw invalid_input(input_error::size_mismatch, no_index,
                          "edge_ranks: the fiedler_result of a disconnected graph needs its component labels; pass "
                          "the result of fiedler_vector() unchanged");
    std::vector<double> size(static_cast<std::size_t>(fiedler.components), 0.0);
    for (const index_t l : fiedler.component) size[static_cast<std::size_t>(l)] += 1;
    for (std::size_t e = 0; e < candidates.size(); ++e) {
      const auto la = fiedler.component[static_cast<std::size_t>(candidates[e].first)];
      const auto lb = fiedler.component[static_cast<std::size_t>(candidates[e].second)];
      if (la != lb)
        rank[e] = detail::edge_weight(weights, e) *
                  (1.0 / size[static_cast<std::size_t>(la)] + 1.0 / size[static_cast<std::size_t>(lb)]);
    }
    return rank;
  }
  for (std::size_t e = 0; e < candidates.size(); ++e) {
    const double d = fiedler.vector(candidates[e].first) - fiedler.vector(candidates[e].second);
    rank[e] = detail::edge_weight(weights, e) * d * d;
  }
  return rank;
}

}  // namespace shapestruct
