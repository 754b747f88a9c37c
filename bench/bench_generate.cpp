// SPDX-License-Identifier: MIT
// Generation speed of the synthetic collections (shapes/s): creatures, chairs, tables, airplanes, and the
// ground-truth map between two creatures.
#include <benchmark/benchmark.h>

#include "shapestruct/generate/assembly_generator.hpp"
#include "shapestruct/generate/catmull_clark_patches.hpp"
#include "shapestruct/generate/creature_generator.hpp"
#include "shapestruct/generate/creature_map.hpp"

using namespace shapestruct;

static void BM_generate_creature(benchmark::State& state) {
  const creature_generator<double> g(1);
  std::uint64_t i = 0;
  std::int64_t faces = 0;
  for (auto _ : state) {
    const auto c = g.generate(i++);
    faces += c.mesh.num_faces();
    benchmark::DoNotOptimize(c.mesh.V.data());
  }
  state.counters["shapes/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["faces/shape"] = static_cast<double>(faces) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_generate_creature)->Unit(benchmark::kMillisecond);

static void BM_generate_creature_range(benchmark::State& state) {
  const creature_generator<double> g(1);
  const auto threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(g.generate_range(0, 32, threads).data());
  state.counters["shapes/s"] = benchmark::Counter(32.0 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_generate_creature_range)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_generate_assembly(benchmark::State& state) {
  const assembly_generator<double> g(static_cast<assembly_kind>(state.range(0)), 1);
  std::uint64_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(g.generate(i++).mesh.V.data());
  state.counters["shapes/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.SetLabel(to_string(static_cast<assembly_kind>(state.range(0))));
}
BENCHMARK(BM_generate_assembly)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

static void BM_generate_map_creatures(benchmark::State& state) {
  const creature_generator<double> g(1);
  const auto a = g.generate(0), b = g.generate(1);
  for (auto _ : state) benchmark::DoNotOptimize(map_creatures(a, b).points.data());
  state.counters["source_vertices"] = static_cast<double>(a.mesh.num_vertices());
}
BENCHMARK(BM_generate_map_creatures)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
