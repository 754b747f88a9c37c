// SPDX-License-Identifier: MIT
// Micro-benchmarks of the collection stage: the global shape descriptor of one shape.
//   BM_collection_sh_descriptor/32 is the target figure: 1,024 torus surface points, default options, one thread.
#include <benchmark/benchmark.h>

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

}  // namespace

BENCHMARK_MAIN();
