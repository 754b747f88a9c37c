// SPDX-License-Identifier: MIT
// Micro-benchmarks of the part-based template stage: one fit, one alpha-expansion labeling, shape sampling.
#include <benchmark/benchmark.h>

#include <random>

#include "shapestruct/generate/assembly_generator.hpp"
#include "shapestruct/templates/make_shape_samples.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/template_fitter.hpp"

using namespace shapestruct;

namespace {
part_template chair() {
  part_template t;
  auto box = [](index_t l, Eigen::Vector3d c, Eigen::Vector3d s) {
    part_box b;
    b.label = l;
    b.center = c;
    b.size = s;
    return b;
  };
  t.parts = {box(0, {0, -0.05, 0.02}, {0.40, 0.04, 0.38}), box(1, {0, 0.2, -0.19}, {0.38, 0.40, 0.04}),
             box(2, {-0.17, -0.27, 0.16}, {0.03, 0.34, 0.03}), box(2, {0.17, -0.27, 0.16}, {0.03, 0.34, 0.03}),
             box(2, {-0.17, -0.27, -0.16}, {0.03, 0.34, 0.03}), box(2, {0.17, -0.27, -0.16}, {0.03, 0.34, 0.03})};
  return t;
}
}  // namespace

static void BM_templates_fit(benchmark::State& state) {
  const auto a = assembly_generator<double>(assembly_kind::chair, 1).generate(0);
  const auto s = make_shape_samples(a.mesh, {.points = state.range(0)});
  const auto t = chair();
  for (auto _ : state) benchmark::DoNotOptimize(fit_template(t, s).energy);
}
BENCHMARK(BM_templates_fit)->Arg(1000)->Arg(1500)->Unit(benchmark::kMillisecond);

static void BM_templates_make_samples(benchmark::State& state) {
  const auto a = assembly_generator<double>(assembly_kind::chair, 1).generate(0);
  for (auto _ : state)
    benchmark::DoNotOptimize(make_shape_samples(a.mesh, {.points = state.range(0)}).size());
}
BENCHMARK(BM_templates_make_samples)->Arg(1500)->Unit(benchmark::kMillisecond);

static void BM_templates_alpha_expansion(benchmark::State& state) {
  const auto n = state.range(0);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::MatrixXd U(n, 7);
  for (index_t i = 0; i < n; ++i)
    for (index_t l = 0; l < 7; ++l) U(i, l) = u(rng);
  std::vector<potts_edge> E;
  for (index_t i = 0; i + 1 < n; ++i) E.push_back({i, i + 1, 0.3});
  for (index_t i = 0; i + 40 < n; ++i) E.push_back({i, i + 40, 0.3});
  for (auto _ : state) benchmark::DoNotOptimize(alpha_expansion(U, E, {}, {.max_sweeps = 1}).energy);
}
BENCHMARK(BM_templates_alpha_expansion)->Arg(1500)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
