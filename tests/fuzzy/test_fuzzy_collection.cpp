// SPDX-License-Identifier: MIT
// Tests of the fuzzy-correspondence core: the correspondence matrix, the diffusion embedding, f, and Algorithm 1.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>
#include <filesystem>
#include <mutex>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "shapestruct/collection/alignment_graph.hpp"
#include "shapestruct/fuzzy/correspondence_matrix.hpp"
#include "shapestruct/fuzzy/diffusion_embedding.hpp"
#include "shapestruct/fuzzy/fuzzy_collection.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"
#include "support/thread_exchange.hpp"

namespace ss = shapestruct;
using sparse_scores = Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>;

namespace {

/// Scores that send sample i of the source to sample perm[i] of the target (and, more weakly, to its two
/// neighbours in index order), scaled by `global`.
sparse_scores permutation_scores(const std::vector<int>& perm, float global) {
  const auto K = static_cast<ss::index_t>(perm.size());
  Eigen::MatrixXf dense = Eigen::MatrixXf::Zero(K, K);
  for (ss::index_t i = 0; i < K; ++i) {
    const int j = perm[std::size_t(i)];
    dense(i, j) = global;
    dense(i, (j + 1) % K) = 0.2f * global;
    dense(i, (j + K - 1) % K) = 0.2f * global;
  }
  return dense.sparseView();
}

std::vector<int> identity(int K) {
  std::vector<int> p(static_cast<std::size_t>(K));
  for (int i = 0; i < K; ++i) p[std::size_t(i)] = i;
  return p;
}

std::vector<int> reversed(int K) {
  std::vector<int> p(static_cast<std::size_t>(K));
  for (int i = 0; i < K; ++i) p[std::size_t(i)] = K - 1 - i;
  return p;
}

Eigen::MatrixXd dense_of(const ss::correspondence_matrix& C) {
  const ss::index_t n = C.rows();
  Eigen::MatrixXd M(n, n);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
  for (ss::index_t j = 0; j < n; ++j) {
    e[j] = 1;
    C.perform_op(e.data(), M.col(j).data());
    e[j] = 0;
  }
  return M;
}

/// A collection whose samples correspond by index; every pair aligns exactly (alternative 0, B = 0.9) and
/// also offers the reversed correspondence (alternative 1, B = 0.5), except the planted pair, whose initial
/// alternative is the reversed one (B = 0.95) with the true one as alternative 1 (B = 0.6).
struct planted_aligner {
  int K;
  std::pair<ss::index_t, ss::index_t> planted;
  ss::pair_alignment align(ss::index_t a, ss::index_t b) const {
    ss::pair_alignment out;
    const bool wrong = std::pair{std::min(a, b), std::max(a, b)} == planted;
    ss::alignment_alternative right, flip;
    right.scores = permutation_scores(identity(K), wrong ? 0.6f : 0.9f);
    right.global_score = wrong ? 0.6 : 0.9;
    flip.scores = permutation_scores(reversed(K), wrong ? 0.95f : 0.5f);
    flip.global_score = wrong ? 0.95 : 0.5;
    out.alternatives = {right, flip};
    out.initial = ss::best_global_alternative(out.alternatives);
    return out;
  }
};

/// Every pair aligns exactly (alternative 0) and offers the reversed correspondence (alternative 1), except
/// `wrong`, which starts from the reversal (higher B) with the true correspondence as its alternative 0.
struct split_aligner {
  int K;
  std::pair<ss::index_t, ss::index_t> wrong;
  ss::pair_alignment align(ss::index_t a, ss::index_t b) const {
    const bool w = std::pair{std::min(a, b), std::max(a, b)} == wrong;
    ss::pair_alignment out;
    ss::alignment_alternative right, flip;
    right.scores = permutation_scores(identity(K), 0.9f);
    right.global_score = w ? 0.8 : 0.9;
    flip.scores = permutation_scores(reversed(K), 0.9f);
    flip.global_score = w ? 0.9 : 0.8;
    out.alternatives = {right, flip};
    out.initial = ss::best_global_alternative(out.alternatives);
    return out;
  }
};

std::vector<ss::shape_record> planted_records(int N, int K) {
  std::vector<ss::shape_record> r(static_cast<std::size_t>(N));
  std::mt19937_64 rng(3);
  for (int k = 0; k < N; ++k) {
    r[std::size_t(k)].name = "shape" + std::to_string(k);
    r[std::size_t(k)].samples = Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(K, 3);
    // Descriptors on a line: the MST is the path 0-1-2-..., the planted edge is one of its links.
    r[std::size_t(k)].descriptor = Eigen::VectorXd::Constant(4, double(k) + 1e-3 * double(rng() % 100));
  }
  return r;
}

/// The same graph, the same alternatives and a bit-identical embedding.
void check_same_result(const ss::fuzzy_collection_result& a, const ss::fuzzy_collection_result& b) {
  REQUIRE(a.edges.size() == b.edges.size());
  for (std::size_t e = 0; e < a.edges.size(); ++e) {
    CHECK(a.edges[e].source == b.edges[e].source);
    CHECK(a.edges[e].target == b.edges[e].target);
    CHECK(a.edges[e].alternative == b.edges[e].alternative);
  }
  CHECK((a.fuzzy.embedding().coordinates - b.fuzzy.embedding().coordinates).cwiseAbs().maxCoeff() == 0.0f);
}

}  // namespace

