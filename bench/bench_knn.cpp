// SPDX-License-Identifier: MIT
// k-nearest-neighbour micro-benchmarks: knn_index (nanoflann kd-tree) against brute force, k = 8, on uniform
// random 3-D points (10K, 100K, 1M). Counters report queries per second ("items_per_second").
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <limits>
#include <random>

#include "shapestruct/knn/knn_index.hpp"

using namespace shapestruct;

namespace {

constexpr shapestruct::index_t k_neighbors = 8;

matrix_x3<double> uniform_points(index_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  matrix_x3<double> P(n, 3);
  for (index_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) P(i, d) = double(rng() >> 11) * 0x1.0p-53;
  return P;
}

void BM_knn_build(benchmark::State& state) {
  const auto P = uniform_points(state.range(0), 1);
  for (auto _ : state) {
    knn_index<double> index(P);
    benchmark::DoNotOptimize(index.size());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));  // points indexed per second
}

void BM_knn_nanoflann(benchmark::State& state) {
  const auto P = uniform_points(state.range(0), 1);
  const auto Q = uniform_points(4096, 2);
  const knn_index<double> index(P);
  index_t q = 0;
  for (auto _ : state) {
    auto r = index.knn(Q.row(q), k_neighbors);
    benchmark::DoNotOptimize(r.indices.data());
    q = (q + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());
}

// The same queries without the Morton reordering of the stored points (knn_index_options::spatial_sort).
void BM_knn_nanoflann_unsorted(benchmark::State& state) {
  const auto P = uniform_points(state.range(0), 1);
  const auto Q = uniform_points(4096, 2);
  const knn_index<double> index(P, {.spatial_sort = false});
  index_t q = 0;
  for (auto _ : state) {
    auto r = index.knn(Q.row(q), k_neighbors);
    benchmark::DoNotOptimize(r.indices.data());
    q = (q + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());
}

// The batch API on 2 threads: what the library's own callers (features, fuzzy correspondences) use.
void BM_knn_nanoflann_batch_2threads(benchmark::State& state) {
  const auto P = uniform_points(state.range(0), 1);
  const auto Q = uniform_points(4096, 2);
  const knn_index<double> index(P);
  for (auto _ : state) {
    auto r = index.knn_batch(Q, k_neighbors, 2);
    benchmark::DoNotOptimize(r.indices.data());
  }
  state.SetItemsProcessed(state.iterations() * Q.rows());
}

// Brute force: one pass over all points keeping the 8 best in a sorted array.
void BM_knn_brute_force(benchmark::State& state) {
  const auto P = uniform_points(state.range(0), 1);
  const auto Q = uniform_points(4096, 2);
  index_t q = 0;
  for (auto _ : state) {
    std::array<double, k_neighbors> best;
    std::array<index_t, k_neighbors> ids{};
    best.fill(std::numeric_limits<double>::infinity());
    const double x = Q(q, 0), y = Q(q, 1), z = Q(q, 2);
    for (index_t i = 0; i < P.rows(); ++i) {
      const double dx = P(i, 0) - x, dy = P(i, 1) - y, dz = P(i, 2) - z;
      const double d = dx * dx + dy * dy + dz * dz;
      if (d >= best[k_neighbors - 1]) continue;
      std::size_t j = k_neighbors - 1;
      while (j > 0 && best[j - 1] > d) {
        best[j] = best[j - 1];
        ids[j] = ids[j - 1];
        --j;
      }
      best[j] = d;
      ids[j] = i;
    }
    benchmark::DoNotOptimize(ids.data());
    q = (q + 1) & 4095;
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

BENCHMARK(BM_knn_build)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_knn_nanoflann)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_knn_nanoflann_unsorted)->Arg(10000)->Arg(100000)->Arg(1000000);
BENCHMARK(BM_knn_nanoflann_batch_2threads)->Arg(10000)->Arg(100000)->Arg(1000000)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_knn_brute_force)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
