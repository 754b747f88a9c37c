// SPDX-License-Identifier: MIT
// Micro-benchmarks of the fuzzy stage: one extrinsic pairwise alignment of two generated chairs (K = 128 samples,
// M = 1,024 surface points, default options), upright (4 starts) and without an up axis (24 starts), one thread.
//   BM_fuzzy_align_extrinsic/1: the upright alignment every extrinsic edge costs (4.3.3).
//   BM_fuzzy_align_extrinsic/-1: up_axis = no_up_axis, for collections that share no up direction.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>
#include <vector>

#include "shapestruct/collection/make_shape_record.hpp"
#include "shapestruct/collection/spherical_harmonic_descriptor.hpp"
#include "shapestruct/fuzzy/extrinsic_alignment.hpp"
#include "shapestruct/generate/assembly_generator.hpp"

using namespace shapestruct;

namespace {

/// The records of the first two chairs of seed 1, as `shapestruct fuzzy` makes them (Euclidean samples on soups).
const std::vector<shape_record>& chair_records() {
  static const std::vector<shape_record> records = [] {
    const assembly_generator<double> chairs(assembly_kind::chair, 1);
    const spherical_harmonic_descriptor describe;
    std::vector<shape_record> out;
    for (std::uint64_t i = 0; i < 2; ++i)
      out.push_back(make_shape_record(chairs.generate(i).mesh, "chair" + std::to_string(i), describe));
    return out;
  }();
  return records;
}

/// Argument: the up axis (1 = +y, the default; -1 = no_up_axis).
void BM_fuzzy_align_extrinsic(benchmark::State& state) {
  const auto& records = chair_records();
  extrinsic_alignment_options options;
  options.up_axis = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(align_extrinsic(records[0], records[1], options).alternatives.data());
}
BENCHMARK(BM_fuzzy_align_extrinsic)->Arg(1)->Arg(-1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
