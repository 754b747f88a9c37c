// SPDX-License-Identifier: MIT
// align_extrinsic: recovery of a known upright similarity, the four alternatives, the sparse scores, determinism
// and every invalid_input reason.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "fuzzy/extrinsic_fixtures.hpp"
#include "shapestruct/core/concepts/shape_aligner.hpp"
#include "shapestruct/fuzzy/extrinsic_alignment.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "shapestruct/geometry/surface_sampling.hpp"

using namespace shapestruct;
using test::asymmetric_shape;
using test::box_union;

static_assert(ShapeAligner<extrinsic_aligner>);

namespace {

using points = Eigen::Matrix<double, Eigen::Dynamic, 3>;

double mean_pairwise_distance(const points& P) {
  double sum = 0;
  for (index_t i = 0; i < P.rows(); ++i)
    for (index_t j = 0; j < P.rows(); ++j) sum += (P.row(i) - P.row(j)).norm();
  return sum / double(P.rows() * P.rows());
}

/// A record as the collection builds one: the surface points, K farthest-point samples among them, Diam(S).
shape_record make_record(const points& surface, index_t K = 64) {
  shape_record r;
  r.surface_points = surface;
  const auto fps = farthest_point_sampling(surface, K);
  r.samples.resize(K, 3);
  for (index_t k = 0; k < K; ++k) r.samples.row(k) = surface.row(fps.indices[std::size_t(k)]);
  r.diameter = mean_pairwise_distance(r.samples);
  return r;
}

points sample_mesh(const triangle_mesh<double>& m, index_t count, std::uint64_t seed) {
  surface_sampling_options so;
  so.seed = seed;
  so.threads = 1;
  return sample_surface_even<double>(m.V, m.F, count, so).points;
}

/// x -> scale * R_y(angle) x + t.
struct similarity {
  double scale = 1;
  double angle = 0;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();

  [[nodiscard]] Eigen::Matrix3d linear() const {
    return scale * Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  }
  [[nodiscard]] points apply(const points& P) const {
    return ((P * linear().transpose()).rowwise() + t.transpose()).eval();
  }
  /// The 3 x 4 affine of the inverse map.
  [[nodiscard]] Eigen::Matrix<double, 3, 4> inverse_affine() const {
    Eigen::Matrix<double, 3, 4> M;
    M.leftCols<3>() = linear().inverse();
    M.col(3) = -M.leftCols<3>() * t;
    return M;
  }
};

/// The record with every point moved by T (sample i stays sample i), Diam recomputed.
shape_record transformed(const shape_record& r, const similarity& T) {
  shape_record out = r;
  out.samples = T.apply(r.samples);
  out.surface_points = T.apply(r.surface_points);
  out.diameter = mean_pairwise_distance(out.samples);
  return out;
}

/// Rotation angle about +y of the linear part of an upright similarity.
double angle_about_y(const Eigen::Matrix<double, 3, 4>& M) { return std::atan2(M(0, 2), M(0, 0)); }
double scale_of(const Eigen::Matrix<double, 3, 4>& M) { return std::cbrt(M.leftCols<3>().determinant()); }
double angle_difference(double a, double b) { return std::abs(std::remainder(a - b, 2 * std::numbers::pi)); }

const shape_record& asymmetric_record() {
  static const shape_record r = make_record(sample_mesh(asymmetric_shape(), 1024, 7));
  return r;
}

/// Runs f, which must throw invalid_input for `reason` with a message naming every one of `words`.
void check_invalid(const std::function<void()>& f, input_error reason, std::initializer_list<const char*> words) {
  try {
    f();
    FAIL("no invalid_input was thrown");
  } catch (const invalid_input& e) {
    CHECK(e.reason() == reason);
    const std::string message = e.what();
    for (const char* w : words) {
      INFO("message: ", message, ", expected word: ", w);
      CHECK(message.find(w) != std::string::npos);
    }
  }
}

void check_same(const pair_alignment& a, const pair_alignment& b) {
  REQUIRE(a.alternatives.size() == b.alternatives.size());
  CHECK(a.initial == b.initial);
  for (std::size_t k = 0; k < a.alternatives.size(); ++k) {
    const auto& x = a.alternatives[k];
    const auto& y = b.alternatives[k];
    CHECK(x.global_score == y.global_score);
    CHECK(x.parameters == y.parameters);
    REQUIRE(x.scores.nonZeros() == y.scores.nonZeros());
    CHECK(std::equal(x.scores.outerIndexPtr(), x.scores.outerIndexPtr() + x.scores.rows() + 1,
                     y.scores.outerIndexPtr()));
    CHECK(std::equal(x.scores.innerIndexPtr(), x.scores.innerIndexPtr() + x.scores.nonZeros(),
                     y.scores.innerIndexPtr()));
    CHECK(std::equal(x.scores.valuePtr(), x.scores.valuePtr() + x.scores.nonZeros(), y.scores.valuePtr()));
  }
}

}  // namespace

