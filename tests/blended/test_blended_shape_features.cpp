// SPDX-License-Identifier: MIT
// blended_shape's feature points: too few AGD maxima completed to blended_shape_options::min_features, maxima
// below min_feature_persistence dropped, and the second feature set without the low bumps.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "blended_fixtures.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/generate/primitive_meshes.hpp"

using namespace shapestruct;

namespace {
blended_shape_options small_options() {
  blended_shape_options o;
  o.num_samples = 96;
  o.threads = 2;
  return o;
}

/// A body with two arms pointing (nearly) opposite ways, of different lengths: its AGD has two maxima, the tips,
/// as a pair of glasses has only its two temple tips.
triangle_mesh<double> two_tips() {
  auto m = make_icosphere<double>(4);
  const Eigen::Vector3d dirs[2] = {Eigen::Vector3d(1, 0.1, 0.05).normalized(), Eigen::Vector3d(-1, 0.15, -0.1).normalized()};
  const double lengths[2] = {1.6, 1.2};
  for (index_t v = 0; v < m.V.rows(); ++v) {
    const Eigen::Vector3d p = m.V.row(v).transpose().normalized();
    double r = 1;
    for (int k = 0; k < 2; ++k) {
      const double t = std::max(0.0, (p.dot(dirs[k]) - 0.88) / (1 - 0.88));
      r += lengths[k] * t * t;
    }
    m.V.row(v) = (r * p).transpose();
  }
  return m;
}

bool same_map(const surface_map<double>& x, const surface_map<double>& y) {
  if (x.points.size() != y.points.size()) return false;
  for (std::size_t i = 0; i < x.points.size(); ++i)
    if (x.points[i].face != y.points[i].face || x.points[i].bary != y.points[i].bary) return false;
  return true;
}
}  // namespace

TEST_CASE("blended_shape completes two AGD maxima with the most central vertex and the farthest point") {
  const auto m = two_tips();
  blended_shape_options maxima_only = small_options();
  maxima_only.min_features = 0;
  const blended_shape<double> plain(m.V, m.F, maxima_only);
  REQUIRE(plain.features().size() == 2);
  CHECK(plain.num_agd_maxima() == 2);

  const blended_shape<double> completed(m.V, m.F, small_options());
  REQUIRE(completed.features().size() == 4);
  CHECK(completed.num_agd_maxima() == 2);
  const auto& f = completed.features();
  CHECK(f[0] == plain.features()[0]);  // the maxima first, unchanged
  CHECK(f[1] == plain.features()[1]);
  index_t centre = 0;
  completed.agd().minCoeff(&centre);
  CHECK(f[2] == centre);
  // The fourth lies farthest from the first three, by the brute-force minimum over their distances.
  const auto& geo = completed.geodesics();
  vector_x<double> nearest = vector_x<double>::Constant(completed.mesh().V.rows(), std::numeric_limits<double>::infinity());
  for (int k = 0; k < 3; ++k) nearest = nearest.cwiseMin(geo.distances_from(f[static_cast<std::size_t>(k)]));
  CHECK(nearest[f[3]] == doctest::Approx(nearest.maxCoeff()));
  CHECK(completed.feature_distances().cols() == 4);
}

TEST_CASE("blended_shape keeps enough AGD maxima as they are") {
  const auto m = test::armed_sphere(4, 5);
  const blended_shape<double> s(m.V, m.F, small_options());
  CHECK(s.features().size() >= 4);
  CHECK(static_cast<std::size_t>(s.num_agd_maxima()) == s.features().size());
}

