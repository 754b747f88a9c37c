// SPDX-License-Identifier: MIT
// shape_record: the small per-shape summary a collection keeps in memory (samples, descriptor, scale).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// What the collection stages keep of one shape once its file has been read and forgotten (ch. 4.3.1): K
/// farthest-point samples, where every vertex lies relative to them, a dense point cloud for extrinsic
/// alignment, a global descriptor and the scales the alignment scores use. About 30 KB for K = 128.
struct shape_record {
  std::string name;                     ///< the shape's file stem (unique within a collection)
  Eigen::Matrix<double, Eigen::Dynamic, 3> samples;  ///< (K x 3) farthest-point samples P_i
  /// (K) vertex of each sample on manifolds (geodesic sampling), no_index for samples drawn from the surface of
  /// a soup or point cloud (Euclidean sampling over surface_points).
  std::vector<index_t> sample_vertex;
  /// (#V) nearest sample of every vertex of the input mesh (geodesically on manifolds, Euclidean otherwise):
  /// the nearest-neighbour interpolation of per-sample values to the whole shape.
  std::vector<std::int32_t> vertex_sample;
  /// (M x 3) evenly spread surface points (M = 1,024 by default): the shape's surface for ICP and for the
  /// global alignment term (eq. 4.3), which measures distances to the other shape's surface.
  Eigen::Matrix<double, Eigen::Dynamic, 3> surface_points;
  /// (K x K) geodesic distances between samples (edge-graph Dijkstra), in model units; empty when the shape is
  /// not a manifold (extrinsic collections).
  Eigen::MatrixXf sample_geodesics;
  Eigen::VectorXd descriptor;  ///< global shape descriptor (ShapeDescriptor policy), compared by L2 distance
  /// Diam(S) of ch. 4.3.3: mean Euclidean distance between all pairs of samples; sigma(S) = Diam / 5.
  double diameter = 0;
  double area = 0;             ///< total surface area (0 for point clouds)
  /// Closed, connected, genus-0 surface (a manifold once pinched vertices are split): eligible for intrinsic
  /// (blended-map) alignment.
  bool closed_genus0 = false;
  index_t vertex_count = 0;    ///< #V of the input mesh (the length of vertex_sample)

  [[nodiscard]] index_t sample_count() const noexcept { return samples.rows(); }
};

}  // namespace shapestruct