TEST_CASE("correspondence matrix: C is row-stochastic and W symmetric") {
  const int K = 6;
  const auto a01 = permutation_scores(identity(K), 0.7f);
  const auto a12 = permutation_scores(reversed(K), 0.4f);
  const std::vector<ss::index_t> counts{K, K, K};
  const std::vector<ss::correspondence_edge> edges{{0, 1, &a01}, {1, 2, &a12}};
  const ss::correspondence_matrix C(counts, edges, 1);
  const Eigen::MatrixXd A = dense_of(C);
  CHECK((A - A.transpose()).cwiseAbs().maxCoeff() < 1e-12);
  // The random walk D^-1 W = D^-1/2 A D^1/2 has rows summing to one.
  const Eigen::VectorXd s = C.degrees().cwiseSqrt();
  const Eigen::MatrixXd P = C.inverse_sqrt_degrees().asDiagonal() * A * s.asDiagonal();
  for (ss::index_t i = 0; i < P.rows(); ++i) CHECK(P.row(i).sum() == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(P.minCoeff() >= 0.0);
}

TEST_CASE("correspondence matrix: edges naming missing shapes or wrong block sizes are invalid_input") {
  const auto a = permutation_scores(identity(4), 1.0f);
  const std::vector<ss::index_t> counts{4, 4};
  const std::vector<ss::correspondence_edge> out_of_range{{0, 2, &a}};
  CHECK_THROWS_AS(ss::correspondence_matrix(counts, out_of_range), ss::invalid_input);
  const std::vector<ss::index_t> wrong{4, 5};
  const std::vector<ss::correspondence_edge> e{{0, 1, &a}};
  CHECK_THROWS_AS(ss::correspondence_matrix(wrong, e), ss::invalid_input);
  sparse_scores negative = a;
  negative.valuePtr()[0] = -1.0f;
  const std::vector<ss::correspondence_edge> n{{0, 1, &negative}};
  CHECK_THROWS_AS(ss::correspondence_matrix(counts, n), ss::invalid_input);
}

TEST_CASE("correspondence matrix: blocks fetched one at a time give the matrix of the edge list, whatever the threads") {
  const int K = 5;
  const std::vector<sparse_scores> scores{permutation_scores(identity(K), 0.7f), permutation_scores(reversed(K), 0.4f),
                                          permutation_scores(identity(K), 0.9f)};
  const std::vector<ss::index_t> counts{K, K, K, K};
  const std::vector<std::pair<ss::index_t, ss::index_t>> pairs{{0, 1}, {1, 2}, {3, 2}};
  std::vector<ss::correspondence_edge> edges;
  for (std::size_t e = 0; e < pairs.size(); ++e) edges.push_back({pairs[e].first, pairs[e].second, &scores[e]});
  const Eigen::MatrixXd listed = dense_of(ss::correspondence_matrix(counts, edges, 1));
  for (const int threads : {1, 2, 3}) {
    std::vector<int> fetched(pairs.size(), 0);
    std::mutex m;
    const ss::correspondence_matrix C(counts, pairs, [&](ss::index_t e) {
      std::lock_guard lock(m);
      ++fetched[std::size_t(e)];
      return scores[std::size_t(e)];  // by value, as a block read from a cache file
    }, threads);
    CHECK((dense_of(C) - listed).cwiseAbs().maxCoeff() == 0.0);
    CHECK(fetched == std::vector<int>(pairs.size(), 1));
  }
  // Two bad blocks: the first is named, whatever the thread count.
  sparse_scores negative = scores[0];
  negative.valuePtr()[0] = -1.0f;
  const sparse_scores too_small = permutation_scores(identity(K - 1), 1.0f);
  for (const int threads : {1, 3}) {
    try {
      (void)ss::correspondence_matrix(counts, pairs, [&](ss::index_t e) -> const sparse_scores& {
        return e == 1 ? negative : e == 2 ? too_small : scores[0];
      }, threads);
      FAIL("no error");
    } catch (const ss::invalid_input& error) {
      CHECK(std::string(error.what()).find("edge 1 has a negative") != std::string::npos);
    }
  }
}

TEST_CASE("diffusion embedding: Lanczos agrees with a dense eigen-decomposition") {
  // 6 shapes of 40 samples on a cycle of exact and noisy alignments: n = 240.
  const int K = 40, N = 6;
  std::mt19937_64 rng(7);
  std::vector<sparse_scores> blocks;
  std::vector<ss::correspondence_edge> edges;
  blocks.reserve(std::size_t(N));
  for (int k = 0; k < N; ++k) {
    Eigen::MatrixXf d = Eigen::MatrixXf::Zero(K, K);
    for (int i = 0; i < K; ++i) {
      d(i, i) = 1.0f;
      d(i, (i + 1) % K) = 0.3f + 0.01f * float(rng() % 10);
      d(i, (i + 3) % K) = 0.05f;
    }
    blocks.push_back(d.sparseView());
  }
  for (int k = 0; k < N; ++k) edges.push_back({k, (k + 1) % N, &blocks[std::size_t(k)]});
  const std::vector<ss::index_t> counts(std::size_t(N), K);
  const ss::correspondence_matrix C(counts, edges, 2);
  const ss::diffusion_embedding_options o{.time = 10, .dimensions = 12};
  const auto lanczos = ss::embed_diffusion(C, o, ss::lanczos_embedding_solver{});
  const auto dense = ss::embed_diffusion(C, o, ss::dense_embedding_solver{});
  REQUIRE(lanczos.info == ss::status::ok);
  CHECK(lanczos.trivial_eigenvalue == doctest::Approx(1.0).epsilon(1e-9));
  CHECK((lanczos.eigenvalues - dense.eigenvalues).cwiseAbs().maxCoeff() < 1e-7);
  // Diffusion distances do not depend on the eigenvectors' signs or on rotations within an eigenspace.
  double worst = 0, scale = 0;
  for (ss::index_t p = 0; p < C.rows(); p += 7)
    for (ss::index_t q = 0; q < C.rows(); q += 5) {
      worst = std::max(worst, std::abs(lanczos.squared_distance(p, q) - dense.squared_distance(p, q)));
      scale = std::max(scale, dense.squared_distance(p, q));
    }
  CHECK(worst < 1e-4 * scale);
}

TEST_CASE("diffusion embedding: corresponding samples coincide and others stay apart") {
  const int K = 16;
  const auto a = permutation_scores(identity(K), 1.0f);
  const std::vector<ss::index_t> counts{K, K, K};
  const std::vector<ss::correspondence_edge> edges{{0, 1, &a}, {1, 2, &a}, {0, 2, &a}};
  const ss::correspondence_matrix C(counts, edges, 1);
  const auto e = ss::embed_diffusion(C, {.time = 10, .dimensions = 20}, ss::dense_embedding_solver{});
  const auto f = ss::make_fuzzy_correspondence(e);
  for (ss::index_t i = 0; i < K; ++i) {
    CHECK(f.best_match(f.point(0, i), 1) == i);
    CHECK(f.best_match(f.point(2, i), 0) == i);
    CHECK(f.value(f.point(0, i), f.point(1, i)) > 0.9);
  }
  // tau is the 15 % quantile of a point's distances to the other shapes' points: 15 % of 32 is 4.8, so the
  // 5th nearest; f there is exp(-1).
  const ss::index_t p = f.point(0, 3);
  std::vector<double> d;
  for (ss::index_t q = f.point(1, 0); q < f.points(); ++q) d.push_back(std::sqrt(e.squared_distance(p, q)));
  std::sort(d.begin(), d.end());
  CHECK(double(f.tau()[p]) == doctest::Approx(d[4]).epsilon(1e-4));
}

TEST_CASE("fuzzy correspondence options out of range are invalid_input") {
  const auto a = permutation_scores(identity(8), 1.0f);
  const std::vector<ss::index_t> counts{8, 8};
  const std::vector<ss::correspondence_edge> edges{{0, 1, &a}};
  const ss::correspondence_matrix C(counts, edges, 1);
  CHECK_THROWS_AS((void)ss::embed_diffusion(C, {.time = -1}), ss::invalid_input);
  CHECK_THROWS_AS((void)ss::embed_diffusion(C, {.dimensions = 0}), ss::invalid_input);
  const auto e = ss::embed_diffusion(C, {.dimensions = 4}, ss::dense_embedding_solver{});
  CHECK_THROWS_AS((void)ss::make_fuzzy_correspondence(e, {.tau_fraction = 0}), ss::invalid_input);
  CHECK_THROWS_AS((void)ss::make_fuzzy_correspondence(e, {.cutoff = 0}), ss::invalid_input);
}

TEST_CASE("graph optimisation repairs a deliberately wrong edge planted in a small collection") {
  const int N = 12, K = 10;
  const auto records = planted_records(N, K);
  const planted_aligner aligner{K, {4, 5}};
  ss::fuzzy_collection_options o;
  o.embedding.dimensions = 16;
  o.threads = 1;
  const auto r = ss::compute_fuzzy_correspondences(records, aligner, o, ss::dense_embedding_solver{});
  REQUIRE(r.log.size() >= 2);
  // The wrong edge entered the initial graph with its reversed alternative (highest B) ...
  CHECK(r.log.front().edges >= N - 1);
  // ... and the optimisation switched it to the consistent one or pruned it.
  bool planted_wrong = false;
  for (const auto& e : r.edges)
    if (e.source == 4 && e.target == 5) planted_wrong = e.alternative != 0;
  CHECK_FALSE(planted_wrong);
  CHECK(r.log[1].alternatives_changed >= 1);
  // Afterwards every sample maps to its own index on every other shape.
  for (ss::index_t k = 0; k < N; ++k)
    for (ss::index_t l = 0; l < N; ++l) {
      if (k == l) continue;
      const auto m = r.fuzzy.best_matches(k, l);
      for (ss::index_t i = 0; i < K; ++i) CHECK(m[std::size_t(i)] == i);
    }
}

TEST_CASE("graph optimisation aligns a shape whose two alignments disagree once more, and then settles it") {
  const int N = 12, K = 10;
  const auto records = planted_records(N, K);
  ss::fuzzy_collection_options o;
  o.embedding.dimensions = 16;
  o.threads = 1;
  o.graph.edges_per_shape = 1;
  // A shape with exactly two alignments in the initial graph; one of them starts reversed.
  std::vector<Eigen::VectorXd> d;
  for (const auto& r : records) d.push_back(r.descriptor);
  const auto g0 = ss::initial_alignment_graph(ss::descriptor_distance_matrix(d), o.graph);
  std::vector<std::vector<ss::index_t>> adjacent(N);
  for (const auto& [a, b] : g0.edges) adjacent[std::size_t(a)].push_back(b), adjacent[std::size_t(b)].push_back(a);
  ss::index_t X = ss::no_index;
  for (ss::index_t k = 0; k < N && X == ss::no_index; ++k)
    if (adjacent[std::size_t(k)].size() == 2) X = k;
  REQUIRE(X != ss::no_index);
  const ss::index_t Y = adjacent[std::size_t(X)][1];
  const split_aligner aligner{K, {std::min(X, Y), std::max(X, Y)}};
  auto maps_by_index = [&](const ss::fuzzy_collection_result& r, ss::index_t k, ss::index_t l) {
    const auto m = r.fuzzy.best_matches(k, l);
    for (ss::index_t i = 0; i < K; ++i)
      if (m[std::size_t(i)] != i) return false;
    return true;
  };
  o.weak_support_fraction = 0;  // the chapter: one right and one reversed alignment look alike, X is never settled
  const auto stuck = ss::compute_fuzzy_correspondences(records, aligner, o, ss::dense_embedding_solver{});
  bool settled = true;
  for (ss::index_t l = 0; l < N; ++l)
    if (l != X) settled = settled && maps_by_index(stuck, X, l);
  CHECK_FALSE(settled);
  for (const auto& it : stuck.log) CHECK(it.reinforced == 0);
  o.weak_support_fraction = 0.8;  // the default
  const auto r = ss::compute_fuzzy_correspondences(records, aligner, o, ss::dense_embedding_solver{});
  ss::index_t reinforced = 0;
  for (const auto& it : r.log) reinforced += it.reinforced;
  CHECK(reinforced >= 1);
  CHECK(reinforced <= o.extra_edges_per_weak_shape * N);
  CHECK(r.pairs_aligned == stuck.pairs_aligned + std::size_t(reinforced));
  CHECK(r.converged);
  for (ss::index_t k = 0; k < N; ++k)
    for (ss::index_t l = 0; l < N; ++l)
      if (k != l) CHECK(maps_by_index(r, k, l));
  o.weak_support_fraction = 1.5;
  CHECK_THROWS_AS((void)ss::compute_fuzzy_correspondences(records, aligner, o), ss::invalid_input);
}

TEST_CASE("fuzzy collection: one and two threads give identical results, and a resumed run aligns nothing") {
  const int N = 10, K = 8;
  const auto records = planted_records(N, K);
  const planted_aligner aligner{K, {2, 3}};
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_test_fuzzy_resume";
  std::filesystem::remove_all(dir);
  ss::fuzzy_collection_options o;
  o.embedding.dimensions = 12;
  o.cache_folder = dir;
  o.threads = 1;
  const auto one = ss::compute_fuzzy_correspondences(records, aligner, o);
  o.threads = 2;
  const auto two = ss::compute_fuzzy_correspondences(records, aligner, o);
  CHECK(one.pairs_computed == one.pairs_aligned);
  CHECK(two.pairs_computed == 0);  // every alignment came from the cache
  check_same_result(one, two);
  CHECK((one.fuzzy.tau() - two.fuzzy.tau()).cwiseAbs().maxCoeff() == 0.0f);
  std::filesystem::remove_all(dir);
}

TEST_CASE("fuzzy collection: alignments read back from the cache folder give what alignments kept in memory give") {
  const int N = 10, K = 8;
  const auto records = planted_records(N, K);
  const planted_aligner aligner{K, {2, 3}};
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_test_fuzzy_spill";
  std::filesystem::remove_all(dir);
  ss::fuzzy_collection_options o;
  o.embedding.dimensions = 12;
  o.threads = 2;
  const auto no_folder = ss::compute_fuzzy_correspondences(records, aligner, o);
  o.cache_folder = dir;
  REQUIRE_FALSE(o.alignments_in_memory);  // the default with a folder: read back
  const auto read_back = ss::compute_fuzzy_correspondences(records, aligner, o);
  CHECK(read_back.pairs_computed == read_back.pairs_aligned);
  o.alignments_in_memory = true;
  const auto kept = ss::compute_fuzzy_correspondences(records, aligner, o);
  CHECK(kept.pairs_computed == 0);
  REQUIRE(read_back.log.size() > 1);  // the graph optimisation ran, visiting every edge's alternatives
  check_same_result(no_folder, read_back);
  check_same_result(read_back, kept);
  CHECK((no_folder.fuzzy.tau() - read_back.fuzzy.tau()).cwiseAbs().maxCoeff() == 0.0f);
  std::filesystem::remove_all(dir);
}

TEST_CASE("alignment store: reading back keeps only summaries, and a cache file lost during the run is an io_error") {
  const int K = 6;
  const auto records = planted_records(4, K);
  const planted_aligner aligner{K, {1, 2}};
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_test_alignment_store";
  std::filesystem::remove_all(dir);
  ss::alignment_store store(records, dir, /*in_memory=*/false);
  store.ensure({{0, 1}, {2, 1}}, aligner, 1);
  CHECK(store.size() == 2);
  CHECK(store.contains(1, 2));
  CHECK(store.alternative_count(0, 1) > 0);
  const auto n = store.visit(1, 2, [](const ss::pair_alignment& pa) { return pa.source * 10 + pa.target; });
  CHECK(n == 12);  // the smaller index is the source
  CHECK_THROWS_AS((void)store.visit(0, 3, [](const ss::pair_alignment&) { return 0; }), std::out_of_range);
  std::filesystem::remove(store.file_of({0, 1}));
  CHECK_THROWS_AS((void)store.visit(1, 0, [](const ss::pair_alignment&) { return 0; }), ss::io_error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("fuzzy collection: fewer than two shapes and bad options are invalid_input") {
  const planted_aligner aligner{4, {0, 1}};
  CHECK_THROWS_AS((void)ss::compute_fuzzy_correspondences(planted_records(1, 4), aligner), ss::invalid_input);
  ss::fuzzy_collection_options o;
  o.prune_fraction = 2;
  CHECK_THROWS_AS((void)ss::compute_fuzzy_correspondences(planted_records(3, 4), aligner, o), ss::invalid_input);
}

namespace {
/// Rejects every pair that involves shape 0 (no alternative), aligns the rest exactly.
struct rejecting_aligner {
  int K;
  ss::pair_alignment align(ss::index_t a, ss::index_t b) const {
    ss::pair_alignment out;
    if (a == 0 || b == 0) return out;
    ss::alignment_alternative right;
    right.scores = permutation_scores(identity(K), 0.9f);
    right.global_score = 0.9;
    out.alternatives = {right};
    return out;
  }
};
}  // namespace

TEST_CASE("fuzzy collection: a shape whose every alignment is rejected is reported as disconnected") {
  const auto records = planted_records(8, 6);
  ss::fuzzy_collection_options o;
  o.embedding.dimensions = 8;
  o.threads = 1;
  const auto r = ss::compute_fuzzy_correspondences(records, rejecting_aligner{6}, o, ss::dense_embedding_solver{});
  REQUIRE(r.disconnected.size() == 1);
  CHECK(r.disconnected[0] == 0);
  for (const auto& e : r.edges) CHECK(e.source != 0);
  // The others still correspond sample by sample.
  for (ss::index_t i = 0; i < 6; ++i) CHECK(r.fuzzy.best_match(r.fuzzy.point(3, i), 5) == i);
}

namespace {
/// The planted aligner that "dies" (throws) after `budget` alignments: an interrupted pairwise stage.
struct interrupted_aligner {
  planted_aligner inner;
  mutable std::atomic<int> left;
  ss::pair_alignment align(ss::index_t a, ss::index_t b) const {
    if (left.fetch_sub(1) <= 0) throw std::runtime_error("interrupted");
    return inner.align(a, b);
  }
};
}  // namespace

TEST_CASE("fuzzy collection: interrupting the pairwise stage and resuming gives the uninterrupted result") {
  const int N = 10, K = 8;
  const auto records = planted_records(N, K);
  const planted_aligner aligner{K, {2, 3}};
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_test_fuzzy_interrupt";
  std::filesystem::remove_all(dir);
  ss::fuzzy_collection_options o;
  o.embedding.dimensions = 12;
  o.threads = 2;
  const auto whole = ss::compute_fuzzy_correspondences(records, aligner, o);  // no cache: the reference
  o.cache_folder = dir;
  const interrupted_aligner dying{aligner, 7};
  CHECK_THROWS_AS((void)ss::compute_fuzzy_correspondences(records, dying, o), std::runtime_error);
  const auto cached = std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator{});
  CHECK(cached >= 1);
  CHECK(cached <= 7);  // what finished before the interruption is on disk, nothing half-written
  const auto resumed = ss::compute_fuzzy_correspondences(records, aligner, o);
  CHECK(resumed.pairs_computed == resumed.pairs_aligned - std::size_t(cached));
  check_same_result(resumed, whole);
  std::filesystem::remove_all(dir);
}

namespace {
/// The planted aligner that fails on one pair.
struct failing_aligner {
  planted_aligner inner;
  std::pair<ss::index_t, ss::index_t> bad;
  ss::pair_alignment align(ss::index_t a, ss::index_t b) const {
    if (std::pair{a, b} == bad) throw std::runtime_error("this pair fails");
    return inner.align(a, b);
  }
};
}  // namespace

TEST_CASE("fuzzy collection: three processes sharing the alignments give the one-process result") {
  const int N = 10, K = 8;
  const auto records = planted_records(N, K);
  const planted_aligner aligner{K, {2, 3}};
  const auto dir = std::filesystem::temp_directory_path() / "shapestruct_test_fuzzy_shared";
  std::filesystem::remove_all(dir);
  ss::fuzzy_collection_options o;
  o.embedding.dimensions = 12;
  o.threads = 1;
  const auto alone = ss::compute_fuzzy_correspondences(records, aligner, o);
  o.cache_folder = dir;
  const auto parts = ss::test::run_parts(3, [&](const ss::work_share& share) {
    auto own = o;
    own.share = share;
    return ss::compute_fuzzy_correspondences(records, aligner, own);
  });
  std::size_t computed = 0;
  for (const auto& r : parts) {
    check_same_result(r, alone);
    CHECK(r.pairs_aligned == alone.pairs_aligned);
    computed += r.pairs_computed;
  }
  CHECK(computed == alone.pairs_aligned);  // every pair aligned once, by one part
  CHECK(parts[1].pairs_computed > 0);
  // A pair that fails in one part stops every part (none waits forever); the failing part rethrows the
  // aligner's own exception.
  std::filesystem::remove_all(dir);
  const failing_aligner failing{aligner, {0, 1}};
  std::atomic<int> failed{0};
  ss::test::thread_exchange ex(2);
  std::vector<std::thread> threads;
  for (std::size_t p = 0; p < 2; ++p)
    threads.emplace_back([&, p] {
      auto own = o;
      own.share = ex.share(p);
      try {
        (void)ss::compute_fuzzy_correspondences(records, failing, own);
      } catch (const std::runtime_error& e) {
        if (std::string(e.what()).find("fails") != std::string::npos) ++failed;
      }
    });
  for (auto& t : threads) t.join();
  CHECK(failed == 2);
  std::filesystem::remove_all(dir);
}
