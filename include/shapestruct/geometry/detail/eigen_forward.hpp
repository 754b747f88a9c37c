// SPDX-License-Identifier: MIT
// Private: the constraint the geometry kernels' convenience overloads use to accept any dense Eigen
// expression (and forward it to the Eigen::Ref kernel) without competing with an explicit `<Scalar>` call.
#pragma once

#include <concepts>
#include <type_traits>

#include <Eigen/Core>

namespace shapestruct::detail {

/// A dense Eigen expression type (Matrix, Block, Map, Ref, ...). The arithmetic check comes first so that
/// `kernel<double>(V, F)` never instantiates Eigen::MatrixBase<double>.
template <class D>
concept geometry_dense = !std::is_arithmetic_v<D> && std::derived_from<D, Eigen::MatrixBase<D>>;

/// A dense Eigen expression with floating-point coefficients (vertex positions).
template <class D>
concept geometry_dense_real = geometry_dense<D> && std::floating_point<typename D::Scalar>;

}  // namespace shapestruct::detail
