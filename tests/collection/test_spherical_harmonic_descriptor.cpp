// SPDX-License-Identifier: MIT
// spherical_harmonic_descriptor: invariance, discrimination, an analytic oracle, determinism and the input errors.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <thread>
#include <vector>

#include <Eigen/Geometry>

#include "shapestruct/collection/spherical_harmonic_descriptor.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"
#include "shapestruct/geometry/surface_sampling.hpp"

using namespace shapestruct;

namespace {

using points_t = Eigen::Matrix<double, Eigen::Dynamic, 3>;

static_assert(ShapeDescriptor<spherical_harmonic_descriptor>);

/// 1,024 evenly spread surface points, the size shape_record::surface_points has by default.
points_t surface_points(const triangle_mesh<double>& m, std::uint64_t seed) {
  return sample_surface_even(m, 1024, {.seed = seed}).points;
}

/// s * R p + t for every row p.
points_t similarity(const points_t& p, const Eigen::Matrix3d& R, double s, const Eigen::Vector3d& t) {
  points_t q = s * (p * R.transpose());
  q.rowwise() += t.transpose();
  return q;
}

// Three shapes of different kinds: a round sphere, a flat elongated box (2 x 1 x 0.5) and a ring.
triangle_mesh<double> sphere() { return make_icosphere<double>(4); }
triangle_mesh<double> box() { return make_box<double>(1.0, 0.5, 0.25); }
triangle_mesh<double> ring() { return make_torus<double>(1.0, 0.3, 48, 24); }

}  // namespace

TEST_CASE("spherical_harmonic_descriptor is invariant to rotation, translation and uniform scale") {
  const spherical_harmonic_descriptor describe;
  const std::vector<points_t> shapes = {surface_points(sphere(), 1), surface_points(box(), 1),
                                        surface_points(ring(), 1)};
  std::vector<Eigen::VectorXd> d;
  for (const auto& p : shapes) d.push_back(describe(p));
  double between = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < d.size(); ++a)
    for (std::size_t b = a + 1; b < d.size(); ++b) between = std::min(between, (d[a] - d[b]).norm());
  // The closest pair (box and ring, 0.15 measured) is still far apart in absolute terms.
  CHECK(between > 0.05);

  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::Vector3d axis(u(rng), u(rng), u(rng));
    const Eigen::Matrix3d R = Eigen::AngleAxisd(3.0 * u(rng), axis.normalized()).toRotationMatrix();
    const double s = std::exp(2.0 * u(rng));  // 0.14 .. 7.4
    const Eigen::Vector3d t(10 * u(rng), 10 * u(rng), 10 * u(rng));
    for (std::size_t k = 0; k < shapes.size(); ++k) {
      CAPTURE(trial);
      CAPTURE(k);
      const double moved = (describe(similarity(shapes[k], R, s, t)) - d[k]).norm();
      // Measured: at most 0.0033 (the box, whose flat faces cross voxel layers differently in each pose), i.e.
      // about 2 % of the closest pair of different shapes. Exact invariance holds only for the continuous GEDT.
      CHECK(moved < 0.1 * between);
    }
  }
}

TEST_CASE("spherical_harmonic_descriptor separates different shapes far more than perturbed copies") {
  const spherical_harmonic_descriptor describe;
  const Eigen::VectorXd ball = describe(surface_points(sphere(), 1));
  const Eigen::VectorXd brick = describe(surface_points(box(), 1));
  const Eigen::VectorXd torus = describe(surface_points(ring(), 1));

  // A bumpy sphere: every vertex moved radially by up to 3 %, sampled with another seed.
  auto bumpy = sphere();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (index_t i = 0; i < bumpy.V.rows(); ++i) bumpy.V.row(i) *= 1 + 0.03 * u(rng);
  const double near_sphere = (describe(surface_points(bumpy, 2)) - ball).norm();
  const double sphere_box = (brick - ball).norm();
  // Measured: 0.0085 against 0.31.
  CHECK(sphere_box > 10 * near_sphere);

  // Another sample of the same surface is also close: the descriptor sees the surface, not the samples.
  CHECK((describe(surface_points(box(), 7)) - brick).norm() < 0.2 * (torus - brick).norm());
  CHECK((describe(surface_points(ring(), 7)) - torus).norm() < 0.2 * (torus - brick).norm());
}

TEST_CASE("spherical_harmonic_descriptor of coincident points is the sampled radial Gaussian") {
  // All points at one place: the centre of mass lands on the grid centre (a voxel corner), every voxel's distance
  // is exact, so on sphere r the GEDT is the constant exp(-rho^2 / (2 s^2)) up to trilinear interpolation, whose
  // only harmonic is degree 0 with norm sqrt(4 pi) times that constant. A Gaussian 4 voxels wide keeps the
  // interpolation error (about (1/8) f'' voxel^2) near 1 % of the peak; at the default 2 voxels it is 4 %.
  const spherical_harmonic_descriptor describe({.gaussian_width = 0.5});
  points_t p(5, 3);
  p.rowwise() = Eigen::RowVector3d(3, -2, 7);
  const Eigen::VectorXd d = describe(p);
  const auto& o = describe.options();
  const double sigma = o.gaussian_width * o.grid / 4.0;  // voxels
  const double shell = std::sqrt(3 / (4 * std::numbers::pi * std::pow(double(o.radii), 3)));
  for (int r = 0; r < o.radii; ++r) {
    CAPTURE(r);
    const double rho = (r + 1) * (o.grid / 2.0) / o.radii;
    const double expected = (r + 1) * shell * std::sqrt(4 * std::numbers::pi) * std::exp(-rho * rho / (2 * sigma * sigma));
    // Measured: 1.2 % and 0.16 % of the largest entry.
    CHECK(std::abs(d[r * o.bands] - expected) < 0.025 * d.maxCoeff());
    for (int l = 1; l < o.bands; ++l) CHECK(d[r * o.bands + l] < 0.005 * d.maxCoeff());
  }
}

