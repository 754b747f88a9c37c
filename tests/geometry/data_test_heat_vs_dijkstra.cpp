// SPDX-License-Identifier: MIT
// Heat-method vs Dijkstra distances on real scanned meshes (SCAPE): agreement in the mean, no NaN on slivers.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/heat_geodesics.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "support/data_path.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {
/// Mean of |heat - dijkstra| / dijkstra over all (source, target) pairs with the Dijkstra distance above
/// 5 mean edge lengths (the heat method smooths over ~sqrt(t) = h near a source, where relative differences
/// mean nothing).
template <class S>
double mean_relative_difference(const matrix_x<S>& H, const matrix_x<S>& D, double cutoff, long& pairs,
                                double& signed_mean) {
  double sum = 0;
  signed_mean = 0;
  pairs = 0;
  for (index_t k = 0; k < D.cols(); ++k)
    for (index_t v = 0; v < D.rows(); ++v) {
      const double d = double(D(v, k));
      if (!(d > cutoff) || !std::isfinite(d)) continue;
      sum += std::abs(double(H(v, k)) - d) / d;
      signed_mean += (double(H(v, k)) - d) / d;
      ++pairs;
    }
  signed_mean /= double(pairs);
  return sum / double(pairs);
}
}  // namespace

TEST_CASE("heat method within 10% of Dijkstra in the mean on SCAPE meshes") {
  SHAPESTRUCT_REQUIRE_DATA(scape, "SCAPE");
  std::mt19937_64 rng(2013);
  double overall = 0;
  int meshes = 0;
  for (const char* name : {"mesh000.off", "mesh010.off", "mesh025.off", "mesh050.off", "mesh070.off"}) {
    const auto path = scape / "Meshes" / name;
    if (!std::filesystem::exists(path)) continue;
    const auto m = read_mesh(path).mesh;
    const heat_geodesic_solver<double> heat(m.V, m.F);
    REQUIRE(heat.info() == status::ok);
    const dijkstra_geodesics<double> dij(m.V, m.F);
    std::uniform_int_distribution<index_t> pick(0, m.V.rows() - 1);
    std::vector<index_t> src(32);
    for (auto& s : src) s = pick(rng);
    const auto H = heat.distance_table(src, 0);
    REQUIRE(H.info == status::ok);
    CHECK(H.distances.allFinite());  // SCAPE has slivers: still no NaN/Inf
    const auto D = dij.distance_table(src, 0);
    long pairs = 0;
    double signed_mean = 0;
    const double rel = mean_relative_difference(H.distances, D, 5 * heat.mean_edge(), pairs, signed_mean);
    MESSAGE(std::string(name) << ": mean |heat - Dijkstra| / Dijkstra = " << rel << " (signed " << signed_mean
                              << ") over " << pairs << " pairs");
    CHECK(rel < 0.10);
    CHECK(signed_mean < 0);  // Dijkstra's edge paths zig-zag: it overestimates, so heat is shorter on average
    overall += rel;
    ++meshes;
  }
  REQUIRE(meshes > 0);
  MESSAGE("SCAPE mean relative difference over " << meshes << " meshes: " << overall / meshes);
}

TEST_CASE("SCAPE mesh through the legacy model: float heat solver agrees with double") {
  SHAPESTRUCT_REQUIRE_DATA(scape, "SCAPE");
  const auto path = scape / "Meshes" / "mesh000.off";
  REQUIRE(std::filesystem::exists(path));
  const auto m = read_mesh(path).mesh;
  const heat_geodesic_solver<float> heatf(test::to_legacy(m));
  const heat_geodesic_solver<double> heat(m.V, m.F);
  REQUIRE(heatf.info() == status::ok);
  const std::vector<index_t> src = {0, 6000};
  const Eigen::MatrixXd a = heatf.distance_table(src, 2).distances.cast<double>();  // evaluated: no dangling
  const Eigen::MatrixXd b = heat.distance_table(src, 2).distances;
  CHECK((a - b).cwiseAbs().maxCoeff() < 1e-3 * b.maxCoeff());
}