TEST_CASE("align_extrinsic recovers a rotation about up, a scale and a translation of an exact copy") {
  const shape_record& source = asymmetric_record();
  const similarity truth{1.7, 2.1, Eigen::Vector3d(3, -0.5, 2)};
  const shape_record target = transformed(source, truth);
  const pair_alignment out = align_extrinsic(source, target);
  REQUIRE(out.alternatives.size() == 4);
  const alignment_alternative& best = out.alternatives[std::size_t(out.initial)];
  const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(best);
  const Eigen::Matrix<double, 3, 4> expected = truth.inverse_affine();
  CHECK((M.leftCols<3>() - expected.leftCols<3>()).norm() < 1e-5);
  CHECK((M.col(3) - expected.col(3)).norm() < 1e-5 * source.diameter);
  CHECK(scale_of(M) == doctest::Approx(1 / 1.7).epsilon(1e-6));
  CHECK(angle_difference(angle_about_y(M), -2.1) < 1e-6);
  CHECK(best.global_score > 0.99);

  // The same alignment turned by 180 degrees about up (about the source's centroid) scores lower, and so does
  // every returned alternative that did not find the true rotation.
  const Eigen::Vector3d c = source.surface_points.colwise().mean().transpose();
  const Eigen::Matrix3d half_turn = Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitY()).toRotationMatrix();
  Eigen::Matrix<double, 3, 4> wrong;
  wrong.leftCols<3>() = half_turn * expected.leftCols<3>();
  wrong.col(3) = half_turn * (expected.col(3) - c) + c;
  const alignment_alternative turned = score_extrinsic_alignment(source, target, wrong);
  CHECK(turned.global_score < 0.5 * best.global_score);
  for (const auto& alt : out.alternatives)
    if (angle_difference(angle_about_y(extrinsic_transform(alt)), -2.1) > 0.1)
      CHECK(alt.global_score < best.global_score - 0.1);
  // Scoring the found transform again reproduces the alternative.
  CHECK(score_extrinsic_alignment(source, target, M).global_score == doctest::Approx(best.global_score));
}

TEST_CASE("align_extrinsic recovers the transform between independently sampled copies") {
  const triangle_mesh<double> mesh = asymmetric_shape();
  const shape_record& source = asymmetric_record();
  const similarity truth{1.7, -0.8, Eigen::Vector3d(-1, 0.25, 4)};
  triangle_mesh<double> moved = mesh;
  moved.V = truth.apply(mesh.V);
  const shape_record target = make_record(sample_mesh(moved, 1024, 99));
  const pair_alignment out = align_extrinsic(source, target);
  const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(out.alternatives[std::size_t(out.initial)]);
  const Eigen::Matrix<double, 3, 4> expected = truth.inverse_affine();
  CHECK(angle_difference(angle_about_y(M), 0.8) < 0.02);
  CHECK(scale_of(M) == doctest::Approx(1 / 1.7).epsilon(0.01));
  CHECK((M.col(3) - expected.col(3)).norm() < 0.02 * source.diameter);
  // Rotation about up only: the up axis stays the up axis.
  CHECK((M.leftCols<3>().col(1) / scale_of(M) - Eigen::Vector3d::UnitY()).norm() < 1e-12);
  // B_a stays below 1 here: distances go to the nearest of the other's 1,024 surface points, not to its surface.
  CHECK(out.alternatives[std::size_t(out.initial)].global_score > 0.7);
}

