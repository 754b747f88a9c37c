// SPDX-License-Identifier: MIT
// LinearOperator: a matrix known only through its product with a vector (Spectra's OpType requirements).
#pragma once

#include <concepts>

#include "shapestruct/core/status.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// y = A x for square or rectangular A. Identical to Spectra's operator requirements, so every Spectra MatOp
/// (DenseSymMatProd, SparseSymMatProd, ...) is a model unchanged, and a model can be handed to Spectra.
template <class Op>
concept LinearOperator = requires(const Op& op, const typename Op::Scalar* x, typename Op::Scalar* y) {
  { op.rows() } -> std::convertible_to<index_t>;
  { op.cols() } -> std::convertible_to<index_t>;
  op.perform_op(x, y);
};

/// Computes the k leading eigenpairs of a symmetric operator. The result has `values` (k, descending),
/// `vectors` (n x k) and `info` (status).
template <class Sv, class Op>
concept EmbeddingSolver = LinearOperator<Op> && requires(Sv& s, const Op& op, index_t k) {
  s.solve(op, k).values;
  s.solve(op, k).vectors;
  { s.solve(op, k).info } -> std::convertible_to<status>;
};

}  // namespace shapestruct
