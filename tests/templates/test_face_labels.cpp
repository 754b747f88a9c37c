// SPDX-License-Identifier: MIT
// project_labels_to_faces: votes, the fuzzy-cut boundary placement on manifold meshes, soups, bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/templates/face_labels.hpp"
#include "support/fixtures.hpp"

using namespace shapestruct;

namespace {

using surface_fn = std::function<Eigen::Vector3d(double u, double y)>;

/// A strip [0, u_max] x [0, 1] of the (u, y) plane, nu x ny cells of two triangles, mapped into space by `at`.
/// Triangles are counter-clockwise in (u, y), so normals are d(at)/du x d(at)/dy.
triangle_mesh<double> strip(const surface_fn& at, double u_max, int nu, int ny) {
  triangle_mesh<double> m;
  m.V.resize((nu + 1) * (ny + 1), 3);
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= ny; ++j) m.V.row(i * (ny + 1) + j) = at(u_max * i / nu, double(j) / ny).transpose();
  m.F.resize(2 * nu * ny, 3);
  int f = 0;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < ny; ++j) {
      const int a = i * (ny + 1) + j, b = a + ny + 1;
      m.F.row(f++) << a, b, b + 1;
      m.F.row(f++) << a, b + 1, a + 1;
    }
  return m;
}

/// Flat for u <= 1, then straight up (a concave, valley crease at u = 1 seen from the normal side), then for the
/// Z fold flat again from u = 2 (a convex, ridge crease).
Eigen::Vector3d z_fold(double u, double y) {
  if (u <= 1) return {u, y, 0};
  if (u <= 2) return {1, y, u - 1};
  return {u - 1, y, 1};
}

/// Samples on a finer grid of the same strip, labeled by whether u is below `boundary_u`.
std::pair<shape_samples, std::vector<index_t>> samples_on(const surface_fn& at, double u_max, double h,
                                                          double boundary_u) {
  std::vector<Eigen::Vector3d> pts;
  std::vector<index_t> labels;
  for (double u = h / 2; u < u_max; u += h)
    for (double y = h / 2; y < 1; y += h) {
      pts.push_back(at(u, y));
      labels.push_back(u < boundary_u ? 0 : 1);
    }
  shape_samples s;
  s.points.resize(static_cast<index_t>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) s.points.row(static_cast<index_t>(i)) = pts[i].transpose();
  return {s, labels};
}

/// The u coordinate of a face's centroid on the Z fold (inverse of z_fold on the centroid).
double centroid_u(const triangle_mesh<double>& m, index_t f) {
  const Eigen::RowVector3d c = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3.0;
  if (c.z() < 1e-9) return c.x();
  if (c.z() > 1 - 1e-9) return c.x() + 1;
  return 1 + c.z();
}

}  // namespace

TEST_CASE("fuzzy-cut capacities: concave creases are cheaper to cut than convex ones, both cheaper than flat") {
  const auto m = strip(z_fold, 3.0, 30, 10);
  const auto edges = detail::fuzzy_cut_edges(m, 0.2);
  double concave = -1, convex = -1, flat_min = 1e9;
  for (const auto& e : edges) {
    const double ua = centroid_u(m, e.a), ub = centroid_u(m, e.b);
    const bool across_1 = std::min(ua, ub) < 1 && std::max(ua, ub) > 1;
    const bool across_2 = std::min(ua, ub) < 2 && std::max(ua, ub) > 2;
    if (across_1) concave = e.weight;
    else if (across_2) convex = e.weight;
    else flat_min = std::min(flat_min, e.weight);
  }
  REQUIRE(concave > 0);
  REQUIRE(convex > 0);
  CHECK(concave < convex);
  CHECK(convex < flat_min);
  // Without the convexity distinction (eta 1 for both) the two creases cost the same.
  double c1 = -1, c2 = -1;
  for (const auto& e : detail::fuzzy_cut_edges(m, 1.0)) {
    const double ua = centroid_u(m, e.a), ub = centroid_u(m, e.b);
    if (std::min(ua, ub) < 1 && std::max(ua, ub) > 1) c1 = e.weight;
    if (std::min(ua, ub) < 2 && std::max(ua, ub) > 2) c2 = e.weight;
  }
  CHECK(c1 == doctest::Approx(c2));
}

TEST_CASE("project_labels_to_faces: the fuzzy cut moves a boundary the samples place near a crease onto it") {
  const auto m = strip(z_fold, 2.0, 40, 20);  // flat, then the concave crease at u = 1, then the wall
  const auto [s, labels] = samples_on(z_fold, 2.0, 0.05, 0.9);  // the samples' boundary is 0.1 before the crease
  face_label_options vote_only;
  vote_only.smooth_manifold = false;
  const auto voted = project_labels_to_faces(m, s, labels, vote_only);
  const auto cut = project_labels_to_faces(m, s, labels);
  int voted_wrong = 0, cut_wrong = 0;
  for (index_t f = 0; f < m.F.rows(); ++f) {
    const index_t truth = centroid_u(m, f) < 1 ? 0 : 1;  // the part boundary is the crease
    voted_wrong += voted[static_cast<std::size_t>(f)] != truth;
    cut_wrong += cut[static_cast<std::size_t>(f)] != truth;
    // Faces far from the samples' boundary are fixed: all their fuzzy voters agree.
    if (centroid_u(m, f) < 0.6 || centroid_u(m, f) > 1.3) CHECK(cut[static_cast<std::size_t>(f)] == truth);
  }
  CHECK(voted_wrong >= 2 * 20);  // the two columns of cells between u = 0.9 and 1 follow the samples
  CHECK(cut_wrong == 0);
}

TEST_CASE("project_labels_to_faces: a polygon soup (no shared edges) keeps the nearest-sample vote") {
  const auto m = strip(z_fold, 2.0, 20, 10);
  const auto soup = test::as_soup(m);
  const auto [s, labels] = samples_on(z_fold, 2.0, 0.05, 0.9);
  face_label_options vote_only;
  vote_only.smooth_manifold = false;
  CHECK(project_labels_to_faces(soup, s, labels) == project_labels_to_faces(soup, s, labels, vote_only));
  CHECK(project_labels_to_faces(soup, s, labels) == project_labels_to_faces(m, s, labels, vote_only));
}

TEST_CASE("project_labels_to_faces: null labels do not vote, bad input is a typed error") {
  const auto m = strip(z_fold, 2.0, 10, 5);
  auto [s, labels] = samples_on(z_fold, 2.0, 0.1, 0.9);
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (s.points(static_cast<index_t>(i), 0) > 0.5 && labels[i] == 0) labels[i] = -1;  // unlabeled middle
  const auto out = project_labels_to_faces(m, s, labels);
  for (const auto l : out) CHECK((l == 0 || l == 1));
  auto check_reason = [&](const std::vector<index_t>& lab, const face_label_options& o, input_error reason) {
    try {
      (void)project_labels_to_faces(m, s, lab, o);
      FAIL("expected invalid_input");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == reason);
    }
  };
  check_reason(std::vector<index_t>(labels.size() - 1, 0), {}, input_error::size_mismatch);
  check_reason(std::vector<index_t>(labels.size(), -1), {}, input_error::empty);
  face_label_options bad;
  bad.fuzzy_voters = 0;
  check_reason(labels, bad, input_error::bad_parameter);
  bad = {};
  bad.convex_eta = std::nan("");
  check_reason(labels, bad, input_error::bad_parameter);
  triangle_mesh<double> broken = m;
  broken.V(0, 0) = std::nan("");
  CHECK_THROWS_AS((void)project_labels_to_faces(broken, s, labels), invalid_input);
}
