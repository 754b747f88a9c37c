// SPDX-License-Identifier: MIT
// What `shapestruct analyze`'s report draws from the fuzzy stage: per-sample variance and colour-transfer
// correspondences (defined in report_fuzzy.cpp, so cmd_analyze.cpp does not compile the fuzzy headers).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace shapestruct::cli {

struct fuzzy_colours {
  std::vector<std::string> names;                                ///< shapes of the fuzzy collection, in its order
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 3>> samples; ///< per shape, its K samples (input coordinates)
  std::vector<std::vector<float>> variance;  ///< per shape and sample: sample_variance, 1 = most variable in it
  /// per shape and sample: the best fuzzy correspondence on shape 0 (the reference of the colour transfer)
  std::vector<std::vector<long>> to_reference;
};

/// Reads OUT/fuzzy (read_fuzzy_output) and computes sample_variance (chapter 4.5.1, default options) and every
/// sample's best match on shape 0. Deterministic, whatever `threads`.
/// \throws io_error when the folder is not complete fuzzy output.
fuzzy_colours read_fuzzy_colours(const std::filesystem::path& fuzzy_dir, int threads);

}  // namespace shapestruct::cli
