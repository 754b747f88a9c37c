// SPDX-License-Identifier: MIT
// refined_fuzzy_alignment: the best fuzzy correspondence of an extrinsic collection made precise by one ICP
// started from it (the extrinsic counterpart of refined_fuzzy_map).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/fuzzy/extrinsic_alignment.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"
#include "shapestruct/knn/knn_index.hpp"

namespace shapestruct {

namespace detail {

/// The similarity best taking the target points onto the source points: fitted in closed form, then refitted twice
/// on the 80 % of pairs it fits best, so that a few wrong matches do not pull it.
template <class Similarity>
Similarity fit_to_matches(const std::vector<Eigen::Vector3d>& target_points,
                          const std::vector<Eigen::Vector3d>& source_points,
                          const extrinsic_alignment_options& options) {
  Similarity T = fit_like(Similarity{}, target_points, source_points, options);
  constexpr int refits = 2;
  constexpr double keep = 0.8;
  std::vector<double> d2, scratch;
  for (int round = 0; round < refits; ++round) {
    const affine_pair M = to_affine_pair(T, options.up_axis);
    std::vector<Eigen::Vector3d> p = target_points, x = source_points;
    d2.clear();
    for (std::size_t k = 0; k < p.size(); ++k) d2.push_back((M.A * p[k] + M.t - x[k]).squaredNorm());
    trim_pairs(p, x, d2, 0, keep, scratch);
    T = fit_like(T, p, x, options);
  }
  return T;
}

}  // namespace detail

/// The best fuzzy correspondence of shapes a -> b (ch. 4.4.2) turned into a precise alignment: the similarity
/// (upright, or any rotation with options.up_axis = no_up_axis) that best takes every sample of a's best fuzzy
/// match on b onto that sample (detail::fit_to_matches), refined by the extrinsic matcher's trimmed ICP and scored
/// as align_extrinsic scores its alternatives. f is right globally wherever the collection is, but only to the
/// spacing of the K samples and blurred by the diffusion; the ICP keeps its global placement and sharpens it
/// locally. One ICP from where the collection says the shapes correspond, instead of the
/// matcher's four from principal axes chosen by B_a. With options.axis_scales (upright collections) a second ICP
/// also fits a scale per axis: shapes of other proportions then fit more closely (docs/fuzzy.md measures it).
/// \param f the collection's fuzzy correspondence  \param records the collection's records (f's shapes)
/// \param a, b source and target: the transform takes b into a's frame, as an alternative of the pair (a, b)
/// \returns the alternative: its scores rank b's samples for each sample of a, its parameters the transform
///          (extrinsic_transform)
/// \throws invalid_input (bad_parameter) for shapes out of range or a == b, or options out of range; (empty)
///         when fewer than 3 samples of a have a non-zero f on b (shapes in different components of the graph, or
///         that the embedding puts far apart); as align_extrinsic for bad records.
[[nodiscard]] inline alignment_alternative refined_fuzzy_alignment(const fuzzy_correspondence& f,
                                                                   const std::vector<shape_record>& records,
                                                                   index_t a, index_t b,
                                                                   const extrinsic_alignment_options& options = {}) {
  const char* who = "refined_fuzzy_alignment";
  const index_t N = f.shapes();
  if (a < 0 || a >= N || b < 0 || b >= N || a == b || static_cast<index_t>(records.size()) != N)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": shapes " + std::to_string(a) + " and " + std::to_string(b) +
                            " are not two different shapes of a collection of " + std::to_string(N) + " (" +
                            std::to_string(records.size()) + " records)");
  detail::check_extrinsic_options(options, who);
  const shape_record& ra = records[std::size_t(a)];
  const shape_record& rb = records[std::size_t(b)];
  detail::check_extrinsic_record(ra, "source", who);
  detail::check_extrinsic_record(rb, "target", who);

  // Pairs (b's best match, a's sample) for every sample of a that has a non-zero f on b.
  const Eigen::MatrixXd F = f.block(a, b);
  std::vector<Eigen::Vector3d> target_points, source_points;
  for (index_t i = 0; i < F.rows(); ++i) {
    index_t j = 0;
    if (!(F.row(i).maxCoeff(&j) > 0)) continue;
    target_points.push_back(rb.samples.row(j).transpose());
    source_points.push_back(ra.samples.row(i).transpose());
  }
  if (target_points.size() < 3)  // f vanishes: the collection does not say where these shapes correspond
    throw invalid_input(input_error::empty, no_index,
                        std::string(who) + ": shapes '" + ra.name + "' and '" + rb.name +
                            "' have no fuzzy correspondence: f is zero on '" + rb.name + "' for all but " +
                            std::to_string(target_points.size()) + " of the " + std::to_string(F.rows()) +
                            " samples of '" + ra.name + "' (the others lie beyond f's cutoff in the embedding), and an "
                            "alignment needs 3; the collection relates "
                            "the two too weakly (they lie in different components of its alignment graph, or far "
                            "apart in its embedding). Their best fuzzy map (nearest in the embedding) is still "
                            "defined");

  const detail::extrinsic_pair_geometry geometry(ra, rb);
  if (options.up_axis == no_up_axis)
    return geometry.refine_and_score(
        detail::fit_to_matches<detail::free_similarity>(target_points, source_points, options), options);
  return geometry.refine_and_score(
      detail::fit_to_matches<detail::upright_similarity>(target_points, source_points, options), options);
}

/// The dense vertex map of refined_fuzzy_alignment: every vertex of a, taken into b's frame by the inverse of the
/// alignment's transform, goes to the nearest vertex of b (the benchmark's dense .map).
/// \param a_vertices, b_vertices (#V x 3) the two shapes' vertices
/// \returns (#V_a) target vertex per source vertex
/// \throws as refined_fuzzy_alignment; invalid_input (empty) for a shape without vertices, (non_finite) for a
///         NaN/Inf vertex.
[[nodiscard]] inline std::vector<index_t> refined_fuzzy_vertex_map(const fuzzy_correspondence& f,
                                                                  const std::vector<shape_record>& records,
                                                                  index_t a, index_t b,
                                                                  const Eigen::Matrix<double, Eigen::Dynamic, 3>& a_vertices,
                                                                  const Eigen::Matrix<double, Eigen::Dynamic, 3>& b_vertices,
                                                                  const extrinsic_alignment_options& options = {}) {
  if (a_vertices.rows() == 0 || b_vertices.rows() == 0)
    throw invalid_input(input_error::empty, no_index,
                        std::string("refined_fuzzy_vertex_map: shape ") + (a_vertices.rows() == 0 ? "a" : "b") +
                            " has no vertices");
  if (!a_vertices.allFinite())
    throw invalid_input(input_error::non_finite, no_index, "refined_fuzzy_vertex_map: a vertex of shape a is not finite");
  const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(refined_fuzzy_alignment(f, records, a, b, options));
  const Eigen::Matrix3d A_inverse = M.leftCols<3>().inverse();
  const knn_index<double, 3> target(b_vertices);  // throws non_finite naming the vertex
  std::vector<index_t> out(static_cast<std::size_t>(a_vertices.rows()));
  for (index_t v = 0; v < a_vertices.rows(); ++v)
    out[std::size_t(v)] = target.nearest(Eigen::Vector3d(A_inverse * (a_vertices.row(v).transpose() - M.col(3)))).index;
  return out;
}

}  // namespace shapestruct
