// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "blended_fixtures.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/core/concepts/pairwise_matcher.hpp"
#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/maps/vertex_map.hpp"
#include "shapestruct/refine/no_refinement.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

static_assert(PairwiseMatcher<blended_matcher<>, triangle_mesh<double>, test::legacy_mesh>);
static_assert(CorrespondenceMap<surface_map<double>>);
static_assert(CorrespondenceMap<vertex_map<double>>);

namespace {
blended_matcher_options small_options() {
  blended_matcher_options o;
  o.shape.num_samples = 128;  // a 2,562-vertex test shape does not need 256 samples
  o.threads = 2;
  return o;
}

/// Mean geodesic error (the benchmark's scale, d / sqrt(area of the target)) of a map against the truth truth[v].
/// The bounds below (0.02 for a correct map, 0.2 for a flip) were set on half that scale as 0.01 and 0.1.
double mean_error(const blended_shape<double>& target, const surface_map<double>& map, const std::vector<index_t>& truth,
                  index_t stride = 7) {
  std::vector<index_t> pred, tru;
  for (index_t v = 0; v < map.source_size(); v += stride) {
    pred.push_back(map.target_vertex(v));
    tru.push_back(truth[static_cast<std::size_t>(v)]);
  }
  const auto e = benchmark_geodesic_errors(target.mesh().V, target.mesh().F, target.geodesics(),
                                           std::span<const index_t>(pred), std::span<const index_t>(tru));
  return summarize_errors(std::span<const double>(e)).mean;
}
}  // namespace

TEST_CASE("blended_matcher: a shape matched to itself gives the identity (triangle_mesh and legacy_mesh)") {
  const auto m = test::armed_sphere(4);
  const blended_matcher<> matcher(small_options());
  std::vector<index_t> id(static_cast<std::size_t>(m.V.rows()));
  std::iota(id.begin(), id.end(), index_t(0));
  const auto r = matcher.match(m, m);
  CHECK(r.info == status::ok);
  CHECK(r.candidates.size() > 0);
  CHECK(r.blended.size() >= 1);
  const auto sm = matcher.prepare(m);
  CHECK(sm.features().size() >= 4);  // the arm tips
  CHECK(mean_error(sm, r.map, id) < 0.02);

  const auto legacy = test::to_legacy(m);
  const auto r2 = matcher.match(legacy, legacy);
  CHECK(mean_error(sm, r2.map, id) < 0.02);
}

TEST_CASE("blended_matcher: a rigidly moved, vertex-permuted copy is matched up to the permutation") {
  const auto m = test::armed_sphere(4);
  std::vector<index_t> perm;
  const auto moved = test::moved_and_permuted(m, perm);
  const blended_matcher<> matcher(small_options());
  const auto r = matcher.match(m, moved);
  const auto target = matcher.prepare(moved);
  CHECK(mean_error(target, r.map, perm) < 0.02);
  // Every source vertex is mapped, to a valid surface point.
  for (index_t v = 0; v < r.map.source_size(); ++v) {
    REQUIRE(r.map.point(v).valid());
    CHECK(r.map.target_vertex(v) >= 0);
    CHECK(r.map.target_vertex(v) < moved.V.rows());
  }
}

TEST_CASE("blended_matcher: results do not depend on the thread count") {
  const auto m = test::armed_sphere(3);
  std::vector<index_t> perm;
  const auto moved = test::moved_and_permuted(m, perm);
  auto o1 = small_options();
  o1.threads = 1;
  auto o3 = small_options();
  o3.threads = 3;
  const auto r1 = blended_matcher<>(o1).match(m, moved);
  const auto r3 = blended_matcher<>(o3).match(m, moved);
  REQUIRE(r1.map.source_size() == r3.map.source_size());
  for (index_t v = 0; v < r1.map.source_size(); ++v) {
    CHECK(r1.map.target_vertex(v) == r3.map.target_vertex(v));
    CHECK(r1.map.point(v).bary.isApprox(r3.map.point(v).bary, 0.0));
  }
  CHECK(r1.selected == r3.selected);
}

