// SPDX-License-Identifier: MIT
// blended_shape cuts its flattening away from the feature points (blended_shape_options::cut_clearance).
#include <algorithm>
#include <vector>

#include <doctest/doctest.h>

#include "blended_fixtures.hpp"
#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"

using namespace shapestruct;

namespace {
/// Smallest geodesic distance from a corner of face f to a feature point of s.
double clearance_of(const blended_shape<double>& s, index_t f) {
  double d = 1e300;
  for (int k = 0; k < 3; ++k) d = std::min(d, s.feature_distances().row(s.mesh().F(f, k)).minCoeff());
  return d;
}
}  // namespace

TEST_CASE("cut_face_away_from_features keeps a clear largest face and otherwise cuts around the least-AGD vertex") {
  // Four faces of a strip; vertex 0 is a feature, vertex 5 the most central (least AGD).
  matrix_x3<double> V(6, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 3, 0, 0, 3, 2, 0, 1, 1, 0;
  face_matrix F(4, 3);
  F << 0, 1, 2, 1, 3, 4, 1, 4, 5, 1, 5, 2;
  matrix_x<double> to_feature(6, 1);
  to_feature << 0.0, 0.1, 0.1, 0.5, 0.6, 0.3;
  vector_x<double> agd(6);
  agd << 0.9, 0.5, 0.6, 0.8, 0.7, 0.2;
  // Face 1 (area 2) is clear of the feature by 0.1 only: with clearance 0.05 it stays, with 0.2 the cut moves to
  // the larger of the faces around vertex 5 (face 2, area 1, over face 3, area 0.5).
  CHECK(detail::cut_face_away_from_features<double>(V, F, 1, to_feature, agd, 0.05) == 1);
  CHECK(detail::cut_face_away_from_features<double>(V, F, 1, to_feature, agd, 0.2) == 2);
  // No features: the largest face.
  CHECK(detail::cut_face_away_from_features<double>(V, F, 1, matrix_x<double>(6, 0), agd, 0.2) == 1);
}

TEST_CASE("blended_shape moves a cut that a tip's enlarged face would attract away from the features") {
  auto m = test::armed_sphere(3);
  blended_shape_options o;
  o.num_samples = 96;
  o.threads = 2;
  const blended_shape<double> plain(m.V, m.F, o);
  REQUIRE(plain.features().size() >= 3);
  // Pull the first feature (an arm tip) outwards: its incident faces become the largest of the mesh, so the
  // flattening's own choice (the largest face) lands at the tip.
  const index_t tip = plain.features().front();
  const double edge = mean_edge_length(m.V, m.F);
  const Eigen::RowVector3d out = m.V.row(tip).normalized();
  m.V.row(tip) += 4 * edge * out;
  blended_shape_options largest = o;
  largest.cut_clearance = 0;
  const blended_shape<double> at_tip(m.V, m.F, largest);
  REQUIRE(std::find(at_tip.features().begin(), at_tip.features().end(), tip) != at_tip.features().end());
  REQUIRE(clearance_of(at_tip, at_tip.flattening().cut_face()) < o.cut_clearance);  // the case the rule is for
  const blended_shape<double> moved(m.V, m.F, o);
  CHECK(moved.flattening().cut_face() != at_tip.flattening().cut_face());
  CHECK(clearance_of(moved, moved.flattening().cut_face()) >= o.cut_clearance);
  CHECK(moved.flattening().count_foldovers() == 0);
  // Features and samples do not depend on the cut.
  CHECK(moved.features() == at_tip.features());
  CHECK(moved.samples() == at_tip.samples());
  blended_shape_options bad = o;
  bad.cut_clearance = -1;
  CHECK_THROWS_AS(blended_shape<double>(m.V, m.F, bad), invalid_input);
}
