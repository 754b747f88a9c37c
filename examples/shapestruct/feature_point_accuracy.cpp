// SPDX-License-Identifier: MIT
// evaluate_feature_points: see feature_point_accuracy.hpp.
#include "feature_point_accuracy.hpp"

#include <algorithm>
#include <span>

#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/fuzzy/fuzzy_maps.hpp"
#include "shapestruct/fuzzy/fuzzy_output.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/io/bim_benchmark_files.hpp"
#include "shapestruct/io/read_mesh.hpp"

namespace shapestruct::cli {

namespace fs = std::filesystem;

fs::path feature_point_file(const fs::path& truth_dir, const std::string& name) {
  for (const char* ext : {".vts", ".pid"})
    if (fs::exists(truth_dir / (name + ext))) return truth_dir / (name + ext);
  return {};
}

feature_point_accuracy evaluate_feature_points(const fs::path& fuzzy_dir, const fs::path& truth_dir, int threads,
                                               const std::function<void(std::size_t, std::size_t)>& progress) {
  const fuzzy_output f = read_fuzzy_output(fuzzy_dir);
  feature_point_accuracy out;
  std::vector<index_t> scored;
  std::vector<std::vector<index_t>> features(f.records.size());
  for (index_t k = 0; k < f.shapes(); ++k) {
    const fs::path file = feature_point_file(truth_dir, f.records[std::size_t(k)].name);
    if (file.empty()) {
      out.not_scored.push_back(f.records[std::size_t(k)].name);
      continue;
    }
    features[std::size_t(k)] = read_bim_feature_vertices(file.string());
    scored.push_back(k);
  }
  out.shapes_scored = scored.size();
  std::vector<double> errors;
  for (std::size_t j = 0; j < scored.size(); ++j) {
    const index_t b = scored[j];
    const auto B = read_mesh(f.files[std::size_t(b)]).mesh;
    const dijkstra_geodesics<double> geo(B.V, B.F);
    const auto& fb = features[std::size_t(b)];
    // Every source's predictions for b in one call: the geodesics from b's feature points are computed once,
    // not once per source.
    std::vector<index_t> predicted, truth, sources;
    std::vector<std::size_t> begin;
    for (const index_t a : scored) {
      if (a == b) continue;
      const auto& fa = features[std::size_t(a)];
      const auto map = best_fuzzy_vertex_map(f.fuzzy, f.records, a, b, B.V);
      const std::size_t n = std::min(fa.size(), fb.size());
      sources.push_back(a);
      begin.push_back(predicted.size());
      for (std::size_t k = 0; k < n; ++k) {
        const bool a_bad = std::size_t(fa[k]) >= map.size(), b_bad = fb[k] >= B.V.rows();
        if (a_bad || b_bad)
          throw io_error(file_error::bad_value, feature_point_file(truth_dir, f.records[std::size_t(a_bad ? a : b)].name).string(),
                         0, 0,
                         "feature point " + std::to_string(k) + " names vertex " + std::to_string(a_bad ? fa[k] : fb[k]) +
                             ", which the mesh does not have (is this the truth of another mesh?)");
        predicted.push_back(map[std::size_t(fa[k])]);
        truth.push_back(fb[k]);
      }
    }
    begin.push_back(predicted.size());
    const auto e = benchmark_geodesic_errors<double>(B.V, B.F, geo, std::span<const index_t>(predicted),
                                                     std::span<const index_t>(truth), threads);
    errors.insert(errors.end(), e.begin(), e.end());
    for (std::size_t p = 0; p < sources.size(); ++p) {
      double sum = 0;
      std::size_t near = 0;
      for (std::size_t i = begin[p]; i < begin[p + 1]; ++i) sum += e[i], near += e[i] <= 0.25 ? 1 : 0;
      const double n = double(begin[p + 1] - begin[p]);
      out.per_pair.push_back({f.records[std::size_t(sources[p])].name, f.records[std::size_t(b)].name,
                              n > 0 ? sum / n : 0.0, n > 0 ? double(near) / n : 0.0});
      ++out.pairs;
    }
    if (progress) progress(j + 1, scored.size());
  }
  out.points = errors.size();
  if (!errors.empty()) {
    auto within = [&](double d) {
      return double(std::count_if(errors.begin(), errors.end(), [d](double x) { return x <= d; })) / double(errors.size());
    };
    out.within_005 = within(0.05);
    out.within_010 = within(0.10);
    out.within_025 = within(0.25);
    double sum = 0;
    for (const double x : errors) sum += x;
    out.mean = sum / double(errors.size());
  }
  return out;
}

}  // namespace shapestruct::cli
