// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "shapestruct/adapters/eigen_points.hpp"
#include "shapestruct/adapters/std_arrays.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "support/fixtures.hpp"

using namespace shapestruct;

namespace {

template <class Scalar, int Dim>
Eigen::Matrix<Scalar, Eigen::Dynamic, Dim> random_points(index_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::Matrix<Scalar, Eigen::Dynamic, Dim> P(n, Dim);
  for (index_t i = 0; i < n; ++i)
    for (int d = 0; d < Dim; ++d)
      // 53-bit uniform in [-1, 1) from the raw engine output (portable, unlike uniform_real_distribution).
      P(i, d) = static_cast<Scalar>(double(rng() >> 11) * 0x1.0p-53 * 2.0 - 1.0);
  return P;
}

// Brute force: all (squared distance, index) pairs sorted.
template <class Scalar, int Dim>
std::vector<std::pair<Scalar, index_t>> brute(const Eigen::Matrix<Scalar, Eigen::Dynamic, Dim>& P,
                                              const Eigen::Matrix<Scalar, Dim, 1>& q) {
  std::vector<std::pair<Scalar, index_t>> all;
  for (index_t i = 0; i < P.rows(); ++i) {
    Scalar s = 0;
    for (int d = 0; d < Dim; ++d) {
      const Scalar t = P(i, d) - q[d];
      s += t * t;
    }
    all.emplace_back(s, i);
  }
  std::sort(all.begin(), all.end());
  return all;
}

template <class Scalar, int Dim>
void check_against_brute_force(index_t n, index_t k, Scalar r, std::uint64_t seed) {
  const auto P = random_points<Scalar, Dim>(n, seed);
  const auto Q = random_points<Scalar, Dim>(50, seed + 1);
  const knn_index<Scalar, Dim> index(P);
  REQUIRE(index.size() == n);
  for (index_t qi = 0; qi < Q.rows(); ++qi) {
    const Eigen::Matrix<Scalar, Dim, 1> q = Q.row(qi).transpose();
    const auto all = brute<Scalar, Dim>(P, q);
    const auto res = index.knn(q, k);
    REQUIRE(res.size() == std::min(k, n));
    for (index_t j = 0; j < res.size(); ++j) {
      CHECK(res.indices[std::size_t(j)] == all[std::size_t(j)].second);
      CHECK(res.sq_distances[std::size_t(j)] == doctest::Approx(all[std::size_t(j)].first).epsilon(1e-5));
    }
    const auto nn = index.nearest(q);
    CHECK(nn.index == all[0].second);

    const auto rad = index.radius(q, r);
    std::vector<index_t> expected;
    for (const auto& [d, i] : all)
      if (d <= r * r) expected.push_back(i);
    REQUIRE(rad.size() == index_t(expected.size()));
    CHECK(rad.indices == expected);
    CHECK(std::is_sorted(rad.sq_distances.begin(), rad.sq_distances.end()));
  }
}

}  // namespace

TEST_CASE("knn_index: knn, nearest and radius equal brute force in 3-D (double and float)") {
  check_against_brute_force<double, 3>(2000, 8, 0.2, 11);
  check_against_brute_force<float, 3>(1500, 5, 0.25f, 12);
  check_against_brute_force<double, 3>(7, 16, 10.0, 13);  // k > #points returns all, radius covers all
}

TEST_CASE("knn_index: knn and radius equal brute force in 2-D and 8-D") {
  check_against_brute_force<double, 2>(1000, 6, 0.1, 21);
  check_against_brute_force<double, 8>(1000, 10, 1.2, 22);
  check_against_brute_force<float, 8>(500, 3, 1.0f, 23);
}