TEST_CASE("blended_matcher keeps every candidate blended map with its score and picks the best") {
  const auto m = test::armed_sphere(3);
  auto o = small_options();
  o.full_maps_for_all_groups = true;
  const auto r = blended_matcher<>(o).match(m, m);
  REQUIRE(r.selected >= 0);
  for (const auto& b : r.blended) {
    CHECK(b.score >= 0);
    CHECK(b.score <= 1);
    CHECK(b.selection_rank >= r.blended[static_cast<std::size_t>(r.selected)].selection_rank);
    CHECK(b.selection_rank <= 2 * static_cast<index_t>(r.blended.size() - 1));
    CHECK(b.selection_score == doctest::Approx(b.score - o.convexity_weight * b.convexity_mismatch));
    CHECK(b.confidence_integral >= 0);
    CHECK(b.confidence_integral <= 1);
    CHECK(b.convexity_mismatch >= 0);
    CHECK(b.geodesic_distortion >= 0);
    CHECK(b.map.source_size() == m.V.rows());
  }
  CHECK(r.confidence.rows() == static_cast<index_t>(r.candidates.size()));
  CHECK(r.confidence.minCoeff() >= 0);
  CHECK(r.confidence.maxCoeff() <= 1);
}

TEST_CASE("blended_matcher selects by the chosen rule: area score, integrated confidence, or their rank sum") {
  const auto m = test::front_back_creature(3);  // its intrinsic flip forms a second group
  auto o = small_options();
  const auto sm = blended_matcher<>(o).prepare(m);
  for (const auto rule : {blended_selection::area_score, blended_selection::integrated_confidence,
                          blended_selection::area_and_confidence_rank, blended_selection::confidence_and_distortion_rank,
                          blended_selection::distortion_adaptive}) {
    o.selection = rule;
    const auto r = blended_matcher<>(o).match(sm, sm);
    REQUIRE(r.blended.size() >= 2);  // several groups, so the rules have something to choose between
    const auto& chosen = r.blended[static_cast<std::size_t>(r.selected)];
    for (const auto& b : r.blended) {
      if (rule == blended_selection::area_score) CHECK(b.selection_score <= chosen.selection_score);
      if (rule == blended_selection::integrated_confidence) CHECK(b.confidence_integral <= chosen.confidence_integral);
      CHECK(b.selection_rank >= chosen.selection_rank);
    }
  }
}

TEST_CASE("blended_matcher's confidence_and_distortion_rank sums the ranks by confidence and by geodesic distortion") {
  // The creature against a copy stretched 1.6 times along x: no map is an isometry, so the groups' distortions
  // differ, and the most confident map is not the least distorted one.
  const auto m = test::front_back_creature(3);
  auto stretched = m;
  stretched.V.col(0) *= 1.6;
  auto o = small_options();
  o.selection = blended_selection::confidence_and_distortion_rank;
  const auto r = blended_matcher<>(o).match(m, stretched);
  const auto n = r.blended.size();
  REQUIRE(n >= 2);
  std::size_t most_confident = 0, least_distorted = 0;
  for (std::size_t g = 0; g < n; ++g) {
    std::size_t by_confidence = 0, by_distortion = 0;  // groups ranked before g (strictly better)
    for (std::size_t h = 0; h < n; ++h) {
      by_confidence += r.blended[h].confidence_integral > r.blended[g].confidence_integral;
      by_distortion += r.blended[h].geodesic_distortion < r.blended[g].geodesic_distortion;
    }
    CAPTURE(g);
    CHECK(r.blended[g].selection_rank == static_cast<index_t>(by_confidence + by_distortion));  // no ties here
    if (r.blended[g].confidence_integral > r.blended[most_confident].confidence_integral) most_confident = g;
    if (r.blended[g].geodesic_distortion < r.blended[least_distorted].geodesic_distortion) least_distorted = g;
  }
  CHECK(most_confident != least_distorted);  // so both ranks matter
  const auto& chosen = r.blended[static_cast<std::size_t>(r.selected)];
  for (const auto& b : r.blended) {
    CHECK(b.selection_rank >= chosen.selection_rank);
    if (b.selection_rank == chosen.selection_rank) CHECK(b.selection_score <= chosen.selection_score);  // ties: area
  }
}