TEST_CASE("align_extrinsic rotates about the configured up axis") {
  // The same shape stood up along +z (a cyclic permutation of the axes, a proper rotation), turned about z.
  const shape_record& upright_y = asymmetric_record();
  Eigen::Matrix3d y_to_z;
  y_to_z << 0, 0, 1, 1, 0, 0, 0, 1, 0;  // (x, y, z) -> (z, x, y): the old y axis becomes z
  shape_record source = upright_y;
  source.samples = upright_y.samples * y_to_z.transpose();
  source.surface_points = upright_y.surface_points * y_to_z.transpose();
  const Eigen::Matrix3d turn = 0.8 * Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d shift(1, 2, 3);
  shape_record target = source;
  target.samples = (source.samples * turn.transpose()).rowwise() + shift.transpose();
  target.surface_points = (source.surface_points * turn.transpose()).rowwise() + shift.transpose();
  target.diameter = 0.8 * source.diameter;
  extrinsic_alignment_options o;
  o.up_axis = 2;
  const pair_alignment out = align_extrinsic(source, target, o);
  const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(out.alternatives[std::size_t(out.initial)]);
  CHECK((M.leftCols<3>() - turn.inverse()).norm() < 1e-5);
  CHECK((M.col(3) + turn.inverse() * shift).norm() < 1e-5 * source.diameter);
  for (const auto& alt : out.alternatives)
    CHECK((extrinsic_transform(alt).leftCols<3>().col(2).normalized() - Eigen::Vector3d::UnitZ()).norm() < 1e-12);
}

TEST_CASE("align_extrinsic always returns four scored alternatives and picks the best as initial") {
  const shape_record& source = asymmetric_record();
  const shape_record other = make_record(
      sample_mesh(box_union({{Eigen::Vector3d(0, 0.5, 0), Eigen::Vector3d(0.3, 0.5, 0.6)},
                             {Eigen::Vector3d(0.5, 0.2, 0), Eigen::Vector3d(0.4, 0.2, 0.2)}}),
                  700, 3),
      48);
  for (const int iterations : {0, 1, 30}) {
    extrinsic_alignment_options o;
    o.icp_iterations = iterations;
    for (const auto& [k, l] : {std::pair{&source, &other}, std::pair{&other, &source}, std::pair{&source, &source}}) {
      const pair_alignment out = align_extrinsic(*k, *l, o);
      REQUIRE(out.alternatives.size() == 4);
      CHECK(out.initial == best_global_alternative(out.alternatives));
      CHECK(out.seconds >= 0);
      for (const auto& alt : out.alternatives) {
        CHECK(alt.parameters.size() == 12);
        CHECK(alt.global_score >= 0);
        CHECK(alt.global_score <= 1);
        CHECK(alt.scores.rows() == k->samples.rows());
        CHECK(alt.scores.cols() == l->samples.rows());
        // Upright: the linear part maps up to a multiple of up.
        const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(alt);
        CHECK((M.leftCols<3>().col(1).normalized() - Eigen::Vector3d::UnitY()).norm() < 1e-12);
      }
    }
  }
  // Without scale the linear parts are rotations.
  extrinsic_alignment_options rigid;
  rigid.allow_scale = false;
  for (const auto& alt : align_extrinsic(source, other, rigid).alternatives)
    CHECK(scale_of(extrinsic_transform(alt)) == doctest::Approx(1.0));
}