TEST_CASE("knn_index: spatial sorting changes nothing but speed") {
  const auto P = random_points<double, 3>(3000, 41);
  const auto Q = random_points<double, 3>(300, 42);
  const knn_index<double> sorted(P, {.spatial_sort = true});
  const knn_index<double> unsorted(P, {.spatial_sort = false});
  const auto a = sorted.knn_batch(Q, 9, 2), b = unsorted.knn_batch(Q, 9, 2);
  CHECK(a.indices == b.indices);
  CHECK(a.sq_distances == b.sq_distances);
  for (index_t i = 0; i < P.rows(); i += 13) {
    CHECK(sorted.point(i) == P.row(i).transpose());
    CHECK(unsorted.point(i) == P.row(i).transpose());
  }
  for (index_t i = 0; i < Q.rows(); i += 7)
    CHECK(sorted.radius(Q.row(i), 0.3).indices == unsorted.radius(Q.row(i), 0.3).indices);
  const auto P2 = random_points<float, 2>(500, 43);
  const knn_index<float, 2> s2(P2), u2(P2, {.spatial_sort = false});
  CHECK(s2.knn_batch(P2, 4, 1).indices == u2.knn_batch(P2, 4, 1).indices);
}

TEST_CASE("knn_index: radius is inclusive at exactly r") {
  Eigen::Matrix<double, Eigen::Dynamic, 3> P(3, 3);
  P << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  const knn_index<double> index(P);
  const Eigen::Vector3d q(0, 0, 0);
  CHECK(index.radius(q, 1.0).indices == std::vector<index_t>{0, 1});
  CHECK(index.radius(q, 0.0).indices == std::vector<index_t>{0});
  CHECK(index.radius(q, 2.0).size() == 3);
}

TEST_CASE("knn_index: batch equals single queries, identical for 1 and 2 threads") {
  const auto P = random_points<double, 3>(5000, 31);
  const auto Q = random_points<double, 3>(1500, 32);  // >= 1024: the Morton-ordered batch path
  const knn_index<double> index(P);
  const auto b1 = index.knn_batch(Q, 8, 1);
  const auto b2 = index.knn_batch(Q, 8, 2);
  const auto b0 = index.knn_batch(Q, 8, 0);
  REQUIRE(b1.indices.rows() == 1500);
  REQUIRE(b1.indices.cols() == 8);
  CHECK(b1.indices == b2.indices);
  CHECK(b1.sq_distances == b2.sq_distances);
  CHECK(b1.indices == b0.indices);
  for (index_t i = 0; i < Q.rows(); ++i) {
    const auto single = index.knn(Q.row(i), 8);
    for (index_t j = 0; j < 8; ++j) {
      CHECK(b1.indices(i, j) == single.indices[std::size_t(j)]);
      CHECK(b1.sq_distances(i, j) == single.sq_distances[std::size_t(j)]);
    }
  }
  // k larger than the point set: as many columns as points.
  const knn_index<double> tiny(P.topRows(3));
  CHECK(tiny.knn_batch(Q, 8, 2).indices.cols() == 3);
}

TEST_CASE("knn_index: built from PointSet models (std::vector<std::array>, mesh vertices, Eigen)") {
  const auto ico = make_icosphere(2);
  const knn_index<double> from_mesh(ico);
  std::vector<std::array<float, 3>> arr;
  for (index_t i = 0; i < ico.V.rows(); ++i) arr.push_back({float(ico.V(i, 0)), float(ico.V(i, 1)), float(ico.V(i, 2))});
  const knn_index<double> from_array(arr);
  const knn_index<double> from_matrix(ico.V);
  Eigen::MatrixXd dyn = ico.V;
  const knn_index<double> from_dynamic(dyn);
  REQUIRE(from_mesh.size() == ico.V.rows());
  REQUIRE(from_array.size() == ico.V.rows());
  REQUIRE(from_dynamic.size() == ico.V.rows());
  for (index_t i = 0; i < ico.V.rows(); i += 7) {
    CHECK(from_mesh.nearest(ico.V.row(i)).index == i);
    CHECK(from_array.nearest(ico.V.row(i)).index == i);
    CHECK(from_matrix.knn(ico.V.row(i), 4).indices == from_mesh.knn(ico.V.row(i), 4).indices);
    CHECK(from_dynamic.nearest(ico.V.row(i)).index == i);
  }
}

