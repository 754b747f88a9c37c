// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <doctest/doctest.h>

#include "blended_fixtures.hpp"
#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/blended/triplet_candidates.hpp"

using namespace shapestruct;

namespace {
/// Test oracle: sum over the triplet's three pairs of |d_a(s_k, s_l) - d_b(t_k, t_l)|.
double triplet_distortion(const blended_shape<double>& a, const blended_shape<double>& b, const candidate_map<double>& c) {
  double sum = 0;
  for (int k = 0; k < 3; ++k)
    for (int l = k + 1; l < 3; ++l)
      sum += std::abs(a.feature_distances()(a.features()[static_cast<std::size_t>(c.source[k])], c.source[l]) -
                      b.feature_distances()(b.features()[static_cast<std::size_t>(c.target[k])], c.target[l]));
  return sum;
}

bool is_identity(const candidate_map<double>& c) { return c.source == c.target; }
}  // namespace

TEST_CASE("triplet_candidates enumerates every triplet correspondence and prunes by feature distances") {
  blended_shape_options so;
  so.num_samples = 128;
  const auto mesh = test::armed_sphere(4, 6);
  const blended_shape<double> s(mesh.V, mesh.F, so);
  const std::size_t nf = s.features().size();
  REQUIRE(nf >= 5);
  const std::size_t triplets = nf * (nf - 1) * (nf - 2) / 6;

  triplet_candidates all;
  all.options.max_maps = -1;
  const auto every = all(s, s);
  CHECK(every.size() == triplets * triplets * 6);
  std::size_t identities = 0;
  for (const auto& c : every) identities += is_identity(c) ? 1 : 0;
  CHECK(identities == triplets);

  const index_t cap = 60;
  REQUIRE(static_cast<std::size_t>(cap) < every.size() / 4);
  SUBCASE("feature_distances keeps the least distorting triplets, among them every identity triplet") {
    triplet_candidates pruned;
    pruned.options.max_maps = cap;
    const auto kept = pruned(s, s);
    REQUIRE(kept.size() == static_cast<std::size_t>(cap));
    std::set<std::pair<std::array<index_t, 3>, std::array<index_t, 3>>> kept_ids;
    double worst_kept = 0;
    std::size_t kept_identities = 0;
    for (const auto& c : kept) {
      kept_ids.insert({c.source, c.target});
      worst_kept = std::max(worst_kept, triplet_distortion(s, s, c));
      kept_identities += is_identity(c) ? 1 : 0;
    }
    CHECK(kept_identities == triplets);  // distortion 0: they preserve every distance
    for (const auto& c : every)
      if (!kept_ids.count({c.source, c.target})) CHECK(triplet_distortion(s, s, c) >= worst_kept);
    // Enumeration order is kept (source triplets ascend).
    CHECK(std::is_sorted(kept.begin(), kept.end(), [](const auto& x, const auto& y) { return x.source < y.source; }));
  }
  SUBCASE("random pruning is seeded and loses true triplets") {
    triplet_candidates random;
    random.options.max_maps = cap;
    random.options.pruning = triplet_pruning::random;
    const auto first = random(s, s);
    const auto again = random(s, s);
    REQUIRE(first.size() == static_cast<std::size_t>(cap));
    REQUIRE(again.size() == first.size());
    std::size_t kept_identities = 0;
    for (std::size_t k = 0; k < first.size(); ++k) {
      CHECK(first[k].source == again[k].source);
      CHECK(first[k].target == again[k].target);
      kept_identities += is_identity(first[k]) ? 1 : 0;
    }
    CHECK(kept_identities < triplets);
  }
}
