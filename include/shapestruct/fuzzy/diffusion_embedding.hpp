// SPDX-License-Identifier: MIT
// diffusion_embedding: the diffusion map of the correspondence matrix at time t (ch. 4.3.5, eq. 4.7-4.8).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "shapestruct/core/concepts/linear_operator.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/fuzzy/correspondence_matrix.hpp"
#include "shapestruct/spectral/top_eigenpairs.hpp"

namespace shapestruct {

/// A non-owning view of a LinearOperator: Spectra keeps a mutable reference to its operator, and the solvers
/// here take theirs by const reference without copying it.
template <LinearOperator Op>
struct operator_view {
  using Scalar = typename Op::Scalar;
  const Op* op;
  [[nodiscard]] index_t rows() const { return op->rows(); }
  [[nodiscard]] index_t cols() const { return op->cols(); }
  void perform_op(const Scalar* x, Scalar* y) const { op->perform_op(x, y); }
};

/// EmbeddingSolver: the leading eigenpairs of a symmetric operator by Spectra's implicitly restarted Lanczos,
/// never forming the matrix. The default.
struct lanczos_embedding_solver {
  /// The diffusion map needs the leading eigenvectors to a few digits only: they are weighted by lambda^t and
  /// compared by distance, so 1e-8 relative accuracy is far below what changes a correspondence.
  top_eigenpairs_options options{.max_iterations = 1000, .tolerance = 1e-8};
  template <LinearOperator Op>
  [[nodiscard]] eigenpairs_result<typename Op::Scalar> solve(const Op& op, index_t k) const {
    operator_view<Op> view{&op};
    return top_eigenpairs_operator(view, k, options);
  }
};

/// EmbeddingSolver: forms the operator densely (n products with unit vectors) and diagonalises it exactly. For
/// tests and small collections (n up to a few thousand).
struct dense_embedding_solver {
  template <LinearOperator Op>
  [[nodiscard]] eigenpairs_result<typename Op::Scalar> solve(const Op& op, index_t k) const {
    using Scalar = typename Op::Scalar;
    const index_t n = op.rows();
    matrix_x<Scalar> M(n, n);
    vector_x<Scalar> e = vector_x<Scalar>::Zero(n);
    for (index_t j = 0; j < n; ++j) {
      e[j] = 1;
      op.perform_op(e.data(), M.col(j).data());
      e[j] = 0;
    }
    Eigen::SelfAdjointEigenSolver<matrix_x<Scalar>> es(0.5 * (M + M.transpose()));
    eigenpairs_result<Scalar> out;
    if (es.info() != Eigen::Success) {
      out.info = status::numerical_issue;
      return out;
    }
    k = std::min(k, n);
    out.values = es.eigenvalues().reverse().head(k);
    out.vectors = es.eigenvectors().rowwise().reverse().leftCols(k);
    return out;
  }
};

/// Options of embed_diffusion (ch. 4.3.5-4.3.6 defaults).
struct diffusion_embedding_options {
  double time = 10;  ///< t: higher values average out misalignments, lower ones keep correspondences sharper
  /// Non-trivial eigenvectors kept; clamped to n - 2. The chapter keeps the top K = 128 (the rank of an ideal C).
  /// 64 is the default because at t = 10 the rest weigh little: on 111 generated chairs lambda_64^10 = 0.010 and
  /// lambda_128^10 = 0.001, the best-fuzzy landmark accuracy within 0.10 is 0.733 with 64 against 0.739 with 128,
  /// and the Lanczos solve is 3 times faster (docs/fuzzy.md).
  index_t dimensions = 64;
};

/// The diffusion map: row p of `coordinates` is Pi_t(p) = (lambda_n^t psi_n(p))_n over the non-trivial
/// eigenvectors, so the Euclidean distance of two rows is the diffusion distance D_t (eq. 4.8).
struct diffusion_embedding {
  Eigen::MatrixXf coordinates;    ///< (NK x d) embedded points, shape by shape (rows offset(k) .. offset(k+1)-1)
  Eigen::VectorXd eigenvalues;    ///< (d) lambda_n of the non-trivial eigenvectors, descending
  double trivial_eigenvalue = 0;  ///< lambda_0 (1 for a connected graph)
  std::vector<index_t> offsets;   ///< (N + 1) first row of each shape
  status info = status::ok;