TEST_CASE("blended_matcher's distortion_adaptive ranks by distortion only when the most confident map is distorted") {
  const auto m = test::front_back_creature(3);
  auto stretched = m;  // as above: the most confident map is not the least distorted one
  stretched.V.col(0) *= 1.6;
  auto o = small_options();
  const blended_matcher<> matcher(o);
  const auto sa = matcher.prepare(m), sb = matcher.prepare(stretched);
  const auto selected_with = [&](blended_selection rule, double threshold) {
    auto oo = o;
    oo.selection = rule;
    oo.near_isometric_distortion = threshold;
    return blended_matcher<>(oo).match(sa, sb);
  };
  const auto by_confidence = selected_with(blended_selection::integrated_confidence, 0);
  const auto by_rank_sum = selected_with(blended_selection::confidence_and_distortion_rank, 0);
  const auto ranks = [](const blended_match_result<double>& r) {
    std::vector<index_t> out;
    for (const auto& b : r.blended) out.push_back(b.selection_rank);
    return out;
  };
  REQUIRE(ranks(by_confidence) != ranks(by_rank_sum));  // so which rule the gate applies can be seen
  const double d = by_confidence.blended[static_cast<std::size_t>(by_confidence.selected)].geodesic_distortion;
  REQUIRE(d > 0);
  // At or above the most confident map's distortion the pair counts as near-isometric: confidence alone.
  for (const double threshold : {d, 2 * d}) {
    const auto gated = selected_with(blended_selection::distortion_adaptive, threshold);
    CHECK(gated.selected == by_confidence.selected);
    CHECK(ranks(gated) == ranks(by_confidence));
  }
  // Below it the distortion is evidence too: the rank sum's choice, with its ranks.
  const auto gated = selected_with(blended_selection::distortion_adaptive, 0.99 * d);
  CHECK(gated.selected == by_rank_sum.selected);
  CHECK(ranks(gated) == ranks(by_rank_sum));
}

TEST_CASE("blended_matcher tells a map from its intrinsic flip by convexity (dome vs dimple)") {
  // Front and back are isometric, so the true map and the front-to-back flip preserve area equally well; the
  // convexity mismatch (a dome must map to a dome) picks the true one.
  const auto m = test::front_back_creature(4);
  std::vector<index_t> perm;
  const auto moved = test::moved_and_permuted(m, perm);
  auto o = small_options();
  o.full_maps_for_all_groups = true;
  o.convexity_weight = 5;
  o.selection = blended_selection::area_score;  // isolate the convexity tie-break
  const auto target = blended_matcher<>(o).prepare(moved);
  const auto r = blended_matcher<>(o).match(m, moved);
  INFO("groups: " << r.blended.size());
  CHECK(mean_error(target, r.map, perm) < 0.02);
  // The flip is among the blended maps, and intrinsically it is (nearly) as good as the truth.
  std::optional<std::size_t> flip;
  for (std::size_t g = 0; g < r.blended.size(); ++g) {
    const double e = mean_error(target, r.blended[g].map, perm);
    MESSAGE("group " << g << ": error " << e << " score " << r.blended[g].score << " convexity "
                     << r.blended[g].convexity_mismatch << " size " << r.blended[g].maps.size());
    if (e > 0.2 && (!flip || r.blended[g].score > r.blended[*flip].score)) flip = g;
  }
  REQUIRE(flip.has_value());
  const auto& chosen = r.blended[static_cast<std::size_t>(r.selected)];
  const auto& flipped = r.blended[*flip];
  MESSAGE("true map: area score " << chosen.score << ", convexity mismatch " << chosen.convexity_mismatch
                                  << "; flip: " << flipped.score << ", " << flipped.convexity_mismatch);
  // Area preservation alone does not separate them (here it even prefers the flip, by discretisation noise)...
  CHECK(flipped.score > chosen.score - 0.02);
  // ...convexity does.
  CHECK(flipped.convexity_mismatch > chosen.convexity_mismatch + 0.003);
}

