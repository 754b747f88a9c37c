// SPDX-License-Identifier: MIT
// PointSet: any indexable set of points with a compile-time dimension, through point_set_traits.
#pragma once

#include <concepts>

#include "shapestruct/core/traits.hpp"
#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// Points with a compile-time dimension and coordinate-wise access (nanoflann's dataset interface, so any
/// model feeds a kd-tree unchanged).
///
/// Required expressions, with T = point_set_traits<std::remove_cvref_t<P>>:
///   T::scalar_type             a floating-point type
///   T::dimension               static constexpr int, > 0
///   T::num_points(p)           -> index_t
///   T::coord(p, i, d)          -> scalar_type, coordinate d of point i; O(1)
/// Models: Eigen `#P x D` matrices (adapters/eigen_points.hpp), std::vector<std::array<S, D>>
/// (adapters/std_arrays.hpp), triangle_mesh vertices (core/triangle_mesh.hpp).
template <class P>
concept PointSet = detail::is_complete<point_set_traits_t<P>>::value &&
                   std::floating_point<typename point_set_traits_t<P>::scalar_type> &&
                   requires(const std::remove_cvref_t<P>& p, index_t i, int d) {
                     { point_set_traits_t<P>::dimension } -> std::convertible_to<int>;
                     { point_set_traits_t<P>::num_points(p) } -> std::convertible_to<index_t>;
                     {
                       point_set_traits_t<P>::coord(p, i, d)
                     } -> std::convertible_to<typename point_set_traits_t<P>::scalar_type>;
                   };

}  // namespace shapestruct