TEST_CASE("blended_shape keeps the AGD maxima of at least min_feature_persistence, in AGD order") {
  // Ripples on a five-armed body: many small AGD maxima beside the five arm tips.
  auto m = test::armed_sphere(4, 5);
  for (index_t v = 0; v < m.V.rows(); ++v) {
    const Eigen::RowVector3d p = m.V.row(v);
    m.V.row(v) *= 1 + 0.03 * std::sin(9 * p.x()) * std::sin(9 * p.y()) * std::sin(9 * p.z());
  }
  blended_shape_options all = small_options();
  all.feature_radius = 0.03;
  all.max_features = 1000;
  all.min_features = 0;
  const blended_shape<double> every(m.V, m.F, all);
  const auto persistence = maximum_persistence<double>(every.geodesics().graph(), every.agd(), every.features());
  std::vector<double> sorted = persistence;
  std::sort(sorted.begin(), sorted.end());
  REQUIRE(sorted.size() >= 8);
  CHECK(sorted.front() < 0.25 * sorted.back());  // ripples and arm tips: a real spread to cut
  const double threshold = sorted[sorted.size() / 2];
  std::vector<index_t> expected;
  for (std::size_t i = 0; i < persistence.size(); ++i)
    if (persistence[i] >= threshold) expected.push_back(every.features()[i]);

  blended_shape_options persistent = all;
  persistent.min_feature_persistence = threshold;
  const blended_shape<double> kept(m.V, m.F, persistent);
  CHECK(kept.features() == expected);
  CHECK(static_cast<std::size_t>(kept.num_agd_maxima()) == expected.size());

  persistent.min_feature_persistence = -0.1;
  CHECK_THROWS_AS((void)blended_shape<double>(m.V, m.F, persistent), invalid_input);
  persistent.min_feature_persistence = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS((void)blended_shape<double>(m.V, m.F, persistent), invalid_input);
}

TEST_CASE("blended_matcher matches through the completed features, not the fallback of too few") {
  blended_matcher_options o;
  o.shape = small_options();
  o.refine = false;
  o.threads = 2;
  const blended_matcher<> completed(o);
  blended_matcher_options maxima_only = o;
  maxima_only.shape.min_features = 0;
  const blended_matcher<> plain(maxima_only);

  // Two maxima: no triplet at all, only the identity of the flattenings, unless the features are completed.
  const auto two = two_tips();
  const auto e_plain = plain.prepare(two);
  CHECK(plain.match(e_plain, e_plain).candidates.size() == 1);
  const auto e_completed = completed.prepare(two);
  CHECK(completed.match(e_completed, e_completed).candidates.size() > 1);

  // Three maxima (two arm tips and the far side of the body) and a completed fourth: the identity is found.
  const auto m = test::armed_sphere(4, 2);
  const auto a = completed.prepare(m);
  REQUIRE(a.num_agd_maxima() == 3);
  REQUIRE(a.features().size() == 4);
  const auto r = completed.match(a, a);
  std::vector<index_t> pred, truth;
  for (index_t v = 0; v < m.V.rows(); v += 7) {
    pred.push_back(r.map.target_vertex(v));
    truth.push_back(v);
  }
  const auto e = benchmark_geodesic_errors(a.mesh().V, a.mesh().F, a.geodesics(), std::span<const index_t>(pred),
                                           std::span<const index_t>(truth));
  CHECK(summarize_errors(std::span<const double>(e)).mean < 0.02);
}

TEST_CASE("blended_shape completes to at most max_features and refuses a negative min_features") {
  const auto m = two_tips();
  blended_shape_options o = small_options();
  o.max_features = 3;  // below the default min_features: the cap wins
  CHECK(blended_shape<double>(m.V, m.F, o).features().size() == 3);
  o.min_features = -1;
  CHECK_THROWS_AS(blended_shape<double>(m.V, m.F, o), invalid_input);
}