TEST_CASE("align_extrinsic sparse scores peak at the true corresponding sample and respect the row limits") {
  const shape_record& source = asymmetric_record();
  const shape_record target = transformed(source, similarity{0.6, 0.4, Eigen::Vector3d(0.5, 1, -2)});
  const pair_alignment out = align_extrinsic(source, target);
  const alignment_alternative& best = out.alternatives[std::size_t(out.initial)];
  const auto& a = best.scores;
  REQUIRE(a.rows() == source.samples.rows());
  REQUIRE(a.cols() == target.samples.rows());
  CHECK(a.isCompressed());
  for (index_t i = 0; i < a.rows(); ++i) {
    index_t argmax = no_index;
    float largest = -1;
    index_t count = 0;
    for (Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>::InnerIterator it(a, i); it; ++it) {
      ++count;
      CHECK(it.value() > 0);
      if (it.value() > largest) {
        largest = it.value();
        argmax = it.col();
      }
    }
    CHECK(count >= 1);
    CHECK(count <= 16);
    CHECK(argmax == i);
    CHECK(largest == doctest::Approx(best.global_score).epsilon(1e-5));  // L_a(p_i, T(p_i)) = 1
  }

  // An entry is L_a * B_a with sigma(S_l) in the frame of S_l (eq. 4.1-4.2).
  const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(best);
  const double sigma_l = 0.2 * target.diameter;
  for (Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>::InnerIterator it(a, 5); it; ++it) {
    const Eigen::Vector3d image = M.leftCols<3>() * target.samples.row(it.col()).transpose() + M.col(3);
    const double d = (source.samples.row(5).transpose() - image).norm() / scale_of(M);
    CHECK(it.value() == doctest::Approx(best.global_score * std::exp(-d * d / (sigma_l * sigma_l))).epsilon(1e-5));
  }

  extrinsic_alignment_options o;
  o.max_entries_per_row = 3;
  const pair_alignment limited = align_extrinsic(source, target, o);
  const auto& few = limited.alternatives[std::size_t(out.initial)].scores;
  for (index_t i = 0; i < few.rows(); ++i) {
    CHECK(few.outerIndexPtr()[i + 1] - few.outerIndexPtr()[i] >= 1);
    CHECK(few.outerIndexPtr()[i + 1] - few.outerIndexPtr()[i] <= 3);
  }
  // keep_fraction = 1 keeps only each row's largest entry.
  o = {};
  o.keep_fraction = 1;
  const pair_alignment single = align_extrinsic(source, target, o);
  const auto& one = single.alternatives[std::size_t(out.initial)].scores;
  CHECK(one.nonZeros() == one.rows());
  for (index_t i = 0; i < one.rows(); ++i) CHECK(one.innerIndexPtr()[one.outerIndexPtr()[i]] == i);
  // keep_fraction = 0 keeps max_entries_per_row everywhere (more target samples than that).
  o.keep_fraction = 0;
  CHECK(align_extrinsic(source, target, o).alternatives[0].scores.nonZeros() == 16 * source.samples.rows());
}

TEST_CASE("align_extrinsic is deterministic and extrinsic_aligner gives the same result from several threads") {
  const shape_record& source = asymmetric_record();
  const std::vector<shape_record> records = {
      source, transformed(source, similarity{1.3, 1.0, Eigen::Vector3d(0, 0, 1)}),
      make_record(sample_mesh(asymmetric_shape(), 900, 5), 40)};
  const pair_alignment first = align_extrinsic(records[0], records[2]);
  check_same(first, align_extrinsic(records[0], records[2]));

  const extrinsic_aligner aligner(records);
  std::vector<pair_alignment> parallel(4);
  const std::array<std::pair<index_t, index_t>, 4> pairs = {{{0, 2}, {2, 0}, {0, 1}, {1, 2}}};
  {
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < pairs.size(); ++k)
      threads.emplace_back([&, k] { parallel[k] = aligner.align(pairs[k].first, pairs[k].second); });
    for (auto& t : threads) t.join();
  }
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    CHECK(parallel[k].source == pairs[k].first);
    CHECK(parallel[k].target == pairs[k].second);
    check_same(parallel[k], align_extrinsic(records[std::size_t(pairs[k].first)],
                                            records[std::size_t(pairs[k].second)]));
  }
  check_same(parallel[0], first);
}

TEST_CASE("align_extrinsic rejects a record without samples") {
  shape_record bad = asymmetric_record();
  bad.samples.resize(0, 3);
  check_invalid([&] { (void)align_extrinsic(bad, asymmetric_record()); }, input_error::empty,
                {"align_extrinsic", "source.samples"});
  check_invalid([&] { (void)align_extrinsic(asymmetric_record(), bad); }, input_error::empty,
                {"align_extrinsic", "target.samples"});
}

TEST_CASE("align_extrinsic rejects a record without surface points") {
  shape_record bad = asymmetric_record();
  bad.surface_points.resize(0, 3);
  check_invalid([&] { (void)align_extrinsic(asymmetric_record(), bad); }, input_error::empty,
                {"align_extrinsic", "target.surface_points"});
}

TEST_CASE("align_extrinsic rejects a non-positive or non-finite diameter") {
  shape_record bad = asymmetric_record();
  for (const double d : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    bad.diameter = d;
    check_invalid([&] { (void)align_extrinsic(bad, asymmetric_record()); }, input_error::bad_parameter,
                  {"align_extrinsic", "source.diameter"});
  }
}

