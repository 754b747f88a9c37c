// SPDX-License-Identifier: MIT
// Region-of-interest queries (ch. 4.5.3), facet rankings and the canonical co-alignment, on collections whose
// fuzzy correspondences are exact by construction: corresponding samples share their embedded coordinates.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <thread>
#include <vector>

#include "geometry/geometry_test_util.hpp"
#include "shapestruct/explore/affine_alignment.hpp"
#include "shapestruct/explore/co_alignment.hpp"
#include "shapestruct/explore/collection_explorer.hpp"
#include "shapestruct/explore/facet_ranking.hpp"
#include "shapestruct/explore/region_query.hpp"

using namespace shapestruct;
using test::expect_invalid;  // tests/geometry/geometry_test_util.hpp

namespace {

using points = Eigen::Matrix<double, Eigen::Dynamic, 3>;

affine_transform random_affine(std::mt19937_64& rng) {
  // Mild enough that every relative map stays within region_query's default stretch bound (max_stretch 1.5).
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  affine_transform T = identity_affine();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T(r, c) += (c == 3 ? 10.0 : 1.0) * u(rng);
  return T;
}

points transformed(const points& X, const affine_transform& T) {
  return (X * T.leftCols<3>().transpose()).rowwise() + T.col(3).transpose();
}

/// N shapes, each an affine image of one K-point base set; sample i has the same embedded coordinates on every
/// shape, so the best fuzzy correspondence of every sample is its counterpart.
struct exact_collection {
  points base;
  std::vector<affine_transform> placement;  // shape k = placement[k](base)
  std::vector<shape_record> records;
  fuzzy_correspondence f;
};

exact_collection make_exact_collection(index_t N, index_t K, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  exact_collection c;
  c.base = points(K, 3);
  for (index_t i = 0; i < K; ++i) c.base.row(i) << g(rng), g(rng), g(rng);
  Eigen::MatrixXf code(K, 8);
  for (index_t i = 0; i < K; ++i)
    for (index_t d = 0; d < 8; ++d) code(i, d) = float(g(rng));
  diffusion_embedding e;
  e.coordinates = Eigen::MatrixXf(N * K, 8);
  e.eigenvalues = Eigen::VectorXd::Ones(8);
  e.trivial_eigenvalue = 1;
  for (index_t k = 0; k <= N; ++k) e.offsets.push_back(k * K);
  for (index_t k = 0; k < N; ++k) {
    e.coordinates.middleRows(k * K, K) = code;
    c.placement.push_back(k == 0 ? identity_affine() : random_affine(rng));
    shape_record r;
    r.name = "shape" + std::to_string(k);
    r.samples = transformed(c.base, c.placement.back());
    r.surface_points = r.samples;
    r.vertex_count = K;
    c.records.push_back(r);
  }
  c.f = make_fuzzy_correspondence(std::move(e));
  return c;
}

/// Moves the given samples of a shape by random offsets of length 0.8 (its surface is its samples).
void deform(shape_record& r, const std::vector<index_t>& samples, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  for (const index_t i : samples) r.samples.row(i) += 0.8 * Eigen::RowVector3d(g(rng), g(rng), g(rng)).normalized();
  r.surface_points = r.samples;
}

/// The affine map taking shape j's coordinates to shape i's: placement[i] o placement[j]^-1.
affine_transform relative(const exact_collection& c, index_t j, index_t i) {
  const Eigen::Matrix3d Aj = c.placement[std::size_t(j)].leftCols<3>(), Ai = c.placement[std::size_t(i)].leftCols<3>();
  affine_transform T;
  T.leftCols<3>() = Ai * Aj.inverse();
  T.col(3) = c.placement[std::size_t(i)].col(3) - T.leftCols<3>() * c.placement[std::size_t(j)].col(3);
  return T;
}

}  // namespace

TEST_CASE("affine_least_squares recovers an affine map exactly from exact correspondences") {
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g(0.0, 1.0);
  const affine_transform T = random_affine(rng);
  affine_least_squares fit;
  for (int n = 0; n < 30; ++n) {
    const Eigen::Vector3d x(g(rng), g(rng), g(rng));
    fit.add(x, apply(T, x), 0.5 + std::abs(g(rng)));  // any positive weights
  }
  CHECK((fit.solve() - T).cwiseAbs().maxCoeff() < 1e-7);
}

