// SPDX-License-Identifier: MIT
// Micro-benchmarks of the Laplace-Beltrami basis ZoomOut refines with: Lanczos on every vertex against the
// Galerkin solver, on a procedural shape (no data needed). Arg: subdivision level (5: 10,242 vertices).
#include <benchmark/benchmark.h>

#include "blended/blended_fixtures.hpp"
#include "shapestruct/spectral/laplace_beltrami_basis.hpp"

using namespace shapestruct;

namespace {
void run_basis(benchmark::State& state, laplace_beltrami_solver solver) {
  const auto m = test::armed_sphere(static_cast<int>(state.range(0)));
  laplace_beltrami_options options;
  options.tolerance = 1e-5;  // as zoomout_refiner asks
  options.solver = solver;
  for (auto _ : state) {
    const auto basis = compute_laplace_beltrami_basis<double>(m.V, m.F, 100, options);
    benchmark::DoNotOptimize(basis.vectors.data());
  }
  state.counters["vertices"] = static_cast<double>(m.V.rows());
}
}  // namespace

static void BM_laplace_beltrami_basis_lanczos(benchmark::State& state) { run_basis(state, laplace_beltrami_solver::lanczos); }
BENCHMARK(BM_laplace_beltrami_basis_lanczos)->Arg(5)->Unit(benchmark::kMillisecond);

static void BM_laplace_beltrami_basis_galerkin(benchmark::State& state) { run_basis(state, laplace_beltrami_solver::galerkin); }
BENCHMARK(BM_laplace_beltrami_basis_galerkin)->Arg(5)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
