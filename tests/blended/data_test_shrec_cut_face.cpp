// SPDX-License-Identifier: MIT
// SHREC'07 human 8 -> 13: mesh 8's largest face sits on a finger tip; cut there, its flattening folds and every
// map with mesh 8 failed (mean error 0.78 on the benchmark's scale, d / sqrt(area)). blended_shape cuts away from
// the features. Skipped without $SHAPESTRUCT_DATA.
#include <algorithm>

#include <doctest/doctest.h>

#include "dense_benchmark_error.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "support/data_path.hpp"

using namespace shapestruct;

TEST_CASE("blended_matcher maps SHREC'07 human 8 to 13 with the cut away from mesh 8's finger tip") {
  SHAPESTRUCT_REQUIRE_DATA(shrec, "watertight_shrec07");
  const auto A = read_mesh(shrec / "Meshes/8.off").mesh;
  const auto B = read_mesh(shrec / "Meshes/13.off").mesh;
  blended_matcher_options o;
  o.threads = 2;
  // The cut's effect, isolated from the selection rule: with the cut moved, the rank sum selects the true group
  // (0.087); the default integrated-confidence rule picks a group that is 0.224 off on this pair.
  o.selection = blended_selection::area_and_confidence_rank;
  const blended_matcher<> matcher(o);
  const auto sa = matcher.prepare(A);
  const auto sb = matcher.prepare(B);
  double clearance = 1e300;
  for (int k = 0; k < 3; ++k)
    clearance = std::min(clearance, sa.feature_distances().row(sa.mesh().F(sa.flattening().cut_face(), k)).minCoeff());
  CHECK(clearance >= o.shape.cut_clearance);
  const auto r = matcher.match(sa, sb);
  // The benchmark's protocol for SHREC'07: the class's feature points (8.vts, 13.vts), d / sqrt(area of the target).
  const auto s = test::feature_point_errors(sb, r.map, shrec / "Corrs/8.vts", shrec / "Corrs/13.vts");
  MESSAGE("SHREC'07 8 -> 13: mean " << s.mean << ", within 0.25 " << s.within_025);
  // The original program's stored result for this pair, 0.0881, on the same scale; the map errs 0.0871, so the
  // margin is small (1 %).
  CHECK(s.mean < 0.0881);
  CHECK(s.within_025 >= 0.99);
  // ZoomOut drifts on this pair (0.169 at the feature points). The move check puts back the blended image where it
  // jumped, and what is left distorts no more than 1.5 times the blended map, so the refinement is kept.
  MESSAGE("refinement: " << r.refinement_moves_undone << " images put back, distortion " << r.refined_distortion
                         << " against " << r.blended[static_cast<std::size_t>(r.selected)].geodesic_distortion);
  CHECK(r.refinement_moves_undone > 0);
  CHECK(r.refinement_accepted);
  // Without the check, its geodesic distortion at the even samples is 1.75 times the blended map's, so the
  // distortion check undoes it and the map is the blended one.
  blended_matcher_options unchecked = o;
  unchecked.refinement_move_check = 0;
  const auto u = blended_matcher<>(unchecked).match(sa, sb);
  CHECK(!u.refinement_accepted);
  const auto& u_blended = u.blended[static_cast<std::size_t>(u.selected)];
  CHECK(u.refined_distortion > o.max_refined_distortion_ratio * u_blended.geodesic_distortion);
  CHECK(u.map.nearest == u_blended.map.nearest);
}