TEST_CASE("affine_least_squares keeps the undetermined directions of planar pairs as a uniform scale would") {
  // Points in the plane z = 0 mapped by a rotation about z, scale 2 and a shift: z is not determined by them.
  const double c = std::cos(0.4), s = std::sin(0.4);
  affine_least_squares fit;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 0; n < 20; ++n) {
    const Eigen::Vector3d x(u(rng), u(rng), 0);
    fit.add(x, Eigen::Vector3d(2 * (c * x.x() - s * x.y()) + 1, 2 * (s * x.x() + c * x.y()), 3), 1.0);
  }
  const affine_transform T = fit.solve();
  CHECK(std::isfinite(T.norm()));
  const Eigen::Vector3d y = apply(T, Eigen::Vector3d(0.5, -0.5, 0));
  CHECK(y.x() == doctest::Approx(2 * (c * 0.5 + s * 0.5) + 1).epsilon(1e-6));
  CHECK(y.z() == doctest::Approx(3).epsilon(1e-6));
  CHECK(affine_least_squares().solve() == identity_affine());  // no pairs: the identity
}

TEST_CASE("affine_least_squares with max_stretch neither flattens nor mirrors, and keeps a moderate map exact") {
  // Scattered points all sent to one plane (y = 0) and mirrored in x: the plain fit flattens y and reflects.
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  affine_least_squares flat;
  for (int n = 0; n < 30; ++n) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    flat.add(x, Eigen::Vector3d(-x.x(), 0, x.z()), 1.0);
  }
  CHECK(std::abs(flat.solve().leftCols<3>().determinant()) < 1e-6);
  const Eigen::Matrix3d A = flat.solve(1e-9, 2.0).leftCols<3>();
  const Eigen::Vector3d sigma = Eigen::JacobiSVD<Eigen::Matrix3d>(A).singularValues();
  CHECK(sigma[0] == doctest::Approx(1.0));
  CHECK(sigma[2] == doctest::Approx(0.5));  // clamped to median / 2, not 0
  CHECK(A.determinant() > 0);               // a rotation-like map, not a mirror
  // A map whose stretch is within the bound is recovered exactly.
  const affine_transform T = random_affine(rng);
  affine_least_squares exact;
  for (int n = 0; n < 30; ++n) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    exact.add(x, apply(T, x), 1.0);
  }
  const Eigen::Vector3d s = Eigen::JacobiSVD<Eigen::Matrix3d>(T.leftCols<3>()).singularValues();
  REQUIRE(s[0] < 2 * s[1]);
  REQUIRE(s[2] > s[1] / 2);
  CHECK((exact.solve(1e-12, 2.0) - T).norm() < 1e-8);
}

TEST_CASE("region_query aligns every shape onto the example exactly when the correspondences are exact") {
  const exact_collection c = make_exact_collection(5, 40, 11);
  const region R{2, {0, 3, 4, 9, 17, 25}};
  const region_query q(c.f, c.records, R);
  CHECK(q.damping() == doctest::Approx(1.0 / (4 * 40)));
  for (index_t j = 0; j < 5; ++j) {
    CAPTURE(j);
    const region_match m = q.match(j);
    CHECK((m.transform - relative(c, j, 2)).cwiseAbs().maxCoeff() < 1e-6);
    CHECK(m.distance < 1e-6);
    // f_R is 1 exactly on R's counterparts (f(p, p) = 1 both ways), and below 1 elsewhere
    for (index_t i = 0; i < 40; ++i) {
      const bool in_region = std::find(R.samples.begin(), R.samples.end(), i) != R.samples.end();
      if (in_region) CHECK(m.correspondence[i] == doctest::Approx(1.0));
      else CHECK(m.correspondence[i] < 1.0);
    }
    CHECK(m.highlight().maxCoeff() == doctest::Approx(1.0));
    // the orbit centre lies in the example's frame, on the f_R-weighted centroid of the aligned samples
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (index_t i = 0; i < 40; ++i) centre += m.correspondence[i] * c.records[2].samples.row(i).transpose();
    CHECK((m.centre - centre / m.correspondence.sum()).norm() < 1e-6);
  }
}

TEST_CASE("region_query: a shape whose region differs is farther than the shapes whose region matches") {
  exact_collection c = make_exact_collection(6, 40, 12);
  const region R{0, {1, 2, 5, 8, 13, 14, 20, 21, 26, 30, 33, 39}};
  // Shape 4 keeps its correspondences but its region is deformed (a differently shaped part), in a way no affine
  // map undoes.
  deform(c.records[4], R.samples, 17);
  for (const bool symmetric : {false, true}) {
    CAPTURE(symmetric);
    const auto d = region_query(c.f, c.records, R, {.symmetric = symmetric}).distances();
    CHECK(d[0] == 0.0);
    for (const index_t j : {1, 2, 3, 5}) CHECK(d[std::size_t(j)] < 1e-6);
    CHECK(d[4] > 0.05);
  }
}

TEST_CASE("region_query: distances() is the same whatever the thread count") {
  const exact_collection c = make_exact_collection(7, 30, 13);
  const region R{3, {0, 1, 2}};
  CHECK(region_query(c.f, c.records, R, {.threads = 1}).distances() ==
        region_query(c.f, c.records, R, {.threads = 3}).distances());
}