TEST_CASE("blended_matcher rejects meshes that are not closed genus-0 manifolds, naming the repair option") {
  const blended_matcher<> matcher(small_options());
  const auto good = test::armed_sphere(2);
  auto reason = [&](const triangle_mesh<double>& bad) -> std::optional<invalid_input> {
    try {
      (void)matcher.match(bad, good);
    } catch (const invalid_input& e) {
      return e;
    }
    return std::nullopt;
  };
  SUBCASE("holes") {
    auto open = good;
    open.F.conservativeResize(open.F.rows() - 1, 3);  // remove one face: a 3-edge hole
    const auto e = reason(open);
    REQUIRE(e.has_value());
    CHECK(e->reason() == input_error::unsupported_topology);
    CHECK(std::string(e->what()).find("close_small_holes") != std::string::npos);
    auto o = small_options();
    o.shape.repairs.close_small_holes = true;
    CHECK_NOTHROW((void)blended_matcher<>(o).match(open, good));
  }
  SUBCASE("higher genus") {
    const auto e = reason(make_torus<double>(1.0, 0.4, 16, 10));
    REQUIRE(e.has_value());
    CHECK(e->reason() == input_error::unsupported_topology);
  }
  SUBCASE("several components") {
    const auto e = reason(test::two_copies(good));
    REQUIRE(e.has_value());
    CHECK(e->reason() == input_error::unsupported_topology);
    CHECK(std::string(e->what()).find("keep_largest_component") != std::string::npos);
    auto o = small_options();
    o.shape.repairs.keep_largest_component = true;
    const auto r = blended_matcher<>(o).match(test::two_copies(good), good);
    // vertices of the dropped copy are unmapped, the kept copy is mapped
    CHECK(r.map.source_size() == 2 * good.V.rows());
    CHECK(r.map.target_vertex(0) != no_index);
    CHECK(r.map.target_vertex(good.V.rows()) == no_index);
  }
  SUBCASE("non-manifold edge") {
    const auto e = reason(test::fin<double>());
    REQUIRE(e.has_value());
    CHECK(e->reason() == input_error::non_manifold);
  }
  SUBCASE("empty, non-finite, bad face") {
    CHECK(reason(test::with_nan_vertex<double>())->reason() == input_error::non_finite);
    CHECK(reason(test::with_bad_index<double>())->reason() == input_error::bad_face);
    triangle_mesh<double> empty;
    empty.V.resize(0, 3);
    empty.F.resize(0, 3);
    CHECK(reason(empty)->reason() == input_error::empty);
  }
  SUBCASE("bad parameter") {
    auto o = small_options();
    o.shape.num_samples = 1;
    CHECK_THROWS_AS((void)blended_matcher<>(o).match(good, good), invalid_input);
  }
}

TEST_CASE("blended_matcher keeps the max_maps most confident candidates, in enumeration order") {
  const auto m = test::armed_sphere(4);
  auto o = small_options();
  o.max_maps = 0;  // all
  const blended_matcher<> all(o);
  const auto sm = all.prepare(m);
  const auto full = all.match(sm, sm);
  REQUIRE(full.candidates.size() > 40);
  o.max_maps = 40;
  const blended_matcher<> pruned(o);
  const auto r = pruned.match(sm, sm);
  REQUIRE(r.candidates.size() == 40);
  REQUIRE(r.confidence.rows() == 40);
  // The 40 largest integrated squared confidences of the full set, ties by index.
  const vector_x<double> self = full.confidence.rowwise().squaredNorm();
  std::vector<index_t> order(full.candidates.size());
  std::iota(order.begin(), order.end(), index_t(0));
  std::stable_sort(order.begin(), order.end(), [&](index_t x, index_t y) { return self[x] > self[y]; });
  order.resize(40);
  std::sort(order.begin(), order.end());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto& want = full.candidates[static_cast<std::size_t>(order[k])];
    CHECK(r.candidates[k].source == want.source);
    CHECK(r.candidates[k].target == want.target);
    CHECK(r.confidence.row(static_cast<index_t>(k)).isApprox(full.confidence.row(order[k])));
  }
  // The identity is among the most confident maps, so the pruned match still finds it.
  std::vector<index_t> id(static_cast<std::size_t>(m.V.rows()));
  std::iota(id.begin(), id.end(), index_t(0));
  CHECK(mean_error(sm, r.map, id) < 0.02);
}

