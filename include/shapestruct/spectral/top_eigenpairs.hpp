// SPDX-License-Identifier: MIT
// top_eigenpairs: the largest eigenvalues and eigenvectors of a symmetric operator (Spectra, dense fallback).
#pragma once

#include <algorithm>
#include <string>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

#include "shapestruct/core/concepts/linear_operator.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Options of top_eigenpairs.
struct top_eigenpairs_options {
  int max_iterations = 1000;  ///< Spectra restarts before giving up (status::not_converged)
  double tolerance = 1e-10;   ///< relative eigenvalue tolerance
  /// Below this size the dense solver is used: it is exact and, for small n, faster than Lanczos.
  index_t dense_below = 400;
};

/// Result of top_eigenpairs: `values` (k, descending), `vectors` (n x k), `info`.
template <class Scalar = double>
struct eigenpairs_result {
  vector_x<Scalar> values;
  matrix_x<Scalar> vectors;
  status info = status::ok;
};

/// The k algebraically largest eigenpairs of a symmetric LinearOperator (Spectra's implicitly restarted
/// Lanczos). On non-convergence the result holds whatever Spectra converged (possibly fewer than k columns)
/// and info = not_converged.
/// \param op symmetric n x n operator (non-const: Spectra keeps a mutable reference)  \param k number of pairs, 1 <= k < n
/// \throws invalid_input (bad_parameter) for k out of range. Complexity O(iterations * (cost(op) + n * ncv)).
template <LinearOperator Op>
[[nodiscard]] eigenpairs_result<typename Op::Scalar> top_eigenpairs_operator(Op& op, index_t k,
                                                                              const top_eigenpairs_options& options = {}) {
  using Scalar = typename Op::Scalar;
  const index_t n = op.rows();
  if (k < 1 || k >= n)
    throw invalid_input(input_error::bad_parameter, no_index,
                        "top_eigenpairs: need 1 <= k < n, got k = " + std::to_string(k) + ", n = " + std::to_string(n));
  const index_t ncv = std::min<index_t>(n, std::max<index_t>(2 * k + 1, 20));
  Spectra::SymEigsSolver<Op> solver(op, static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(ncv));
  solver.init();
  solver.compute(Spectra::SortRule::LargestAlge, options.max_iterations, options.tolerance);
  eigenpairs_result<Scalar> out;
  out.values = solver.eigenvalues();
  out.vectors = solver.eigenvectors();
  if (solver.info() != Spectra::CompInfo::Successful) out.info = status::not_converged;
  return out;
}

/// The k largest eigenpairs of a symmetric sparse matrix: dense self-adjoint solver below
/// options.dense_below, Spectra above. k is clamped to n.
/// \param A symmetric (n x n)  \param k number of pairs (>= 1)
/// \throws invalid_input (size_mismatch) if A is not square, (empty) if n = 0, (bad_parameter) if k < 1.
template <class Scalar>
[[nodiscard]] eigenpairs_result<Scalar> top_eigenpairs(const Eigen::SparseMatrix<Scalar>& A, index_t k,
                                                       const top_eigenpairs_options& options = {}) {
  if (A.rows() != A.cols())
    throw invalid_input(input_error::size_mismatch, no_index, "top_eigenpairs: the matrix must be square");
  if (A.rows() == 0) throw invalid_input(input_error::empty, no_index, "top_eigenpairs: the matrix is empty");
  if (k < 1) throw invalid_input(input_error::bad_parameter, no_index, "top_eigenpairs: k must be >= 1");
  const index_t n = A.rows();
  k = std::min(k, n);
  if (n < options.dense_below || k >= n - 1) {
    Eigen::SelfAdjointEigenSolver<matrix_x<Scalar>> es{matrix_x<Scalar>(A)};
    eigenpairs_result<Scalar> out;
    if (es.info() != Eigen::Success) {
      out.info = status::numerical_issue;
      return out;
    }
    out.values = es.eigenvalues().reverse().head(k);
    out.vectors = es.eigenvectors().rowwise().reverse().leftCols(k);
    return out;
  }
  Spectra::SparseSymMatProd<Scalar> op(A);
  return top_eigenpairs_operator(op, k, options);
}

}  // namespace shapestruct
