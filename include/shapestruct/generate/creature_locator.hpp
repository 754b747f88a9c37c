// SPDX-License-Identifier: MIT
// creature_locator: finds the face and barycentric coordinates of a common-domain point on one creature.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/surface_point.hpp"
#include "shapestruct/generate/creature.hpp"

namespace shapestruct {

/// Point location in a creature's common domain. Every face of a creature lies inside one patch, where it is
/// a straight triangle in (u, v); locating (patch, u, v) is therefore a 2D point-in-triangle test among that
/// patch's faces, and the barycentric weights found in (u, v) are exactly the weights of the surface point.
template <class Scalar = double>
class creature_locator {
 public:
  /// Indexes the faces of `c` by patch. O(F). Keeps a reference to `c`, which must outlive the locator.
  /// \throws invalid_input (size_mismatch) if the ground-truth arrays do not match the mesh.
  explicit creature_locator(const creature<Scalar>& c) : c_(c) {
    const index_t nf = c.mesh.num_faces();
    if (static_cast<index_t>(c.face_patch.size()) != nf || c.face_uv.rows() != nf)
      throw invalid_input(input_error::size_mismatch, no_index,
                          "creature_locator: face_patch and face_uv must have one entry per face (" +
                              std::to_string(nf) + ")");
    index_t max_patch = -1;
    for (const index_t p : c.face_patch) max_patch = std::max(max_patch, p);
    by_patch_.assign(static_cast<std::size_t>(max_patch + 1), {});
    for (index_t f = 0; f < nf; ++f)
      if (c.face_patch[static_cast<std::size_t>(f)] >= 0)
        by_patch_[static_cast<std::size_t>(c.face_patch[static_cast<std::size_t>(f)])].push_back(f);
  }

  /// True if the creature has faces in `patch`.
  [[nodiscard]] bool has_patch(index_t patch) const noexcept {
    return patch >= 0 && patch < static_cast<index_t>(by_patch_.size()) &&
           !by_patch_[static_cast<std::size_t>(patch)].empty();
  }

  /// The surface point at `p`, or an invalid surface_point (face == no_index) if this creature lacks the
  /// patch (the body part is missing). Points a rounding error outside every triangle go to the nearest one,
  /// with weights clamped to [0, 1]. O(faces in the patch), about 2 * resolution^2.
  [[nodiscard]] surface_point<Scalar> locate(const canonical_point& p) const {
    surface_point<Scalar> out;
    if (!has_patch(p.patch)) return out;
    double best = -std::numeric_limits<double>::infinity();
    double bw[3] = {0, 0, 0};
    for (const index_t f : by_patch_[static_cast<std::size_t>(p.patch)]) {
      double w[3];
      if (!bary(f, p.u, p.v, w)) continue;
      const double worst = std::min({w[0], w[1], w[2]});
      if (worst > best) {
        best = worst;
        out.face = f;
        std::copy(w, w + 3, bw);
        if (worst >= 0) break;  // inside: faces of one patch do not overlap, so this is the one
      }
    }
    if (out.face == no_index) return out;
    double sum = 0;
    for (double& x : bw) sum += (x = std::clamp(x, 0.0, 1.0));
    for (int k = 0; k < 3; ++k) out.bary[k] = static_cast<Scalar>(bw[k] / sum);
    return out;
  }

  /// The common-domain coordinates of a surface point of this creature (the inverse of locate).
  [[nodiscard]] canonical_point canonical_of(const surface_point<Scalar>& s) const {
    canonical_point out;
    if (!s.valid()) return out;
    out.patch = c_.face_patch[static_cast<std::size_t>(s.face)];
    for (int k = 0; k < 3; ++k) {
      out.u += static_cast<double>(s.bary[k]) * c_.face_uv(s.face, 2 * k);
      out.v += static_cast<double>(s.bary[k]) * c_.face_uv(s.face, 2 * k + 1);
    }
    return out;
  }

 private:
  bool bary(index_t f, double u, double v, double* w) const {
    const auto& t = c_.face_uv;
    const double x0 = t(f, 0), y0 = t(f, 1), x1 = t(f, 2), y1 = t(f, 3), x2 = t(f, 4), y2 = t(f, 5);
    const double det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    if (!(std::abs(det) > 1e-300)) return false;
    w[1] = ((u - x0) * (y2 - y0) - (x2 - x0) * (v - y0)) / det;
    w[2] = ((x1 - x0) * (v - y0) - (u - x0) * (y1 - y0)) / det;
    w[0] = 1.0 - w[1] - w[2];
    return true;
  }

  const creature<Scalar>& c_;
  std::vector<std::vector<index_t>> by_patch_;
};

}  // namespace shapestruct