TEST_CASE("knn_index: duplicates, empty sets and moves") {
  Eigen::Matrix<double, Eigen::Dynamic, 3> P = Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(50, 3);
  const knn_index<double> same(P);
  const auto r = same.knn(Eigen::Vector3d(1, 0, 0), 5);
  CHECK(r.indices == std::vector<index_t>{0, 1, 2, 3, 4});  // ties broken by index
  CHECK(same.radius(Eigen::Vector3d(0, 0, 0), 0.0).size() == 50);

  const knn_index<double> none;
  CHECK(none.empty());
  CHECK(none.knn(Eigen::Vector3d(0, 0, 0), 3).size() == 0);
  CHECK(none.radius(Eigen::Vector3d(0, 0, 0), 1.0).size() == 0);
  CHECK(none.nearest(Eigen::Vector3d(0, 0, 0)).index == no_index);
  const auto eb = none.knn_batch(random_points<double, 3>(4, 1), 3, 1);
  CHECK(eb.indices.rows() == 4);
  CHECK(eb.indices.cols() == 0);
  const knn_index<double> from_empty(Eigen::Matrix<double, Eigen::Dynamic, 3>(0, 3));
  CHECK(from_empty.knn(Eigen::Vector3d(0, 0, 0), 1).size() == 0);

  knn_index<double> a(random_points<double, 3>(100, 5));
  knn_index<double> b(std::move(a));
  CHECK(b.size() == 100);
  CHECK(b.knn(Eigen::Vector3d(0, 0, 0), 3).size() == 3);
}

TEST_CASE("knn_index: one test per invalid_input reason") {
  const auto P = random_points<double, 3>(20, 3);
  SUBCASE("non_finite point") {
    auto bad = P;
    bad(7, 1) = std::numeric_limits<double>::quiet_NaN();
    try {
      const knn_index<double> index(bad);
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::non_finite);
      CHECK(e.element() == 7);
    }
  }
  const knn_index<double> index(P);
  SUBCASE("non_finite query") {
    CHECK_THROWS_AS((void)index.knn(Eigen::Vector3d(0, std::numeric_limits<double>::infinity(), 0), 1), invalid_input);
    CHECK_THROWS_AS((void)index.nearest(Eigen::Vector3d(std::nan(""), 0, 0)), invalid_input);
    auto Q = random_points<double, 3>(10, 4);
    Q(6, 2) = std::numeric_limits<double>::quiet_NaN();
    try {
      (void)index.knn_batch(Q, 2, 2);
      FAIL("no throw");
    } catch (const invalid_input& e) {
      CHECK(e.reason() == input_error::non_finite);
      CHECK(e.element() == 6);
    }
  }
  SUBCASE("bad_parameter") {
    auto reason = [&](auto&& f) {
      try {
        f();
      } catch (const invalid_input& e) {
        return e.reason();
      }
      return input_error::empty;  // any reason but bad_parameter: the check below fails
    };
    CHECK(reason([&] { (void)index.knn(Eigen::Vector3d(0, 0, 0), 0); }) == input_error::bad_parameter);
    CHECK(reason([&] { (void)index.radius(Eigen::Vector3d(0, 0, 0), -1.0); }) == input_error::bad_parameter);
    CHECK(reason([&] { (void)index.radius(Eigen::Vector3d(0, 0, 0), std::nan("")); }) == input_error::bad_parameter);
    CHECK(reason([&] { (void)index.knn(Eigen::Vector2d(0, 0), 1); }) == input_error::bad_parameter);
    CHECK(reason([&] { (void)index.knn_batch(P, 1, -1); }) == input_error::bad_parameter);
    CHECK(reason([&] { const knn_index<double> bad(P, {.leaf_size = 0}); }) == input_error::bad_parameter);
  }
}
