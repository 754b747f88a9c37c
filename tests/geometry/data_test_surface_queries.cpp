// SPDX-License-Identifier: MIT
// Closest points, sampling and local shape features on real scanned / modelled meshes (SCAPE, COSEG chairs):
// slivers, near-degenerate faces and many components that procedural meshes do not have.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include "shapestruct/geometry/closest_point_query.hpp"
#include "shapestruct/geometry/local_shape_features.hpp"
#include "shapestruct/geometry/surface_sampling.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "support/data_path.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

void check_mesh(const triangle_mesh<double>& m) {
  // Closest points against brute force for queries around the bounding box.
  const closest_point_query<double> cpq(m);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  std::mt19937_64 rng(1);
  matrix_x3<double> Q(60, 3);
  for (index_t i = 0; i < Q.rows(); ++i)
    for (int d = 0; d < 3; ++d)
      Q(i, d) = lo[d] + (hi[d] - lo[d]) * (1.4 * (double(rng() >> 11) * 0x1.0p-53) - 0.2);
  const auto got = cpq.query_batch(Q, 2);
  for (index_t i = 0; i < Q.rows(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (index_t f = 0; f < m.F.rows(); ++f)
      best = std::min(best, closest_point_on_triangle<double>(Q.row(i).transpose(), m.V.row(m.F(f, 0)).transpose(),
                                                             m.V.row(m.F(f, 1)).transpose(),
                                                             m.V.row(m.F(f, 2)).transpose())
                                .sq_distance);
    CHECK(got.sq_distances[i] == best);
  }
  CHECK(got.bary.allFinite());

  // Sampling: exact counts, finite rows; the legacy model gives the same faces.
  const auto s = sample_surface_even(m, 3000, {.seed = 2});
  REQUIRE(s.size() == 3000);
  CHECK(s.points.allFinite());
  CHECK(s.normals.allFinite());
  const auto legacy = test::to_legacy(m);
  const auto r1 = sample_surface_random(m, 500, {.seed = 3});
  const auto r2 = sample_surface_random(legacy, 500, {.seed = 3});
  // Float coordinates shift the area CDF slightly, so only nearly all samples land on the same face.
  CHECK((r1.faces.array() == r2.faces.array()).count() > 490);

  // Features with the dissertation's defaults are finite and in [0, 1].
  const auto f = local_shape_features<double>(s.points);
  CHECK(f.features.allFinite());
  CHECK(f.features.minCoeff() >= 0);
  CHECK(f.features.maxCoeff() <= 1);
  CHECK(f.degenerate == 0);
}

}  // namespace

TEST_CASE("surface queries on a SCAPE scan") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "SCAPE/Meshes");
  check_mesh(read_mesh(dir / "mesh000.off").mesh);
}

TEST_CASE("surface queries on a COSEG chair (many components)") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "coseg_subset/res/chairs/shapes");
  check_mesh(read_mesh(dir / "14.off").mesh);
}
