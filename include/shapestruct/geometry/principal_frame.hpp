// SPDX-License-Identifier: MIT
// principal_frame: mean, principal axes and variances of a subset of points (the PCA frame of a part box,
// dissertation 5.3.1 and 5.3.4).
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// The principal frame of a point set.
struct principal_frame {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  /// Rows are the principal axes in ascending order of variance, forming a right-handed frame (determinant +1).
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  /// Variance of the points along each axis (same order as the rows of `axes`), >= 0.
  Eigen::Vector3d variances = Eigen::Vector3d::Zero();
};

/// Principal frame of the rows `members` of P. An empty `members` gives the identity frame at the origin with zero
/// variances; fewer than 3 distinct points give a frame whose extra axes are arbitrary but orthonormal. O(|members|).
inline principal_frame principal_frame_of(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 3>>& P,
                                          const std::vector<index_t>& members) {
  principal_frame f;
  if (members.empty()) return f;
  const double n = static_cast<double>(members.size());
  for (const auto i : members) f.mean += P.row(i).transpose();
  f.mean /= n;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto i : members) {
    const Eigen::Vector3d d = P.row(i).transpose() - f.mean;
    covariance += d * d.transpose();
  }
  covariance /= n;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(covariance);
  f.axes = es.eigenvectors().transpose();
  if (f.axes.determinant() < 0) f.axes.row(0) *= -1;  // right-handed, so a box's rotation is a proper rotation
  f.variances = es.eigenvalues().cwiseMax(0.0);
  return f;
}

}  // namespace shapestruct
