// SPDX-License-Identifier: MIT
// Micro-benchmarks of the collection stage: the global shape descriptor of one shape, the initial alignment graph.
//   BM_collection_sh_descriptor/32 is the target figure: 1,024 torus surface points, default options, one thread.
//   BM_collection_initial_graph/1000: G_0 of 1,000 shapes from their descriptors (distances, Kruskal, edge ranks).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "shapestruct/collection/alignment_graph.hpp"
#include "shapestruct/collection/spherical_harmonic_descriptor.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/surface_sampling.hpp"

using namespace shapestruct;

namespace {

/// 1,024 evenly spread points on a torus: the size of shape_record::surface_points, and a shape with a hole, so
/// every stage (distance transform, sphere sampling, harmonics) does its full work.
const Eigen::Matrix<double, Eigen::Dynamic, 3>& torus_points() {
  static const Eigen::Matrix<double, Eigen::Dynamic, 3> points =
      sample_surface_even(make_torus<double>(1.0, 0.3, 48, 24), 1024, {.seed = 1}).points;
  return points;
}

/// Argument: the grid side (32 = default; 64 = Funkhouser et al.'s resolution, with 32 spheres).
void BM_collection_sh_descriptor(benchmark::State& state) {
  const int grid = static_cast<int>(state.range(0));
  const spherical_harmonic_descriptor describe({.grid = grid, .radii = grid / 2});
  const auto& points = torus_points();
  for (auto _ : state) benchmark::DoNotOptimize(describe(points).data());
}
BENCHMARK(BM_collection_sh_descriptor)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);

/// Argument: the number of shapes N. Descriptors are seeded Gaussian vectors of length 256, the size of the
/// default spherical_harmonic_descriptor (16 radii x 16 bands); M = 5, 3M candidates per shape.
void BM_collection_initial_graph(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::mt19937_64 rng(1);
  std::normal_distribution<double> gauss;
  std::vector<Eigen::VectorXd> descriptors(n, Eigen::VectorXd(256));
  for (auto& d : descriptors)
    for (auto& x : d) x = gauss(rng);
  for (auto _ : state) benchmark::DoNotOptimize(initial_alignment_graph(descriptors).edges.data());
}
BENCHMARK(BM_collection_initial_graph)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
