// SPDX-License-Identifier: MIT
// Geometry query micro-benchmarks: closest-point tree build and queries at 12.5K and 50K faces, random and even
// sampling of 10K points, local shape features of 10K points. Meshes are procedural tori (2 * rings * sides
// faces) so the benchmark needs no data set.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>

#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/closest_point_query.hpp"
#include "shapestruct/geometry/local_shape_features.hpp"
#include "shapestruct/geometry/surface_sampling.hpp"

using namespace shapestruct;

namespace {

// 12500 faces = 2 * 125 * 50, 50000 faces = 2 * 250 * 100.
triangle_mesh<double> torus_with_faces(index_t faces) {
  return faces <= 12500 ? make_torus<double>(1.0, 0.3, 125, 50) : make_torus<double>(1.0, 0.3, 250, 100);
}

// Queries near the surface (samples pushed off along the normal by up to 0.05), the typical use: projecting
// points of one shape onto another.
matrix_x3<double> near_surface_queries(const triangle_mesh<double>& m, index_t n) {
  const auto s = sample_surface_random(m, n, {.seed = 5});
  std::mt19937_64 rng(6);
  matrix_x3<double> Q = s.points;
  for (index_t i = 0; i < n; ++i) Q.row(i) += (double(rng() >> 11) * 0x1.0p-53 - 0.5) * 0.1 * s.normals.row(i);
  return Q;
}

void BM_geometry_closest_point_build(benchmark::State& state) {
  const auto m = torus_with_faces(state.range(0));
  for (auto _ : state) {
    closest_point_query<double> cpq(m.V, m.F);
    benchmark::DoNotOptimize(cpq.num_faces());
  }
  state.SetItemsProcessed(state.iterations() * m.F.rows());  // faces per second
}

void BM_geometry_closest_point_query(benchmark::State& state) {
  const auto m = torus_with_faces(state.range(0));
  const closest_point_query<double> cpq(m.V, m.F);
  const auto Q = near_surface_queries(m, 4096);
  index_t q = 0;
  for (auto _ : state) {
    auto r = cpq.query(Q.row(q));
    benchmark::DoNotOptimize(r.sq_distance);
    q = (q + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());  // queries per second
}

void BM_geometry_closest_point_batch_2threads(benchmark::State& state) {
  const auto m = torus_with_faces(state.range(0));
  const closest_point_query<double> cpq(m.V, m.F);
  const auto Q = near_surface_queries(m, 4096);
  for (auto _ : state) {
    auto r = cpq.query_batch(Q, 2);
    benchmark::DoNotOptimize(r.faces.data());
  }
  state.SetItemsProcessed(state.iterations() * Q.rows());
}

void BM_geometry_sample_random(benchmark::State& state) {
  const auto m = torus_with_faces(50000);
  for (auto _ : state) {
    auto s = sample_surface_random(m, state.range(0), {.seed = 1});
    benchmark::DoNotOptimize(s.points.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_geometry_sample_even(benchmark::State& state) {
  const auto m = torus_with_faces(50000);
  for (auto _ : state) {
    auto s = sample_surface_even(m, state.range(0), {.seed = 1, .threads = 2});
    benchmark::DoNotOptimize(s.points.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// Dissertation defaults (radius 0.15 R); range(1) = threads.
void BM_geometry_local_shape_features(benchmark::State& state) {
  const auto m = torus_with_faces(50000);
  const auto s = sample_surface_even(m, state.range(0), {.seed = 1});
  for (auto _ : state) {
    auto f = local_shape_features<double>(s.points, {.threads = static_cast<int>(state.range(1))});
    benchmark::DoNotOptimize(f.features.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

// k = 16 nearest neighbours instead of the radius: the cheaper option for dense samplings.
void BM_geometry_local_shape_features_k16(benchmark::State& state) {
  const auto m = torus_with_faces(50000);
  const auto s = sample_surface_even(m, state.range(0), {.seed = 1});
  for (auto _ : state) {
    auto f = local_shape_features<double>(s.points, {.k = 16, .threads = 2});
    benchmark::DoNotOptimize(f.features.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

}  // namespace

BENCHMARK(BM_geometry_closest_point_build)->Arg(12500)->Arg(50000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_geometry_closest_point_query)->Arg(12500)->Arg(50000);
BENCHMARK(BM_geometry_closest_point_batch_2threads)->Arg(12500)->Arg(50000)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_geometry_sample_random)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_geometry_sample_even)->Arg(10000)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_geometry_local_shape_features)->Args({10000, 1})->Args({10000, 2})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_geometry_local_shape_features_k16)->Arg(10000)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
