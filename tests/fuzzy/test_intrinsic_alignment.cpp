// SPDX-License-Identifier: MIT
// Tests of intrinsic_aligner (ch. 4.3.4), every blended map kept as a scored alternative, and of the consistent
// blended map (ch. 4.4.5) with its margin over the blended matcher's own choice.
#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include <doctest/doctest.h>

#include "blended/blended_fixtures.hpp"
#include "shapestruct/collection/make_shape_record.hpp"
#include "shapestruct/collection/spherical_harmonic_descriptor.hpp"
#include "shapestruct/fuzzy/fuzzy_collection.hpp"
#include "shapestruct/fuzzy/fuzzy_maps.hpp"
#include "shapestruct/fuzzy/intrinsic_alignment.hpp"

using namespace shapestruct;

namespace {
struct creatures {
  std::vector<triangle_mesh<double>> meshes;
  std::vector<shape_record> records;
  std::vector<index_t> perm;  // the copy's vertex of each original vertex
};

// A creature with a front-back intrinsic symmetry and moved, vertex-permuted copies of it (perm: the first copy's).
creatures make_creatures(int count = 2) {
  creatures c;
  c.meshes.push_back(test::front_back_creature(4));
  c.meshes.push_back(test::moved_and_permuted(c.meshes[0], c.perm));
  std::vector<index_t> unused;
  for (int k = 2; k < count; ++k) c.meshes.push_back(test::moved_and_permuted(c.meshes[0], unused, std::uint64_t(7 + k)));
  const spherical_harmonic_descriptor describe;
  for (std::size_t k = 0; k < c.meshes.size(); ++k)
    c.records.push_back(make_shape_record(c.meshes[k], "creature" + std::to_string(k), describe, {.samples = 64, .surface_points = 256}));
  return c;
}

// A 16-dimension embedding on 2 threads: plenty for three shapes.
fuzzy_collection_options small_collection_options() {
  fuzzy_collection_options fo;
  fo.embedding.dimensions = 16;
  fo.threads = 2;
  return fo;
}

intrinsic_alignment_options flip_telling_options() {
  intrinsic_alignment_options o;
  o.matcher.shape.num_samples = 128;
  o.matcher.convexity_weight = 5;  // as the matcher's own flip test: convexity decides between the two groups
  o.matcher.selection = blended_selection::area_score;
  return o;
}
}  // namespace

TEST_CASE("intrinsic_aligner keeps every blended map as a scored alternative, the best area score B first") {
  const auto c = make_creatures();
  REQUIRE(c.records[0].closed_genus0);
  REQUIRE(c.records[1].closed_genus0);
  const auto options = flip_telling_options();
  const intrinsic_aligner aligner(c.records, [&](index_t k) { return c.meshes[std::size_t(k)]; }, options);
  const auto match = aligner.match(0, 1);
  REQUIRE(match.blended.size() >= 2);  // the true map and the flip form separate groups
  const pair_alignment alignment = aligner.alignment_from(0, 1, match);
  REQUIRE(alignment.alternatives.size() == match.blended.size());
  index_t best_area = 0;
  for (std::size_t k = 0; k < alignment.alternatives.size(); ++k) {
    const auto& alt = alignment.alternatives[k];
    CHECK(static_cast<index_t>(alt.parameters.at(0)) == static_cast<index_t>(k));  // one alternative per group
    CHECK(alt.scores.rows() == c.records[0].sample_count());
    CHECK(alt.scores.cols() == c.records[1].sample_count());
    for (index_t i = 0; i < alt.scores.outerSize(); ++i)
      CHECK(alt.scores.outerIndexPtr()[i + 1] - alt.scores.outerIndexPtr()[i] <= options.max_entries_per_row);
    CHECK(alt.global_score > 0);
    CHECK(alt.global_score <= 1);
    if (alt.global_score > alignment.alternatives[std::size_t(best_area)].global_score) best_area = static_cast<index_t>(k);
  }
  MESSAGE("matcher selects group " << match.selected << ", best area score B is group " << best_area);
  CHECK(alignment.initial == best_area);  // the chapter's start (4.3.4)
  auto from_selection = options;
  from_selection.start_from_matcher_selection = true;
  const intrinsic_aligner selecting(c.records, [&](index_t k) { return c.meshes[std::size_t(k)]; }, from_selection);
  const pair_alignment started = selecting.alignment_from(0, 1, match);
  CHECK(static_cast<index_t>(started.alternatives[std::size_t(started.initial)].parameters.at(0)) == match.selected);

  // The matcher's selected map is the true one, the best-B map is not (the flip): count the source samples
  // whose best-scoring target sample is the one nearest their true image.
  const shape_record& ra = c.records[0];
  const shape_record& rb = c.records[1];
  auto samples_right = [&](index_t group) {
    const auto& scores = alignment.alternatives[std::size_t(group)].scores;
    index_t right = 0;
    for (index_t i = 0; i < ra.sample_count(); ++i) {
      index_t best = no_index;
      float top = -1;
      for (Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>::InnerIterator it(scores, i); it; ++it)
        if (it.value() > top) top = it.value(), best = it.col();
      const index_t true_image = c.perm[std::size_t(ra.sample_vertex[std::size_t(i)])];
      const index_t true_sample = rb.vertex_sample[std::size_t(true_image)];
      if (best != no_index && rb.sample_geodesics(best, true_sample) < 0.1 * std::sqrt(rb.area)) ++right;
    }
    return right;
  };
  CHECK(samples_right(match.selected) >= ra.sample_count() * 9 / 10);
  if (best_area != match.selected) CHECK(samples_right(best_area) < ra.sample_count() / 2);
}

