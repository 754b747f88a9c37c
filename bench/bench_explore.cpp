// SPDX-License-Identifier: MIT
// Micro-benchmarks of the explorer's queries (ch. 4.5) on collections of 111 and 1,000 shapes, one thread:
//   BM_explore_region_query/N   sort the collection by one region of 12 samples (D_R of every shape + ranking)
//   BM_explore_resort/N         sort again by two facets whose distances are cached (what a page does after a
//                               facet is added or removed: only the new region costs a query)
//   BM_explore_details/N        alignment, highlight and orbit centre for one results page (24 shapes)
//   BM_explore_variance/N       the variance of one shape (computed when a shape is first shown)
//   BM_explore_canonical/N      the canonical view of the whole collection (computed once at start)
// The collection: K = 128 samples and 1,024 surface points per shape, a 64-dimensional embedding in which
// corresponding samples lie close together (a shared code per sample plus per-shape noise), tau as the pipeline
// computes it. Its cost structure is that of a real collection; the values are not.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>
#include <vector>

#include "shapestruct/explore/collection_explorer.hpp"

using namespace shapestruct;

namespace {

constexpr index_t K = 128, surface = 1024, dims = 64;

std::unique_ptr<collection_explorer> make_collection(index_t N) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Matrix<double, Eigen::Dynamic, 3> base(K, 3);
  for (index_t i = 0; i < K; ++i) base.row(i) << g(rng), g(rng), g(rng);
  Eigen::MatrixXf code(K, dims);
  for (index_t i = 0; i < K; ++i)
    for (index_t d = 0; d < dims; ++d) code(i, d) = float(g(rng));
  diffusion_embedding e;
  e.coordinates = Eigen::MatrixXf(N * K, dims);
  e.eigenvalues = Eigen::VectorXd::Ones(dims);
  e.trivial_eigenvalue = 1;
  std::vector<shape_record> records;
  for (index_t k = 0; k <= N; ++k) e.offsets.push_back(k * K);
  for (index_t k = 0; k < N; ++k) {
    for (index_t i = 0; i < K; ++i)
      for (index_t d = 0; d < dims; ++d) e.coordinates(k * K + i, d) = code(i, d) + 0.3f * float(g(rng));
    shape_record r;
    r.name = "shape" + std::to_string(k);
    r.samples = base;
    for (index_t i = 0; i < K; ++i) r.samples.row(i) += 0.1 * Eigen::RowVector3d(g(rng), g(rng), g(rng));
    r.surface_points = Eigen::Matrix<double, Eigen::Dynamic, 3>(surface, 3);
    for (index_t s = 0; s < surface; ++s)
      r.surface_points.row(s) = r.samples.row(s % K) + 0.05 * Eigen::RowVector3d(g(rng), g(rng), g(rng));
    r.vertex_count = K;
    records.push_back(std::move(r));
  }
  collection_explorer_options options;
  options.query.threads = 1;
  options.variance.threads = 1;
  return std::make_unique<collection_explorer>(make_fuzzy_correspondence(std::move(e)), std::move(records), options);
}

const collection_explorer& collection(index_t N) {
  static std::map<index_t, std::unique_ptr<collection_explorer>> made;
  auto& c = made[N];
  if (!c) c = make_collection(N);
  return *c;
}

region region_of(index_t shape, index_t first) {
  region r{shape, {}};
  for (index_t i = 0; i < 12; ++i) r.samples.push_back(first + i);
  return r;
}

void BM_explore_region_query(benchmark::State& state) {
  const auto& x = collection(state.range(0));
  const region_query_options one_thread{.threads = 1};
  const region r = region_of(3, 20);
  for (auto _ : state) {
    // a fresh region_query each time: the explorer's cache would otherwise answer
    const std::vector<std::vector<double>> d{region_query(x.fuzzy(), x.records(), r, one_thread).distances()};
    const std::vector<index_t> examples{r.shape};
    benchmark::DoNotOptimize(rank_by_facets(d, examples).order.data());
  }
}
BENCHMARK(BM_explore_region_query)->Arg(111)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_explore_resort(benchmark::State& state) {
  const auto& x = collection(state.range(0));
  const std::vector<region> facets{region_of(3, 20), region_of(5, 60)};
  (void)x.sort(facets);  // both regions now cached
  for (auto _ : state) benchmark::DoNotOptimize(x.sort(facets).order.data());
}
BENCHMARK(BM_explore_resort)->Arg(111)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_explore_details(benchmark::State& state) {
  const auto& x = collection(state.range(0));
  const std::vector<region> facets{region_of(3, 20)};
  std::vector<index_t> page;
  for (index_t k = 0; k < 24; ++k) page.push_back(k * (state.range(0) / 24));
  for (auto _ : state) benchmark::DoNotOptimize(x.details(facets, page).data());
}
BENCHMARK(BM_explore_details)->Arg(111)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_explore_variance(benchmark::State& state) {
  const auto& x = collection(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(shape_variance(x.fuzzy().embedding(), 7, {.threads = 1}).data());
}
BENCHMARK(BM_explore_variance)->Arg(111)->Arg(1000)->Unit(benchmark::kMillisecond);

void BM_explore_canonical(benchmark::State& state) {
  const auto& x = collection(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(canonical_alignment(x.fuzzy(), x.records(), 0, 1).data());
}
BENCHMARK(BM_explore_canonical)->Arg(111)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
