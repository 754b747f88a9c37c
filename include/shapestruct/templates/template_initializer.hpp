// SPDX-License-Identifier: MIT
// Automatic template initialisation (dissertation 5.3.4): templates from segmentations of candidate shapes.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/geometry/principal_frame.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/segment_into_boxes.hpp"
#include "shapestruct/templates/shape_samples.hpp"
#include "shapestruct/templates/template_fitter.hpp"
#include "shapestruct/templates/template_learner.hpp"

namespace shapestruct {

/// Options of template_from_shape and auto_templates.
struct template_initializer_options {
  int parts = 4;       ///< N_seg: parts of a candidate segmentation (Voronoi seeds when oversegment <= parts)
  int candidates = 0;  ///< shapes segmented into candidate templates (seeded shuffle); 0 = all (chapter)
  int learn_best = 2;  ///< fully automatic mode: learn from this many best candidates (chapter: 10)
  int up_axis = 1;
  double init_sigma = 0.08;  ///< loose Gaussians of an initial template (positions and sizes, canonical units)
  std::uint64_t seed = 1;
  /// Initial cells of the structure-following segmentation (segment_into_boxes): this many farthest-point seeds,
  /// cells grown along the neighbourhood graph, then merged down to `parts`. <= parts: the chapter's plain
  /// Voronoi cells of `parts` seeds.
  int oversegment = 64;
  /// RMS box-abstraction error (canonical units) up to which cells always merge (segment_into_boxes).
  double merge_tolerance = 0.03;
  /// auto_templates: progress(done, total) after each candidate template is made (under a lock, from any worker),
  /// before the learning rounds, which report through template_learner_options::progress. May be empty.
  std::function<void(std::size_t, std::size_t)> progress{};
};

namespace detail {

/// Gives copies of one part in a template one output label, then numbers the labels 0, 1, ... by first
/// appearance. Copies are boxes with the same upright extents (congruent_boxes) at the same height: the legs of a
/// chair, its two arms; an arm and a leg of a figure may have the same extents but not the same height.
/// segment_into_boxes groups congruent CELLS, but a cell can carry a strip of the seat or a stretcher, so one leg
/// of four may miss its group; the refitted boxes have shed those strips.
inline void share_labels_of_congruent_boxes(part_template& t) {
  const std::size_t B = t.parts.size();
  std::vector<std::size_t> root(B);
  std::iota(root.begin(), root.end(), std::size_t{0});
  const auto find = [&](std::size_t x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  std::vector<Eigen::Vector3d> ext(B);
  for (std::size_t b = 0; b < B; ++b) {
    cell_box box;
    box.axes = t.parts[b].axes;
    box.size = t.parts[b].size;
    ext[b] = upright_extents(box, t.up_axis);
  }
  // Boxes that already share a label stay together; congruent boxes join them.
  for (std::size_t a = 0; a < B; ++a)
    for (std::size_t b = a + 1; b < B; ++b)
      if (t.parts[a].label == t.parts[b].label ||
          (congruent_boxes(ext[a], ext[b]) &&
           std::abs(t.parts[a].center[t.up_axis] - t.parts[b].center[t.up_axis]) <=
               0.3 * std::max(ext[a][0], ext[b][0]) + 0.02))
        root[find(b)] = find(a);
  std::vector<index_t> label_of_root(B, no_index);
  index_t next = 0;
  for (std::size_t b = 0; b < B; ++b) {
    auto& l = label_of_root[find(b)];
    if (l == no_index) l = next++;
    t.parts[b].label = l;
  }
}

}  // namespace detail

/// A candidate template from one shape (5.3.4): a segmentation into N_seg cells (segment_into_boxes: with
/// opt.oversegment > N_seg, cells grown along the neighbourhood graph and merged by box-abstraction error; else
/// the chapter's Voronoi cells of N_seg farthest points), one box per cell oriented along the cell's PCA axes with
/// side lengths sqrt(12) standard deviations (the extent of a uniform distribution with that spread; the chapter
/// says "one standard deviation"), then the fitter re-labels the shape with E_data + E_smooth only (loose
/// deformation prior) and the fitted boxes become the template; fitted boxes that are congruent (copies of one
/// part, as four legs) share an output label. Returns the template and its fitting energy.
/// \throws invalid_input empty (fewer samples than parts), bad_parameter (parts < 1), validate_samples'.
inline std::pair<part_template, double> template_from_shape(const shape_samples& s,
                                                            const template_initializer_options& opt = {},
                                                            const template_fit_options& fit_opt = {}) {
  validate_samples(s, "template_from_shape");
  if (opt.parts < 1 || opt.up_axis < 0 || opt.up_axis > 2 || !(opt.init_sigma > 0))
    throw invalid_input(input_error::bad_parameter, no_index,
                        "template_from_shape: parts >= 1, up_axis in {0, 1, 2}, init_sigma > 0");
  const index_t n = s.size(), K = opt.parts;
  if (n < 4 * K)
    throw invalid_input(
        input_error::empty, no_index,
        "template_from_shape: " + std::to_string(n) + " samples are too few for " + std::to_string(K) + " parts");
  const box_segmentation seg = segment_into_boxes(s, opt.parts, opt.oversegment, opt.up_axis, opt.merge_tolerance);
  const std::vector<index_t>& cell = seg.cell;
  part_template t;
  t.id = "auto";
  t.up_axis = opt.up_axis;
  for (index_t k = 0; k < seg.num_cells(); ++k) {
    std::vector<index_t> mem;
    for (index_t i = 0; i < n; ++i)
      if (cell[static_cast<std::size_t>(i)] == k) mem.push_back(i);
    const principal_frame frame = principal_frame_of(s.points, mem);
    part_box b;
    b.name = "part " + std::to_string(k);
    b.label = seg.cell_label[static_cast<std::size_t>(k)];
    b.center = frame.mean;
    b.axes = frame.axes;
    // Side lengths of the box whose uniform distribution has the cell's variances (var = side^2 / 12).
    b.size = (12.0 * frame.variances).cwiseSqrt().cwiseMax(0.01);
    b.sigma_center = Eigen::Vector3d::Constant(opt.init_sigma);
    b.sigma_size = Eigen::Vector3d::Constant(opt.init_sigma);
    t.parts.push_back(std::move(b));
  }
  // Refit on its own shape without the deformation prior (E_data + E_smooth) and keep the fitted boxes.
  template_fit_options fo = fit_opt;
  fo.rotations = 1;
  const auto free_energy = energy_sum<distance_term, feature_term, smoothness_term>(
      distance_term{1.0}, feature_term{2.0, 1.0}, smoothness_term{2.0});
  const auto fit = fit_template(t, s, fo, free_energy);
  for (std::size_t b = 0; b < t.parts.size(); ++b) {
    t.parts[b].center = fit.centers[b];
    t.parts[b].size = fit.sizes[b].cwiseMax(0.01);
  }
  detail::share_labels_of_congruent_boxes(t);
  return {t, fit.energy};
}

/// Fully automatic templates (5.3.4): candidate templates from `candidates` shapes (template_from_shape; by
/// default every shape, as the chapter segments every shape),
/// sorted by their fitting energy; the best `learn_best` are each learned on the collection (learn_templates)
/// and the resulting template set with the lowest average fitting energy over the collection is returned.
/// \throws invalid_input empty (no shapes), and those of template_from_shape / learn_templates.
inline std::vector<part_template> auto_templates(const std::vector<shape_samples>& shapes,
                                                 const template_learner_options& learn = {},
                                                 const template_initializer_options& opt = {}) {
  if (shapes.empty()) throw invalid_input(input_error::empty, no_index, "auto_templates: no shapes");
  std::vector<std::size_t> order(shapes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::mt19937_64 rng(opt.seed);
  std::shuffle(order.begin(), order.end(), rng);
  if (opt.candidates > 0) order.resize(std::min<std::size_t>(order.size(), static_cast<std::size_t>(opt.candidates)));
  std::vector<std::pair<double, part_template>> cands(order.size());
  std::mutex progress_lock;
  std::size_t made = 0;
  detail::parallel_for(order.size(), detail::resolve_threads(learn.threads, "auto_templates"), [&](std::size_t k) {
    auto [t, e] = template_from_shape(shapes[order[k]], opt, learn.fit);
    t.id = "auto from shape " + std::to_string(order[k]);
    cands[k] = {e, std::move(t)};
    if (opt.progress) {
      std::lock_guard lock(progress_lock);
      opt.progress(++made, order.size());
    }
  });
  std::stable_sort(cands.begin(), cands.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<part_template> best;
  double best_avg = std::numeric_limits<double>::infinity();
  const std::size_t tries = std::min<std::size_t>(cands.size(), static_cast<std::size_t>(std::max(1, opt.learn_best)));
  for (std::size_t c = 0; c < tries; ++c) {
    auto learned = learn_templates({cands[c].second}, shapes, learn).templates;
    const auto fits = fit_template_set(learned, shapes, learn);
    double avg = 0;
    for (const auto& f : fits) avg += f.fit.energy;
    avg /= static_cast<double>(fits.size());
    if (avg < best_avg) {
      best_avg = avg;
      best = std::move(learned);
    }
  }
  return best;
}

}  // namespace shapestruct
