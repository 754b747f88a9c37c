// SPDX-License-Identifier: MIT
// affine_alignment: the weighted least-squares affine map between corresponding point sets (ch. 4.5.3).
#pragma once
#include <algorithm>
#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/SVD>
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// A 3-D affine map x -> A x + t, stored as the 3 x 4 matrix [A | t].
using affine_transform = Eigen::Matrix<double, 3, 4>;

/// The identity affine map.
[[nodiscard]] inline affine_transform identity_affine() {
  affine_transform T = affine_transform::Zero();
  T.leftCols<3>().setIdentity();
  return T;
}

/// T applied to x.
[[nodiscard]] inline Eigen::Vector3d apply(const affine_transform& T, const Eigen::Vector3d& x) {
  return T.leftCols<3>() * x + T.col(3);
}

/// Accumulates weighted pairs (x, y, w) and solves min over T of sum w |T x - y|^2. Pairs are added one by one or
/// as pre-summed moments, so K x K fuzzy weights cost O(K^2) to add, not O(K^2) matrix products.
class affine_least_squares {
 public:
  /// Adds weight w on the pair x -> y.
  void add(const Eigen::Vector3d& x, const Eigen::Vector3d& y, double w) { add_moments(x, y * w, w); }
  /// Adds the pairs (x, y_i, w_i) of one source point at once: `weighted_targets` = sum w_i y_i, `weight` = sum w_i.
  void add_moments(const Eigen::Vector3d& x, const Eigen::Vector3d& weighted_targets, double weight) {
    if (!(weight > 0)) return;
    Eigen::Vector4d xh;
    xh << x, 1.0;
    xx_ += weight * xh * xh.transpose();
    yx_ += weighted_targets * xh.transpose();
    total_ += weight;
  }
  [[nodiscard]] double total_weight() const noexcept { return total_; }

  /// The minimiser. Where the pairs do not determine T (fewer than 4 affinely independent weighted source
  /// points, e.g. a region on a planar patch), the undetermined directions stay as the identity would map them: a
  /// ridge of relative size `ridge` pulls the linear part towards the best uniform scale (it changes a
  /// well-determined solution by about that relative amount). No pairs: the identity.
  /// `max_stretch` > 0 bounds the linear part: its singular values are clamped to [m / max_stretch, m max_stretch]
  /// about their median m, and a reflection is undone, keeping the weighted centroids matched. Pairs that cannot
  /// be an affine image of each other (a region whose counterparts scatter over a shape that lacks it) otherwise
  /// flatten the target onto a plane; 0 keeps the plain least-squares map.
  [[nodiscard]] affine_transform solve(double ridge = 1e-9, double max_stretch = 0) const {
    if (!(total_ > 0)) return identity_affine();
    const Eigen::Vector3d mx = xx_.block<3, 1>(0, 3) / total_;  // weighted centroids
    const Eigen::Vector3d my = yx_.col(3) / total_;
    // Centred second moments: Sxx = sum w (x - mx)(x - mx)^T, Syx = sum w (y - my)(x - mx)^T.
    const Eigen::Matrix3d Sxx = xx_.topLeftCorner<3, 3>() - total_ * mx * mx.transpose();
    const Eigen::Matrix3d Syx = yx_.leftCols<3>() - total_ * my * mx.transpose();
    const double trace = Sxx.trace();
    Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
    if (trace > 0) {
      const double lambda = ridge * trace;
      const double s = Syx.trace() / trace;  // the least-squares uniform scale (rotation-free): the ridge's target
      const Eigen::Matrix3d lhs = Sxx + lambda * Eigen::Matrix3d::Identity();
      A = (lhs.ldlt().solve((Syx + lambda * s * Eigen::Matrix3d::Identity()).transpose())).transpose();
    }
    if (max_stretch > 0) A = limit_stretch(A, max_stretch);
    affine_transform T;
    T.leftCols<3>() = A;
    T.col(3) = my - A * mx;
    return T;
  }

  /// A with its singular values clamped to [m / ratio, m ratio] about their median m and its orientation kept
  /// (a negative determinant flips the smallest singular direction).
  [[nodiscard]] static Eigen::Matrix3d limit_stretch(const Eigen::Matrix3d& A, double ratio) {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Vector3d sigma = svd.singularValues();  // descending
    const double median = sigma[1];
    if (!(median > 0)) return A;
    for (int k = 0; k < 3; ++k) sigma[k] = std::clamp(sigma[k], median / ratio, median * ratio);
    Eigen::Matrix3d U = svd.matrixU();
    if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(2) = -U.col(2);
    return U * sigma.asDiagonal() * svd.matrixV().transpose();
  }

 private:
  Eigen::Matrix4d xx_ = Eigen::Matrix4d::Zero();               // sum w xh xh^T
  Eigen::Matrix<double, 3, 4> yx_ = Eigen::Matrix<double, 3, 4>::Zero();  // sum w y xh^T
  double total_ = 0;
};

}  // namespace shapestruct
