// SPDX-License-Identifier: MIT
// Micro-benchmarks of the geometry kernels on tori of 3,200 / 12,500 / 50,000 vertices (exact counts), and on
// the SCAPE mesh000 (12,500 vertices) when $SHAPESTRUCT_DATA is set.
//   BM_geometry_dijkstra_table_256/12500/1 is the target figure: 256 sources, 12.5K vertices, one thread.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <numeric>
#include <optional>
#include <vector>

#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/average_geodesic_distance.hpp"
#include "shapestruct/geometry/cotan_laplacian.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/edge_graph.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "shapestruct/geometry/heat_geodesics.hpp"
#include "shapestruct/geometry/mass_matrix.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"

using namespace shapestruct;

namespace {

/// Torus with exactly n vertices for n in {3200, 12500, 50000} (rings x sides = 80x40, 125x100, 250x200).
const triangle_mesh<double>& torus(long n) {
  static std::map<long, triangle_mesh<double>> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  const int rings = n == 3200 ? 80 : n == 12500 ? 125 : 250;
  const int sides = static_cast<int>(n / rings);
  return cache.emplace(n, make_torus<double>(1.0, 0.3, rings, sides)).first->second;
}

/// SCAPE mesh000 (the licence forbids copying it: read from $SHAPESTRUCT_DATA at run time), or nullopt.
const std::optional<triangle_mesh<double>>& scape_mesh() {
  static const std::optional<triangle_mesh<double>> mesh = []() -> std::optional<triangle_mesh<double>> {
    const char* env = std::getenv("SHAPESTRUCT_DATA");
    if (env == nullptr) return std::nullopt;
    const auto path = std::filesystem::path(env) / "SCAPE" / "Meshes" / "mesh000.off";
    if (!std::filesystem::exists(path)) return std::nullopt;
    return read_mesh(path).mesh;
  }();
  return mesh;
}

std::vector<index_t> spread_sources(index_t n, index_t count) {
  std::vector<index_t> s(static_cast<std::size_t>(count));
  for (index_t k = 0; k < count; ++k) s[static_cast<std::size_t>(k)] = (k * 7919) % n;  // prime stride
  return s;
}

void sizes(benchmark::internal::Benchmark* b) {
  for (long n : {3200L, 12500L, 50000L}) b->Arg(n);
  b->Unit(benchmark::kMillisecond);
}

void BM_geometry_face_areas(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(face_areas(m.V, m.F));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_geometry_face_areas)->Apply(sizes)->Complexity();

void BM_geometry_vertex_normals(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(vertex_normals(m.V, m.F));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_geometry_vertex_normals)->Apply(sizes)->Complexity();

void BM_geometry_cotan_laplacian(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(cotan_laplacian(m.V, m.F));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_geometry_cotan_laplacian)->Apply(sizes)->Complexity();

void BM_geometry_mass_matrix_voronoi(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(mass_matrix(m.V, m.F, mass_type::voronoi));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_geometry_mass_matrix_voronoi)->Apply(sizes)->Complexity();

void BM_geometry_edge_graph(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(make_edge_graph(m.V, m.F));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_geometry_edge_graph)->Apply(sizes)->Complexity();

void BM_geometry_dijkstra_single(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  const dijkstra_geodesics<double> geo(m.V, m.F);
  for (auto _ : state) benchmark::DoNotOptimize(geo.distances_from(0));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_geometry_dijkstra_single)->Apply(sizes)->Complexity();

/// The same run through the heap: a graph built without positions never takes the bucket queue.
void BM_geometry_dijkstra_single_heap(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  const dijkstra_geodesics<double> geo(make_edge_graph(m.V, m.F));
  for (auto _ : state) benchmark::DoNotOptimize(geo.distances_from(0));
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_geometry_dijkstra_single_heap)->Apply(sizes)->Complexity();

void BM_geometry_dijkstra_early_exit(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  const dijkstra_geodesics<double> geo(m.V, m.F);
  for (auto _ : state) benchmark::DoNotOptimize(geo.geodesic_distance(0, 5));
}
BENCHMARK(BM_geometry_dijkstra_early_exit)->Apply(sizes);

/// 256 sources; second argument = threads.
void BM_geometry_dijkstra_table_256(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  const dijkstra_geodesics<double> geo(m.V, m.F);
  const auto src = spread_sources(m.V.rows(), 256);
  for (auto _ : state) benchmark::DoNotOptimize(geo.distance_table(src, static_cast<int>(state.range(1))));
}
BENCHMARK(BM_geometry_dijkstra_table_256)
    ->Args({12500, 1})
    ->Args({12500, 2})
    ->Args({50000, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_geometry_dijkstra_table_256_float(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  const matrix_x3<float> Vf = m.V.cast<float>();
  const dijkstra_geodesics<float> geo(Vf, m.F);
  const auto src = spread_sources(m.V.rows(), 256);
  for (auto _ : state) benchmark::DoNotOptimize(geo.distance_table(src, 1));
}
BENCHMARK(BM_geometry_dijkstra_table_256_float)->Arg(12500)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The same on a real scan: SCAPE mesh000 (12,500 vertices), one thread.
void BM_geometry_dijkstra_table_256_scape(benchmark::State& state) {
  const auto& m = scape_mesh();
  if (!m) {
    state.SkipWithError("$SHAPESTRUCT_DATA/SCAPE/Meshes/mesh000.off not found");
    for (auto _ : state) {
    }
    return;
  }
  const dijkstra_geodesics<double> geo(m->V, m->F);
  const auto src = spread_sources(m->V.rows(), 256);
  for (auto _ : state) benchmark::DoNotOptimize(geo.distance_table(src, static_cast<int>(state.range(0))));
}
BENCHMARK(BM_geometry_dijkstra_table_256_scape)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_geometry_heat_factorise(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) {
    heat_geodesic_solver<double> heat(m.V, m.F);
    benchmark::DoNotOptimize(heat.info());
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_geometry_heat_factorise)->Apply(sizes);

void BM_geometry_heat_distances(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  const heat_geodesic_solver<double> heat(m.V, m.F);
  for (auto _ : state) benchmark::DoNotOptimize(heat.distances(0));
}
BENCHMARK(BM_geometry_heat_distances)->Apply(sizes);

void BM_geometry_heat_distances_scape(benchmark::State& state) {
  const auto& m = scape_mesh();
  if (!m) {
    state.SkipWithError("$SHAPESTRUCT_DATA/SCAPE/Meshes/mesh000.off not found");
    for (auto _ : state) {
    }
    return;
  }
  const heat_geodesic_solver<double> heat(m->V, m->F);
  for (auto _ : state) benchmark::DoNotOptimize(heat.distances(0));
}
BENCHMARK(BM_geometry_heat_distances_scape)->Unit(benchmark::kMillisecond);

void BM_geometry_euclidean_fps_64(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(farthest_point_sampling(m.V, 64));
}
BENCHMARK(BM_geometry_euclidean_fps_64)->Apply(sizes);

void BM_geometry_geodesic_fps_64(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  const dijkstra_geodesics<double> geo(m.V, m.F);
  for (auto _ : state) benchmark::DoNotOptimize(geodesic_farthest_point_sampling(geo, 64));
}
BENCHMARK(BM_geometry_geodesic_fps_64)->Apply(sizes);

void BM_geometry_agd_64(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(average_geodesic_distance(m.V, m.F, {.threads = 1}));
}
BENCHMARK(BM_geometry_agd_64)->Apply(sizes);

void BM_geometry_agd_local_maxima(benchmark::State& state) {
  const auto& m = torus(state.range(0));
  const auto agd = average_geodesic_distance(m.V, m.F);
  for (auto _ : state) benchmark::DoNotOptimize(agd_local_maxima(m.V, m.F, agd));
}
BENCHMARK(BM_geometry_agd_local_maxima)->Apply(sizes);

}  // namespace

BENCHMARK_MAIN();
