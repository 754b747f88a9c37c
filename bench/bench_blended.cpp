// SPDX-License-Identifier: MIT
// Micro-benchmarks of the blended-intrinsic-maps kernels on a procedural shape (no data needed).
#include <complex>
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "blended/blended_fixtures.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/conformal/mid_edge_flattening.hpp"

using namespace shapestruct;

static void BM_blended_flattening(benchmark::State& state) {
  const auto m = test::armed_sphere(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    mid_edge_flattening<double> fl(m.V, m.F);
    benchmark::DoNotOptimize(fl.vertex_coordinates().data());
  }
  state.counters["vertices"] = static_cast<double>(m.V.rows());
}
BENCHMARK(BM_blended_flattening)->Arg(4)->Arg(5)->Unit(benchmark::kMillisecond);

static void BM_blended_locate(benchmark::State& state) {
  const auto m = test::armed_sphere(5);
  const mid_edge_flattening<double> fl(m.V, m.F);
  index_t v = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fl.locate(fl.coordinate(v)).face);
    v = (v + 7919) % m.V.rows();
  }
}
BENCHMARK(BM_blended_locate);

// Blending's access pattern: the images of neighbouring vertices under one map, located one after the other,
// through the tree (locate) or by a walk from the previous answer (locate with a hint). The same answers.
static std::vector<std::complex<double>> moved_vertex_images(const mid_edge_flattening<double>& fl, index_t n) {
  std::vector<std::complex<double>> q(static_cast<std::size_t>(n));
  const std::complex<double> motion = std::polar(1.02, 0.01);
  for (index_t v = 0; v < n; ++v) q[static_cast<std::size_t>(v)] = motion * fl.coordinate(v);
  return q;
}

static void BM_blended_locate_sequence_tree(benchmark::State& state) {
  const auto m = test::armed_sphere(5);
  const mid_edge_flattening<double> fl(m.V, m.F);
  const auto queries = moved_vertex_images(fl, m.V.rows());
  for (auto _ : state)
    for (const auto& z : queries) benchmark::DoNotOptimize(fl.locate(z).face);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(queries.size()));
}
BENCHMARK(BM_blended_locate_sequence_tree)->Unit(benchmark::kMillisecond);

static void BM_blended_locate_sequence_walk(benchmark::State& state) {
  const auto m = test::armed_sphere(5);
  const mid_edge_flattening<double> fl(m.V, m.F);
  const auto queries = moved_vertex_images(fl, m.V.rows());
  for (auto _ : state) {
    index_t hint = no_index;
    for (const auto& z : queries) benchmark::DoNotOptimize(fl.locate(z, hint).face);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(queries.size()));
}
BENCHMARK(BM_blended_locate_sequence_walk)->Unit(benchmark::kMillisecond);

static void BM_blended_prepare(benchmark::State& state) {
  const auto m = test::armed_sphere(5);
  blended_matcher_options o;
  o.threads = static_cast<int>(state.range(0));
  const blended_matcher<> matcher(o);
  for (auto _ : state) benchmark::DoNotOptimize(matcher.prepare(m).features().size());
}
BENCHMARK(BM_blended_prepare)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

static void BM_blended_match_prepared(benchmark::State& state) {
  const auto m = test::armed_sphere(5);
  std::vector<index_t> perm;
  const auto moved = test::moved_and_permuted(m, perm);
  blended_matcher_options o;
  o.threads = static_cast<int>(state.range(0));
  const blended_matcher<> matcher(o);
  const auto a = matcher.prepare(m);
  const auto b = matcher.prepare(moved);
  for (auto _ : state) benchmark::DoNotOptimize(matcher.match(a, b).selected);
}
BENCHMARK(BM_blended_match_prepared)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
