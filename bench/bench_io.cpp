// SPDX-License-Identifier: MIT
// Mesh file reading and writing speed. Target (docs/BENCHMARKS): a 50K-vertex / 100K-face ASCII OFF in < 50 ms.
// Inputs are tori from make_torus written once to a temporary folder (never benchmark data).
#include <filesystem>
#include <map>
#include <string>

#include <benchmark/benchmark.h>

#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/write_mesh.hpp"

namespace {

using namespace shapestruct;

/// Torus with `vertices` vertices (rings = 2 * sides) and twice as many faces.
triangle_mesh<double> torus_with(int vertices) {
  const int sides = std::max(3, static_cast<int>(std::sqrt(vertices / 2.0)));
  return make_torus<double>(1.0, 0.3, vertices / sides, sides);
}

/// The folder holding the generated files; removed at exit.
struct bench_folder {
  std::filesystem::path path = std::filesystem::temp_directory_path() / "shapestruct-bench-io";
  bench_folder() { std::filesystem::create_directories(path); }
  ~bench_folder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};
bench_folder& folder() {
  static bench_folder f;
  return f;
}

/// Writes (once) and returns the file for this size and format.
std::filesystem::path input(int vertices, const std::string& name, const mesh_write_options& opt) {
  const auto p = folder().path / (std::to_string(vertices) + "-" + name);
  if (!std::filesystem::exists(p)) write_mesh(p, torus_with(vertices), opt);
  return p;
}

template <class Reader>
void run_read(benchmark::State& state, const std::string& name, const mesh_write_options& opt, Reader read) {
  const auto p = input(static_cast<int>(state.range(0)), name, opt);
  index_t faces = 0;
  for (auto _ : state) {
    auto m = read(p);
    faces = m.mesh.num_faces();
    benchmark::DoNotOptimize(m.mesh.V.data());
  }
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["MB/s"] = benchmark::Counter(static_cast<double>(std::filesystem::file_size(p)) * state.iterations() / 1e6,
                                              benchmark::Counter::kIsRate);
}

void BM_io_read_off(benchmark::State& s) { run_read(s, "a.off", {}, [](const auto& p) { return read_off(p); }); }
void BM_io_read_obj(benchmark::State& s) { run_read(s, "a.obj", {}, [](const auto& p) { return read_obj(p); }); }
void BM_io_read_ply_ascii(benchmark::State& s) { run_read(s, "a.ply", {}, [](const auto& p) { return read_ply(p); }); }
void BM_io_read_ply_binary(benchmark::State& s) {
  run_read(s, "b.ply", {.binary = true}, [](const auto& p) { return read_ply(p); });
}
void BM_io_read_stl_binary(benchmark::State& s) {
  run_read(s, "b.stl", {.binary = true}, [](const auto& p) { return read_stl(p); });
}
void BM_io_read_stl_ascii(benchmark::State& s) { run_read(s, "a.stl", {}, [](const auto& p) { return read_stl(p); }); }

void BM_io_write_off(benchmark::State& state) {
  const auto mesh = torus_with(static_cast<int>(state.range(0)));
  const auto p = folder().path / "written.off";
  for (auto _ : state) write_off(p, mesh);
}
void BM_io_write_ply_binary(benchmark::State& state) {
  const auto mesh = torus_with(static_cast<int>(state.range(0)));
  const auto p = folder().path / "written.ply";
  for (auto _ : state) write_ply(p, mesh, {.binary = true});
}

}  // namespace

BENCHMARK(BM_io_read_off)->Arg(5000)->Arg(50000)->Arg(200000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_io_read_obj)->Arg(5000)->Arg(50000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_io_read_ply_ascii)->Arg(5000)->Arg(50000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_io_read_ply_binary)->Arg(5000)->Arg(50000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_io_read_stl_binary)->Arg(5000)->Arg(50000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_io_read_stl_ascii)->Arg(50000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_io_write_off)->Arg(50000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_io_write_ply_binary)->Arg(50000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