TEST_CASE("blended_shape's alternative drops the maxima below alternative_feature_persistence and shares the rest") {
  const auto m = test::bumpy_creature();
  blended_shape_options one_set = small_options();
  one_set.alternative_feature_persistence = 0;
  const blended_shape<double> plain(m.V, m.F, one_set);
  CHECK(plain.alternative() == nullptr);
  const auto persistence = maximum_persistence<double>(plain.geodesics().graph(), plain.agd(), plain.features());
  std::vector<index_t> expected;
  for (std::size_t i = 0; i < persistence.size(); ++i)
    if (persistence[i] >= 0.08) expected.push_back(plain.features()[i]);
  REQUIRE(expected.size() >= 4);  // the arm tips
  REQUIRE(expected.size() < plain.features().size());  // and a bump below 0.08

  blended_shape_options two_sets = small_options();
  two_sets.alternative_feature_persistence = 0.08;
  const blended_shape<double> s(m.V, m.F, two_sets);
  CHECK(s.features() == plain.features());  // the first set is the full one, unchanged
  REQUIRE(s.alternative() != nullptr);
  CHECK(s.alternative()->features() == expected);
  CHECK(s.alternative()->alternative() == nullptr);
  CHECK(s.alternative()->feature_distances().cols() == static_cast<index_t>(expected.size()));
  CHECK(&s.alternative()->sample_distances() == &s.sample_distances());  // shared, not copied
  CHECK(&s.alternative()->geodesics() == &s.geodesics());
  CHECK(s.heap_bytes() > plain.heap_bytes());
  CHECK(s.heap_bytes() < plain.heap_bytes() + plain.heap_bytes() / 5);

  // No maximum below the threshold: no second set.
  two_sets.alternative_feature_persistence = 0.5 * *std::min_element(persistence.begin(), persistence.end());
  CHECK(blended_shape<double>(m.V, m.F, two_sets).alternative() == nullptr);
  CHECK(blended_shape<double>(test::armed_sphere(4, 5).V, test::armed_sphere(4, 5).F, small_options()).alternative() ==
        nullptr);
  two_sets.alternative_feature_persistence = -0.1;
  CHECK_THROWS_AS((void)blended_shape<double>(m.V, m.F, two_sets), invalid_input);
  two_sets.alternative_feature_persistence = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS((void)blended_shape<double>(m.V, m.F, two_sets), invalid_input);
}

TEST_CASE("blended_matcher keeps the second feature set when its blended map distorts geodesic distances clearly less") {
  blended_matcher_options o;
  o.shape = small_options();
  o.shape.num_samples = 128;  // with 96 the two sets' maps of this pair distort within 1 % of each other
  o.refine = false;
  o.threads = 2;
  o.both_directions = false;  // the stage timings below are counted for one direction
  const blended_matcher<> matcher(o);
  blended_matcher_options one_set_options = o;
  one_set_options.shape.alternative_feature_persistence = 0;
  const blended_matcher<> one_set(one_set_options);

  const auto source = test::bumpy_creature();
  const auto target = test::armed_sphere(4, 6);
  const auto a = matcher.prepare(source);
  const auto b = matcher.prepare(target);
  REQUIRE(a.alternative() != nullptr);
  REQUIRE(b.alternative() == nullptr);

  // The two runs on their own: the full set, and the source's alternative against the target.
  const auto full = one_set.match(one_set.prepare(source), one_set.prepare(target));
  const auto fewer = matcher.match(*a.alternative(), b);
  const double d_full = full.blended[static_cast<std::size_t>(full.selected)].geodesic_distortion;
  const double d_fewer = fewer.blended[static_cast<std::size_t>(fewer.selected)].geodesic_distortion;
  // A pair that tells the rule from its reverse and from a plain comparison: here the alternative wins.
  REQUIRE(d_fewer < (1 - o.alternative_distortion_margin) * d_full);
  CHECK_FALSE(full.alternative_features);
  CHECK(std::isnan(full.other_features_distortion));

  const auto r = matcher.match(a, b);
  const bool take_fewer = d_fewer < (1 - o.alternative_distortion_margin) * d_full;
  CHECK(r.alternative_features == take_fewer);
  CHECK(same_map(r.map, take_fewer ? fewer.map : full.map));
  CHECK(r.blended[static_cast<std::size_t>(r.selected)].geodesic_distortion == (take_fewer ? d_fewer : d_full));
  CHECK(r.other_features_distortion == (take_fewer ? d_full : d_fewer));
  CHECK(r.candidates.size() == (take_fewer ? fewer : full).candidates.size());
  // A margin the second set does not clear: the full set's map.
  blended_matcher_options wide = o;
  wide.alternative_distortion_margin = 0.5;
  const auto r_wide = blended_matcher<>(wide).match(a, b);
  CHECK_FALSE(r_wide.alternative_features);
  CHECK(same_map(r_wide.map, full.map));
  CHECK(r_wide.other_features_distortion == d_fewer);
  // Both runs' stages are timed, the second set's marked.
  const auto marked = std::count_if(r.timings.begin(), r.timings.end(), [](const auto& t) {
    return t.first.find(", alternative features") != std::string::npos;
  });
  CHECK(marked == static_cast<long>(full.timings.size()));
  CHECK(r.timings.size() == 2 * full.timings.size());
}