TEST_CASE("region_query and checked_region refuse bad regions, naming the shape or the sample") {
  const exact_collection c = make_exact_collection(3, 20, 14);
  expect_invalid([&] { (void)region_query(c.f, c.records, region{3, {0}}); }, input_error::bad_parameter, 3);
  expect_invalid([&] { (void)region_query(c.f, c.records, region{-1, {0}}); }, input_error::bad_parameter, -1);
  expect_invalid([&] { (void)region_query(c.f, c.records, region{1, {}}); }, input_error::empty, 1);
  expect_invalid([&] { (void)region_query(c.f, c.records, region{1, {4, 20}}); }, input_error::bad_parameter, 20);
  const std::vector<shape_record> fewer(c.records.begin(), c.records.begin() + 2);
  expect_invalid([&] { (void)region_query(c.f, fewer, region{1, {0}}); }, input_error::size_mismatch);
  const region r = checked_region(c.f.embedding(), region{1, {5, 2, 5, 0}});
  CHECK(r.samples == std::vector<index_t>{0, 2, 5});
}

TEST_CASE("rank_by_facets: each facet normalised by its median, then averaged (hand-computed)") {
  // facet 1 medians over shapes 1-3: 4; facet 2: 20. Normalised: (0.5, 1, 1.5) and (1.5, 0.5, 1); means (1, 0.75, 1.25).
  const std::vector<std::vector<double>> d{{0, 2, 4, 6}, {0, 30, 10, 20}};
  const std::vector<index_t> examples{0};
  const collection_ranking r = rank_by_facets(d, examples);
  CHECK(r.order == std::vector<index_t>{0, 2, 1, 3});
  CHECK(r.distance[1] == doctest::Approx(1.0));
  CHECK(r.distance[2] == doctest::Approx(0.75));
  CHECK(r.distance[3] == doctest::Approx(1.25));
  // no correspondence at all (+infinity) goes last; the examples first even with a larger index
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::vector<double>> e{{inf, 1, 3, 2}};
  const std::vector<index_t> last_example{3};
  CHECK(rank_by_facets(e, last_example).order == std::vector<index_t>{3, 1, 2, 0});
  expect_invalid([] { (void)rank_by_facets({}, {}); }, input_error::empty);
  const std::vector<std::vector<double>> uneven{{0, 1}, {0, 1, 2}};
  expect_invalid([&] { (void)rank_by_facets(uneven, examples); }, input_error::size_mismatch, 1);
  const std::vector<std::vector<double>> negative{{0, -1, 2}};
  expect_invalid([&] { (void)rank_by_facets(negative, examples); }, input_error::bad_parameter, 1);
}

TEST_CASE("canonical_alignment maps every shape onto the reference exactly when the correspondences are exact") {
  const exact_collection c = make_exact_collection(5, 40, 15);
  const index_t ref = canonical_reference(c.f);
  REQUIRE(ref >= 0);
  REQUIRE(ref < 5);
  const auto T = canonical_alignment(c.f, c.records, ref);
  REQUIRE(T.size() == 5);
  for (index_t j = 0; j < 5; ++j) CHECK((T[std::size_t(j)] - relative(c, j, ref)).cwiseAbs().maxCoeff() < 1e-6);
}

TEST_CASE("collection_explorer: sort, details and their caches agree with the plain queries, from several threads") {
  exact_collection c = make_exact_collection(6, 40, 16);
  const region a{0, {1, 2, 5, 6, 7, 8, 9, 20, 21, 22}}, b{3, {10, 11, 12, 13}};
  deform(c.records[4], a.samples, 18);
  const auto da = region_query(c.f, c.records, a).distances();
  const auto db = region_query(c.f, c.records, b).distances();
  const collection_explorer x(c.f, c.records);
  const std::vector<region> facets{a, b};
  const std::vector<std::vector<double>> both{da, db};
  const std::vector<index_t> examples{0, 3};
  const collection_ranking expected = rank_by_facets(both, examples);
  std::vector<collection_ranking> got(4);
  std::vector<std::thread> pool;
  for (std::size_t t = 0; t < got.size(); ++t) pool.emplace_back([&, t] { got[t] = x.sort(facets); });
  for (auto& t : pool) t.join();
  for (const auto& g : got) CHECK(g.order == expected.order);
  CHECK(got[0].order.back() == 4);
  // details: framed by the first example, highlight the largest of the facets' normalised f_R
  const std::vector<index_t> shapes{4, 0};
  const auto d = x.details(facets, shapes);
  REQUIRE(d.size() == 2);
  CHECK(d[1].transform == identity_affine());
  for (const index_t i : {1, 2, 5, 10, 11, 12, 13}) CHECK(d[1].correspondence[i] == doctest::Approx(1.0));
  expect_invalid([&] { (void)x.sort({}); }, input_error::empty);
  const std::vector<index_t> unknown{9};
  expect_invalid([&] { (void)x.details(facets, unknown); }, input_error::bad_parameter, 9);
}