TEST_CASE("consistent blended map: the collection overrules the matcher only by the required margin") {
  const auto c = make_creatures(3);
  // Started from B (which cannot tell the flip), this collection of copies was seen to prefer the flip for the pair;
  // started from the matcher's choice it agrees with the matcher.
  auto options = flip_telling_options();
  options.start_from_matcher_selection = true;
  const intrinsic_aligner aligner(c.records, [&](index_t k) { return c.meshes[std::size_t(k)]; }, options);
  const auto r = compute_fuzzy_correspondences(c.records, aligner, small_collection_options());
  const auto match = aligner.match(0, 1);
  // gain 0 is the chapter's rule: the most consistent map, always.
  const auto chapter = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, match,
                                                   {.min_consistency_gain = 0, .fuzzy_candidate = false});
  REQUIRE(chapter.groups.size() == chapter.consistency.size());
  REQUIRE(chapter.groups.size() >= 2);
  std::size_t best = 0;
  for (std::size_t k = 1; k < chapter.consistency.size(); ++k)
    if (chapter.consistency[k] > chapter.consistency[best]) best = k;
  CHECK(chapter.most_consistent_group == chapter.groups[best]);
  CHECK(chapter.group == chapter.most_consistent_group);
  CHECK(chapter.pairwise_group == match.selected);
  // With an unreachable margin the matcher's own choice stays; with the default, either choice is explained.
  const auto never = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, match, {.min_consistency_gain = 1e9});
  CHECK_FALSE(never.fuzzy_chosen);
  CHECK(never.group == match.selected);
  const auto by_default = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, match, {.fuzzy_candidate = false});
  double pairwise = 0;
  for (std::size_t k = 0; k < by_default.groups.size(); ++k)
    if (by_default.groups[k] == match.selected) pairwise = by_default.consistency[k];
  const double gain = consistent_blended_options{}.min_consistency_gain;
  CHECK(by_default.group == (by_default.consistency[best] > (1 + gain) * pairwise ? by_default.most_consistent_group : match.selected));
  // On this exact copy the matcher and the collection agree on the true map.
  CHECK(by_default.group == match.selected);
  for (const double bad : {-0.1, std::nan("")})
    CHECK_THROWS_AS((void)make_consistent_blended_map(aligner, r.fuzzy, 0, 1, match, {.min_consistency_gain = bad}), invalid_input);
}

