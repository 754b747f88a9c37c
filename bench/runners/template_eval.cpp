// SPDX-License-Identifier: MIT
// run_template_eval: scores the per-face labels written by `shapestruct templates` against ground truth.
//   run_template_eval SHAPES_DIR OUT_DIR [--gt GT_DIR] [--one-based]
// For every mesh STEM in SHAPES_DIR with OUT_DIR/STEM.seg and GT_DIR/STEM.seg (GT_DIR defaults to SHAPES_DIR, the
// layout of `shapestruct generate`), prints the area-weighted labeling accuracy after the best one-to-one
// mapping of predicted to true labels over the whole collection, plus the same with a mapping per shape.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "shapestruct/eval/labeling_accuracy.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "shapestruct/templates/collection_runner.hpp"
#include "runner_errors.hpp"

namespace fs = std::filesystem;
using namespace shapestruct;

static int run(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: run_template_eval SHAPES_DIR OUT_DIR [--gt GT_DIR] [--one-based]\n";
    return 2;
  }
  const fs::path shapes = argv[1], out = argv[2];
  fs::path gt = shapes;
  bool one_based = false;
  for (int i = 3; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--gt" && i + 1 < argc) gt = argv[++i];
    else if (a == "--one-based") one_based = true;
  }
  std::vector<labeled_shape> all;
  double per_shape_sum = 0;
  for (const auto& f : list_shape_files(shapes)) {
    const auto stem = f.stem().string();
    if (!fs::exists(out / (stem + ".seg")) || !fs::exists(gt / (stem + ".seg"))) continue;
    const auto m = read_mesh(f).mesh;
    labeled_shape s;
    s.predicted = read_segmentation(out / (stem + ".seg"), m.F.rows());
    s.truth = read_segmentation(gt / (stem + ".seg"), m.F.rows());
    if (one_based)
      for (auto& t : s.truth) t -= 1;
    const auto A = face_areas<double>(m.V, m.F);
    s.weight.assign(A.data(), A.data() + A.size());
    per_shape_sum += labeling_accuracy({s}).accuracy;
    all.push_back(std::move(s));
  }
  if (all.empty()) {
    std::cerr << "run_template_eval: no shape has both a predicted and a true .seg\n";
    return 1;
  }
  const auto acc = labeling_accuracy(all);
  std::cout << "shapes: " << all.size() << "\n";
  std::cout << "accuracy (area, one mapping for the collection): " << 100.0 * acc.accuracy << " %\n";
  std::cout << "accuracy (area, mapping per shape): " << 100.0 * per_shape_sum / double(all.size()) << " %\n";
  return 0;
}

int main(int argc, char** argv) {
  return shapestruct::bench::run_reporting_errors("run_template_eval", [&] { return run(argc, argv); });
}
