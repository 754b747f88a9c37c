// SPDX-License-Identifier: MIT
// principal_frame_of: axes, variances and the degenerate member sets.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "shapestruct/geometry/principal_frame.hpp"

using namespace shapestruct;

TEST_CASE("principal_frame_of recovers the axes and variances of a rotated box of points") {
  // A 4 x 2 x 1 box of uniform points, rotated and moved: variances side^2 / 12 along the rotated axes.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const Eigen::Vector3d t(5, -1, 2), side(1, 2, 4);
  Eigen::Matrix<double, Eigen::Dynamic, 3> P(20000, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d local(side(0) * u(rng), side(1) * u(rng), side(2) * u(rng));
    P.row(i) = (R * local + t).transpose();
  }
  std::vector<index_t> all(static_cast<std::size_t>(P.rows()));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<index_t>(i);
  const principal_frame f = principal_frame_of(P, all);
  CHECK((f.mean - t).norm() < 0.05);
  CHECK(f.axes.determinant() == doctest::Approx(1.0));
  CHECK((f.axes * f.axes.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-10);
  for (int k = 0; k < 3; ++k) {
    CHECK(f.variances(k) == doctest::Approx(side(k) * side(k) / 12).epsilon(0.05));
    CHECK(std::abs(f.axes.row(k).dot(R.col(k))) == doctest::Approx(1.0).epsilon(1e-3));  // ascending variance
  }
}

TEST_CASE("principal_frame_of uses only the given members and handles empty and single-point sets") {
  Eigen::Matrix<double, Eigen::Dynamic, 3> P(4, 3);
  P << 0, 0, 0, 2, 0, 0, 100, 100, 100, 1, 0, 0;
  const principal_frame line = principal_frame_of(P, {0, 1, 3});
  CHECK(line.mean.isApprox(Eigen::Vector3d(1, 0, 0)));
  CHECK(std::abs(line.axes.row(2).x()) == doctest::Approx(1.0));  // the largest variance lies along x
  CHECK(line.variances(2) == doctest::Approx(2.0 / 3));
  CHECK(line.variances(0) == doctest::Approx(0.0));
  CHECK(line.axes.determinant() == doctest::Approx(1.0));
  const principal_frame none = principal_frame_of(P, {});
  CHECK(none.mean.isZero());
  CHECK(none.axes.isIdentity());
  const principal_frame one = principal_frame_of(P, {2});
  CHECK(one.mean.isApprox(Eigen::Vector3d(100, 100, 100)));
  CHECK(one.variances.isZero());
  CHECK(one.axes.determinant() == doctest::Approx(1.0));
}