TEST_CASE("consistent blended map: by default the chosen blended map is refined as the matcher refines its own") {
  const auto c = make_creatures(3);
  auto options = flip_telling_options();
  options.start_from_matcher_selection = true;  // so the collection agrees with the matcher on the true map
  const intrinsic_aligner aligner(c.records, [&](index_t k) { return c.meshes[std::size_t(k)]; }, options);
  const auto r = compute_fuzzy_correspondences(c.records, aligner, small_collection_options());
  const auto match = aligner.match(0, 1);
  const auto plain = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, match,
                                                 {.fuzzy_candidate = false, .refine_choice = false});
  // On by default.
  const auto refined =
      make_consistent_blended_map(aligner, r.fuzzy, 0, 1, match, {.fuzzy_candidate = false, .threads = 2});
  REQUIRE(refined.group == plain.group);
  auto matcher_options = aligner.options().matcher;
  matcher_options.threads = 2;
  const auto expected = blended_matcher<>(matcher_options)
                            .refine_checked(*aligner.prepared_shape(0), *aligner.prepared_shape(1),
                                            match.blended[std::size_t(plain.group)]);
  CHECK(refined.refinement_accepted == expected.accepted);
  CHECK(refined.map.nearest == (expected.accepted ? expected.map.nearest : plain.map.nearest));
  CHECK(plain.refinement_distortion_ratio == -1);  // nothing refined
  CHECK(refined.refinement_distortion_ratio ==
        doctest::Approx(expected.distortion / match.blended[std::size_t(plain.group)].geodesic_distortion));
  // The pair is a moved copy: the refinement lands more vertices exactly on their true images than the blend.
  const auto exact = [&](const std::vector<index_t>& image) {
    index_t hits = 0;
    for (std::size_t v = 0; v < image.size(); ++v) hits += image[v] == c.perm[v];
    return hits;
  };
  MESSAGE("exact images: blended " << exact(plain.map.nearest) << ", refined " << exact(refined.map.nearest) << " of "
                                   << c.perm.size());
  CHECK(refined.refinement_accepted);
  CHECK(exact(refined.map.nearest) > exact(plain.map.nearest));
}

TEST_CASE("consistent blended map: between shapes of opposite orientation the matcher's own choice is kept") {
  const auto c = make_creatures(3);
  // Started from B, which cannot tell the creature's front from its back: the collection may settle a copy mirrored.
  const intrinsic_aligner aligner(c.records, [&](index_t k) { return c.meshes[std::size_t(k)]; }, flip_telling_options());
  auto fo = small_collection_options();
  CHECK(compute_fuzzy_correspondences(c.records, aligner, fo).orientation.empty());  // off by default
  fo.orientation_margin = 0.1;
  const auto r = compute_fuzzy_correspondences(c.records, aligner, fo);
  REQUIRE(r.orientation.size() == 3);
  CHECK(r.orientation_votes > 0);
  for (const auto& e : r.edges) CHECK(e.preferred != no_index);  // the blended matcher always states its choice
  index_t repaired = 0;  // pairs where the orientation changes the choice
  for (index_t a = 0; a < 3; ++a)
    for (index_t b = a + 1; b < 3; ++b) {
      const auto match = aligner.match(a, b);
      const auto oriented = make_consistent_blended_map(aligner, r.fuzzy, a, b, match,
                                                        {.orientation = r.orientation, .fuzzy_candidate = false});
      const auto plain = make_consistent_blended_map(aligner, r.fuzzy, a, b, match, {.fuzzy_candidate = false});
      MESSAGE("pair " << a << "-" << b << ": orientations " << int(r.orientation[std::size_t(a)]) << ", "
                      << int(r.orientation[std::size_t(b)]) << "; matcher " << match.selected << ", without orientation "
                      << plain.group << ", with " << oriented.group);
      CHECK(oriented.opposite_orientation == (r.orientation[std::size_t(a)] != r.orientation[std::size_t(b)]));
      // The copies are exact, so the matcher's selection is the true map: the oriented choice must be it.
      CHECK(oriented.group == match.selected);
      if (plain.group != oriented.group) ++repaired;
    }
  // Seen on this collection: one copy settles mirrored, and without the orientation both of its pairs take the flip.
  CHECK(repaired == 2);
  CHECK_THROWS_AS((void)make_consistent_blended_map(aligner, r.fuzzy, 0, 1, {.orientation = {1, 1}}), invalid_input);
}

