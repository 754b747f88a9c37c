// SPDX-License-Identifier: MIT
// co_aligned_points / canonical_correspondence: shapes in the template's canonical space (dissertation 5.4.4,
// 5.4.5) and shape-to-shape correspondences through it.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/shape_samples.hpp"
#include "shapestruct/templates/template_fitter.hpp"

namespace shapestruct {

/// The samples of a fitted shape in the template's canonical space. Rigid only (`deformed = false`): p = R q.
/// Rigid + part deformation: m(p) + o with m(p) the corresponding point on the MEAN template and
/// o = p - d(m(p)) the point's offset from the deformed template (5.4.4), which factors out part moves and
/// stretches. Null-labeled samples keep their rigid position.
/// \param t the template the fit used; \param s the samples; \param f fit_template(t, s).
/// \throws invalid_input size_mismatch when the fit does not belong to these samples / template.
/// \returns (#P x 3) points. O(P).
inline Eigen::Matrix<double, Eigen::Dynamic, 3> co_aligned_points(const part_template& t, const shape_samples& s,
                                                                  const template_fit& f, bool deformed = true) {
  if (static_cast<index_t>(f.parts.size()) != s.size() || f.centers.size() != t.parts.size() ||
      f.correspondence.size() != f.parts.size())
    throw invalid_input(input_error::size_mismatch, no_index,
                        "co_aligned_points: the fit does not belong to these samples and template");
  Eigen::Matrix<double, Eigen::Dynamic, 3> out = s.points * f.rotation.transpose();
  if (!deformed) return out;
  for (index_t i = 0; i < s.size(); ++i) {
    const index_t b = f.parts[static_cast<std::size_t>(i)];
    if (b < 0) continue;
    const auto& box = t.parts[static_cast<std::size_t>(b)];
    const Eigen::Vector3d& u = f.correspondence[static_cast<std::size_t>(i)].u;
    const Eigen::Vector3d d = f.centers[static_cast<std::size_t>(b)] +
                              box.axes.transpose() * f.sizes[static_cast<std::size_t>(b)].cwiseProduct(u);
    const Eigen::Vector3d m = box.center + box.axes.transpose() * box.size.cwiseProduct(u);
    out.row(i) = (m + (out.row(i).transpose() - d)).transpose();
  }
  return out;
}

/// Correspondences from shape A's samples to shape B's samples through the canonical space (5.4.5): each
/// co-aligned point of A maps to the nearest co-aligned point of B carrying the same part (any point of B when
/// A's point is null or B has no point of that part). Both shapes must be fitted to the same template.
/// \returns per sample of A, a sample index of B. O((P_A + P_B) log P_B).
inline std::vector<index_t> canonical_correspondence(const part_template& t, const shape_samples& sa,
                                                     const template_fit& fa, const shape_samples& sb,
                                                     const template_fit& fb) {
  const auto A = co_aligned_points(t, sa, fa);
  const auto B = co_aligned_points(t, sb, fb);
  const index_t K = t.num_parts();
  std::vector<std::vector<index_t>> members(static_cast<std::size_t>(K));
  for (index_t j = 0; j < sb.size(); ++j)
    if (fb.parts[static_cast<std::size_t>(j)] >= 0) members[static_cast<std::size_t>(fb.parts[static_cast<std::size_t>(j)])].push_back(j);
  std::vector<knn_index<double, 3>> trees;
  for (index_t b = 0; b < K; ++b) {
    Eigen::Matrix<double, Eigen::Dynamic, 3> P(static_cast<index_t>(members[static_cast<std::size_t>(b)].size()), 3);
    for (std::size_t k = 0; k < members[static_cast<std::size_t>(b)].size(); ++k)
      P.row(static_cast<index_t>(k)) = B.row(members[static_cast<std::size_t>(b)][k]);
    trees.emplace_back(P);
  }
  const knn_index<double, 3> all(B);
  std::vector<index_t> out(static_cast<std::size_t>(sa.size()));
  for (index_t i = 0; i < sa.size(); ++i) {
    const index_t b = fa.parts[static_cast<std::size_t>(i)];
    const Eigen::Vector3d q = A.row(i).transpose();
    if (b >= 0 && !members[static_cast<std::size_t>(b)].empty()) {
      const auto nn = trees[static_cast<std::size_t>(b)].nearest(q);
      out[static_cast<std::size_t>(i)] = members[static_cast<std::size_t>(b)][static_cast<std::size_t>(nn.index)];
    } else {
      out[static_cast<std::size_t>(i)] = all.nearest(q).index;
    }
  }
  return out;
}

}  // namespace shapestruct