TEST_CASE("blended_matcher keep_both_feature_sets keeps every blended map of both sets and the rule's choice") {
  blended_matcher_options o;
  o.shape = small_options();
  o.shape.num_samples = 128;
  o.refine = false;
  o.threads = 2;
  blended_matcher_options one_set_options = o;
  one_set_options.shape.alternative_feature_persistence = 0;
  const blended_matcher<> one_set(one_set_options);
  const auto source = test::bumpy_creature();
  const auto target = test::armed_sphere(4, 6);
  const auto full = one_set.match(one_set.prepare(source), one_set.prepare(target));
  const blended_matcher<> matcher(o);
  const auto a = matcher.prepare(source);
  const auto b = matcher.prepare(target);
  REQUIRE(a.alternative() != nullptr);
  const auto fewer = matcher.match(*a.alternative(), b);

  for (const double margin : {o.alternative_distortion_margin, 0.5}) {
    CAPTURE(margin);
    blended_matcher_options pooling = o;
    pooling.keep_both_feature_sets = true;
    pooling.alternative_distortion_margin = margin;
    const auto kept = blended_matcher<>(pooling).match(a, b);
    const auto single = [&] {
      blended_matcher_options plain = pooling;
      plain.keep_both_feature_sets = false;
      return blended_matcher<>(plain).match(a, b);
    }();
    // The choice and its map are the ones the matcher makes without pooling.
    CHECK(kept.alternative_features == single.alternative_features);
    CHECK(same_map(kept.map, single.map));
    const auto& chosen = kept.blended[static_cast<std::size_t>(kept.selected)];
    CHECK(chosen.alternative_features == kept.alternative_features);
    CHECK(chosen.geodesic_distortion == single.blended[static_cast<std::size_t>(single.selected)].geodesic_distortion);
    // Every map of both runs, the full set's first, with candidate indices into the joined list.
    REQUIRE(kept.blended.size() == full.blended.size() + fewer.blended.size());
    REQUIRE(kept.candidates.size() == full.candidates.size() + fewer.candidates.size());
    CHECK(kept.confidence.rows() == static_cast<index_t>(kept.candidates.size()));
    CHECK(kept.confidence.bottomRows(fewer.confidence.rows()) == fewer.confidence);
    const auto offset = static_cast<index_t>(full.candidates.size());
    for (std::size_t g = 0; g < kept.blended.size(); ++g) {
      const bool second = g >= full.blended.size();
      const auto& original = second ? fewer.blended[g - full.blended.size()] : full.blended[g];
      CHECK(kept.blended[g].alternative_features == second);
      CHECK(kept.blended[g].geodesic_distortion == original.geodesic_distortion);
      REQUIRE(kept.blended[g].maps.size() == original.maps.size());
      for (std::size_t m = 0; m < original.maps.size(); ++m)
        CHECK(kept.blended[g].maps[m] == original.maps[m] + (second ? offset : 0));
    }
  }
}