TEST_CASE("consistent blended map: the refined best fuzzy map wins where every blended map is wrong") {
  const auto c = make_creatures(3);
  auto options = flip_telling_options();
  options.start_from_matcher_selection = true;  // this collection then settles on the true maps (test above)
  const intrinsic_aligner aligner(c.records, [&](index_t k) { return c.meshes[std::size_t(k)]; }, options);
  const auto r = compute_fuzzy_correspondences(c.records, aligner, small_collection_options());
  const auto match = aligner.match(0, 1);
  REQUIRE(match.blended.size() >= 2);
  // The same match without its true map: the matcher is left choosing among wrong ones.
  blended_match_result<double> wrong_only = match;
  wrong_only.blended.erase(wrong_only.blended.begin() + match.selected);
  wrong_only.selected = 0;
  const shape_record& ra = c.records[0];
  const shape_record& rb = c.records[1];
  auto right_fraction = [&](const surface_map<double>& map) {  // source samples mapped within 0.1 sqrt(area)
    index_t right = 0;
    for (index_t i = 0; i < ra.sample_count(); ++i) {
      const index_t v = ra.sample_vertex[std::size_t(i)];
      const index_t image = map.target_vertex(v), truth = c.perm[std::size_t(v)];
      if (image != no_index &&
          rb.sample_geodesics(rb.vertex_sample[std::size_t(image)], rb.vertex_sample[std::size_t(truth)]) < 0.1 * std::sqrt(rb.area))
        ++right;
    }
    return double(right) / double(ra.sample_count());
  };
  const auto blended_only = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only, {.fuzzy_candidate = false});
  CHECK_FALSE(blended_only.fuzzy_chosen);
  CHECK(blended_only.fuzzy_consistency == -1);
  CHECK(right_fraction(blended_only.map) < 0.5);
  const auto with_fuzzy = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only, {.threads = 2});
  MESSAGE("fuzzy candidate consistency " << with_fuzzy.fuzzy_consistency << ", blended " << with_fuzzy.consistency.size()
                                         << " maps, right fraction " << right_fraction(with_fuzzy.map));
  REQUIRE(with_fuzzy.fuzzy_chosen);
  CHECK(with_fuzzy.group == no_index);
  for (const double s : with_fuzzy.consistency) CHECK(with_fuzzy.fuzzy_consistency > s);
  CHECK(right_fraction(with_fuzzy.map) >= 0.9);
  // The chosen map is refined_fuzzy_map, whatever the thread count.
  CHECK(refined_fuzzy_map(aligner, r.fuzzy, 0, 1, 1).nearest == with_fuzzy.map.nearest);
  // fuzzy_min_gain: the fuzzy map must lead the best blended map by that fraction, else the blended maps' choice.
  const double lead = with_fuzzy.fuzzy_consistency /
                          *std::max_element(with_fuzzy.consistency.begin(), with_fuzzy.consistency.end()) - 1;
  REQUIRE(lead > 0);
  CHECK(make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only, {.fuzzy_min_gain = 0.9 * lead}).fuzzy_chosen);
  const auto short_lead = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only, {.fuzzy_min_gain = 1.1 * lead});
  CHECK_FALSE(short_lead.fuzzy_chosen);
  CHECK(short_lead.fuzzy_consistency == with_fuzzy.fuzzy_consistency);
  CHECK(short_lead.group == blended_only.group);
  CHECK(short_lead.map.nearest == blended_only.map.nearest);
  for (const double bad : {-0.1, std::nan("")})
    CHECK_THROWS_AS((void)make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only, {.fuzzy_min_gain = bad}), invalid_input);
  // max_fuzzy_distortion_ratio: the fuzzy map must not distort geodesic distances more than that many times the
  // most consistent blended map, else the blended maps' choice.
  REQUIRE(with_fuzzy.most_consistent_distortion > 0);
  const auto shape0 = aligner.prepared_shape(0);
  const auto shape1 = aligner.prepared_shape(1);
  const double fuzzy_distortion = input_map_geodesic_distortion(*shape0, *shape1, with_fuzzy.map);
  CHECK(with_fuzzy.fuzzy_distortion == doctest::Approx(fuzzy_distortion));
  const double distortion_ratio = with_fuzzy.fuzzy_distortion / with_fuzzy.most_consistent_distortion;
  MESSAGE("fuzzy map distortion " << with_fuzzy.fuzzy_distortion << ", most consistent blended map "
                                  << with_fuzzy.most_consistent_distortion);
  CHECK(make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only,
                                    {.max_fuzzy_distortion_ratio = 1.01 * distortion_ratio})
            .fuzzy_chosen);
  const auto distorted = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only,
                                                     {.max_fuzzy_distortion_ratio = 0.99 * distortion_ratio});
  CHECK_FALSE(distorted.fuzzy_chosen);
  CHECK(distorted.fuzzy_distortion == with_fuzzy.fuzzy_distortion);
  CHECK(distorted.group == blended_only.group);
  CHECK(distorted.map.nearest == blended_only.map.nearest);
  for (const double bad : {-1.0, std::nan("")})
    CHECK_THROWS_AS(
        (void)make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only, {.max_fuzzy_distortion_ratio = bad}),
        invalid_input);
  // fuzzy_min_distance: the fuzzy map must send the samples at least that far from the most consistent blended
  // map's images; here every blended map is wrong, so it does.
  REQUIRE(with_fuzzy.fuzzy_distance > 0);
  CHECK(make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only,
                                    {.fuzzy_min_distance = 0.99 * with_fuzzy.fuzzy_distance})
            .fuzzy_chosen);
  const auto close = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only,
                                                 {.fuzzy_min_distance = 1.01 * with_fuzzy.fuzzy_distance});
  CHECK_FALSE(close.fuzzy_chosen);
  CHECK(close.fuzzy_distance == with_fuzzy.fuzzy_distance);
  CHECK(close.map.nearest == blended_only.map.nearest);
  CHECK_THROWS_AS((void)make_consistent_blended_map(aligner, r.fuzzy, 0, 1, wrong_only, {.fuzzy_min_distance = -0.5}),
                  invalid_input);
  // With the true map present, the matcher's right choice stays unless the fuzzy map is clearly more consistent;
  // either way the result is right.
  const auto full = make_consistent_blended_map(aligner, r.fuzzy, 0, 1, match);
  CHECK(right_fraction(full.map) >= 0.9);
  surface_map<double> short_map;
  short_map.points.resize(3);
  short_map.nearest.assign(3, 0);
  CHECK_THROWS_AS((void)aligner.score_map(0, 1, short_map), invalid_input);
}

