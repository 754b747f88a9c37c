// SPDX-License-Identifier: MIT
// region_query: how every shape of a collection compares with a region of interest on one example (ch. 4.5.3).
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>
#include <Eigen/Core>
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/explore/affine_alignment.hpp"
#include "shapestruct/explore/region.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"
#include "shapestruct/knn/knn_index.hpp"

namespace shapestruct {

/// Options of region_query.
struct region_query_options {
  /// alpha: the weight of the fuzzy correspondences of unselected example points in the alignment T_R, which
  /// keeps it stable for small regions; <= 0 means the chapter's 1 / (4K), K the example's sample count.
  double damping = 0;
  /// Also measure the region against the aligned target (see region_match::distance). The chapter's term alone
  /// cannot see geometry a target lacks: a chair without arms has no points to misplace, so its arm-region
  /// distance is as small as an armed chair's.
  bool symmetric = true;
  /// Bound on T_R's anisotropy (affine_least_squares::solve): its singular values stay within this factor of
  /// their median, and it never reflects. A shape lacking the region has counterparts that are no affine image of
  /// it, and the chapter's unbounded fit then flattens that shape; 0 = the unbounded fit.
  double max_stretch = 1.5;
  int threads = 0;  ///< 0 = all cores, for distances(); the result does not depend on it
};

/// One target shape against a region R on an example shape S_i (ch. 4.5.3).
struct region_match {
  index_t shape = 0;
  /// D_R(S_j) = sum_p D(T_R(p), S_i) f_R(p) / sum_p f_R(p) (ch. 4.5.3): the f_R-weighted Euclidean distance
  /// from the aligned target samples to the example's surface, in the example's units. With the symmetric option
  /// (the default) the mean of that and of the distance from R's samples to the aligned target's surface (what
  /// of the region the target has). +infinity when no sample of the target corresponds to R at all (f_R = 0
  /// everywhere), 0 for the example itself.
  double distance = 0;
  /// T_R(S_j): the affine map from the target's coordinates to the example's that best aligns its fuzzy
  /// correspondences (those of R fully, the rest damped by alpha), in the weighted least-squares sense.
  affine_transform transform = identity_affine();
  /// f_R(p) = max over p' in R of f(p', p) f(p, p') for every sample p of the target.
  Eigen::VectorXd correspondence;
  /// The orbit centre: the f_R-weighted centroid of the aligned target samples (their plain centroid when f_R = 0).
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();

  /// f_R normalised by its maximum within the shape (ch. 4.5.2: the highlight is visible on every shape).
  [[nodiscard]] Eigen::VectorXd highlight() const {
    const double top = correspondence.size() > 0 ? correspondence.maxCoeff() : 0.0;
    return top > 0 ? Eigen::VectorXd(correspondence / top) : Eigen::VectorXd::Zero(correspondence.size());
  }
};

/// A region of interest prepared for many targets: the example's surface in a kd-tree and its selection mask.
/// Reads f and records; both must outlive the query. Thread-safe: match() may run concurrently.
class region_query {
 public:
  /// \throws invalid_input: as checked_region for a bad region; size_mismatch when records and f disagree.
  region_query(const fuzzy_correspondence& f, std::span<const shape_record> records, region r,
               const region_query_options& options = {})
      : f_(&f), records_(records), region_(checked_region(f.embedding(), std::move(r))) {
    if (static_cast<index_t>(records.size()) != f.shapes())
      throw invalid_input(input_error::size_mismatch, no_index,
                          "region_query: " + std::to_string(records.size()) + " records for a fuzzy correspondence of " +
                              std::to_string(f.shapes()) + " shapes");
    for (index_t k = 0; k < f.shapes(); ++k)
      if (records[std::size_t(k)].sample_count() != f.embedding().samples_of(k))
        throw invalid_input(input_error::size_mismatch, k,
                            "region_query: shape " + std::to_string(k) + " has " +
                                std::to_string(records[std::size_t(k)].sample_count()) + " samples in its record and " +
                                std::to_string(f.embedding().samples_of(k)) + " in the embedding");
    const shape_record& example = records[std::size_t(region_.shape)];
    const index_t K = example.sample_count();
    selected_.assign(std::size_t(K), 0);
    for (const index_t s : region_.samples) selected_[std::size_t(s)] = 1;
    damping_ = options.damping > 0 ? options.damping : 1.0 / (4.0 * double(K));
    threads_ = options.threads;
    symmetric_ = options.symmetric;
    max_stretch_ = options.max_stretch;
    surface_ = knn_index<double, 3>(example.surface_points.rows() > 0 ? example.surface_points : example.samples);
  }

  [[nodiscard]] const region& selection() const noexcept { return region_; }
  [[nodiscard]] double damping() const noexcept { return damping_; }

