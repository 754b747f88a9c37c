// SPDX-License-Identifier: MIT
// Micro-benchmarks of the mesh checks and repairs on tori of 3,200 / 12,500 / 50,000 / 200,000 vertices.
//   BM_core_check_mesh/12500 is the figure quoted in docs/inspect.md (a SCAPE-sized mesh).
#include <benchmark/benchmark.h>

#include <map>

#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/connected_components.hpp"
#include "shapestruct/geometry/mesh_repair.hpp"

using namespace shapestruct;

namespace {

/// Torus with exactly n vertices (rings x sides = n / 100 ... chosen so both are >= 40).
const triangle_mesh<double>& torus(long n) {
  static std::map<long, triangle_mesh<double>> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  const int rings = n == 3200 ? 80 : n == 12500 ? 125 : n == 50000 ? 250 : 500;
  const int sides = static_cast<int>(n / rings);
  return cache.emplace(n, make_torus<double>(1.0, 0.3, rings, sides)).first->second;
}

void sizes(benchmark::internal::Benchmark* b) {
  for (const long n : {3200L, 12500L, 50000L, 200000L}) b->Arg(n);
  b->Unit(benchmark::kMillisecond);
}

void BM_core_check_mesh(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) {
    const auto r = check_mesh(m);
    benchmark::DoNotOptimize(r.num_edges);
  }
  state.SetItemsProcessed(state.iterations() * m.num_faces());
}
BENCHMARK(BM_core_check_mesh)->Apply(sizes);

void BM_geometry_connected_components(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) {
    const auto cc = connected_components(m);
    benchmark::DoNotOptimize(cc.count);
  }
  state.SetItemsProcessed(state.iterations() * m.num_faces());
}
BENCHMARK(BM_geometry_connected_components)->Apply(sizes);

void BM_geometry_merge_duplicate_vertices(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) {
    const auto r = merge_duplicate_vertices(m);
    benchmark::DoNotOptimize(r.removed_vertices);
  }
  state.SetItemsProcessed(state.iterations() * m.num_vertices());
}
BENCHMARK(BM_geometry_merge_duplicate_vertices)->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