TEST_CASE("spherical_harmonic_descriptor quadrature is exact for the orthonormal Legendre functions") {
  // sum_j w_j 2 pi Pbar_l^m(x_j) Pbar_k^m(x_j) = delta_lk for all m <= l, k < bands: the degree-l norms the
  // descriptor reports are the norms of orthonormal projections.
  const int bands = 16;
  std::vector<double> x, w;
  detail::gauss_legendre(2 * bands, x, w);
  const auto tri = static_cast<std::size_t>(bands * (bands + 1) / 2);
  std::vector<double> table(tri * x.size());
  for (std::size_t j = 0; j < x.size(); ++j) detail::normalized_legendre(bands, x[j], table.data() + j * tri);
  double worst = 0;
  for (int m = 0; m < bands; ++m)
    for (int l = m; l < bands; ++l)
      for (int k = m; k < bands; ++k) {
        double sum = 0;
        for (std::size_t j = 0; j < x.size(); ++j)
          sum += w[j] * 2 * std::numbers::pi * table[j * tri + std::size_t(l * (l + 1) / 2 + m)] *
                 table[j * tri + std::size_t(k * (k + 1) / 2 + m)];
        worst = std::max(worst, std::abs(sum - (l == k ? 1.0 : 0.0)));
      }
  CHECK(worst < 1e-12);
}

TEST_CASE("spherical_harmonic_descriptor is deterministic and thread-safe with a fixed length") {
  const points_t p = surface_points(ring(), 3);
  const spherical_harmonic_descriptor describe({.grid = 16, .radii = 8, .bands = 6});
  CHECK(describe.size() == 48);
  const Eigen::VectorXd once = describe(p);
  REQUIRE(once.size() == 48);
  CHECK(once.allFinite());
  CHECK((once.array() >= 0).all());
  CHECK(once == describe(p));
  // The same const object from two threads at once gives bit-identical results.
  Eigen::VectorXd a, b;
  std::thread ta([&] { a = describe(p); }), tb([&] { b = describe(p); });
  ta.join();
  tb.join();
  CHECK(a == once);
  CHECK(b == once);
  // Default options: 16 spheres x 16 degrees, whatever the number of points.
  const spherical_harmonic_descriptor standard;
  CHECK(standard(p).size() == 256);
  CHECK(standard(p.topRows(10)).size() == 256);
}

TEST_CASE("spherical_harmonic_descriptor: one test per invalid_input reason") {
  auto reason_of = [](auto&& f) {
    try {
      f();
    } catch (const invalid_input& e) {
      return std::make_pair(e.reason(), e.element());
    }
    FAIL("no invalid_input thrown");
    return std::make_pair(input_error::empty, no_index);
  };
  const spherical_harmonic_descriptor describe;
  SUBCASE("empty") {
    const points_t none(0, 3);
    CHECK(reason_of([&] { (void)describe(none); }) == std::make_pair(input_error::empty, no_index));
  }
  SUBCASE("non_finite") {
    points_t p = points_t::Zero(4, 3);
    p(2, 1) = std::numeric_limits<double>::quiet_NaN();
    CHECK(reason_of([&] { (void)describe(p); }) == std::make_pair(input_error::non_finite, index_t(2)));
    p(2, 1) = 0;
    p(3, 0) = std::numeric_limits<double>::infinity();
    CHECK(reason_of([&] { (void)describe(p); }) == std::make_pair(input_error::non_finite, index_t(3)));
  }
  SUBCASE("bad_parameter") {
    auto make = [&](const spherical_harmonic_descriptor_options& o) {
      return reason_of([&] { (void)spherical_harmonic_descriptor(o); }).first;
    };
    CHECK(make({.grid = 3}) == input_error::bad_parameter);
    CHECK(make({.grid = 257}) == input_error::bad_parameter);
    CHECK(make({.radii = 0}) == input_error::bad_parameter);
    CHECK(make({.radii = 1025}) == input_error::bad_parameter);
    CHECK(make({.bands = 0}) == input_error::bad_parameter);
    CHECK(make({.bands = 129}) == input_error::bad_parameter);
    CHECK(make({.gaussian_width = 0}) == input_error::bad_parameter);
    CHECK(make({.gaussian_width = -1}) == input_error::bad_parameter);
    CHECK(make({.gaussian_width = std::numeric_limits<double>::quiet_NaN()}) == input_error::bad_parameter);
    CHECK(make({.gaussian_width = std::numeric_limits<double>::infinity()}) == input_error::bad_parameter);
  }
}
