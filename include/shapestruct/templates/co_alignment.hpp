// SPDX-License-Identifier: MIT
// co_aligned_points / canonical_correspondence: shapes in the template's canonical space (dissertation 5.4.4,
// 5.4.5) and shape-to-shape correspondences through it.
#pragma once

#include <limits>
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

/// Correspondences between the parts of two templates: part a of `ta` maps to the part of `tb` with the same
/// output label (part_box::label) whose mean centre is nearest to a's mean centre, or to -1 when `tb` has no
/// part with that label. For ta == tb this is the identity. Labels are what make parts of different templates
/// "mean the same thing" (hand-authored sets share them; spawned templates inherit them), which is how the
/// chapter relates the templates of one collection. O(K_a K_b).
inline std::vector<index_t> template_part_map(const part_template& ta, const part_template& tb) {
  std::vector<index_t> out(ta.parts.size(), -1);
  for (std::size_t a = 0; a < ta.parts.size(); ++a) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < tb.parts.size(); ++b) {
      if (tb.parts[b].label != ta.parts[a].label) continue;
      const double d = (tb.parts[b].center - ta.parts[a].center).squaredNorm();
      if (d < best) {
        best = d;
        out[a] = static_cast<index_t>(b);
      }
    }
  }
  return out;
}

/// Correspondences from shape A's samples to shape B's samples through the canonical space (5.4.5), also when A
/// and B were fitted to different templates of one set: a sample of A on part a at unit-box coordinate u, with
/// offset o from its deformed box, goes to the point m_b(u) + o of the mean box b = template_part_map(ta, tb)[a]
/// of B's template and from there to the nearest co-aligned sample of B on part b. Samples whose part has no
/// counterpart (or is null, or empty in B) go to the nearest co-aligned sample of B overall.
/// \param ta, sa, fa  A's template, samples and fit_template(ta, sa); \param tb, sb, fb  the same for B.
/// \throws invalid_input size_mismatch when a fit does not belong to its samples / template.
/// \returns per sample of A, a sample index of B. O(K_a K_b + (P_A + P_B) log P_B).
inline std::vector<index_t> canonical_correspondence(const part_template& ta, const shape_samples& sa,
                                                     const template_fit& fa, const part_template& tb,
                                                     const shape_samples& sb, const template_fit& fb) {
  const auto A = co_aligned_points(ta, sa, fa);
  const auto B = co_aligned_points(tb, sb, fb);
  const auto pmap = template_part_map(ta, tb);
  const index_t K = tb.num_parts();
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
    const index_t a = fa.parts[static_cast<std::size_t>(i)];
    const index_t b = a >= 0 ? pmap[static_cast<std::size_t>(a)] : -1;
    Eigen::Vector3d q = A.row(i).transpose();
    if (b >= 0 && !members[static_cast<std::size_t>(b)].empty()) {
      if (&ta != &tb) {  // move from A's mean box to B's: same unit-box coordinate, same offset
        const auto& pa = ta.parts[static_cast<std::size_t>(a)];
        const auto& pb = tb.parts[static_cast<std::size_t>(b)];
        const Eigen::Vector3d& u = fa.correspondence[static_cast<std::size_t>(i)].u;
        q += (pb.center + pb.axes.transpose() * pb.size.cwiseProduct(u)) -
             (pa.center + pa.axes.transpose() * pa.size.cwiseProduct(u));
      }
      const auto nn = trees[static_cast<std::size_t>(b)].nearest(q);
      out[static_cast<std::size_t>(i)] = members[static_cast<std::size_t>(b)][static_cast<std::size_t>(nn.index)];
    } else {
      out[static_cast<std::size_t>(i)] = all.nearest(q).index;
    }
  }
  return out;
}

/// Correspondences from shape A's samples to shape B's samples through the canonical space (5.4.5): each
/// co-aligned point of A maps to the nearest co-aligned point of B carrying the same part (any point of B when
/// A's point is null or B has no point of that part). Both shapes must be fitted to the same template t.
/// \returns per sample of A, a sample index of B. O((P_A + P_B) log P_B).
inline std::vector<index_t> canonical_correspondence(const part_template& t, const shape_samples& sa,
                                                     const template_fit& fa, const shape_samples& sb,
                                                     const template_fit& fb) {
  return canonical_correspondence(t, sa, fa, t, sb, fb);
}

}  // namespace shapestruct
