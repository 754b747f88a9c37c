// SPDX-License-Identifier: MIT
// ShapeDescriptor: a global descriptor of a shape's surface, compared by L2 distance (initial alignment graph).
#pragma once

#include <concepts>

#include <Eigen/Core>

namespace shapestruct {

/// Computes a fixed-length descriptor of a shape from evenly spread points on its surface (#P x 3), such that
/// the L2 distance between two descriptors predicts whether the shapes are similar enough to be aligned
/// automatically (ch. 4.3.2). The same descriptor object must give equal-length vectors for every shape.
/// Models: spherical_harmonic_descriptor (collection/), and any user type with a conforming operator().
template <class D>
concept ShapeDescriptor = requires(const D& d, const Eigen::Matrix<double, Eigen::Dynamic, 3>& points) {
  { d(points) } -> std::convertible_to<Eigen::VectorXd>;
};

}  // namespace shapestruct
