// SPDX-License-Identifier: MIT
// AGD feature points on SCAPE: a handful per pose, at the extremities, and consistent across poses (the
// SCAPE meshes share connectivity, so vertex i is the same body point in every pose).
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/geometry/average_geodesic_distance.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "support/data_path.hpp"

using namespace shapestruct;

TEST_CASE("AGD maxima on SCAPE poses: 5 to 10 feature points, intrinsic (the same body points in every pose)") {
  SHAPESTRUCT_REQUIRE_DATA(scape, "SCAPE");
  const char* names[] = {"mesh000.off", "mesh010.off", "mesh050.off"};
  std::vector<triangle_mesh<double>> meshes;
  std::vector<std::vector<index_t>> maxima;
  for (const char* name : names) {
    const auto path = scape / "Meshes" / name;
    if (!std::filesystem::exists(path)) continue;
    meshes.push_back(read_mesh(path).mesh);
    const auto& m = meshes.back();
    const auto agd = average_geodesic_distance(m, {.threads = 0});
    maxima.push_back(agd_local_maxima(m, agd));
    MESSAGE(std::string(name) << ": " << maxima.back().size() << " AGD maxima");
    // dissertation ch. 3: tips of extremities and top of head, usually <= 10
    CHECK(maxima.back().size() >= 5);
    CHECK(maxima.back().size() <= 10);
  }
  REQUIRE(meshes.size() >= 2);
  // Every maximum of pose a has a maximum of pose b nearby (measured on b) whenever b has at least as many:
  // a pose may split one extremity into two maxima (toe and heel of a flexed foot in mesh010), so only the
  // sparser set is required to be found in the denser one.
  for (std::size_t a = 0; a < meshes.size(); ++a)
    for (std::size_t b = 0; b < meshes.size(); ++b) {
      if (a == b || maxima[a].size() > maxima[b].size()) continue;
      const dijkstra_geodesics<double> geo(meshes[b].V, meshes[b].F);
      const auto near_b = geo.distances_from(maxima[b]);
      const double tol = 0.1 * std::sqrt(total_area(meshes[b]));
      for (std::size_t k = 0; k < maxima[a].size(); ++k) {
        INFO("pose " << a << " maximum " << maxima[a][k] << " vs pose " << b);
        CHECK(near_b[maxima[a][k]] < tol);
      }
    }
}