  [[nodiscard]] index_t shapes() const noexcept { return static_cast<index_t>(offsets.size()) - 1; }
  [[nodiscard]] index_t points() const noexcept { return coordinates.rows(); }
  [[nodiscard]] index_t dimensions() const noexcept { return coordinates.cols(); }
  [[nodiscard]] index_t offset(index_t k) const { return offsets[std::size_t(k)]; }
  [[nodiscard]] index_t samples_of(index_t k) const { return offsets[std::size_t(k + 1)] - offsets[std::size_t(k)]; }
  /// Squared diffusion distance between rows p and q.
  [[nodiscard]] double squared_distance(index_t p, index_t q) const {
    return double((coordinates.row(p) - coordinates.row(q)).squaredNorm());
  }
};

/// Computes the diffusion map of C at time t with the EmbeddingSolver `solver` (eq. 4.7): the leading
/// dimensions + 1 eigenpairs of D^-1/2 W D^-1/2, the first (lambda = 1, constant psi) dropped, psi = D^-1/2 u,
/// coordinates lambda^t psi. Eigenvalues below zero (which a bipartite-like graph has) are sorted last by the
/// algebraic ordering and weighted by |lambda|^t.
/// \throws invalid_input (bad_parameter) for t < 0 or dimensions < 1, (empty) for fewer than 3 points.
template <class Solver = lanczos_embedding_solver>
  requires EmbeddingSolver<Solver, correspondence_matrix>
[[nodiscard]] diffusion_embedding embed_diffusion(const correspondence_matrix& C,
                                                  const diffusion_embedding_options& options = {},
                                                  const Solver& solver = {}) {
  const char* who = "embed_diffusion";
  if (!(options.time >= 0) || !std::isfinite(options.time))
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": time must be finite and >= 0");
  if (options.dimensions < 1)
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": dimensions must be >= 1");
  const index_t n = C.rows();
  if (n < 3) throw invalid_input(input_error::empty, no_index, std::string(who) + ": fewer than 3 points to embed");
  const index_t d = std::min(options.dimensions, n - 2);
  auto eig = solver.solve(C, d + 1);
  diffusion_embedding out;
  out.info = eig.info;
  out.offsets.resize(static_cast<std::size_t>(C.shapes() + 1));
  for (index_t k = 0; k <= C.shapes(); ++k) out.offsets[std::size_t(k)] = k < C.shapes() ? C.offset(k) : n;
  const index_t got = eig.vectors.cols();
  if (got == 0) {
    out.info = status::not_converged;
    return out;
  }
  out.trivial_eigenvalue = eig.values[0];
  const index_t dims = got - 1;
  out.eigenvalues = eig.values.segment(1, dims);
  out.coordinates.resize(n, dims);
  for (index_t c = 0; c < dims; ++c) {
    const double w = std::pow(std::abs(eig.values[c + 1]), options.time);
    out.coordinates.col(c) = (w * eig.vectors.col(c + 1).cwiseProduct(C.inverse_sqrt_degrees())).template cast<float>();
  }
  // Fix each eigenvector's arbitrary sign (largest |entry| positive) so that files are reproducible.
  for (index_t c = 0; c < dims; ++c) {
    index_t at = 0;
    out.coordinates.col(c).cwiseAbs().maxCoeff(&at);
    if (out.coordinates(at, c) < 0) out.coordinates.col(c) *= -1.0f;
  }
  return out;
}

}  // namespace shapestruct
