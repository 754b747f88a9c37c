// SPDX-License-Identifier: MIT
// The explorer's variance (ch. 4.5.1): zero on identical shapes, largest where one shape departs from the rest.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/explore/sample_variance.hpp"

using namespace shapestruct;
using test::expect_invalid;  // tests/geometry/geometry_test_util.hpp

namespace {

/// N shapes of K samples whose embedded coordinates are identical (a collection of identical shapes).
diffusion_embedding identical_shapes(index_t N, index_t K, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  Eigen::MatrixXf code(K, 6);
  for (index_t i = 0; i < K; ++i)
    for (index_t d = 0; d < 6; ++d) code(i, d) = g(rng);
  diffusion_embedding e;
  e.coordinates = Eigen::MatrixXf(N * K, 6);
  for (index_t k = 0; k <= N; ++k) e.offsets.push_back(k * K);
  for (index_t k = 0; k < N; ++k) e.coordinates.middleRows(k * K, K) = code;
  e.eigenvalues = Eigen::VectorXd::Ones(6);
  return e;
}

}  // namespace

TEST_CASE("sample_variance is zero everywhere on a collection of identical shapes") {
  const diffusion_embedding e = identical_shapes(8, 30, 1);
  const Eigen::VectorXf v = sample_variance(e);
  REQUIRE(v.size() == 8 * 30);
  CHECK(v.cwiseAbs().maxCoeff() == 0.0f);
  CHECK(shape_variance(e, 3).cwiseAbs().maxCoeff() == 0.0f);
}

TEST_CASE("sample_variance marks where a shape departs from the rest, normalised within the shape") {
  diffusion_embedding e = identical_shapes(6, 20, 2);
  // Shape 2's samples 4 and 7 move in the embedding (that region differs): 7 twice as far as 4.
  e.coordinates.row(2 * 20 + 4) += Eigen::RowVectorXf::Constant(6, 0.5f);
  e.coordinates.row(2 * 20 + 7) += Eigen::RowVectorXf::Constant(6, 1.0f);
  const Eigen::VectorXf v = shape_variance(e, 2, {.fraction = 1.0});
  // their nearest counterparts may be another sample, but never farther than the moved distance
  CHECK(v[7] == doctest::Approx(1.0f));
  CHECK(v[4] > 0.0f);
  CHECK(v[4] < 1.0f);
  for (index_t i = 0; i < 20; ++i)
    if (i != 4 && i != 7) CHECK(v[i] == 0.0f);
  // every shape's values lie in [0, 1], and the whole-collection version agrees with the per-shape one
  const Eigen::VectorXf all = sample_variance(e, {.fraction = 1.0, .threads = 2});
  CHECK(all.minCoeff() >= 0.0f);
  CHECK(all.maxCoeff() <= 1.0f);
  CHECK((all.segment(40, 20) - v).cwiseAbs().maxCoeff() == 0.0f);
}

TEST_CASE("sample_variance with a subset of reference shapes is deterministic and close to the full one") {
  std::mt19937_64 rng(3);
  std::normal_distribution<float> g(0.0f, 1.0f);
  diffusion_embedding e = identical_shapes(40, 16, 4);
  for (index_t p = 0; p < e.points(); ++p)
    for (index_t d = 0; d < 6; ++d) e.coordinates(p, d) += 0.05f * g(rng);
  const Eigen::VectorXf a = sample_variance(e, {.reference_shapes = 10, .threads = 1});
  const Eigen::VectorXf b = sample_variance(e, {.reference_shapes = 10, .threads = 2});
  CHECK(a == b);
}

TEST_CASE("sample_variance refuses bad options and unknown shapes") {
  const diffusion_embedding e = identical_shapes(3, 5, 5);
  expect_invalid([&] { (void)sample_variance(e, {.fraction = 0}); }, input_error::bad_parameter);
  expect_invalid([&] { (void)sample_variance(e, {.fraction = 1.5}); }, input_error::bad_parameter);
  expect_invalid([&] { (void)sample_variance(e, {.reference_shapes = 0}); }, input_error::bad_parameter);
  expect_invalid([&] { (void)shape_variance(e, 3); }, input_error::bad_parameter, 3);
}