TEST_CASE("blended_matcher refines the selected blended map (ZoomOut) unless refine is off") {
  const auto m = test::armed_sphere(4);
  std::vector<index_t> perm;
  const auto moved = test::moved_and_permuted(m, perm);
  auto o = small_options();
  const auto target = blended_matcher<>(o).prepare(moved);
  const auto refined = blended_matcher<>(o).match(m, moved);
  o.refine = false;
  const auto blended = blended_matcher<>(o).match(m, moved);
  const auto has_stage = [](const blended_match_result<double>& r, const std::string& name) {
    return std::any_of(r.timings.begin(), r.timings.end(), [&](const auto& t) { return t.first == name; });
  };
  CHECK(has_stage(refined, "refinement"));
  CHECK(!has_stage(blended, "refinement"));
  CHECK(refined.refinement_accepted);
  CHECK(refined.map.nearest == refined.refined_map.nearest);
  // Without refinement the result is the selected group's map; with it, that map stays in `blended`.
  CHECK(blended.map.nearest == blended.blended[static_cast<std::size_t>(blended.selected)].map.nearest);
  CHECK(refined.blended[static_cast<std::size_t>(refined.selected)].map.nearest == blended.map.nearest);
  const double e_blended = mean_error(target, blended.map, perm, 1);
  const double e_refined = mean_error(target, refined.map, perm, 1);
  MESSAGE("mean error blended " << e_blended << ", refined " << e_refined);
  CHECK(e_refined < 0.5 * e_blended);
}

TEST_CASE("blended_matcher with no_refinement is the unrefined matcher") {
  const auto m = test::armed_sphere(3);
  std::vector<index_t> perm;
  const auto moved = test::moved_and_permuted(m, perm);
  auto o = small_options();
  const auto r = blended_matcher<triplet_candidates, area_confidence, geodesic_consistency, no_refinement>(o).match(m, moved);
  o.refine = false;
  const auto off = blended_matcher<>(o).match(m, moved);
  CHECK(r.map.nearest == off.map.nearest);
}

namespace {
/// A user's MapRefiner that ruins the map: the images are reversed in vertex order, which scrambles distances.
struct scrambling_refiner {
  template <class Scalar>
  surface_map<Scalar> refine(const triangle_mesh<Scalar>&, const triangle_mesh<Scalar>&, const surface_map<Scalar>& map,
                             int) const {
    surface_map<Scalar> out = map;
    std::reverse(out.points.begin(), out.points.end());
    std::reverse(out.nearest.begin(), out.nearest.end());
    return out;
  }
};
static_assert(MapRefiner<scrambling_refiner>);
}  // namespace

TEST_CASE("blended_matcher undoes a refinement that distorts distances, unless the check is off") {
  const auto m = test::armed_sphere(3);
  std::vector<index_t> perm;
  const auto moved = test::moved_and_permuted(m, perm);
  auto o = small_options();
  o.refinement_move_check = 0;  // the distortion check alone (the move check would put most scrambled images back)
  using matcher_type = blended_matcher<triplet_candidates, area_confidence, geodesic_consistency, scrambling_refiner>;
  const auto r = matcher_type(o).match(m, moved);
  CHECK(!r.refinement_accepted);
  CHECK(r.refined_distortion > o.max_refined_distortion_ratio * r.blended[static_cast<std::size_t>(r.selected)].geodesic_distortion);
  CHECK(r.map.nearest == r.blended[static_cast<std::size_t>(r.selected)].map.nearest);
  o.max_refined_distortion_ratio = 0;
  const auto kept = matcher_type(o).match(m, moved);
  CHECK(kept.refinement_accepted);
  CHECK(kept.map.nearest == kept.refined_map.nearest);
  CHECK(kept.map.nearest != kept.blended[static_cast<std::size_t>(kept.selected)].map.nearest);
}

