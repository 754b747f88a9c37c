// SPDX-License-Identifier: MIT
// Blended intrinsic maps on TOSCA david6 -> david12 with feature radius 0.1 (10 x 10 feature points: 86,400
// triplet maps, pruned to 30,000 before the confidence stage). With random pruning the true triplets were mostly
// lost and the selected map was the front-to-back flip (mean error 0.52 on the benchmark's scale, d / sqrt(area));
// pruning by feature-distance preservation keeps them (0.050; the stored original 0.033).
// Skipped without $SHAPESTRUCT_DATA.
#include <doctest/doctest.h>

#include "dense_benchmark_error.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "support/data_path.hpp"

using namespace shapestruct;

TEST_CASE("blended_matcher on TOSCA david6 -> david12 (pruned candidates) keeps the true triplets and does not flip") {
  SHAPESTRUCT_REQUIRE_DATA(tosca, "TOSCA");
  const auto A = read_mesh(tosca / "Meshes/david6.off").mesh;
  const auto B = read_mesh(tosca / "Meshes/david12.off").mesh;
  blended_matcher_options o;
  o.shape.repairs.close_small_holes = true;  // TOSCA's meshes have small holes (the benchmark runner's setting)
  o.shape.repairs.keep_largest_component = true;
  o.shape.feature_radius = 0.1;  // 10 AGD maxima per shape (the default 0.15 gives 5, too few to prune)
  const blended_matcher<> matcher(o);
  const auto sa = matcher.prepare(A);
  const auto sb = matcher.prepare(B);
  REQUIRE(sa.features().size() * sb.features().size() >= 81);  // enough features for the pruning to act
  const auto r = matcher.match(sa, sb);
  CHECK(r.info == status::ok);
  // The meshes share their vertex numbering, so the truth is the identity.
  const auto s = test::dense_identity_errors(sa, sb, r.map);
  const double stored = test::stored_blended_map_mean(tosca, "Results_Corr_TOSCA", "david6_to_david12", 0.0334);
  MESSAGE("david6 -> david12: mean " << s.mean << " (stored original " << stored << "), within 0.25 " << s.within_025);
  // On the benchmark's scale the map errs 0.050, behind the stored 0.033 (this test used to claim it beat it,
  // comparing half-scale errors with the stored ones). What it guards is the pruning: the flip errs 0.52, so a
  // bound of 0.10 separates the true map from the flip with room on both sides.
  CHECK(s.mean <= 0.10);
  CHECK(s.within_025 >= 0.99);
}
