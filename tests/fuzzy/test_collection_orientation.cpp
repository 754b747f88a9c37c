// SPDX-License-Identifier: MIT
// Tests of orient_collection (which shapes sit in f mirrored, voted by the edges' aligners) and of the votes the
// final alignment graph casts.
#include <cstdint>
#include <limits>
#include <vector>

#include <doctest/doctest.h>

#include "shapestruct/fuzzy/collection_orientation.hpp"
#include "shapestruct/fuzzy/fuzzy_collection.hpp"

using namespace shapestruct;

namespace {
// Votes on a ring with chords (every shape has 4 edges) agreeing with `truth`, except the edges listed in `wrong`.
std::vector<orientation_vote> ring_votes(const std::vector<int>& truth, const std::vector<std::size_t>& wrong) {
  const auto n = static_cast<index_t>(truth.size());
  std::vector<orientation_vote> votes;
  for (index_t k = 0; k < n; ++k)
    for (const index_t step : {1, 2}) {
      const index_t l = (k + step) % n;
      votes.push_back({k, l, truth[std::size_t(k)] * truth[std::size_t(l)], 1.0});
    }
  for (const auto e : wrong) votes[e].sign = -votes[e].sign;
  return votes;
}
}  // namespace

TEST_CASE("orient_collection recovers planted orientations from votes with a few wrong ones") {
  std::vector<int> truth(24, 1);
  for (const std::size_t k : {3, 4, 5, 11, 17, 20}) truth[k] = -1;  // mirrored shapes, a run of three among them
  // Six wrong votes, no two at the same shape, so every shape keeps a majority of right ones.
  const auto votes = ring_votes(truth, {0, 9, 18, 27, 36, 42});
  const auto x = orient_collection(24, votes);
  REQUIRE(x.size() == truth.size());
  for (std::size_t k = 0; k < truth.size(); ++k) CHECK(int(x[k]) == truth[k]);
}

TEST_CASE("orient_collection flips a whole group that agrees within itself, keeping the majority at +1") {
  // Shapes 0-9 one way, 10-14 the other; every vote right. Each mirrored shape has more agreeing votes inside its
  // group than disagreeing ones outside, so only the group as a whole can flip.
  std::vector<orientation_vote> votes;
  for (index_t a = 0; a < 15; ++a)
    for (index_t b = a + 1; b < 15; ++b) {
      const bool same = (a < 10) == (b < 10);
      if (same || (a + b) % 4 == 0) votes.push_back({a, b, same ? 1 : -1, 1.0});
    }
  const auto x = orient_collection(15, votes);
  for (index_t k = 0; k < 15; ++k) CHECK(int(x[std::size_t(k)]) == (k < 10 ? 1 : -1));
}

TEST_CASE("orient_collection: no votes, separate components and bad votes") {
  CHECK(orient_collection(4, {}) == std::vector<std::int8_t>{1, 1, 1, 1});
  // Two components, each with one shape voted against the other two: the majority of each stays +1, and shape 6
  // without votes is +1.
  const std::vector<orientation_vote> votes{{0, 1, -1, 1}, {0, 2, -1, 1}, {1, 2, 1, 1}, {3, 4, 1, 1}, {3, 5, -1, 1}, {4, 5, -1, 1}};
  CHECK(orient_collection(7, votes) == std::vector<std::int8_t>{-1, 1, 1, 1, 1, -1, 1});
  // A tie (two shapes voted opposite) keeps the lower-indexed shape at +1.
  const std::vector<orientation_vote> tie{{2, 0, -1, 1}};
  CHECK(orient_collection(3, tie) == std::vector<std::int8_t>{1, 1, -1});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto bad : {orientation_vote{0, 3, 1, 1}, orientation_vote{1, 1, 1, 1}, orientation_vote{0, 1, 0, 1},
                         orientation_vote{0, 1, 1, -1}, orientation_vote{0, 1, 1, nan}}) {
    const std::vector<orientation_vote> one{bad};
    CHECK_THROWS_AS((void)orient_collection(3, one), invalid_input);
  }
}

TEST_CASE("the final graph votes: agreement, a clear overrule, and no say on near ties or without a preference") {
  std::vector<fuzzy_graph_edge> edges(4);
  edges[0] = {0, 1, 2, 10.0, 2, 10.0};    // the collection chose the aligner's own alternative
  edges[1] = {1, 2, 0, 12.0, 1, 10.0};    // 20 % more consistent than the preferred one: overruled
  edges[2] = {2, 3, 0, 10.5, 1, 10.0};    // 5 %: a near tie, f cannot tell the two apart
  edges[3] = {0, 3, 1, 10.0, no_index, 0.0};  // the aligner states no preference
  const auto votes = detail::orientation_votes_of(edges, 0.1);
  REQUIRE(votes.size() == 2);
  CHECK(votes[0].a == 0);
  CHECK(votes[0].b == 1);
  CHECK(votes[0].sign == 1);
  CHECK(votes[1].a == 1);
  CHECK(votes[1].b == 2);
  CHECK(votes[1].sign == -1);
  CHECK(detail::orientation_votes_of(edges, -1).empty());  // orientation off
  CHECK(detail::orientation_votes_of(edges, 0.01).size() == 3);
}
