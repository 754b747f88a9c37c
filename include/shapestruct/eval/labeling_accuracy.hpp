// SPDX-License-Identifier: MIT
// labeling_accuracy: fraction of surface area labeled correctly after the best one-to-one label mapping.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/eval/best_label_matching.hpp"

namespace shapestruct {

/// One labeled shape for labeling_accuracy: per-face predicted and true labels (non-negative; a negative
/// predicted label means "unlabeled" and always counts as wrong) and per-face weights (areas, or 1 for the
/// face-count variant).
struct labeled_shape {
  std::vector<index_t> predicted;
  std::vector<index_t> truth;
  std::vector<double> weight;
};

/// Result: `accuracy` over the whole collection (weight-averaged), `per_shape` accuracies, and the mapping
/// from predicted label to true label that was applied (one mapping for the whole collection, as the COSEG
/// protocol fixes it per class).
struct labeling_accuracy_result {
  double accuracy = 0;
  std::vector<double> per_shape;
  label_matching mapping;
};

/// COSEG protocol: builds the (#predicted labels x #true labels) table of agreeing weight summed over all shapes,
/// finds the best one-to-one mapping (best_label_matching) and returns the fraction of weight whose mapped
/// predicted label equals the truth. Collection accuracy weights every shape by its total weight; when
/// `normalize_shapes` is true every shape counts equally instead (area fractions per shape, then averaged).
/// \throws invalid_input size_mismatch (shape index) when the three vectors of a shape differ in length,
///         bad_parameter when a weight is negative or not finite, empty when there is no weight at all.
/// \returns the accuracy in [0, 1]. O(total faces + L^3).
inline labeling_accuracy_result labeling_accuracy(const std::vector<labeled_shape>& shapes,
                                                  bool normalize_shapes = true) {
  index_t np = 0, nt = 0;
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    const auto& sh = shapes[s];
    if (sh.predicted.size() != sh.truth.size() || sh.weight.size() != sh.truth.size())
      throw invalid_input(input_error::size_mismatch, static_cast<index_t>(s),
                          "labeling_accuracy: shape " + std::to_string(s) + " has " +
                              std::to_string(sh.predicted.size()) + " predicted labels, " +
                              std::to_string(sh.truth.size()) + " true labels and " +
                              std::to_string(sh.weight.size()) + " weights; they must agree");
    for (std::size_t f = 0; f < sh.truth.size(); ++f) {
      if (!(sh.weight[f] >= 0) || !std::isfinite(sh.weight[f]))
        throw invalid_input(input_error::bad_parameter, static_cast<index_t>(s),
                            "labeling_accuracy: shape " + std::to_string(s) + " face " + std::to_string(f) +
                                " has a negative or non-finite weight");
      if (sh.truth[f] < 0)
        throw invalid_input(input_error::bad_parameter, static_cast<index_t>(s),
                            "labeling_accuracy: shape " + std::to_string(s) + " face " + std::to_string(f) +
                                " has a negative ground-truth label");
      np = std::max(np, sh.predicted[f] + 1);
      nt = std::max(nt, sh.truth[f] + 1);
    }
  }
  Eigen::MatrixXd table = Eigen::MatrixXd::Zero(std::max<index_t>(np, 1), std::max<index_t>(nt, 1));
  double total_all = 0;
  std::vector<double> totals(shapes.size(), 0);
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    const auto& sh = shapes[s];
    for (const double w : sh.weight) totals[s] += w;
    total_all += totals[s];
  }
  if (!(total_all > 0)) throw invalid_input(input_error::empty, no_index, "labeling_accuracy: no labeled weight");
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    const auto& sh = shapes[s];
    const double scale = normalize_shapes ? (totals[s] > 0 ? 1.0 / totals[s] : 0.0) : 1.0;
    for (std::size_t f = 0; f < sh.truth.size(); ++f)
      if (sh.predicted[f] >= 0) table(sh.predicted[f], sh.truth[f]) += sh.weight[f] * scale;
  }
  labeling_accuracy_result r;
  r.mapping = best_label_matching(table);
  double correct_all = 0, denom = 0;
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    const auto& sh = shapes[s];
    double correct = 0;
    for (std::size_t f = 0; f < sh.truth.size(); ++f) {
      const index_t p = sh.predicted[f];
      if (p >= 0 && p < static_cast<index_t>(r.mapping.to_truth.size()) &&
          r.mapping.to_truth[static_cast<std::size_t>(p)] == sh.truth[f])
        correct += sh.weight[f];
    }
    const double acc = totals[s] > 0 ? correct / totals[s] : 0.0;
    r.per_shape.push_back(acc);
    if (totals[s] > 0) {
      correct_all += normalize_shapes ? acc : correct;
      denom += normalize_shapes ? 1.0 : totals[s];
    }
  }
  r.accuracy = denom > 0 ? correct_all / denom : 0.0;
  return r;
}

}  // namespace shapestruct
