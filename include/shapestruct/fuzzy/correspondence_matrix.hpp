// SPDX-License-Identifier: MIT
// correspondence_matrix: the sparse, row-normalised NK x NK matrix C of ch. 4.3.5 as a matrix-free operator.
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"

namespace shapestruct {

/// One edge of the alignment graph as it enters C: the shapes and the chosen alternative's scores a(p_i, p_j)
/// (rows: samples of `source`, columns: samples of `target`).
struct correspondence_edge {
  index_t source = no_index;
  index_t target = no_index;
  const Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>* scores = nullptr;
};

/// The correspondence matrix of a collection (eq. 4.6), one block of W per edge (its target reads it transposed),
/// never assembled: for an edge (k, l) the block C(P_k, P_l) is a(., .) with every row normalised to sum 1 (each
/// point is mapped somewhere with constant energy) and C(P_l, P_k) is a^T row-normalised likewise. Diffusion
/// needs a symmetric kernel, so the operator is W = (C + C^T) / 2 with degrees d = W 1, applied as the symmetric
/// normalised form A = D^-1/2 W D^-1/2, whose eigenvectors U give the right eigenvectors D^-1/2 U of the
/// random walk D^-1 W (Nadler et al.'s normalisation). A tiny self-weight keeps every degree positive.
/// Models LinearOperator (Spectra's requirements), so any EmbeddingSolver can take it. perform_op runs in
/// parallel over shapes (each writes only its own rows), so results do not depend on the thread count.
class correspondence_matrix {
 public:
  using Scalar = double;

  /// \param sample_counts K_i per shape  \param edges the graph's edges with their chosen alternatives
  /// \param threads std::threads for the products (0 = all cores)
  /// \throws invalid_input: bad_parameter for an edge naming a shape out of range, without a block, or with a
  ///         negative or non-finite score; size_mismatch for a block of the wrong size.
  correspondence_matrix(std::span<const index_t> sample_counts, std::span<const correspondence_edge> edges,
                        int threads = 0)
      : correspondence_matrix(sample_counts, pairs_of(edges), [&edges](index_t e) -> const score_block& {
          return *edges[std::size_t(e)].scores;
        }, threads) {}

