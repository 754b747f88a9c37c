// SPDX-License-Identifier: MIT
// refined_fuzzy_alignment / refined_fuzzy_vertex_map: on moved copies of one shape (upright, or tipped over with no
// up axis) the collection's best fuzzy correspondence, refined by one ICP, recovers the true transform and the true
// vertex map; bad input throws.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "fuzzy/extrinsic_fixtures.hpp"
#include "shapestruct/collection/make_shape_record.hpp"
#include "shapestruct/collection/spherical_harmonic_descriptor.hpp"
#include "shapestruct/fuzzy/fuzzy_collection.hpp"
#include "shapestruct/fuzzy/refined_fuzzy_alignment.hpp"

using namespace shapestruct;

namespace {

using points = Eigen::Matrix<double, Eigen::Dynamic, 3>;

/// x -> scale R(angle about y) x + shift.
struct upright_move {
  double angle, scale;
  Eigen::Vector3d shift;
  [[nodiscard]] Eigen::Vector3d operator()(const Eigen::Vector3d& x) const {
    return scale * (Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()) * x) + shift;
  }
};

struct moved_copies {
  std::vector<triangle_mesh<double>> meshes;
  std::vector<shape_record> records;
};

/// Copy k moved by an upright move, or with `tilted` also tipped over about a horizontal axis (no common up).
moved_copies make_copies(int count, bool tilted = false) {
  moved_copies c;
  const triangle_mesh<double> base = test::asymmetric_shape();
  const spherical_harmonic_descriptor describe;
  for (int k = 0; k < count; ++k) {
    const upright_move move{0.9 * k, 1.0 + 0.15 * k, Eigen::Vector3d(2.0 * k, 0.1 * k, -1.0 * k)};
    const Eigen::Matrix3d tip =
        tilted ? Eigen::AngleAxisd(0.7 * k, Eigen::Vector3d(1, 0, 0.4 * k).normalized()).toRotationMatrix()
               : Eigen::Matrix3d::Identity();
    triangle_mesh<double> m = base;
    for (index_t v = 0; v < m.V.rows(); ++v) m.V.row(v) = move(tip * base.V.row(v).transpose()).transpose();
    c.records.push_back(make_shape_record(m, "copy" + std::to_string(k), describe,
                                          {.samples = 48, .surface_points = 512, .metric = sample_metric::euclidean}));
    c.meshes.push_back(std::move(m));
  }
  return c;
}

fuzzy_collection_result collection_of(const moved_copies& c, const extrinsic_alignment_options& options = {}) {
  fuzzy_collection_options o;
  o.threads = 1;
  o.embedding.dimensions = 16;
  return compute_fuzzy_correspondences(c.records, extrinsic_aligner(c.records, options), o, dense_embedding_solver{});
}

/// The largest distance between a vertex of b taken into a's frame by the alignment and the same vertex of a (the
/// copies share vertex ids).
double worst_vertex_error(const moved_copies& c, index_t a, index_t b, const alignment_alternative& alt) {
  const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(alt);
  double worst = 0;
  for (index_t v = 0; v < c.meshes[std::size_t(b)].V.rows(); ++v) {
    const Eigen::Vector3d x = c.meshes[std::size_t(b)].V.row(v).transpose();
    worst = std::max(worst, (M.leftCols<3>() * x + M.col(3) - c.meshes[std::size_t(a)].V.row(v).transpose()).norm());
  }
  return worst;
}

}  // namespace

TEST_CASE("refined fuzzy alignment recovers the transform between moved copies, and its vertex map the copies' own vertices") {
  const moved_copies c = make_copies(5);
  const auto r = collection_of(c);
  for (const auto& [a, b] : {std::pair<index_t, index_t>{0, 3}, {4, 1}, {2, 0}}) {
    CAPTURE(a);
    CAPTURE(b);
    const alignment_alternative alt = refined_fuzzy_alignment(r.fuzzy, c.records, a, b);
    CHECK(worst_vertex_error(c, a, b, alt) < 0.02 * c.records[std::size_t(a)].diameter);
    CHECK(alt.global_score > 0.9);
    const auto map = refined_fuzzy_vertex_map(r.fuzzy, c.records, a, b, c.meshes[std::size_t(a)].V, c.meshes[std::size_t(b)].V);
    REQUIRE(map.size() == std::size_t(c.meshes[std::size_t(a)].V.rows()));
    // Its own vertex, or one at the same place (where two boxes share a corner).
    const auto& Vb = c.meshes[std::size_t(b)].V;
    for (std::size_t v = 0; v < map.size(); ++v) CHECK((Vb.row(map[v]) - Vb.row(index_t(v))).norm() < 1e-9);
  }
}