TEST_CASE("blended_matcher with both_directions pairs every map with its inverse and keeps a selection both agree on") {
  const auto m = test::front_back_creature(3);  // its intrinsic flip forms a second group in each direction
  std::vector<index_t> perm;
  const auto moved = test::moved_and_permuted(m, perm);
  auto o = small_options();
  REQUIRE(o.both_directions);  // the default
  const auto r = blended_matcher<>(o).match(m, moved);
  o.both_directions = false;
  const auto one_way = blended_matcher<>(o).match(m, moved);
  REQUIRE(!r.reverse_blended.empty());
  REQUIRE(r.reverse_selected >= 0);
  CHECK(r.reverse_selected < static_cast<index_t>(r.reverse_blended.size()));
  // The forward pass is the one-way match; the directions agree here (on the flip, which intrinsic measures cannot
  // tell from the truth on this creature in either direction), so its selection and map stand.
  CHECK(r.forward_selected == one_way.selected);
  CHECK(r.selected == one_way.selected);
  CHECK(r.map.nearest == one_way.map.nearest);
  const auto& chosen = r.blended[static_cast<std::size_t>(r.selected)];
  CHECK(chosen.reverse_partner == r.reverse_selected);
  CHECK(chosen.reverse_cycle_error <= o.reverse_agreement);
  for (const auto& b : r.blended) {
    REQUIRE(b.reverse_partner >= 0);
    CHECK(b.reverse_partner < static_cast<index_t>(r.reverse_blended.size()));
    CHECK(b.reverse_cycle_errors.size() == r.reverse_blended.size());
    CHECK(b.reverse_cycle_error == *std::min_element(b.reverse_cycle_errors.begin(), b.reverse_cycle_errors.end()));
    CHECK(std::isfinite(b.reverse_cycle_error));
    CHECK(b.two_way_confidence >= b.confidence_integral);
    CHECK(b.two_way_confidence <= chosen.two_way_confidence + o.reverse_margin);
  }
  // Without the option nothing of the reverse pass is reported.
  CHECK(one_way.reverse_blended.empty());
  CHECK(one_way.reverse_selected == no_index);
  CHECK(one_way.forward_selected == one_way.selected);
  // Nor with a selection by area: the two-way rule compares confidences, and would overrule the area score.
  o.both_directions = true;
  o.selection = blended_selection::area_score;
  CHECK(!blended_matcher<>::judges_both_directions(o));
  const auto by_area = blended_matcher<>(o).match(m, moved);
  CHECK(by_area.reverse_blended.empty());
  CHECK(by_area.forward_selected == by_area.selected);
  o.selection = blended_selection::integrated_confidence;
  CHECK(blended_matcher<>::judges_both_directions(o));
}

namespace {
blended_candidate<double> with_confidence(double confidence, std::vector<double> cycle_errors = {}) {
  blended_candidate<double> c;
  c.confidence_integral = confidence;
  c.reverse_cycle_errors = std::move(cycle_errors);
  return c;
}
}  // namespace

TEST_CASE("blended_matcher's reconciled_selection replaces the selection only for a clearly higher 2-way confidence") {
  using matcher = blended_matcher<>;
  // Reverse maps: 0 with confidence 0.80, 1 with 0.74.
  const std::vector<blended_candidate<double>> reverse = {with_confidence(0.80), with_confidence(0.74)};
  // Forward 0 (selected, 0.78) is the inverse of reverse 1 only; forward 1 (0.77) of reverse 0: two-way
  // confidences 1.52 and 1.57, so forward 1 replaces the selection.
  std::vector<blended_candidate<double>> forward = {with_confidence(0.78, {0.45, 0.04}),
                                                    with_confidence(0.77, {0.03, 0.50})};
  CHECK(matcher::reconciled_selection(forward, 0, reverse, 0.1, 0.01) == 1);
  CHECK(forward[0].two_way_confidence == doctest::Approx(0.78 + 0.74));
  CHECK(forward[1].two_way_confidence == doctest::Approx(0.77 + 0.80));
  // Not by more than the margin: the selection stands.
  CHECK(matcher::reconciled_selection(forward, 0, reverse, 0.1, 0.06) == 0);
  // A forward map with no reverse map within the agreement keeps its one-way confidence and cannot be taken.
  forward[1].reverse_cycle_errors = {0.30, 0.50};
  CHECK(matcher::reconciled_selection(forward, 0, reverse, 0.1, 0.01) == 0);
  CHECK(forward[1].two_way_confidence == doctest::Approx(0.77));
  // Nor is a selection without one overruled: the reverse pass has no opinion on it.
  forward = {with_confidence(0.78, {0.45, 0.30}), with_confidence(0.77, {0.03, 0.50})};
  CHECK(matcher::reconciled_selection(forward, 0, reverse, 0.1, 0.01) == 0);
  CHECK(forward[0].two_way_confidence == doctest::Approx(0.78));
  forward = {with_confidence(0.78, {0.45, 0.04}), with_confidence(0.77, {0.03, 0.50})};
  // The most confident reverse map within the agreement counts: forward 1 close to both reverse maps takes 0.80.
  forward[1].reverse_cycle_errors = {0.09, 0.08};
  CHECK(matcher::reconciled_selection(forward, 0, reverse, 0.1, 0.01) == 1);
  CHECK(forward[1].two_way_confidence == doctest::Approx(0.77 + 0.80));
}
