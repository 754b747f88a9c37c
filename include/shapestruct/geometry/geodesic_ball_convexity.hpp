// SPDX-License-Identifier: MIT
// geodesic_ball_convexity: how far a point sticks out of (or sinks into) its geodesic neighbourhood, per scale.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"

namespace shapestruct {

/// Signed convexity of the surface at sample points, at several geodesic radii: for sample s and radius r,
///   c_r(s) = n_r(s) . (x_s - centroid_r(s)) / r,
/// where centroid_r and n_r are the area-weighted centroid and mean normal of the vertices within geodesic
/// distance r of s. Bumps (nose, knee caps, toes, heels) are positive, pits negative, flat patches 0.
/// It is invariant to rigid motions and scale-free per radius, but, unlike intrinsic descriptors, it tells the
/// two sides of an intrinsic near-symmetry apart (the front of a human from the back), which is why blended
/// maps use it to break ties between flipped blended maps.
/// Normals are taken outward: if the mesh's signed volume is negative its faces are read reversed.
/// \param V (#V x 3), F (#F x 3) the mesh
/// \param distances (#V x #samples) geodesic distances from each sample (column) to every vertex (row)
/// \param samples the sample vertex of each column
/// \param radii the radii (same units as `distances`), each > 0
/// \returns (#samples x #radii); 0 where a ball holds no area.
/// \throws invalid_input (size_mismatch if distances and samples disagree, bad_parameter for a radius <= 0).
/// Complexity O(#samples * #radii * V / threads).
template <class Scalar>
[[nodiscard]] matrix_x<Scalar> geodesic_ball_convexity(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                       const Eigen::Ref<const face_matrix>& F,
                                                       const Eigen::Ref<const matrix_x<Scalar>>& distances,
                                                       std::span<const index_t> samples,
                                                       std::span<const Scalar> radii, int threads = 0) {
  const index_t ns = static_cast<index_t>(samples.size());
  if (distances.cols() != ns || distances.rows() != V.rows())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "geodesic_ball_convexity: the distance table must be #V x #samples");
  for (index_t k = 0; k < static_cast<index_t>(radii.size()); ++k)
    if (!(radii[static_cast<std::size_t>(k)] > 0))
      throw invalid_input(input_error::bad_parameter, k, "geodesic_ball_convexity: every radius must be > 0");
  const vector_x<Scalar> area = vertex_areas<Scalar>(V, F);
  matrix_x3<Scalar> normal = vertex_normals<Scalar>(V, F);
  // Outward orientation: a closed mesh with clockwise faces has negative signed volume.
  Scalar volume = 0;
  for (index_t f = 0; f < F.rows(); ++f)
    volume += V.row(F(f, 0)).dot(V.row(F(f, 1)).cross(V.row(F(f, 2))));
  if (volume < 0) normal = -normal;
  const index_t nr = static_cast<index_t>(radii.size());
  matrix_x<Scalar> out = matrix_x<Scalar>::Zero(ns, nr);
  Scalar r_max = 0;
  for (const Scalar r : radii) r_max = std::max(r_max, r);
  detail::parallel_for(ns, detail::resolve_threads(threads, "geodesic_ball_convexity"), [&](index_t s) {
    const index_t v0 = samples[static_cast<std::size_t>(s)];
    // One pass over the vertices for all radii: each vertex within the largest ball feeds every ball holding it.
    matrix_x3<Scalar> centroid = matrix_x3<Scalar>::Zero(nr, 3);
    matrix_x3<Scalar> n = matrix_x3<Scalar>::Zero(nr, 3);
    vector_x<Scalar> w = vector_x<Scalar>::Zero(nr);
    for (index_t v = 0; v < V.rows(); ++v) {
      const Scalar d = distances(v, s);
      if (!(d <= r_max)) continue;
      for (index_t k = 0; k < nr; ++k) {
        if (!(d <= radii[static_cast<std::size_t>(k)])) continue;
        centroid.row(k) += area[v] * V.row(v);
        n.row(k) += area[v] * normal.row(v);
        w[k] += area[v];
      }
    }
    for (index_t k = 0; k < nr; ++k) {
      const Scalar len = n.row(k).norm();
      if (!(w[k] > 0) || !(len > 0)) continue;
      out(s, k) = (n.row(k) / len).dot(V.row(v0) - centroid.row(k) / w[k]) / radii[static_cast<std::size_t>(k)];
    }
  });
  return out;
}

}  // namespace shapestruct