  /// Builds C from edges whose score blocks are fetched one at a time, `score_block_of(e)` giving edge e's block
  /// (by value or reference; called once per edge, from up to `threads` threads at once), so that only the blocks
  /// of W are held, not a second copy of every score block (a collection's cache folder can serve them).
  /// \param sample_counts K_i per shape  \param edges (source, target) per edge
  /// \throws as the constructor above (the first bad edge is named, whatever the thread count), and whatever
  ///         score_block_of throws.
  template <class ScoreBlockOf>
    requires std::invocable<ScoreBlockOf&, index_t>
  correspondence_matrix(std::span<const index_t> sample_counts, std::span<const std::pair<index_t, index_t>> edges,
                        ScoreBlockOf&& score_block_of, int threads = 0)
      : threads_(detail::resolve_threads(threads, "correspondence_matrix")) {
    const char* who = "correspondence_matrix";
    const index_t N = static_cast<index_t>(sample_counts.size());
    offset_.assign(static_cast<std::size_t>(N + 1), 0);
    for (index_t i = 0; i < N; ++i) offset_[std::size_t(i + 1)] = offset_[std::size_t(i)] + sample_counts[std::size_t(i)];
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [source, target] = edges[e];
      if (source < 0 || source >= N || target < 0 || target >= N || source == target)
        throw invalid_input(input_error::bad_parameter, static_cast<index_t>(e),
                            std::string(who) + ": edge " + std::to_string(e) + " names shapes " +
                                std::to_string(source) + " and " + std::to_string(target) + " of " + std::to_string(N));
    }
    blocks_.resize(edges.size());
    std::vector<std::optional<invalid_input>> failed(edges.size());
    detail::parallel_for(static_cast<index_t>(edges.size()), threads_, [&](index_t e) {
      const auto [source, target] = edges[std::size_t(e)];
      const auto& a = score_block_of(e);
      const index_t rows = sample_counts[std::size_t(source)], cols = sample_counts[std::size_t(target)];
      if (a.rows() != rows || a.cols() != cols) {
        failed[std::size_t(e)].emplace(input_error::size_mismatch, e,
                                       std::string(who) + ": edge " + std::to_string(e) + " has a " +
                                           std::to_string(a.rows()) + " x " + std::to_string(a.cols()) +
                                           " score block for shapes of " + std::to_string(rows) + " and " +
                                           std::to_string(cols) + " samples");
        return;
      }
      for (index_t k = 0; k < a.nonZeros(); ++k) {
        const float v = a.valuePtr()[k];
        if (!(v >= 0.0f) || !std::isfinite(v)) {
          failed[std::size_t(e)].emplace(input_error::bad_parameter, e,
                                         std::string(who) + ": edge " + std::to_string(e) +
                                             " has a negative or non-finite score");
          return;
        }
      }
      const block_matrix forward = row_normalised(a.template cast<double>());
      const block_matrix backward = row_normalised(block_matrix(a.template cast<double>().transpose()));
      // W(P_k, P_l) = (C(P_k, P_l) + C(P_l, P_k)^T) / 2, stored once: W(P_l, P_k) is its transpose.
      blocks_[std::size_t(e)] = {source, target, 0.5 * (forward + block_matrix(backward.transpose()))};
    });
    for (auto& f : failed)
      if (f) throw *f;
    incident_.resize(static_cast<std::size_t>(N));
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      incident_[std::size_t(blocks_[b].source)].push_back({static_cast<index_t>(b), true});
      incident_[std::size_t(blocks_[b].target)].push_back({static_cast<index_t>(b), false});
    }
    const index_t n = offset_.back();
    degree_.setConstant(n, self_weight);
    for (const auto& B : blocks_) {
      const index_t os = offset_[std::size_t(B.source)], ot = offset_[std::size_t(B.target)];
      for (index_t r = 0; r < B.w.outerSize(); ++r)
        for (block_matrix::InnerIterator it(B.w, r); it; ++it) {
          degree_[os + r] += it.value();
          degree_[ot + it.col()] += it.value();
        }
    }
    inv_sqrt_degree_ = degree_.cwiseSqrt().cwiseInverse();
  }

  [[nodiscard]] index_t rows() const noexcept { return offset_.back(); }
  [[nodiscard]] index_t cols() const noexcept { return offset_.back(); }
  [[nodiscard]] index_t shapes() const noexcept { return static_cast<index_t>(incident_.size()); }
  /// First row of shape k (rows of shape k are offset(k) .. offset(k + 1) - 1).
  [[nodiscard]] index_t offset(index_t k) const { return offset_[std::size_t(k)]; }
  [[nodiscard]] const vector_x<double>& degrees() const noexcept { return degree_; }
  [[nodiscard]] const vector_x<double>& inverse_sqrt_degrees() const noexcept { return inv_sqrt_degree_; }

  /// y = D^-1/2 W D^-1/2 x (Spectra's operator interface).
  void perform_op(const double* x_in, double* y_out) const {
    const index_t n = rows();
    Eigen::Map<const vector_x<double>> x(x_in, n);
    Eigen::Map<vector_x<double>> y(y_out, n);
    detail::parallel_for(shapes(), threads_, [&](index_t k) {
      const index_t o = offset_[std::size_t(k)];
      const index_t m = offset_[std::size_t(k + 1)] - o;
      vector_x<double> acc = self_weight * x.segment(o, m).cwiseProduct(inv_sqrt_degree_.segment(o, m));
      for (const auto& [b, is_source] : incident_[std::size_t(k)]) {
        const edge_block& B = blocks_[std::size_t(b)];
        if (is_source) {
          const index_t oo = offset_[std::size_t(B.target)];
          acc.noalias() += B.w * x.segment(oo, B.w.cols()).cwiseProduct(inv_sqrt_degree_.segment(oo, B.w.cols()));
        } else {
          const index_t oo = offset_[std::size_t(B.source)];
          acc.noalias() +=
              B.w.transpose() * x.segment(oo, B.w.rows()).cwiseProduct(inv_sqrt_degree_.segment(oo, B.w.rows()));
        }
      }
      y.segment(o, m) = acc.cwiseProduct(inv_sqrt_degree_.segment(o, m));
    });
  }

  /// The weight every point gives itself: small enough to leave the diffusion unchanged, large enough that a
  /// point whose scores all underflowed still has a positive degree.
  static constexpr double self_weight = 1e-6;

 private:
  using block_matrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  using score_block = Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>;
  struct edge_block {
    index_t source = no_index, target = no_index;
    block_matrix w;  ///< W(P_source, P_target): rows the source's samples, columns the target's
  };
  struct incident_edge {
    index_t block;   ///< index into blocks_
    bool is_source;  ///< this shape is the block's source (its rows), else its target (its columns)
  };

  /// The (source, target) pairs of `edges`. \throws invalid_input (bad_parameter) for an edge without scores.
  static std::vector<std::pair<index_t, index_t>> pairs_of(std::span<const correspondence_edge> edges) {
    std::vector<std::pair<index_t, index_t>> pairs;
    pairs.reserve(edges.size());
    for (std::size_t e = 0; e < edges.size(); ++e) {
      if (!edges[e].scores)
        throw invalid_input(input_error::bad_parameter, static_cast<index_t>(e),
                            "correspondence_matrix: edge " + std::to_string(e) + " (shapes " +
                                std::to_string(edges[e].source) + " and " + std::to_string(edges[e].target) +
                                ") has no score block");
      pairs.push_back({edges[e].source, edges[e].target});
    }
    return pairs;
  }

  static block_matrix row_normalised(block_matrix a) {
    for (index_t r = 0; r < a.outerSize(); ++r) {
      double s = 0;
      for (block_matrix::InnerIterator it(a, r); it; ++it) s += it.value();
      if (s > 0)
        for (block_matrix::InnerIterator it(a, r); it; ++it) it.valueRef() /= s;
    }
    return a;
  }

  unsigned threads_ = 1;
  std::vector<index_t> offset_;
  std::vector<edge_block> blocks_;
  std::vector<std::vector<incident_edge>> incident_;
  vector_x<double> degree_;
  vector_x<double> inv_sqrt_degree_;
};

}  // namespace shapestruct
