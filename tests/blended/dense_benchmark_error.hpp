// SPDX-License-Identifier: MIT
// The BIM benchmark's protocols for the data-driven tests: dense, for two meshes that share their vertex numbering
// (SCAPE, TOSCA within a class), and at SHREC'07's feature points.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/io/bim_benchmark_files.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "shapestruct/maps/surface_map.hpp"

namespace shapestruct::test {

/// Errors of `map` (input numbering) at 1,024 geodesic FPS samples of the source, against the truth "input vertex
/// v goes to input vertex v", on the benchmark's scale d / sqrt(area of the target) (benchmark_geodesic_errors, as
/// the runner scores). Requires every sample mapped.
inline geodesic_error_summary dense_identity_errors(const blended_shape<double>& source,
                                                    const blended_shape<double>& target, const surface_map<double>& map) {
  const auto fps = geodesic_farthest_point_sampling(source.geodesics(), 1024, 0);
  std::vector<index_t> pred, truth;
  for (index_t v : fps.indices) {
    const index_t input = source.original_vertex(v);
    if (input == no_index) continue;  // a vertex added by a repair has no truth
    const index_t image = map.target_vertex(input);
    REQUIRE(image != no_index);
    pred.push_back(target.internal_vertex(image));
    truth.push_back(target.internal_vertex(input));
  }
  const auto e = benchmark_geodesic_errors(target.mesh().V, target.mesh().F, target.geodesics(),
                                           std::span<const index_t>(pred), std::span<const index_t>(truth));
  return summarize_errors(std::span<const double>(e));
}

/// Errors of `map` (input numbering) at SHREC'07's feature points: the k-th point of `source_vts` should go to the
/// k-th of `target_vts` (the class's .vts files), on the benchmark's scale d / sqrt(area of the target).
inline geodesic_error_summary feature_point_errors(const blended_shape<double>& target, const surface_map<double>& map,
                                                   const std::filesystem::path& source_vts,
                                                   const std::filesystem::path& target_vts) {
  const auto fa = read_bim_feature_vertices(source_vts.string());
  const auto fb = read_bim_feature_vertices(target_vts.string());
  REQUIRE(fa.size() == fb.size());
  std::vector<index_t> pred, truth;
  for (std::size_t k = 0; k < fa.size(); ++k) {
    pred.push_back(target.internal_vertex(map.target_vertex(fa[k])));
    truth.push_back(target.internal_vertex(fb[k]));
  }
  const auto e = benchmark_geodesic_errors(target.mesh().V, target.mesh().F, target.geodesics(),
                                           std::span<const index_t>(pred), std::span<const index_t>(truth));
  return summarize_errors(std::span<const double>(e));
}

/// The original program's stored mean error for a pair (`Results/<results>/BenchResult_BlendedMap_<pair>.txt`
/// beside the data set `set`), or `fallback` (the value read when the test was written) if the file is absent.
inline double stored_blended_map_mean(const std::filesystem::path& set, const std::string& results, const std::string& pair,
                                      double fallback) {
  const auto file = set.parent_path() / "Results" / results / ("BenchResult_BlendedMap_" + pair + ".txt");
  return std::filesystem::exists(file) ? read_bim_result(file.string()).at("Stats").average : fallback;
}

}  // namespace shapestruct::test