TEST_CASE("align_extrinsic rejects non-finite coordinates") {
  shape_record bad = asymmetric_record();
  bad.samples(3, 1) = std::numeric_limits<double>::infinity();
  check_invalid([&] { (void)align_extrinsic(bad, asymmetric_record()); }, input_error::non_finite,
                {"align_extrinsic", "source.samples"});
  bad = asymmetric_record();
  bad.surface_points(7, 0) = std::numeric_limits<double>::quiet_NaN();
  check_invalid([&] { (void)align_extrinsic(asymmetric_record(), bad); }, input_error::non_finite,
                {"align_extrinsic", "target.surface_points"});
}

TEST_CASE("align_extrinsic without an up axis recovers any rotation, a scale and a translation") {
  // A rotation that tips the up axis over: the upright alignment cannot reach it, the free one must.
  const shape_record& source = asymmetric_record();
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 0.3, -0.5).normalized()) *
                                    Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ()))
                                       .toRotationMatrix();
  const double scale = 0.6;
  const Eigen::Vector3d shift(-2, 1, 0.5);
  shape_record target = source;
  const Eigen::Matrix3d linear = scale * rotation;
  target.samples = ((source.samples * linear.transpose()).rowwise() + shift.transpose()).eval();
  target.surface_points = ((source.surface_points * linear.transpose()).rowwise() + shift.transpose()).eval();
  target.diameter = scale * source.diameter;

  extrinsic_alignment_options free;
  free.up_axis = no_up_axis;
  const pair_alignment out = align_extrinsic(source, target, free);
  REQUIRE(out.alternatives.size() == 24);
  CHECK(out.initial == best_global_alternative(out.alternatives));
  const alignment_alternative& best = out.alternatives[std::size_t(out.initial)];
  const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(best);
  const Eigen::Matrix3d expected = (scale * rotation).inverse();
  CHECK((M.leftCols<3>() - expected).norm() < 1e-5);
  CHECK((M.col(3) + expected * shift).norm() < 1e-5 * source.diameter);
  CHECK(best.global_score > 0.99);
  for (const auto& alt : out.alternatives) {
    const Eigen::Matrix3d A = extrinsic_transform(alt).leftCols<3>();
    const double s = std::cbrt(A.determinant());  // a similarity: A / s is a rotation, never a mirror
    CHECK(s > 0);
    CHECK(((A / s) * (A / s).transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-9);
  }

  const pair_alignment upright = align_extrinsic(source, target);
  CHECK(upright.alternatives[std::size_t(upright.initial)].global_score < best.global_score - 0.2);
}

TEST_CASE("fit_free_similarity solves the closed form exactly and never returns a mirror") {
  std::vector<Eigen::Vector3d> p, x;
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(2.5, Eigen::Vector3d(-0.2, 1, 0.7).normalized()).toRotationMatrix();
  const Eigen::Vector3d shift(0.3, -4, 2);
  for (int i = 0; i < 20; ++i) {
    p.emplace_back(std::sin(1.3 * i), std::cos(0.7 * i) * 2, 0.1 * i);
    x.push_back(1.5 * rotation * p.back() + shift);
  }
  const detail::free_similarity T = detail::fit_free_similarity(p, x, true, {});
  CHECK(T.scale == doctest::Approx(1.5).epsilon(1e-12));
  CHECK((T.rotation - rotation).norm() < 1e-12);
  CHECK((T.translation - shift).norm() < 1e-12);
  // Points mirrored in a plane: the best proper rotation, determinant +1.
  std::vector<Eigen::Vector3d> mirrored;
  for (const auto& q : p) mirrored.emplace_back(q.x(), q.y(), -q.z());
  CHECK(detail::fit_free_similarity(p, mirrored, false, {}).rotation.determinant() == doctest::Approx(1));
}

