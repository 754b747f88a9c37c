// SPDX-License-Identifier: MIT
// How well `shapestruct analyze`'s fuzzy correspondences carry feature points from shape to shape, against
// benchmark truth (SHREC'07 / BIM .vts or .pid files). Defined in feature_point_accuracy.cpp, so cmd_analyze.cpp
// does not compile the fuzzy and geodesic headers.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace shapestruct::cli {

/// Accuracy of the best fuzzy correspondence (ch. 4.4.2) at ground-truth feature points.
struct feature_point_accuracy {
  std::size_t shapes_scored = 0;  ///< shapes of the fuzzy collection with a truth file
  std::size_t pairs = 0;          ///< ordered pairs (a, b) of those shapes
  std::size_t points = 0;         ///< feature points mapped, over all pairs
  double within_005 = 0, within_010 = 0, within_025 = 0;  ///< fraction of points with error <= D
  double mean = 0;                                        ///< mean error
  std::vector<std::string> not_scored;  ///< shapes of the collection without a truth file
  struct pair_score {
    std::string source, target;
    double mean = 0, within_025 = 0;
  };
  std::vector<pair_score> per_pair;  ///< in the order (target, source) they were scored
};

/// The truth file of shape `name` in `truth_dir`: NAME.vts or NAME.pid ("" when neither exists).
std::filesystem::path feature_point_file(const std::filesystem::path& truth_dir, const std::string& name);

/// For every ordered pair (a, b) of shapes in the fuzzy output folder that both have a truth file: the k-th
/// feature point of a is mapped by the best fuzzy correspondence (its nearest sample's best match on b) and
/// scored by the geodesic distance on b to b's k-th feature point, divided by sqrt(area of b): the BIM
/// benchmark's error (eval/geodesic_error.hpp, the scale bench/runners/fuzzy_benchmark.cpp reports), raw,
/// without symmetry flips. progress(done, total) per target shape.
/// \throws io_error for an unreadable fuzzy folder, mesh or truth file.
feature_point_accuracy evaluate_feature_points(const std::filesystem::path& fuzzy_dir,
                                               const std::filesystem::path& truth_dir, int threads,
                                               const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace shapestruct::cli
