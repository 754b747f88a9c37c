// SPDX-License-Identifier: MIT
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "shapestruct/collection/alignment_graph.hpp"
#include "geometry/geometry_test_util.hpp"

using namespace shapestruct;

namespace {

using edge_list = std::vector<std::pair<index_t, index_t>>;
constexpr double inf = std::numeric_limits<double>::infinity();

using test::expect_invalid;  // tests/geometry/geometry_test_util.hpp

std::vector<Eigen::VectorXd> random_descriptors(index_t n, index_t d, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Eigen::VectorXd> out(static_cast<std::size_t>(n), Eigen::VectorXd(d));
  for (auto& x : out)
    for (index_t k = 0; k < d; ++k) x(k) = g(rng);
  return out;
}

/// Prim's O(N^2) minimum spanning forest with the same (w, i, j) tie-break: an oracle independent of Boost.
edge_list prim_forest(const Eigen::MatrixXd& D) {
  const index_t n = D.rows();
  std::vector<bool> in(static_cast<std::size_t>(n), false);
  edge_list out;
  for (index_t root = 0; root < n; ++root) {
    if (in[static_cast<std::size_t>(root)]) continue;
    in[static_cast<std::size_t>(root)] = true;
    for (;;) {
      double best = inf;
      std::pair<index_t, index_t> e{-1, -1};
      for (index_t i = 0; i < n; ++i) {
        if (!in[static_cast<std::size_t>(i)]) continue;
        for (index_t j = 0; j < n; ++j) {
          if (in[static_cast<std::size_t>(j)] || !std::isfinite(D(i, j))) continue;
          const std::pair<index_t, index_t> c = std::minmax(i, j);
          if (D(i, j) < best || (D(i, j) == best && c < e)) {
            best = D(i, j);
            e = c;
          }
        }
      }
      if (e.first < 0) break;
      out.push_back(e);
      in[static_cast<std::size_t>(in[static_cast<std::size_t>(e.first)] ? e.second : e.first)] = true;
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool is_valid_graph(const alignment_graph& g) {
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    if (!(g.edges[e].first >= 0 && g.edges[e].first < g.edges[e].second && g.edges[e].second < g.nodes)) return false;
    if (e > 0 && !(g.edges[e - 1] < g.edges[e])) return false;
  }
  return true;
}

/// The k lowest (distance, other) non-tree neighbours of node i.
std::vector<index_t> nearest_non_tree(const Eigen::MatrixXd& D, const alignment_graph& tree, index_t i, index_t k) {
  std::vector<std::pair<double, index_t>> row;
  for (index_t j = 0; j < D.rows(); ++j)
    if (j != i && std::isfinite(D(i, j)) && !tree.has_edge(i, j)) row.emplace_back(D(i, j), j);
  std::sort(row.begin(), row.end());
  std::vector<index_t> out;
  for (std::size_t r = 0; r < row.size() && static_cast<index_t>(r) < k; ++r) out.push_back(row[r].second);
  return out;
}

/// Checks the properties every initial graph has; returns the tree it contains.
alignment_graph check_initial_graph(const Eigen::MatrixXd& D, const alignment_graph& g, index_t M, index_t factor) {
  const index_t n = D.rows();
  CHECK(g.nodes == n);
  CHECK(is_valid_graph(g));
  const alignment_graph tree{.nodes = n, .edges = prim_forest(D)};
  for (const auto& e : tree.edges) CHECK(g.has_edge(e.first, e.second));
  CHECK(g.edge_count() <= n - 1 + n * M);
  for (const auto& edge : g.edges) {
    const index_t i = edge.first, j = edge.second;
    if (tree.has_edge(i, j)) continue;
    CHECK(std::isfinite(D(i, j)));
    const auto ni = nearest_non_tree(D, tree, i, factor * M), nj = nearest_non_tree(D, tree, j, factor * M);
    const bool candidate =
        std::find(ni.begin(), ni.end(), j) != ni.end() || std::find(nj.begin(), nj.end(), i) != nj.end();
    CHECK_MESSAGE(candidate, "edge (" << i << ", " << j << ") is no candidate");
  }
  return tree;
}

double fiedler_value(const alignment_graph& g) { return fiedler_vector(g.nodes, g.edges).value; }

}  // namespace

TEST_CASE("alignment graph helpers: make_alignment_graph, has_edge, neighbours, adjacency lists") {
  const auto g = make_alignment_graph(5, {{3, 1}, {0, 4}, {1, 3}, {2, 0}, {4, 3}});
  CHECK(g.nodes == 5);
  CHECK(g.edges == edge_list{{0, 2}, {0, 4}, {1, 3}, {3, 4}});
  CHECK(g.edge_count() == 4);
  CHECK(g.has_edge(3, 1));
  CHECK(g.has_edge(1, 3));
  CHECK(g.has_edge(4, 0));
  CHECK_FALSE(g.has_edge(1, 2));
  CHECK_FALSE(g.has_edge(2, 2));
  CHECK(g.neighbours(3) == std::vector<index_t>{1, 4});
  CHECK(g.neighbours(0) == std::vector<index_t>{2, 4});
  CHECK(g.neighbours(2) == std::vector<index_t>{0});
  const auto adj = adjacency_lists(g);
  REQUIRE(adj.size() == 5);
  for (index_t v = 0; v < 5; ++v) CHECK(adj[static_cast<std::size_t>(v)] == g.neighbours(v));
  const auto empty = make_alignment_graph(3, {});
  CHECK(empty.edges.empty());
  CHECK(empty.neighbours(1).empty());
}

TEST_CASE("shortest path lengths are BFS hop counts, no_index when unreachable") {
  // a cycle of 8 plus a pendant path 8-9 hanging off node 4, and an isolated node 10
  edge_list e;
  for (index_t i = 0; i < 8; ++i) e.emplace_back(i, (i + 1) % 8);
  e.emplace_back(4, 8);
  e.emplace_back(8, 9);
  const auto g = make_alignment_graph(11, e);
  const auto h = shortest_path_lengths(g, 0);
  CHECK(h == std::vector<index_t>{0, 1, 2, 3, 4, 3, 2, 1, 5, 6, no_index});
  const auto h9 = shortest_path_lengths(g, 9);
  CHECK(h9[9] == 0);
  CHECK(h9[4] == 2);
  CHECK(h9[0] == 6);
  CHECK(shortest_path_lengths(g, 10) == std::vector<index_t>{no_index, no_index, no_index, no_index, no_index, no_index,
                                                             no_index, no_index, no_index, no_index, 0});
}

TEST_CASE("connected components of an alignment graph, numbered by smallest node") {
  const auto g = make_alignment_graph(7, {{5, 6}, {1, 3}, {3, 5}, {2, 4}});
  const auto c = connected_components(g);
  CHECK(c.count == 3);
  CHECK(c.label == std::vector<index_t>{0, 1, 2, 1, 2, 1, 1});
  CHECK(connected_components(alignment_graph{}).count == 0);
}

TEST_CASE("descriptor distance matrix: pairwise L2, symmetric, zero diagonal") {
  const auto x = random_descriptors(9, 5, 3);
  const auto D = descriptor_distance_matrix(x);
  REQUIRE(D.rows() == 9);
  REQUIRE(D.cols() == 9);
  for (index_t i = 0; i < 9; ++i)
    for (index_t j = 0; j < 9; ++j) {
      CHECK(D(i, j) == D(j, i));
      CHECK(D(i, j) == doctest::Approx((x[static_cast<std::size_t>(i)] - x[static_cast<std::size_t>(j)]).norm()));
    }
  CHECK(D.diagonal().isZero(0));
  CHECK(descriptor_distance_matrix({}).size() == 0);
}

TEST_CASE("initial alignment graph: connected, contains the MST, at most N-1 + N M edges, edges are candidates") {
  for (const auto& size : {std::tuple<index_t, index_t, std::uint64_t>{40, 4, 1}, {120, 8, 2}, {200, 3, 3}}) {
    const index_t n = std::get<0>(size), d = std::get<1>(size);
    const std::uint64_t seed = std::get<2>(size);
    INFO("N = " << n << ", d = " << d);
    const auto x = random_descriptors(n, d, seed);
    const auto D = descriptor_distance_matrix(x);
    const auto g = initial_alignment_graph(D);
    const auto tree = check_initial_graph(D, g, 5, 3);
    CHECK(tree.edge_count() == n - 1);
    CHECK(connected_components(g).count == 1);
    // enough candidates: N M edges in all, the tree's included (the chapter's counts)
    CHECK(g.edge_count() == n * 5);
    CHECK(initial_alignment_graph(D, {.tree_in_budget = false}).edge_count() == n - 1 + n * 5);
    // the descriptor overload builds the same graph
    CHECK(initial_alignment_graph(x).edges == g.edges);
    // deterministic
    CHECK(initial_alignment_graph(D).edges == g.edges);
    // the added edges raise the algebraic connectivity far above the tree's
    CHECK(fiedler_value(g) > 3 * fiedler_value(tree));
  }
}

TEST_CASE("initial alignment graph: the added edges are the candidates of highest edge rank on the tree") {
  const index_t n = 80, M = 2;
  const auto D = descriptor_distance_matrix(random_descriptors(n, 5, 17));
  const auto g = initial_alignment_graph(D, {.edges_per_shape = M, .tree_in_budget = false});
  const alignment_graph tree{.nodes = n, .edges = prim_forest(D)};
  // every node's 3M nearest non-tree neighbours, deduplicated
  std::set<std::pair<index_t, index_t>> candidates;
  for (index_t i = 0; i < n; ++i)
    for (const index_t j : nearest_non_tree(D, tree, i, 3 * M)) candidates.insert(std::minmax(i, j));
  const edge_list c(candidates.begin(), candidates.end());
  REQUIRE(c.size() > static_cast<std::size_t>(n * M));
  const auto rank = edge_ranks(fiedler_vector(n, tree.edges), c);
  double lowest_added = inf, highest_left = -inf;
  index_t added = 0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (g.has_edge(c[k].first, c[k].second)) {
      lowest_added = std::min(lowest_added, rank[k]);
      ++added;
    } else {
      highest_left = std::max(highest_left, rank[k]);
    }
  }
  CHECK(added == n * M);
  CHECK(lowest_added >= highest_left);
  CHECK(g.edge_count() == n - 1 + n * M);
}

TEST_CASE("initial alignment graph above 400 shapes ranks on the sparse Fiedler path") {
  const index_t n = 450;
  const auto D = descriptor_distance_matrix(random_descriptors(n, 6, 23));
  const auto g = initial_alignment_graph(D);
  const auto tree = check_initial_graph(D, g, 5, 3);
  CHECK(g.edge_count() == n * 5);
  CHECK(connected_components(g).count == 1);
  CHECK(fiedler_value(g) > 3 * fiedler_value(tree));
}

TEST_CASE("initial alignment graph: small collections and fewer candidates than N M") {
  CHECK(initial_alignment_graph(Eigen::MatrixXd(0, 0)).nodes == 0);
  const auto one = initial_alignment_graph(Eigen::MatrixXd::Zero(1, 1));
  CHECK(one.nodes == 1);
  CHECK(one.edges.empty());
  Eigen::MatrixXd two(2, 2);
  two << 0, 3, 3, 0;
  CHECK(initial_alignment_graph(two).edges == edge_list{{0, 1}});
  // 6 shapes: 5 tree edges, 10 other pairs, all candidates (3M = 15 per node), fewer than N M = 30: all added
  const auto D6 = descriptor_distance_matrix(random_descriptors(6, 3, 5));
  CHECK(initial_alignment_graph(D6).edge_count() == 15);
  // M = 0: the spanning tree alone
  const auto D = descriptor_distance_matrix(random_descriptors(30, 3, 6));
  CHECK(initial_alignment_graph(D, {.edges_per_shape = 0}).edges == prim_forest(D));
  CHECK(initial_alignment_graph(D, {.candidate_factor = 0}).edges == prim_forest(D));
}

TEST_CASE("initial alignment graph: ties are broken by (weight, i, j)") {
  // identical descriptors: every distance 0; Kruskal in (i, j) order builds the star around node 0
  const std::vector<Eigen::VectorXd> same(7, Eigen::VectorXd::Ones(4));
  const auto g = initial_alignment_graph(same, {.edges_per_shape = 0});
  CHECK(g.edges == edge_list{{0, 1}, {0, 2}, {0, 3}, {0, 4}, {0, 5}, {0, 6}});
  const auto full = initial_alignment_graph(same, {.edges_per_shape = 1, .candidate_factor = 1});
  CHECK(full.edge_count() <= 6 + 7);
  CHECK(full.edges == initial_alignment_graph(same, {.edges_per_shape = 1, .candidate_factor = 1}).edges);
}

TEST_CASE("initial alignment graph: +infinity pairs are never edges, a skipped shape stays isolated") {
  const index_t n = 50;
  Eigen::MatrixXd D = descriptor_distance_matrix(random_descriptors(n, 4, 8));
  D.row(7).setConstant(inf);
  D.col(7).setConstant(inf);
  D(7, 7) = 0;
  // and a few forbidden pairs among the rest
  for (const auto& [a, b] : edge_list{{0, 1}, {2, 3}, {10, 40}}) D(a, b) = D(b, a) = inf;
  const auto g = initial_alignment_graph(D);
  check_initial_graph(D, g, 5, 3);
  CHECK(g.neighbours(7).empty());
  for (const auto& [a, b] : g.edges) CHECK(std::isfinite(D(a, b)));
  const auto c = connected_components(g);
  CHECK(c.count == 2);
  for (index_t v = 0; v < n; ++v)
    if (v != 7) CHECK(c.label[static_cast<std::size_t>(v)] == 0);

  // two clusters with no finite pair between them: a spanning forest plus ranked candidates in each
  Eigen::MatrixXd split = descriptor_distance_matrix(random_descriptors(40, 3, 9));
  split.block(0, 20, 20, 20).setConstant(inf);
  split.block(20, 0, 20, 20).setConstant(inf);
  const auto gs = initial_alignment_graph(split);
  check_initial_graph(split, gs, 5, 3);
  CHECK(connected_components(gs).count == 2);
  CHECK(gs.edge_count() <= 38 + 40 * 5);
}

TEST_CASE("alignment graph: one test per invalid_input reason") {
  // initial_alignment_graph
  expect_invalid([] { (void)initial_alignment_graph(Eigen::MatrixXd::Zero(3, 4)); }, input_error::size_mismatch,
                 no_index);
  Eigen::MatrixXd D(3, 3);
  D << 0, 1, 2, 1, 0, 3, 2, 3, 0;
  {
    auto A = D;
    A(0, 2) = 2.5;
    expect_invalid([&] { (void)initial_alignment_graph(A); }, input_error::bad_parameter);
    A(0, 2) = 2 * (1 + 1e-12);  // rounding-level asymmetry is accepted
    CHECK(initial_alignment_graph(A).edge_count() == 3);
  }
  {
    auto A = D;
    A(1, 2) = A(2, 1) = std::nan("");
    expect_invalid([&] { (void)initial_alignment_graph(A); }, input_error::non_finite, 2);
    A(1, 2) = A(2, 1) = -inf;
    expect_invalid([&] { (void)initial_alignment_graph(A); }, input_error::non_finite, 2);
    A = D;
    A(1, 1) = std::nan("");
    expect_invalid([&] { (void)initial_alignment_graph(A); }, input_error::non_finite, 1);
  }
  {
    auto A = D;
    A(0, 1) = A(1, 0) = -1;
    expect_invalid([&] { (void)initial_alignment_graph(A); }, input_error::bad_parameter, 1);
  }
  expect_invalid([&] { (void)initial_alignment_graph(D, {.edges_per_shape = -1}); }, input_error::bad_parameter,
                 no_index);
  expect_invalid([&] { (void)initial_alignment_graph(D, {.candidate_factor = -2}); }, input_error::bad_parameter,
                 no_index);

  // descriptor_distance_matrix
  auto x = random_descriptors(4, 3, 1);
  x[2] = Eigen::VectorXd(5);
  expect_invalid([&] { (void)descriptor_distance_matrix(x); }, input_error::size_mismatch, 2);
  x[2] = Eigen::VectorXd();
  expect_invalid([&] { (void)descriptor_distance_matrix(x); }, input_error::empty, 2);
  x[2] = Eigen::VectorXd::Zero(3);
  x[3](1) = std::nan("");
  expect_invalid([&] { (void)descriptor_distance_matrix(x); }, input_error::non_finite, 3);
  expect_invalid([&] { (void)initial_alignment_graph(x); }, input_error::non_finite, 3);

  // graph helpers
  const auto g = make_alignment_graph(4, {{0, 1}, {1, 2}});
  expect_invalid([&] { (void)shortest_path_lengths(g, 4); }, input_error::bad_parameter, 4);
  expect_invalid([&] { (void)shortest_path_lengths(g, -1); }, input_error::bad_parameter, -1);
  expect_invalid([] { (void)make_alignment_graph(3, {{0, 1}, {1, 3}}); }, input_error::bad_face, 1);
  expect_invalid([] { (void)make_alignment_graph(3, {{0, 1}, {2, 2}}); }, input_error::bad_face, 1);
  expect_invalid([] { (void)make_alignment_graph(-1, {}); }, input_error::bad_parameter, no_index);
  const alignment_graph bad{.nodes = 3, .edges = {{2, 1}}};
  expect_invalid([&] { (void)connected_components(bad); }, input_error::bad_face, 0);
  expect_invalid([&] { (void)adjacency_lists(bad); }, input_error::bad_face, 0);
  expect_invalid([&] { (void)shortest_path_lengths(bad, 0); }, input_error::bad_face, 0);
}
