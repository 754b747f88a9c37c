// SPDX-License-Identifier: MIT
// pair_alignment: the alternatives one pairwise alignment leaves on an edge of the alignment graph.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "shapestruct/core/types.hpp"

namespace shapestruct {

/// One way of aligning shape k (source) to shape l (target): the per-point alignment scores a(p_i, p_j) of
/// eq. 4.1 between the samples of the two shapes, and what produced them.
struct alignment_alternative {
  /// (K_k x K_l) a(p_i in S_k, p_j in S_l) = L_a(p_i, p_j) * B_a, row-major and sparse: entries far below a
  /// row's largest are dropped (see the aligner's options), so a row holds the neighbourhood of p_i's image.
  Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t> scores;
  double global_score = 0;  ///< B_a (eq. 4.3 or 4.5), in [0, 1]; the initial alternative maximises it
  /// What produced the alternative, enough to rebuild a dense map later: for extrinsic alignments the 12
  /// entries of the 3 x 4 affine transform taking target points into the source's frame (column-major); for
  /// intrinsic ones the index of the blended map among the matcher's candidates. Free-form for user aligners.
  std::vector<double> parameters;
};

/// Every alternative a pairwise aligner produced for the pair (source, target); `initial` is the one with the
/// highest global score, which the initial alignment graph uses (ch. 4.3.3-4.3.4). The graph optimisation may
/// later pick another (ch. 4.3.7).
struct pair_alignment {
  index_t source = no_index;
  index_t target = no_index;
  std::vector<alignment_alternative> alternatives;
  index_t initial = 0;
  /// The alternative the aligner itself would pick when it judges by more than the global score (the blended
  /// matcher's selection, which can tell a map from its symmetric flip); no_index when it has no such choice.
  /// The collection's orientation (collection_orientation.hpp) is voted from it.
  index_t preferred = no_index;
  double seconds = 0;  ///< wall time of the alignment (for the timing report)
};

/// Index of the alternative with the highest global score (ties: the lower index); 0 when there is none.
[[nodiscard]] inline index_t best_global_alternative(std::span<const alignment_alternative> alternatives) {
  index_t best = 0;
  for (std::size_t a = 1; a < alternatives.size(); ++a)
    if (alternatives[a].global_score > alternatives[static_cast<std::size_t>(best)].global_score)
      best = static_cast<index_t>(a);
  return best;
}

}  // namespace shapestruct
