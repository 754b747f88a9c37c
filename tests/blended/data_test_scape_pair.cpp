// SPDX-License-Identifier: MIT
// Blended intrinsic maps on one SCAPE benchmark pair (mesh000 -> mesh037), scored with the benchmark's protocol
// against the dense ground truth, on the benchmark's scale (d / sqrt(area), as the stored results). Skipped
// without $SHAPESTRUCT_DATA.
#include <doctest/doctest.h>

#include "dense_benchmark_error.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "support/data_path.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

TEST_CASE("blended_matcher on SCAPE mesh000 -> mesh037, refined, errs well below the stored original result") {
  SHAPESTRUCT_REQUIRE_DATA(scape, "SCAPE");
  const auto A = read_mesh(scape / "Meshes/mesh000.off").mesh;
  const auto B = read_mesh(scape / "Meshes/mesh037.off").mesh;
  const blended_matcher<> matcher;
  const auto sa = matcher.prepare(A);
  // The second mesh goes through the legacy_mesh model (float coordinates): both SurfaceMesh paths are used.
  const auto sb = matcher.prepare(test::to_legacy(B));
  const auto r = matcher.match(sa, sb);
  CHECK(r.info == status::ok);
  // SCAPE's template has a pinched vertex (419): accepted, and every vertex is mapped.
  for (index_t v = 0; v < r.map.source_size(); ++v) REQUIRE(r.map.target_vertex(v) != no_index);
  // The benchmark protocol on the template-aligned meshes (truth: the same vertex).
  const auto s = test::dense_identity_errors(sa, sb, r.map);
  const double stored = test::stored_blended_map_mean(scape, "Results_Corr_Scape", "mesh000_to_mesh037", 0.0391);
  MESSAGE("mesh000 -> mesh037: mean " << s.mean << " (stored original " << stored << "), within 0.25 " << s.within_025);
  // On the benchmark's scale the blended map errs 0.0413 against the stored 0.0391; the ZoomOut refinement (on by
  // default) brings it to 0.0166. The bound keeps a margin over that, and checks the refined map is well ahead.
  CHECK(s.mean <= 0.6 * stored);
  CHECK(s.within_025 >= 0.99);
}