TEST_CASE("fit_upright_stretch converges to a scale per axis, a rotation about up and a translation") {
  std::vector<Eigen::Vector3d> p, x;
  const Eigen::Vector3d scales(1.3, 0.8, 1.1);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d shift(0.3, -4, 2);
  for (int i = 0; i < 40; ++i) {
    p.emplace_back(std::sin(1.3 * i), std::cos(0.7 * i) * 2, 0.5 * std::sin(0.3 * i + 1));
    x.push_back(scales.asDiagonal() * (rotation * p.back()) + shift);
  }
  // One alternation per call, as ICP calls it: repeated, it reaches the exact transform.
  detail::upright_stretch T;
  for (int round = 0; round < 200; ++round) T = detail::fit_upright_stretch(p, x, 1, T);
  CHECK((T.scales - scales).norm() < 1e-6);
  CHECK(std::abs(std::remainder(T.angle - 0.7, 2 * std::numbers::pi)) < 1e-6);
  CHECK((T.translation - shift).norm() < 1e-6);
  // Each axis's scale stays within a factor 2 of the scale it started from, however flat the points along it.
  std::vector<Eigen::Vector3d> flat_x;
  for (const auto& q : p) flat_x.emplace_back(q.x(), 0.01 * q.y(), q.z());
  detail::upright_stretch F;
  for (int round = 0; round < 20; ++round) F = detail::fit_upright_stretch(p, flat_x, 1, F);
  CHECK(F.scales[1] == doctest::Approx(0.5));
  CHECK(F.scales[0] == doctest::Approx(1).epsilon(1e-6));
}

TEST_CASE("align_extrinsic with axis_scales fits a copy stretched along its axes, the similarity does not") {
  const shape_record& source = asymmetric_record();
  // The target is the source stretched: x_source = S R_y(angle) x_target + t, with S a scale per source axis.
  const Eigen::Vector3d scales(1.25, 0.85, 1.1);
  const Eigen::Matrix3d A = scales.asDiagonal() * Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d t(0.5, -0.2, 1.0);
  const Eigen::Matrix3d A_inverse = A.inverse();
  shape_record target = source;
  target.samples = ((source.samples.rowwise() - t.transpose()) * A_inverse.transpose()).eval();
  target.surface_points = ((source.surface_points.rowwise() - t.transpose()) * A_inverse.transpose()).eval();
  target.diameter = mean_pairwise_distance(target.samples);
  auto worst_error = [&](const pair_alignment& out) {
    const Eigen::Matrix<double, 3, 4> M = extrinsic_transform(out.alternatives[std::size_t(out.initial)]);
    return ((target.surface_points * M.leftCols<3>().transpose()).rowwise() + M.col(3).transpose() -
            source.surface_points).rowwise().norm().maxCoeff() / source.diameter;
  };
  extrinsic_alignment_options stretch;
  stretch.axis_scales = true;
  const pair_alignment fitted = align_extrinsic(source, target, stretch);
  const pair_alignment similar = align_extrinsic(source, target);
  const double fitted_error = worst_error(fitted), similar_error = worst_error(similar);
  CAPTURE(fitted_error);
  CAPTURE(similar_error);
  CHECK(fitted_error < 0.35 * similar_error);
  CHECK(fitted.alternatives[std::size_t(fitted.initial)].global_score >
        similar.alternatives[std::size_t(similar.initial)].global_score);
  // The linear part is S R: its rows have the lengths of the axis scales. The horizontal ones come out exact; along
  // up the 10 % trim drops the pairs on the top and bottom faces that would pull it all the way (0.92 for 0.85 here).
  const Eigen::Vector3d found =
      extrinsic_transform(fitted.alternatives[std::size_t(fitted.initial)]).leftCols<3>().rowwise().norm();
  const double uniform = scale_of(extrinsic_transform(similar.alternatives[std::size_t(similar.initial)]));
  CAPTURE(found.transpose());
  CHECK(std::abs(found[0] - scales[0]) < 0.005);
  CHECK(std::abs(found[2] - scales[2]) < 0.005);
  CHECK(std::abs(found[1] - scales[1]) < 0.5 * std::abs(uniform - scales[1]));
}

TEST_CASE("align_extrinsic rejects axis_scales without an up axis or without scaling") {
  extrinsic_alignment_options free;
  free.axis_scales = true;
  free.up_axis = no_up_axis;
  check_invalid([&] { (void)align_extrinsic(asymmetric_record(), asymmetric_record(), free); },
                input_error::bad_parameter, {"align_extrinsic", "axis_scales", "up axis"});
  extrinsic_alignment_options unscaled;
  unscaled.axis_scales = true;
  unscaled.allow_scale = false;
  check_invalid([&] { (void)align_extrinsic(asymmetric_record(), asymmetric_record(), unscaled); },
                input_error::bad_parameter, {"align_extrinsic", "axis_scales", "allow_scale"});
}

