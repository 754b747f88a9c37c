// SPDX-License-Identifier: MIT
// compute_fuzzy_correspondences: the whole chapter-4 pipeline over a collection of shape records (Algorithm 1).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/collection/alignment_graph.hpp"
#include "shapestruct/collection/edge_rank.hpp"
#include "shapestruct/collection/pair_alignment.hpp"
#include "shapestruct/collection/shape_record.hpp"
#include "shapestruct/core/concepts/shape_aligner.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/work_share.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/fuzzy/alignment_store.hpp"
#include "shapestruct/fuzzy/collection_orientation.hpp"
#include "shapestruct/fuzzy/correspondence_matrix.hpp"
#include "shapestruct/fuzzy/diffusion_embedding.hpp"
#include "shapestruct/fuzzy/fuzzy_correspondence.hpp"

namespace shapestruct {

/// Options of compute_fuzzy_correspondences (the chapter's defaults).
struct fuzzy_collection_options {
  initial_graph_options graph{};            ///< M = 5 edges per shape, 3M candidates (ch. 4.3.2)
  diffusion_embedding_options embedding{};  ///< t = 10, the top K eigenvectors (ch. 4.3.5)
  fuzzy_correspondence_options fuzzy{};     ///< tau from the 15 % nearest points, zero beyond 2 tau (ch. 4.3.6)
  /// An edge whose consistency score is below this fraction of the best score at both of its shapes is pruned.
  double prune_fraction = 0.3;
  /// New edges join shapes whose shortest path in the pruned graph is longer than this many edges.
  index_t new_edge_min_path = 3;
  index_t max_iterations = 10;  ///< the chapter converges within 8
  /// A shape whose edges' mean consistency is below this fraction of the median shape's is weakly supported:
  /// its few alignments disagree or lead to shapes that are themselves unsure, so f cannot settle it (two right
  /// and two wrong alignments look alike to the consistency score). Each round it is aligned with the nearest
  /// shape by descriptor that it has no alignment with yet and that is not weak itself, up to
  /// extra_edges_per_weak_shape times in all: in the first round, and later in rounds where Algorithm 1 still
  /// switches or prunes edges. 0 = off (the chapter only swaps pruned edges for new ones).
  double weak_support_fraction = 0.8;
  index_t extra_edges_per_weak_shape = 2;
  /// Integrated fuzzy correspondences rank the candidate new edges over every stride-th sample of each shape
  /// (1 = all K^2 pairs); the first farthest-point samples cover the shape evenly, so 4 (64 of 128^2 pairs)
  /// changes the ranking little and is 16 times cheaper, which matters when O(N^2) pairs are candidates.
  index_t ifc_stride = 4;
  /// Orientation (orient_collection), for aligners that state a preferred alternative: an edge of the final
  /// graph votes that its shapes sit in f the mirror way round when its chosen alternative is more than this
  /// fraction more consistent than the preferred one, and that they agree when the two are the same (a near tie
  /// says nothing). Negative: no orientation, the default: with 0.1 the consistent blended maps of all 11 SHREC'07
  /// classes are worse overall (the votes are too noisy where the matcher flips often; docs/fuzzy.md).
  double orientation_margin = -1;
  int threads = 0;                       ///< 0 = all cores; results do not depend on it
  std::filesystem::path cache_folder{};  ///< pairwise alignments are cached here ("" = not cached)
  /// With a cache folder: keep every alignment's score blocks in memory as well. Off, they are read back from the
  /// folder whenever a round needs them, so memory holds only the chosen blocks while the matrix is built; the
  /// results are the same (the cache format is lossless). Without a folder they are always in memory.
  bool alignments_in_memory = false;
  /// Several processes: each aligns its share of every round's pairs and reads the others' from the cache
  /// folder (required then); the rest (embedding, optimisation, small next to the alignments) runs in every
  /// process alike, so they all hold the same result, the one a single process computes.
  work_share share{};
  /// Progress: (stage, done, total). Stages: "align", "embed", "optimize". The library never prints.
  std::function<void(const std::string&, std::size_t, std::size_t)> on_progress{};
};

/// One edge of the final alignment graph and the alternative it uses.
struct fuzzy_graph_edge {
  index_t source = no_index;  ///< the smaller shape index
  index_t target = no_index;
  index_t alternative = 0;    ///< index into the pair's alignment alternatives
  double consistency = 0;     ///< score_f (eq. 4.10) of that alternative under the final f
  index_t preferred = no_index;        ///< the aligner's own choice (pair_alignment::preferred), if it has one
  double preferred_consistency = 0;    ///< score_f of the preferred alternative under the final f
};

/// What one round of the graph optimisation did (ch. 4.3.7).
struct fuzzy_iteration {
  index_t iteration = 0;             ///< 0: the initial graph
  index_t edges = 0;                 ///< edges in the graph embedded in this round
  index_t alternatives_changed = 0;  ///< edges that switched to a more consistent alternative
  index_t pruned = 0;                ///< inconsistent edges removed
  index_t added = 0;                 ///< new edges aligned and added
  index_t reconnected = 0;           ///< pruned edges put back because the graph fell apart without them
  index_t reinforced = 0;            ///< of the added edges, those that align a weakly supported shape once more
  std::size_t pairs_aligned = 0;     ///< distinct pairs aligned so far (from the cache or computed)
  double mean_consistency = 0;       ///< mean score_f over the graph's edges before pruning
  double align_seconds = 0, embed_seconds = 0, optimize_seconds = 0;
  status embedding_info = status::ok;
};

/// Result of compute_fuzzy_correspondences.
struct fuzzy_collection_result {
  std::vector<fuzzy_graph_edge> edges;  ///< the final graph, sorted by (source, target)
  fuzzy_correspondence fuzzy;           ///< f of the final graph
  std::vector<fuzzy_iteration> log;     ///< one entry per round, the initial graph first
  std::size_t pairs_aligned = 0;        ///< distinct pairs aligned over the whole run
  std::size_t pairs_computed = 0;       ///< of which computed in this process (the rest came from the cache)
  bool converged = false;               ///< the graph stopped changing before max_iterations
  /// Shapes outside the largest connected component of the final graph (every alignment to the rest was
  /// rejected by the aligner): f between them and the rest means nothing.
  std::vector<index_t> disconnected;
  /// +1 / -1 per shape: which shapes sit in f the mirror way round against the rest, voted by the final graph's
  /// edges (orient_collection, fuzzy_collection_options::orientation_margin). Empty when no edge's aligner states
  /// a preferred alternative or orientation is off. The consistent blended map keeps the matcher's own choice
  /// between shapes of opposite orientation (consistent_blended_options::orientation).
  std::vector<std::int8_t> orientation;
  index_t orientation_votes = 0;  ///< edges that voted (agreeing or not)
};

namespace detail {

/// The votes of the final graph (fuzzy_collection_options::orientation_margin).
inline std::vector<orientation_vote> orientation_votes_of(const std::vector<fuzzy_graph_edge>& edges, double margin) {
  std::vector<orientation_vote> votes;
  if (margin < 0) return votes;
  for (const auto& e : edges) {
    if (e.preferred == no_index) continue;
    if (e.preferred == e.alternative) votes.push_back({e.source, e.target, 1, 1.0});
    else if (e.consistency > (1 + margin) * e.preferred_consistency) votes.push_back({e.source, e.target, -1, 1.0});
  }
  return votes;
}

/// Consistency score of an alternative (eq. 4.10) given F = f.block(source, target): sum over source samples p1
/// of sum_p2 a(p1, p2) f(p1, p2), each row divided by sum over the target's samples of f(p1, p).
inline double consistency_score(const alignment_alternative& alt, const Eigen::MatrixXd& F) {
  const auto& a = alt.scores;
  double score = 0;
  for (index_t i = 0; i < a.outerSize(); ++i) {
    if (a.outerIndexPtr()[i] == a.outerIndexPtr()[i + 1]) continue;
    const double norm = F.row(i).sum();
    if (!(norm > 0)) continue;
    double s = 0;
    for (Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>::InnerIterator it(a, i); it; ++it)
      s += double(it.value()) * F(i, it.col());
    score += s / norm;
  }
  return score;
}

/// weak_support_fraction (fuzzy_collection_options): shapes whose edges' mean consistency `score` is below
/// `fraction` of the median over the shapes that have edges. Shapes without edges are not weak (nothing to add to).
inline std::vector<bool> weakly_supported_shapes(index_t N, const std::vector<std::pair<index_t, index_t>>& edges,
                                                 const std::vector<double>& score, double fraction) {
  std::vector<double> sum(static_cast<std::size_t>(N), 0.0);
  std::vector<index_t> degree(static_cast<std::size_t>(N), 0);
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (const index_t s : {edges[e].first, edges[e].second}) sum[std::size_t(s)] += score[e], ++degree[std::size_t(s)];
  std::vector<double> support;
  for (index_t s = 0; s < N; ++s)
    if (degree[std::size_t(s)] > 0) support.push_back(sum[std::size_t(s)] / double(degree[std::size_t(s)]));
  std::vector<bool> weak(static_cast<std::size_t>(N), false);
  if (support.empty()) return weak;
  std::nth_element(support.begin(), support.begin() + std::ptrdiff_t(support.size() / 2), support.end());
  const double median = support[support.size() / 2];
  for (index_t s = 0; s < N; ++s)
    if (degree[std::size_t(s)] > 0 && sum[std::size_t(s)] / double(degree[std::size_t(s)]) < fraction * median)
      weak[std::size_t(s)] = true;
  return weak;
}

}  // namespace detail

/// Fuzzy correspondences of a collection (ch. 4.3): initial alignment graph from the records' descriptors, the
/// pairwise alignments of its edges (ShapeAligner, in parallel, cached), the correspondence matrix and its
/// diffusion embedding, f, and Algorithm 1 until the graph stops changing: every edge takes its most
/// consistent alternative, edges far below both shapes' best are pruned, and as many new pairs are aligned,
/// chosen among those more than new_edge_min_path edges apart by integrated fuzzy correspondence, then by edge
/// rank. The graph is kept connected: a prune that would split it is undone for the most consistent of the
/// pruned edges that reconnect it (the chapter assumes a connected collection and does not say). A shape whose
/// edges are far less consistent than the median shape's is aligned with more shapes (weak_support_fraction).
/// \param records the shapes (at least 2)  \param aligner the pairwise matcher policy
/// \param solver EmbeddingSolver for the diffusion map
/// \throws invalid_input (empty) for fewer than 2 shapes, (size_mismatch) for descriptors of unequal length,
///         (bad_parameter) for options; whatever the aligner throws.
template <ShapeAligner Aligner, class Solver = lanczos_embedding_solver>
[[nodiscard]] fuzzy_collection_result compute_fuzzy_correspondences(const std::vector<shape_record>& records,
                                                                    const Aligner& aligner,
                                                                    const fuzzy_collection_options& options = {},
                                                                    const Solver& solver = {}) {
  using clock = std::chrono::steady_clock;
  auto since = [](clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); };
  const char* who = "compute_fuzzy_correspondences";
  const index_t N = static_cast<index_t>(records.size());
  if (N < 2) throw invalid_input(input_error::empty, no_index, std::string(who) + ": a collection needs at least 2 shapes");
  if (!(options.prune_fraction >= 0 && options.prune_fraction <= 1))
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": prune_fraction must be in [0, 1]");
  if (options.ifc_stride < 1 || options.max_iterations < 0 || options.new_edge_min_path < 1)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": ifc_stride and new_edge_min_path must be >= 1, max_iterations >= 0");
  if (!(options.weak_support_fraction >= 0 && options.weak_support_fraction <= 1) || options.extra_edges_per_weak_shape < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": weak_support_fraction must be in [0, 1], extra_edges_per_weak_shape >= 0");
  if (std::isnan(options.orientation_margin))
    throw invalid_input(input_error::bad_parameter, no_index, std::string(who) + ": orientation_margin is not a number");
  auto progress = [&](const std::string& stage, std::size_t done, std::size_t total) {
    if (options.on_progress) options.on_progress(stage, done, total);
  };

  std::vector<Eigen::VectorXd> descriptors;
  for (const auto& r : records) descriptors.push_back(r.descriptor);
  const alignment_graph g0 = initial_alignment_graph(descriptor_distance_matrix(descriptors), options.graph);

  alignment_store store(records, options.cache_folder, options.alignments_in_memory);
  using key = alignment_store::key;
  std::map<key, index_t> chosen;  // the graph: edge -> alternative
  std::vector<index_t> sample_counts;
  for (const auto& r : records) sample_counts.push_back(r.sample_count());

  auto align = [&](const std::vector<key>& pairs) {
    store.ensure(pairs, aligner, options.threads, [&](std::size_t d, std::size_t t) { progress("align", d, t); },
                 options.share);
  };
  auto embed = [&](fuzzy_iteration& it) {
    const auto t0 = clock::now();
    progress("embed", 0, 1);
    // Each chosen block is read (from the cache folder, unless in memory) only while the matrix takes it in.
    std::vector<std::pair<key, index_t>> graph(chosen.begin(), chosen.end());
    std::vector<std::pair<index_t, index_t>> pairs;
    for (const auto& [k, alt] : graph) pairs.push_back(k);
    const correspondence_matrix C(sample_counts, pairs, [&](index_t e) {
      const auto& [k, alt] = graph[std::size_t(e)];
      return store.visit(k.first, k.second,
                         [&](const pair_alignment& pa) { return pa.alternatives[std::size_t(alt)].scores; });
    }, options.threads);
    auto e = embed_diffusion(C, options.embedding, solver);
    it.embedding_info = e.info;
    fuzzy_correspondence_options fo = options.fuzzy;
    fo.threads = options.threads;
    fuzzy_correspondence f = make_fuzzy_correspondence(std::move(e), fo);
    it.embed_seconds = since(t0);
    progress("embed", 1, 1);
    return f;
  };

  fuzzy_collection_result out;
  std::vector<index_t> extra_edges(static_cast<std::size_t>(N), 0);  // alignments added for weak support, per shape
  fuzzy_iteration first;
  {
    const auto t0 = clock::now();
    std::vector<key> pairs;
    for (const auto& [a, b] : g0.edges) pairs.push_back(alignment_store::make_key(a, b));
    align(pairs);
    for (const auto& p : pairs)  // a pair the aligner rejected (no alternative) is no edge
      if (store.alternative_count(p.first, p.second) > 0) chosen[p] = store.initial(p.first, p.second);
    first.align_seconds = since(t0);
  }
  first.edges = static_cast<index_t>(chosen.size());
  first.pairs_aligned = store.size();
  fuzzy_correspondence f = embed(first);
  out.log.push_back(first);

  for (index_t iteration = 1; iteration <= options.max_iterations; ++iteration) {
    fuzzy_iteration it;
    it.iteration = iteration;
    const auto t_opt = clock::now();
    // 1. Every edge takes its most consistent alternative (scores computed in parallel, one edge per item).
    std::vector<key> edges;
    for (const auto& [k, alt] : chosen) edges.push_back(k);
    std::vector<index_t> best_alt(edges.size());
    std::vector<double> best_score(edges.size());
    const unsigned workers = detail::resolve_threads(options.threads, who);
    detail::parallel_for(static_cast<index_t>(edges.size()), workers, [&](index_t e) {
      const key& k = edges[std::size_t(e)];
      store.visit(k.first, k.second, [&](const pair_alignment& pa) {
        const Eigen::MatrixXd F = f.block(pa.source, pa.target);
        index_t arg = chosen.at(k);
        double best = detail::consistency_score(pa.alternatives[std::size_t(arg)], F);
        for (std::size_t a = 0; a < pa.alternatives.size(); ++a) {
          const double s = detail::consistency_score(pa.alternatives[a], F);
          if (s > best) best = s, arg = static_cast<index_t>(a);
        }
        best_alt[std::size_t(e)] = arg;
        best_score[std::size_t(e)] = best;
      });
    });
    double sum_score = 0;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      if (chosen[edges[e]] != best_alt[e]) ++it.alternatives_changed;
      chosen[edges[e]] = best_alt[e];
      sum_score += best_score[e];
    }
    it.mean_consistency = edges.empty() ? 0 : sum_score / double(edges.size());
    // 2. Prune edges below prune_fraction of the best score at both of their shapes.
    std::vector<double> node_best(static_cast<std::size_t>(N), 0.0);
    for (std::size_t e = 0; e < edges.size(); ++e) {
      node_best[std::size_t(edges[e].first)] = std::max(node_best[std::size_t(edges[e].first)], best_score[e]);
      node_best[std::size_t(edges[e].second)] = std::max(node_best[std::size_t(edges[e].second)], best_score[e]);
    }
    std::vector<std::size_t> pruned;
    for (std::size_t e = 0; e < edges.size(); ++e)
      if (best_score[e] < options.prune_fraction * node_best[std::size_t(edges[e].first)] &&
          best_score[e] < options.prune_fraction * node_best[std::size_t(edges[e].second)])
        pruned.push_back(e);
    for (const auto e : pruned) chosen.erase(edges[e]);
    // Keep the graph connected: put back the most consistent pruned edges that join two components.
    {
      detail::disjoint_sets dsu(N);
      for (const auto& [k, alt] : chosen) dsu.unite(k.first, k.second);
      std::vector<std::size_t> order = pruned;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return best_score[x] > best_score[y]; });
      for (const auto e : order)
        if (dsu.unite(edges[e].first, edges[e].second)) {
          chosen[edges[e]] = best_alt[e];
          ++it.reconnected;
        }
    }
    it.pruned = static_cast<index_t>(pruned.size()) - it.reconnected;
    // 3. As many new edges: far apart in the graph, highest integrated fuzzy correspondence, then edge rank.
    const index_t add = it.pruned;
    std::vector<key> added;
    if (add > 0) {
      std::vector<std::pair<index_t, index_t>> kept;
      for (const auto& [k, alt] : chosen) kept.push_back(k);
      const alignment_graph pruned_graph = make_alignment_graph(N, std::move(kept));
      std::vector<key> far;
      for (index_t s = 0; s < N; ++s) {
        const auto hops = shortest_path_lengths(pruned_graph, s);
        for (index_t t = s + 1; t < N; ++t)
          if ((hops[std::size_t(t)] < 0 || hops[std::size_t(t)] > options.new_edge_min_path) && !store.contains(s, t))
            far.push_back({s, t});
      }
      std::vector<double> ifc(far.size());
      detail::parallel_for(static_cast<index_t>(far.size()), workers, [&](index_t c) {
        ifc[std::size_t(c)] = f.integrated(far[std::size_t(c)].first, far[std::size_t(c)].second, options.ifc_stride);
      });
      std::vector<std::size_t> order(far.size());
      std::iota(order.begin(), order.end(), std::size_t{0});
      std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return ifc[x] > ifc[y]; });
      order.resize(std::min<std::size_t>(order.size(), std::size_t(3 * add)));
      std::vector<std::pair<index_t, index_t>> candidates;
      for (const auto c : order) candidates.push_back(far[c]);
      if (!candidates.empty()) {
        const auto fiedler = fiedler_vector(N, std::span<const std::pair<index_t, index_t>>(pruned_graph.edges));
        const auto rank = edge_ranks(fiedler, std::span<const std::pair<index_t, index_t>>(candidates));
        std::vector<std::size_t> by_rank(candidates.size());
        std::iota(by_rank.begin(), by_rank.end(), std::size_t{0});
        std::stable_sort(by_rank.begin(), by_rank.end(), [&](std::size_t x, std::size_t y) { return rank[x] > rank[y]; });
        by_rank.resize(std::min<std::size_t>(by_rank.size(), std::size_t(add)));
        for (const auto c : by_rank) added.push_back(candidates[c]);
      }
    }
    // 4. Weakly supported shapes: one more alignment each, with the nearest shape by descriptor not yet aligned.
    // After the first round only while Algorithm 1 itself still changes the graph: once it has settled, a few more
    // alignments are not worth another embedding (on 1,000 generated chairs they kept it going for 4 more rounds).
    if (options.weak_support_fraction > 0 && options.extra_edges_per_weak_shape > 0 &&
        (iteration == 1 || it.alternatives_changed > 0 || it.pruned > 0)) {
      const auto weak = detail::weakly_supported_shapes(N, edges, best_score, options.weak_support_fraction);
      std::set<key> taken(added.begin(), added.end());
      for (index_t s = 0; s < N; ++s) {
        if (!weak[std::size_t(s)] || extra_edges[std::size_t(s)] >= options.extra_edges_per_weak_shape) continue;
        index_t partner = no_index;
        double nearest = std::numeric_limits<double>::infinity();
        for (index_t t = 0; t < N; ++t) {
          if (t == s || weak[std::size_t(t)] || store.contains(s, t) || taken.count(alignment_store::make_key(s, t))) continue;
          const double d = (descriptors[std::size_t(s)] - descriptors[std::size_t(t)]).squaredNorm();
          if (d < nearest) nearest = d, partner = t;
        }
        if (partner == no_index) continue;
        taken.insert(alignment_store::make_key(s, partner));
        added.push_back(alignment_store::make_key(s, partner));
        ++extra_edges[std::size_t(s)];
        ++it.reinforced;
      }
    }
    it.optimize_seconds = since(t_opt);
    if (!added.empty()) {
      const auto t0 = clock::now();
      align(added);
      for (const auto& p : added)
        if (store.alternative_count(p.first, p.second) > 0) chosen[p] = store.initial(p.first, p.second);
      it.align_seconds = since(t0);
    }
    it.added = static_cast<index_t>(added.size());
    it.edges = static_cast<index_t>(chosen.size());
    it.pairs_aligned = store.size();
    progress("optimize", std::size_t(iteration), std::size_t(options.max_iterations));
    const bool changed = it.alternatives_changed > 0 || it.pruned > 0 || it.added > 0;
    if (!changed) {
      out.log.push_back(it);
      out.converged = true;
      break;
    }
    f = {};  // the new f does not depend on the old one: freeing it first lowers the peak by one embedding
    f = embed(it);
    out.log.push_back(it);
  }

  {
    const std::vector<std::pair<key, index_t>> graph(chosen.begin(), chosen.end());
    out.edges.resize(graph.size());
    detail::parallel_for(static_cast<index_t>(graph.size()), detail::resolve_threads(options.threads, who), [&](index_t e) {
      const auto& [k, alt] = graph[std::size_t(e)];
      fuzzy_graph_edge& edge = out.edges[std::size_t(e)];
      edge.source = k.first;
      edge.target = k.second;
      edge.alternative = alt;
      store.visit(k.first, k.second, [&](const pair_alignment& pa) {
        const Eigen::MatrixXd F = f.block(k.first, k.second);
        edge.consistency = detail::consistency_score(pa.alternatives[std::size_t(alt)], F);
        edge.preferred = pa.preferred;
        if (pa.preferred != no_index)
          edge.preferred_consistency = detail::consistency_score(pa.alternatives[std::size_t(pa.preferred)], F);
        return 0;
      });
    });
    const auto votes = detail::orientation_votes_of(out.edges, options.orientation_margin);
    out.orientation_votes = static_cast<index_t>(votes.size());
    if (!votes.empty()) out.orientation = orient_collection(N, votes);
  }
  {
    std::vector<std::pair<index_t, index_t>> final_edges;
    for (const auto& [k, alt] : chosen) final_edges.push_back(k);
    const auto comp = connected_components(make_alignment_graph(N, std::move(final_edges)));
    std::vector<index_t> size(static_cast<std::size_t>(comp.count), 0);
    for (const auto c : comp.label) ++size[std::size_t(c)];
    const auto largest = static_cast<index_t>(std::max_element(size.begin(), size.end()) - size.begin());
    for (index_t k = 0; k < N; ++k)
      if (comp.label[std::size_t(k)] != largest) out.disconnected.push_back(k);
  }
  out.fuzzy = std::move(f);
  out.pairs_aligned = store.size();
  out.pairs_computed = store.computed();
  return out;
}

}  // namespace shapestruct
