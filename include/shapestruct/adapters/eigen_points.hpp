// SPDX-License-Identifier: MIT
// Eigen matrices with one point per row as PointSet models.
#pragma once

#include <Eigen/Core>

#include "shapestruct/core/concepts/point_set.hpp"

namespace shapestruct {

/// Any `#P x D` Eigen matrix with a compile-time column count D is a D-dimensional point set.
template <class Scalar, int Cols, int Options, int MaxRows, int MaxCols>
  requires(Cols != Eigen::Dynamic)
struct point_set_traits<Eigen::Matrix<Scalar, Eigen::Dynamic, Cols, Options, MaxRows, MaxCols>> {
  using scalar_type = Scalar;
  static constexpr int dimension = Cols;
  using matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Cols, Options, MaxRows, MaxCols>;
  static index_t num_points(const matrix& p) { return p.rows(); }
  static Scalar coord(const matrix& p, index_t i, int d) { return p(i, d); }
};

}  // namespace shapestruct