TEST_CASE("refined fuzzy alignment without an up axis recovers the transform between copies tipped over") {
  const moved_copies c = make_copies(5, true);
  const extrinsic_alignment_options free{.up_axis = no_up_axis};
  const auto r = collection_of(c, free);
  for (const auto& [a, b] : {std::pair<index_t, index_t>{0, 3}, {4, 1}, {2, 0}}) {
    CAPTURE(a);
    CAPTURE(b);
    const alignment_alternative alt = refined_fuzzy_alignment(r.fuzzy, c.records, a, b, free);
    CHECK(worst_vertex_error(c, a, b, alt) < 0.02 * c.records[std::size_t(a)].diameter);
    CHECK(alt.global_score > 0.9);
    // Upright alignments cannot undo the tipping: ICP rotating about y alone stays far off.
    const alignment_alternative upright = refined_fuzzy_alignment(r.fuzzy, c.records, a, b);
    CHECK(worst_vertex_error(c, a, b, upright) > 0.1 * c.records[std::size_t(a)].diameter);
  }
}

TEST_CASE("refined fuzzy alignment: bad shapes, options and vertices are invalid_input") {
  const moved_copies c = make_copies(3);
  const auto r = collection_of(c);
  const auto& V = c.meshes[0].V;
  for (const auto& [a, b] : {std::pair<index_t, index_t>{1, 1}, {-1, 0}, {0, 3}})
    CHECK_THROWS_AS((void)refined_fuzzy_alignment(r.fuzzy, c.records, a, b), invalid_input);
  const std::vector<shape_record> fewer(c.records.begin(), c.records.begin() + 2);
  CHECK_THROWS_AS((void)refined_fuzzy_alignment(r.fuzzy, fewer, 0, 1), invalid_input);
  extrinsic_alignment_options bad;
  bad.sigma_fraction = 0;
  CHECK_THROWS_AS((void)refined_fuzzy_alignment(r.fuzzy, c.records, 0, 1, bad), invalid_input);
  CHECK_THROWS_AS((void)refined_fuzzy_vertex_map(r.fuzzy, c.records, 0, 1, points(), V), invalid_input);
  points nan_vertex = V;
  nan_vertex(2, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS((void)refined_fuzzy_vertex_map(r.fuzzy, c.records, 0, 1, nan_vertex, V), invalid_input);
  CHECK_THROWS_AS((void)refined_fuzzy_vertex_map(r.fuzzy, c.records, 0, 1, V, nan_vertex), invalid_input);
}

TEST_CASE("refined fuzzy alignment: shapes with no fuzzy correspondence between them are invalid_input (empty)") {
  // Two shapes whose embedded samples lie far apart: f is zero between them (beyond 2 tau).
  const moved_copies c = make_copies(2);
  diffusion_embedding e;
  const index_t K = c.records[0].samples.rows();
  e.offsets = {0, K, 2 * K};
  e.coordinates = Eigen::MatrixXf::Zero(2 * K, 2);
  for (index_t i = 0; i < K; ++i) {
    e.coordinates(i, 0) = float(i);
    e.coordinates(K + i, 0) = float(i);
    e.coordinates(K + i, 1) = 1000.0f;
  }
  e.eigenvalues = Eigen::VectorXd::Ones(2);
  const fuzzy_correspondence f(e, Eigen::VectorXf::Ones(2 * K), 2.0);
  try {
    (void)refined_fuzzy_alignment(f, c.records, 0, 1);
    FAIL("no exception");
  } catch (const invalid_input& error) {
    CHECK(error.reason() == input_error::empty);
    CHECK(std::string(error.what()).find("copy1") != std::string::npos);
    CHECK(std::string(error.what()).find("all but 0 of the " + std::to_string(K) + " samples") != std::string::npos);
  }
}
