// SPDX-License-Identifier: MIT
// Vocabulary types shared by every stage: indices and the canonical Eigen matrix shapes.
#pragma once

#include <Eigen/Core>

namespace shapestruct {

/// Index type for vertices, faces, points and samples. Equal to Eigen::Index so that no conversion is
/// needed at Eigen boundaries.
using index_t = Eigen::Index;

/// `#V x 3` vertex positions (or `#P x 3` points), column-major as in libigl.
template <class Scalar>
using matrix_x3 = Eigen::Matrix<Scalar, Eigen::Dynamic, 3>;

/// `#F x 3` triangle vertex indices.
using face_matrix = Eigen::Matrix<index_t, Eigen::Dynamic, 3>;

template <class Scalar>
using vector_x = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

template <class Scalar>
using vec3 = Eigen::Matrix<Scalar, 3, 1>;

template <class Scalar>
using matrix_x = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// Sentinel for "no element" (no face, no vertex, no label).
inline constexpr index_t no_index = -1;

}  // namespace shapestruct
