// SPDX-License-Identifier: MIT
// fuzzy_maps: dense vertex maps between two shapes of a collection from its fuzzy correspondence (ch. 4.4).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/blended/sample_map_measures.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/concepts/map_refiner.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/fuzzy/fuzzy_collection.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"
#include "shapestruct/fuzzy/intrinsic_alignment.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/maps/surface_map.hpp"
#include "shapestruct/refine/zoomout_refiner.hpp"

namespace shapestruct {

/// The best-fuzzy-correspondence map of ch. 4.4.2: every vertex of shape a goes where its nearest sample's
/// closest sample of shape b in the embedding lies (nearest-neighbour interpolation of a K-sample map).
/// The image of a sample of b is its vertex (geodesic samples) or, for samples drawn on the surface of a soup,
/// the vertex of `b_vertices` nearest to it.
/// \param f the collection's fuzzy correspondence  \param a, b the two shapes' indices in the collection
/// \param b_vertices (#V_b x 3) b's vertices; needed only when b's samples are not vertices
/// \returns (#V_a) target vertex per source vertex (the benchmark's dense .map)
/// \throws invalid_input (bad_parameter) for shapes out of range, (size_mismatch) when b_vertices is needed
///         and missing.
[[nodiscard]] inline std::vector<index_t> best_fuzzy_vertex_map(const fuzzy_correspondence& f,
                                                                const std::vector<shape_record>& records, index_t a,
                                                                index_t b,
                                                                const Eigen::Matrix<double, Eigen::Dynamic, 3>& b_vertices = {}) {
  const index_t N = f.shapes();
  if (a < 0 || a >= N || b < 0 || b >= N || static_cast<index_t>(records.size()) != N)
    throw invalid_input(input_error::bad_parameter, no_index,
                        "best_fuzzy_vertex_map: shapes " + std::to_string(a) + ", " + std::to_string(b) +
                            " are not both in a collection of " + std::to_string(N));
  const shape_record& ra = records[std::size_t(a)];
  const shape_record& rb = records[std::size_t(b)];
  const std::vector<index_t> match = f.best_matches(a, b);
  std::vector<index_t> image(match.size());
  const bool vertices = !rb.sample_vertex.empty() && rb.sample_vertex[0] != no_index;
  if (!vertices && b_vertices.rows() == 0)
    throw invalid_input(input_error::size_mismatch, b,
                        "best_fuzzy_vertex_map: shape '" + rb.name +
                            "' was sampled on its surface; pass its vertices to map onto them");
  if (vertices) {
    for (std::size_t i = 0; i < match.size(); ++i) image[i] = rb.sample_vertex[std::size_t(match[i])];
  } else {
    const knn_index<double, 3> index(b_vertices);
    for (std::size_t i = 0; i < match.size(); ++i)
      image[i] = index.nearest(rb.samples.row(match[i]).transpose()).index;
  }
  std::vector<index_t> out(ra.vertex_sample.size());
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = image[std::size_t(ra.vertex_sample[v])];
  return out;
}

/// The best fuzzy map of an intrinsic collection (best_fuzzy_vertex_map) made precise: ZoomOut (or another
/// MapRefiner) refines it on the two meshes. The fuzzy map is right globally wherever the collection is, but only
/// to the spacing of the K samples; the refinement keeps its global structure and sharpens it locally.
/// \param threads for the refiner (0 = all cores)  \throws as best_fuzzy_vertex_map and the refiner.
template <MapRefiner<double> Refiner = zoomout_refiner>
[[nodiscard]] surface_map<double> refined_fuzzy_map(const intrinsic_aligner& aligner, const fuzzy_correspondence& f,
                                                    index_t a, index_t b, int threads = 0,
                                                    const Refiner& refiner = {}) {
  const std::vector<index_t> coarse = best_fuzzy_vertex_map(f, aligner.records(), a, b);
  const auto mesh_a = aligner.mesh(a);
  const auto mesh_b = aligner.mesh(b);
  return refiner.refine(*mesh_a, *mesh_b, surface_map_at_vertices(*mesh_b, coarse), threads);
}

/// Options of make_consistent_blended_map.
struct consistent_blended_options {
  /// The collection overrules the blended matcher's own choice only when its most consistent map beats the
  /// matcher's choice by this fraction of the latter's consistency (eq. 4.10). Near ties are a symmetry the whole
  /// collection shares (left and right of an airplane): f cannot tell the two maps apart, the matcher's own
  /// selection (area, confidence and convexity ranks) often can. 0 is the chapter's rule (the most consistent map, always).
  double min_consistency_gain = 0.1;
  /// The collection's orientation (fuzzy_collection_result::orientation), or empty. Between two shapes of
  /// opposite orientation f itself is mirrored, and its most consistent map with it: the matcher's own choice is
  /// kept.
  std::vector<std::int8_t> orientation{};
  /// The refined best fuzzy map (refined_fuzzy_map) competes with the blended maps, under the same margin. Where
  /// every blended map of a pair is wrong (each one flipped, say), the collection's own map can still be right
  /// (measured in docs/fuzzy.md).
  bool fuzzy_candidate = true;
  /// ... and is chosen only when it is more consistent than every blended map by this fraction of the best one's
  /// consistency. It maximises f point by point, so eq. 4.10 favours it over a blended map that is just as right.
  double fuzzy_min_gain = 0;
  /// ... and only when its geodesic distortion (input_map_geodesic_distortion) is at most this many times that of
  /// the most consistent blended map: the blended matcher's own check on its refinement
  /// (blended_matcher_options::max_refined_distortion_ratio), here against ZoomOut drifting from the fuzzy map.
  /// 0 = no check (the default: on SHREC'07 no limit separated the pairs it loses; docs/fuzzy.md).
  double max_fuzzy_distortion_ratio = 0;
  /// ... and only when its images lie on average at least this far (mean_image_distance, unit-area units) from
  /// those of the most consistent blended map. Closer, the two are one map up to local precision, and the
  /// blended map, built from the shapes' own features, is the more precise of them. 0 = no check (the default,
  /// likewise).
  double fuzzy_min_distance = 0;
  /// A chosen blended map is refined as the blended matcher refines its own selection (ZoomOut, its long moves
  /// checked, kept unless it distorts much more: blended_matcher::refine_checked). The fuzzy candidate is refined
  /// already. On by default: on all four benchmark lists it gains within 0.05 and in the mean error, within 0.25
  /// it gains or holds (docs/fuzzy.md, "The choice refined").
  bool refine_choice = true;
  /// Threads of the refinements (0 = all cores).
  int threads = 0;
};

/// The consistent blended map of ch. 4.4.5: of the blended maps the blended matcher builds for (a, b), and of the
/// refined best fuzzy map unless consistent_blended_options::fuzzy_candidate is off, the one whose alignment
/// scores agree best with f (the consistency score of eq. 4.10), unless it is only marginally more consistent
/// than the matcher's own choice (consistent_blended_options).
struct consistent_blended_map {
  surface_map<double> map;        ///< source vertices of a -> surface points of b
  index_t group = no_index;       ///< index of the chosen blended map in the match's `blended`
  index_t pairwise_group = no_index;  ///< the group the blended matcher alone selects
  index_t most_consistent_group = no_index;  ///< the group with the highest consistency
  std::vector<double> consistency;    ///< score_f (eq. 4.10) of every group with a map, in `groups`' order
  std::vector<index_t> groups;        ///< the group (index in the match's `blended`) of each consistency entry
  bool opposite_orientation = false;  ///< a and b sit in f the mirror way round: the matcher's choice was kept
  bool fuzzy_chosen = false;          ///< the refined best fuzzy map was chosen (`group` is then no_index)
  double fuzzy_consistency = -1;      ///< its score_f, or -1 when it did not compete
  double fuzzy_distortion = -1;       ///< its geodesic distortion, or -1 when it did not compete
  /// The mean distance between its images and the most consistent blended map's (mean_image_distance), or -1.
  double fuzzy_distance = -1;
  /// Geodesic distortion of the most consistent blended map (blended_candidate::geodesic_distortion), or -1 when
  /// the match has none.
  double most_consistent_distortion = -1;
  /// With consistent_blended_options::refine_choice: the chosen blended map's refinement was kept, and its
  /// geodesic distortion over the blended map's (-1 when nothing was refined).
  bool refinement_accepted = false;
  double refinement_distortion_ratio = -1;
};

/// The blended map `group` of r (a match of a -> b by `aligner`) refined as the blended matcher refines its own
/// selection (blended_matcher::refine_checked with the aligner's matcher options), or the blended map itself where
/// the refinement's distortion check rejects it. `accepted` (optional) says which; `distortion_ratio` (optional)
/// receives the refined map's geodesic distortion over the blended map's.
/// \throws as blended_matcher::refine_checked.
[[nodiscard]] inline surface_map<double> refined_blended_choice(const intrinsic_aligner& aligner, index_t a, index_t b,
                                                                const blended_match_result<double>& r, index_t group,
                                                                int threads, bool* accepted = nullptr,
                                                                double* distortion_ratio = nullptr) {
  const auto& chosen = r.blended.at(std::size_t(group));
  blended_matcher_options o = aligner.options().matcher;
  o.threads = threads;
  const auto shape_a = aligner.prepared_shape(a);
  const auto shape_b = aligner.prepared_shape(b);
  checked_refinement refined = blended_matcher<>(o).refine_checked(*shape_a, *shape_b, chosen);
  if (accepted) *accepted = refined.accepted;
  if (distortion_ratio) *distortion_ratio = refined.distortion / chosen.geodesic_distortion;
  return refined.accepted ? std::move(refined.map) : chosen.map;
}

/// The consistent blended map of shapes a -> b chosen among the blended maps of `r` (and the refined fuzzy map),
/// `r` a match of a -> b by `aligner` (intrinsic_aligner::match), so a caller that also wants the pairwise map
/// matches once.
/// \throws invalid_input (bad_parameter) for a negative or non-finite min_consistency_gain, fuzzy_min_gain,
///         max_fuzzy_distortion_ratio or fuzzy_min_distance, (size_mismatch) for an orientation not of the
///         collection's size.
[[nodiscard]] inline consistent_blended_map make_consistent_blended_map(const intrinsic_aligner& aligner,
                                                                        const fuzzy_correspondence& f, index_t a,
                                                                        index_t b, const blended_match_result<double>& r,
                                                                        const consistent_blended_options& options = {}) {
  const auto require_non_negative = [](double value, const char* name) {
    if (!(value >= 0) || !std::isfinite(value))
      throw invalid_input(input_error::bad_parameter, no_index,
                          std::string("make_consistent_blended_map: ") + name +
                              " must be finite and at least 0, got " + std::to_string(value));
  };
  require_non_negative(options.min_consistency_gain, "min_consistency_gain");
  require_non_negative(options.fuzzy_min_gain, "fuzzy_min_gain");
  require_non_negative(options.max_fuzzy_distortion_ratio, "max_fuzzy_distortion_ratio");
  require_non_negative(options.fuzzy_min_distance, "fuzzy_min_distance");
  const auto& orientation = options.orientation;
  if (!orientation.empty() && static_cast<index_t>(orientation.size()) != f.shapes())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "make_consistent_blended_map: the orientation has " + std::to_string(orientation.size()) +
                            " entries for a collection of " + std::to_string(f.shapes()));
  // Held to the end, so that a cache too small for two shapes does not prepare them again between the steps.
  const auto held_a = aligner.prepared_shape(a);
  const auto held_b = aligner.prepared_shape(b);
  const pair_alignment alts = aligner.alignment_from(a, b, r);
  consistent_blended_map out;
  out.pairwise_group = r.selected;
  double best = -1, pairwise = -1;
  const Eigen::MatrixXd F = f.block(a, b);
  for (const auto& alt : alts.alternatives) {
    const double s = detail::consistency_score(alt, F);
    const auto g = static_cast<index_t>(alt.parameters.at(0));
    out.consistency.push_back(s);
    out.groups.push_back(g);
    if (s > best) best = s, out.most_consistent_group = g;
    if (g == r.selected) pairwise = s;
  }
  if (out.most_consistent_group != no_index)
    out.most_consistent_distortion = r.blended[std::size_t(out.most_consistent_group)].geodesic_distortion;
  out.opposite_orientation = !orientation.empty() && orientation[std::size_t(a)] != orientation[std::size_t(b)];
  const bool keep_matcher = out.opposite_orientation && pairwise >= 0;
  surface_map<double> fuzzy_map;
  if (options.fuzzy_candidate && !keep_matcher) {
    fuzzy_map = refined_fuzzy_map(aligner, f, a, b, options.threads);
    out.fuzzy_consistency = detail::consistency_score(aligner.score_map(a, b, fuzzy_map), F);
    const auto shape_a = aligner.prepared_shape(a);
    const auto shape_b = aligner.prepared_shape(b);
    out.fuzzy_distortion = input_map_geodesic_distortion(*shape_a, *shape_b, fuzzy_map);
    if (out.most_consistent_group != no_index)
      out.fuzzy_distance = mean_image_distance(*shape_a, *shape_b, fuzzy_map,
                                               r.blended[std::size_t(out.most_consistent_group)].map);
  }
  const double distortion_limit = options.max_fuzzy_distortion_ratio * out.most_consistent_distortion;
  const bool fuzzy_undistorted = !(options.max_fuzzy_distortion_ratio > 0) || out.most_consistent_distortion < 0 ||
                                 out.fuzzy_distortion <= distortion_limit;
  const bool fuzzy_distinct = out.fuzzy_distance < 0 || out.fuzzy_distance >= options.fuzzy_min_distance;
  const bool fuzzy_competes = out.fuzzy_consistency >= 0 && fuzzy_undistorted && fuzzy_distinct &&
                              out.fuzzy_consistency > (1 + options.fuzzy_min_gain) * best;
  const double top = fuzzy_competes ? out.fuzzy_consistency : best;
  if (top < 0 || (pairwise >= 0 && top <= (1 + options.min_consistency_gain) * pairwise) || keep_matcher) {
    out.group = r.selected;
  } else if (fuzzy_competes) {
    out.fuzzy_chosen = true;
    out.map = std::move(fuzzy_map);
    return out;
  } else {
    out.group = out.most_consistent_group;
  }
  out.map = options.refine_choice
                ? refined_blended_choice(aligner, a, b, r, out.group, options.threads, &out.refinement_accepted,
                                         &out.refinement_distortion_ratio)
                : r.blended[std::size_t(out.group)].map;
  return out;
}

/// Computes the consistent blended map of shapes a -> b. \throws as intrinsic_aligner::match.
[[nodiscard]] inline consistent_blended_map make_consistent_blended_map(const intrinsic_aligner& aligner,
                                                                        const fuzzy_correspondence& f, index_t a,
                                                                        index_t b,
                                                                        const consistent_blended_options& options = {}) {
  const auto held_a = aligner.prepared_shape(a);
  const auto held_b = aligner.prepared_shape(b);
  return make_consistent_blended_map(aligner, f, a, b, aligner.match(a, b), options);
}

}  // namespace shapestruct
