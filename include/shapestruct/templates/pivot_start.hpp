// pivot_start: an extra starting arrangement for template fitting, for shapes whose proportions differ from the
// template's.
//
// Why: fitting is a local descent from the mean template. In the canonical frame (unit bounding-box diagonal) a
// bar chair's seat sits a quarter of the diagonal higher than an ordinary chair's, under a short back, so from
// the mean arrangement the back box takes the seat and the seat box stays empty among the legs; the right
// arrangement has the lower energy (COSEG chair 9: 1.19 against 1.28) but no descent from the mean reaches it.
// Neither a uniform stretch to the bounding box nor matching the share of area below each height puts the seat
// there (tried: a thin, wide seat holds much of the area). A piecewise-linear map of the up axis does: one
// template height (a box centre, the pivot) goes to one of several shape heights, what lies below and above is
// stretched to the shape's extent, and the horizontal axes are stretched to the shape's bounding box. Every such
// arrangement is scored by a cheap symmetric chamfer distance between the boxes and the points; the best one is
// handed to the fitter as one more start, which then competes with the four mean starts on fitted energy.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/templates/part_template.hpp"

namespace shapestruct {

/// A starting arrangement of a template's boxes in the frame of rotated shape points.
struct pivot_start_result {
  int rotation = 0;                      ///< index of the rotation whose points it was scored on
  double score = std::numeric_limits<double>::infinity();  ///< symmetric mean squared chamfer distance
  std::vector<Eigen::Vector3d> centers;  ///< per part
  std::vector<Eigen::Vector3d> sizes;    ///< per part, along the part's axes
};

namespace detail {

/// The 8 corners and 6 face centres of the unit box: the template side of best_pivot_start's chamfer score.
inline const std::vector<Eigen::Vector3d>& box_corners_and_faces() {
  static const std::vector<Eigen::Vector3d> points = [] {
    std::vector<Eigen::Vector3d> v;
    for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
    for (int k = 0; k < 3; ++k)
      for (const double side : {-0.5, 0.5}) {
        Eigen::Vector3d u = Eigen::Vector3d::Zero();
        u[k] = side;
        v.push_back(u);
      }
    return v;
  }();
  return points;
}

}  // namespace detail

/// Searches piecewise-linear arrangements of t's mean boxes over the shape points seen under each rotation.
/// \param t          a validated template
/// \param rotated    per rotation, the shape's canonical points rotated into the template frame (#P x 3 each)
/// \param index      kd-tree over the UNROTATED canonical points (queries are rotated back with rotations[r])
/// \param rotations  per rotation, the matrix R with rotated = points * R^T
/// \param heights    shape heights tried per pivot, evenly spread over the shape's extent along the up axis
/// \param unit_samples points on the unit box surface (coordinates in [-0.5, 0.5]) used for the template side
/// \param point_stride every point_stride-th shape point is scored (the score only ranks arrangements; >= 1)
/// \returns the arrangement with the lowest chamfer score (score infinite if there is nothing to try)
/// Complexity: rotations x pivots x heights x (P/stride x K + K x |unit_samples| log P).
[[nodiscard]] inline pivot_start_result best_pivot_start(const part_template& t,
                                                         const std::vector<Eigen::MatrixXd>& rotated,
                                                         const knn_index<double, 3>& index,
                                                         const std::vector<Eigen::Matrix3d>& rotations,
                                                         int heights, const std::vector<Eigen::Vector3d>& unit_samples,
                                                         int point_stride = 4) {
  pivot_start_result best;
  const int up = t.up_axis;
  const std::size_t K = t.parts.size();
  // The template's extent and its candidate pivots (distinct box-centre heights).
  Eigen::Vector3d tlo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), thi = -tlo;
  std::vector<Eigen::Vector3d> half(K);
  for (std::size_t b = 0; b < K; ++b) {
    const auto& box = t.parts[b];
    half[b] = 0.5 * box.axes.cwiseAbs().transpose() * box.size;  // world half-extent of the mean box
    tlo = tlo.cwiseMin(box.center - half[b]);
    thi = thi.cwiseMax(box.center + half[b]);
  }
  std::vector<double> pivots;
  for (const auto& box : t.parts) {
    const double h = box.center[up];
    if (h <= tlo[up] || h >= thi[up]) continue;
    if (std::none_of(pivots.begin(), pivots.end(), [&](double p) { return std::abs(p - h) < 0.02; }))
      pivots.push_back(h);
  }
  std::vector<Eigen::Vector3d> centers(K), sizes(K);
  for (std::size_t r = 0; r < rotated.size(); ++r) {
    const Eigen::MatrixXd& p = rotated[r];
    if (p.rows() == 0) continue;
    const Eigen::Vector3d lo = p.colwise().minCoeff().transpose(), hi = p.colwise().maxCoeff().transpose();
    if (!(hi[up] - lo[up] > 1e-9)) continue;  // a flat shape: every arrangement would crush the boxes
    for (const double ht : pivots)
      for (int j = 0; j < heights; ++j) {
        const double hs = lo[up] + (j + 0.5) / heights * (hi[up] - lo[up]);
        auto map = [&](int a, double v) {
          if (a != up) return thi[a] - tlo[a] > 1e-12 ? lo[a] + (v - tlo[a]) * (hi[a] - lo[a]) / (thi[a] - tlo[a]) : v;
          return v <= ht ? lo[a] + (v - tlo[a]) * (hs - lo[a]) / (ht - tlo[a])
                         : hs + (v - ht) * (hi[a] - hs) / (thi[a] - ht);
        };
        for (std::size_t b = 0; b < K; ++b) {
          const auto& box = t.parts[b];
          Eigen::Vector3d scale;
          for (int a = 0; a < 3; ++a) {
            const double l = map(a, box.center[a] - half[b][a]), h = map(a, box.center[a] + half[b][a]);
            centers[b][a] = 0.5 * (l + h);
            scale[a] = half[b][a] > 1e-12 ? (h - l) / (2 * half[b][a]) : 1.0;
          }
          for (int k = 0; k < 3; ++k)
            sizes[b][k] = box.size[k] * scale.cwiseProduct(box.axes.row(k).transpose()).norm();
        }
        // Symmetric chamfer: shape points to the nearest box surface, box-surface samples to the nearest point.
        double s2t = 0;
        index_t ns = 0;
        for (index_t i = 0; i < p.rows(); i += std::max(point_stride, 1), ++ns) {
          double d = std::numeric_limits<double>::infinity();
          for (std::size_t b = 0; b < K; ++b)
            d = std::min(d, detail::closest_on_box_surface(t.parts[b].axes, centers[b], sizes[b],
                                                           p.row(i).transpose()).second);
          s2t += d;
        }
        double t2s = 0;
        for (std::size_t b = 0; b < K; ++b)
          for (const auto& u : unit_samples) {
            const Eigen::Vector3d y = centers[b] + t.parts[b].axes.transpose() * sizes[b].cwiseProduct(u);
            const Eigen::Vector3d q = rotations[r].transpose() * y;
            t2s += index.nearest(q).sq_distance;
          }
        const double score = s2t / static_cast<double>(std::max<index_t>(ns, 1)) +
                             t2s / static_cast<double>(std::max<std::size_t>(K * unit_samples.size(), 1));
        if (score < best.score) {
          best.score = score;
          best.rotation = static_cast<int>(r);
          best.centers = centers;
          best.sizes = sizes;
        }
      }
  }
  return best;
}

}  // namespace shapestruct