TEST_CASE("intrinsic_aligner keeps its prepared shapes within cache_bytes and aligns the same whatever the budget") {
  const auto c = make_creatures(3);
  const auto load = [&](index_t k) { return c.meshes[std::size_t(k)]; };
  const std::vector<std::pair<index_t, index_t>> pairs{{0, 1}, {1, 2}, {0, 2}, {0, 1}};
  const intrinsic_aligner roomy(c.records, load);
  std::vector<pair_alignment> expected;
  for (const auto& [a, b] : pairs) expected.push_back(roomy.align(a, b));
  CHECK(roomy.preparations() == 3);  // each shape once
  const std::size_t three_shapes = roomy.cached_bytes();
  CHECK(three_shapes > 3 * std::size_t(c.meshes[0].V.rows()) * 64 * sizeof(double));  // at least the tables

  intrinsic_alignment_options tight;
  tight.cache_bytes = three_shapes / 2;  // room for one shape: every pair prepares again
  const intrinsic_aligner cramped(c.records, load, tight);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const pair_alignment got = cramped.align(pairs[p].first, pairs[p].second);
    CHECK(cramped.cached_bytes() <= tight.cache_bytes);
    REQUIRE(got.alternatives.size() == expected[p].alternatives.size());
    CHECK(got.initial == expected[p].initial);
    for (std::size_t k = 0; k < got.alternatives.size(); ++k) {
      const auto& x = got.alternatives[k];
      const auto& y = expected[p].alternatives[k];
      CHECK(x.global_score == y.global_score);
      CHECK(x.scores.nonZeros() == y.scores.nonZeros());
      CHECK(Eigen::MatrixXf(x.scores) == Eigen::MatrixXf(y.scores));
    }
  }
  // Each pair prepares what the one before dropped, and align holds its two shapes from the match to the scores:
  // (0, 1) 2, (1, 2) 1, (0, 2) 2, (0, 1) 2.
  CHECK(cramped.preparations() == 7);

  // A shape dropped from the cache while the caller still holds it is taken back, not prepared again.
  const intrinsic_aligner pinned(c.records, load, tight);
  const auto held = pinned.prepared_shape(0);
  (void)pinned.align(1, 2);  // drops shape 0 from the cache
  CHECK(pinned.cached_bytes() <= tight.cache_bytes);
  CHECK(pinned.prepared_shape(0).get() == held.get());
  CHECK(pinned.preparations() == 3);

  // Threads that need a shape another thread is preparing wait for it instead of preparing it too.
  const intrinsic_aligner shared(c.records, load);
  std::vector<pair_alignment> parallel(pairs.size());
  {
    std::vector<std::jthread> workers;
    for (std::size_t p = 0; p < pairs.size(); ++p)
      workers.emplace_back([&, p] { parallel[p] = shared.align(pairs[p].first, pairs[p].second); });
  }
  CHECK(shared.preparations() == 3);
  for (std::size_t p = 0; p < pairs.size(); ++p) CHECK(parallel[p].initial == expected[p].initial);

  intrinsic_alignment_options none;
  none.cache_bytes = 0;
  CHECK_THROWS_AS((void)intrinsic_aligner(c.records, load, none), invalid_input);
}