  /// The target shape j against the region. O(K_i K_j d) for the block of f, O(K_j log M) for the distances.
  [[nodiscard]] region_match match(index_t j) const {
    const fuzzy_correspondence& f = *f_;
    if (j < 0 || j >= f.shapes())
      throw invalid_input(input_error::bad_parameter, j, "region_query: shape " + std::to_string(j) + " is not in the collection");
    const index_t i = region_.shape;
    const auto& X = f.embedding().coordinates;
    const index_t oi = f.embedding().offset(i), oj = f.embedding().offset(j);
    const index_t Ki = f.embedding().samples_of(i), Kj = f.embedding().samples_of(j);
    const auto& example = records_[std::size_t(i)].samples;
    const auto& target = records_[std::size_t(j)].samples;

    // Squared diffusion distances between every example sample (rows) and every target sample (columns).
    const Eigen::MatrixXf A = X.middleRows(oi, Ki), B = X.middleRows(oj, Kj);
    Eigen::MatrixXf D2 = -2.0f * A * B.transpose();
    D2.colwise() += A.rowwise().squaredNorm();
    D2.rowwise() += B.rowwise().squaredNorm().transpose();

    region_match m;
    m.shape = j;
    m.correspondence = Eigen::VectorXd::Zero(Kj);
    for (index_t q = 0; q < Kj; ++q) {
      const double tau_q = double(f.tau()[oj + q]);
      double best = 0;
      for (const index_t p : region_.samples) {
        const double d2 = std::max(0.0, double(D2(p, q)));
        best = std::max(best, value(d2, double(f.tau()[oi + p])) * value(d2, tau_q));
      }
      m.correspondence[q] = best;
    }
    // T_R: every example sample paired with its best fuzzy correspondence on the target, weighted by their
    // mutual f (damped by alpha off the region). Pairing with all of a point's fuzzy correspondences instead
    // regresses each point onto a weighted mean of a wide neighbourhood, and the least-squares affine map then
    // collapses towards the centroid (on generated chairs it scaled the up axis by 0.1).
    affine_least_squares fit;
    for (index_t p = 0; p < Ki; ++p) {
      index_t q = 0;
      D2.row(p).minCoeff(&q);
      const double d2 = std::max(0.0, double(D2(p, q)));
      const double mutual = value(d2, double(f.tau()[oi + p])) * value(d2, double(f.tau()[oj + q]));
      fit.add(target.row(q).transpose(), example.row(p).transpose(), selected_[std::size_t(p)] ? mutual : damping_ * mutual);
    }
    if (j == i) {  // the example against itself: already in its own frame
      m.transform = identity_affine();
    } else {
      m.transform = fit.solve(1e-9, max_stretch_);
    }
    const double total = m.correspondence.sum();
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double distance = 0;
    for (index_t q = 0; q < Kj; ++q) {
      const Eigen::Vector3d y = apply(m.transform, target.row(q).transpose());
      const double w = total > 0 ? m.correspondence[q] : 1.0 / double(Kj);
      if (w == 0) continue;
      centre += w * y;
      if (total > 0 && j != i) distance += w * std::sqrt(double(surface_.nearest(y).sq_distance));
    }
    m.centre = total > 0 ? Eigen::Vector3d(centre / total) : centre;
    m.distance = j == i ? 0.0 : total > 0 ? distance / total : std::numeric_limits<double>::infinity();
    if (symmetric_ && j != i && total > 0) m.distance = 0.5 * (m.distance + region_to_target(m.transform, j));
    return m;
  }

  /// D_R of every shape of the collection (index = shape), in parallel over shapes.
  [[nodiscard]] std::vector<double> distances() const {
    std::vector<double> d(static_cast<std::size_t>(f_->shapes()));
    detail::parallel_for(f_->shapes(), detail::resolve_threads(threads_, "region_query"),
                         [&](index_t j) { d[std::size_t(j)] = match(j).distance; });
    return d;
  }

 private:
  // Mean distance from the region's samples to the target's surface mapped by T (brute force: |R| x M is small).
  [[nodiscard]] double region_to_target(const affine_transform& T, index_t j) const {
    const shape_record& target = records_[std::size_t(j)];
    const auto& P = target.surface_points.rows() > 0 ? target.surface_points : target.samples;
    const Eigen::Matrix<double, Eigen::Dynamic, 3> Y =
        (P * T.leftCols<3>().transpose()).rowwise() + T.col(3).transpose();
    const auto& example = records_[std::size_t(region_.shape)].samples;
    double sum = 0;
    for (const index_t s : region_.samples)
      sum += std::sqrt((Y.rowwise() - example.row(s)).rowwise().squaredNorm().minCoeff());
    return sum / double(region_.samples.size());
  }

  // eq. 4.9 with the cutoff, as fuzzy_correspondence::value
  [[nodiscard]] double value(double d2, double tau) const {
    const double t2 = tau * tau, c = f_->cutoff();
    if (d2 > c * c * t2) return 0.0;
    if (!(t2 > 0)) return d2 > 0 ? 0.0 : 1.0;
    return std::exp(-d2 / t2);
  }

  const fuzzy_correspondence* f_;
  std::span<const shape_record> records_;
  region region_;
  std::vector<char> selected_;
  double damping_ = 0;
  int threads_ = 0;
  bool symmetric_ = true;
  double max_stretch_ = 1.5;
  knn_index<double, 3> surface_;
};

}  // namespace shapestruct
