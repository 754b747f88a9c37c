// SPDX-License-Identifier: MIT
#include <algorithm>
#include <numeric>
#include <vector>

#include <doctest/doctest.h>

#include "blended_fixtures.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/blended/sample_map_measures.hpp"
#include "shapestruct/maps/surface_map.hpp"
#include "support/fixtures.hpp"

using namespace shapestruct;

namespace {
blended_matcher_options small_options() {
  blended_matcher_options o;
  o.shape.num_samples = 128;
  o.threads = 2;
  o.full_maps_for_all_groups = true;  // every group's map, to compare with its recorded distortion
  return o;
}

/// A shape, its rigidly moved and vertex-permuted copy (perm: source vertex -> its copy), both prepared.
struct moved_pair {
  triangle_mesh<double> source = test::armed_sphere(3);
  std::vector<index_t> perm;
  triangle_mesh<double> target = test::moved_and_permuted(source, perm);
  blended_matcher<> matcher{small_options()};
  blended_shape<double> a = matcher.prepare(source);
  blended_shape<double> b = matcher.prepare(target);
};
}  // namespace

TEST_CASE("geodesic distortion: zero for the identity, small for an isometry, large for a scrambled map") {
  const moved_pair p;
  const auto& [m, perm, moved, matcher, a, b] = p;
  std::vector<index_t> identity(static_cast<std::size_t>(m.V.rows()));
  std::iota(identity.begin(), identity.end(), index_t(0));
  CHECK(input_map_geodesic_distortion(a, a, surface_map_at_vertices(m, identity)) == doctest::Approx(0.0));
  // The true map of a rigid copy: only the reading of d_b through b's nearest sample (its covering radius) is left.
  const double truth = input_map_geodesic_distortion(a, b, surface_map_at_vertices(moved, perm));
  std::vector<index_t> scrambled = perm;
  std::reverse(scrambled.begin(), scrambled.end());
  const double wrong = input_map_geodesic_distortion(a, b, surface_map_at_vertices(moved, scrambled));
  MESSAGE("true map " << truth << ", scrambled " << wrong);
  CHECK(truth < 0.05);
  CHECK(wrong > 5 * truth);
  // Unmapped images are left out, not read as vertex 0.
  auto partial = surface_map_at_vertices(moved, perm);
  std::fill(partial.nearest.begin(), partial.nearest.begin() + partial.nearest.size() / 2, no_index);
  CHECK(input_map_geodesic_distortion(a, b, partial) < 0.05);
}

TEST_CASE("mean image distance: near zero for one map, large for a map and its scrambling, symmetric in use") {
  const moved_pair p;
  const auto& [m, perm, moved, matcher, a, b] = p;
  const auto truth = surface_map_at_vertices(moved, perm);
  std::vector<index_t> scrambled = perm;
  std::reverse(scrambled.begin(), scrambled.end());
  const auto wrong = surface_map_at_vertices(moved, scrambled);
  const double same = mean_image_distance(a, b, truth, truth);
  const double apart = mean_image_distance(a, b, truth, wrong);
  MESSAGE("same map " << same << ", scrambled " << apart);
  CHECK(same < 0.05);  // the distance to the image's nearest sample only
  CHECK(apart > 0.3);  // unit area: a sphere of area 1 has a diameter of about 0.89
  CHECK(mean_image_distance(a, b, wrong, truth) == doctest::Approx(apart).epsilon(0.1));
  // Samples either map leaves unmapped do not count.
  auto none = truth;
  std::fill(none.nearest.begin(), none.nearest.end(), no_index);
  CHECK(mean_image_distance(a, b, truth, none) == 0.0);
}

TEST_CASE("geodesic distortion of a blended map in the input numbering is the matcher's own measure") {
  const moved_pair p;
  const auto& [m, perm, moved, matcher, a, b] = p;
  const auto r = matcher.match(m, moved);
  REQUIRE(r.blended.size() >= 1);
  for (const auto& g : r.blended) {
    REQUIRE(g.map.source_size() == m.V.rows());
    CHECK(input_map_geodesic_distortion(a, b, g.map) == doctest::Approx(g.geodesic_distortion));
  }
}