TEST_CASE("align_extrinsic rejects an up_axis other than 0, 1, 2 or no_up_axis") {
  for (const int up : {-2, 3}) {
    extrinsic_alignment_options o;
    o.up_axis = up;
    check_invalid([&] { (void)align_extrinsic(asymmetric_record(), asymmetric_record(), o); },
                  input_error::bad_parameter, {"align_extrinsic", "up_axis"});
  }
}

TEST_CASE("align_extrinsic rejects a non-positive sigma_fraction") {
  for (const double f : {0.0, -0.2, std::numeric_limits<double>::infinity()}) {
    extrinsic_alignment_options o;
    o.sigma_fraction = f;
    check_invalid([&] { (void)align_extrinsic(asymmetric_record(), asymmetric_record(), o); },
                  input_error::bad_parameter, {"align_extrinsic", "sigma_fraction"});
  }
}

TEST_CASE("align_extrinsic rejects negative icp_iterations") {
  extrinsic_alignment_options o;
  o.icp_iterations = -1;
  check_invalid([&] { (void)align_extrinsic(asymmetric_record(), asymmetric_record(), o); },
                input_error::bad_parameter, {"align_extrinsic", "icp_iterations"});
}

TEST_CASE("align_extrinsic rejects a negative or NaN icp_tolerance") {
  for (const double t : {-1e-6, std::numeric_limits<double>::quiet_NaN()}) {
    extrinsic_alignment_options o;
    o.icp_tolerance = t;
    check_invalid([&] { (void)align_extrinsic(asymmetric_record(), asymmetric_record(), o); },
                  input_error::bad_parameter, {"align_extrinsic", "icp_tolerance"});
  }
}

TEST_CASE("align_extrinsic rejects a keep_fraction outside 0 to 1") {
  for (const float f : {-0.1f, 1.5f, std::numeric_limits<float>::quiet_NaN()}) {
    extrinsic_alignment_options o;
    o.keep_fraction = f;
    check_invalid([&] { (void)align_extrinsic(asymmetric_record(), asymmetric_record(), o); },
                  input_error::bad_parameter, {"align_extrinsic", "keep_fraction"});
  }
}

TEST_CASE("align_extrinsic rejects max_entries_per_row below 1") {
  extrinsic_alignment_options o;
  o.max_entries_per_row = 0;
  check_invalid([&] { (void)align_extrinsic(asymmetric_record(), asymmetric_record(), o); },
                input_error::bad_parameter, {"align_extrinsic", "max_entries_per_row"});
}

TEST_CASE("extrinsic_transform rejects parameters that are not a 3 x 4 affine") {
  alignment_alternative alt;
  alt.parameters.assign(5, 0.0);
  check_invalid([&] { (void)extrinsic_transform(alt); }, input_error::size_mismatch,
                {"extrinsic_transform", "parameters"});
}

TEST_CASE("score_extrinsic_alignment rejects a singular transform") {
  const Eigen::Matrix<double, 3, 4> M = Eigen::Matrix<double, 3, 4>::Zero();
  check_invalid([&] { (void)score_extrinsic_alignment(asymmetric_record(), asymmetric_record(), M); },
                input_error::bad_parameter, {"score_extrinsic_alignment", "transform"});
}

TEST_CASE("extrinsic_aligner rejects bad options and shape indices out of range") {
  const std::vector<shape_record> records = {asymmetric_record(), asymmetric_record()};
  extrinsic_alignment_options o;
  o.max_entries_per_row = 0;
  check_invalid([&] { (void)extrinsic_aligner(records, o); }, input_error::bad_parameter,
                {"extrinsic_aligner", "max_entries_per_row"});
  const extrinsic_aligner aligner(records);
  for (const auto& [k, l] : {std::pair<index_t, index_t>{-1, 0}, {0, 2}, {1, 1}})
    check_invalid([&] { (void)aligner.align(k, l); }, input_error::bad_parameter,
                  {"extrinsic_aligner::align", "source", "target"});
}