TEST_CASE("intrinsic_aligner with both_feature_sets offers every blended map of both feature sets") {
  const std::vector<triangle_mesh<double>> meshes{test::bumpy_creature(), test::armed_sphere(4, 6)};
  const spherical_harmonic_descriptor describe;
  std::vector<shape_record> records;
  for (std::size_t k = 0; k < meshes.size(); ++k)
    records.push_back(make_shape_record(meshes[k], "shape" + std::to_string(k), describe, {.samples = 64, .surface_points = 256}));
  intrinsic_alignment_options one_set;
  one_set.matcher.shape.num_samples = 128;
  intrinsic_alignment_options both = one_set;
  both.both_feature_sets = true;
  const auto load = [&](index_t k) { return meshes[std::size_t(k)]; };
  const intrinsic_aligner single(records, load, one_set);
  const intrinsic_aligner pooled(records, load, both);
  CHECK(single.options().matcher.shape.alternative_feature_persistence == 0);
  CHECK(pooled.options().matcher.shape.alternative_feature_persistence > 0);
  REQUIRE(pooled.prepared_shape(0)->alternative() != nullptr);  // the bumps give the source a second set

  const auto r_single = single.match(0, 1);
  const auto r_pooled = pooled.match(0, 1);
  REQUIRE(r_pooled.blended.size() > r_single.blended.size());
  const pair_alignment a_single = single.align(0, 1);
  const pair_alignment a_pooled = pooled.align(0, 1);
  CHECK(a_single.alternatives.size() == r_single.blended.size());
  REQUIRE(a_pooled.alternatives.size() == r_pooled.blended.size());
  // The full set's maps come first and score as they do alone.
  for (std::size_t k = 0; k < a_single.alternatives.size(); ++k) {
    CHECK(a_pooled.alternatives[k].global_score == a_single.alternatives[k].global_score);
    CHECK_FALSE(r_pooled.blended[k].alternative_features);
  }
  CHECK(r_pooled.blended.back().alternative_features);
  CHECK(a_pooled.initial == a_single.initial);  // the edge starts from the full set's best B, as with one set
  // The preferred alternative is the map the matcher's distortion rule keeps.
  REQUIRE(a_pooled.preferred != no_index);
  CHECK(static_cast<index_t>(a_pooled.alternatives[std::size_t(a_pooled.preferred)].parameters.at(0)) == r_pooled.selected);
  CHECK(r_pooled.blended[std::size_t(r_pooled.selected)].alternative_features == r_pooled.alternative_features);
}
