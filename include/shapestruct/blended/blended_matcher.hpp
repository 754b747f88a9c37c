// SPDX-License-Identifier: MIT
// blended_matcher: blended intrinsic maps between two closed genus-0 surfaces (dissertation ch. 3).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include "shapestruct/blended/area_confidence.hpp"
#include "shapestruct/blended/blended_shape.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/blended/geodesic_consistency.hpp"
#include "shapestruct/blended/triplet_candidates.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/maps/surface_map.hpp"
#include "shapestruct/spectral/top_eigenpairs.hpp"

namespace shapestruct {

/// How blended_matcher picks one blended map among those of the consistent groups.
enum class blended_selection {
  /// The highest area preservation of the blended map itself (blended_candidate::score).
  area_score,
  /// The lowest sum of the map's rank by area preservation and its rank by the chapter's integrated confidence
  /// (ties: higher area score). A flip must win on both to be chosen. Measured with `run_bim_benchmark --groups`
  /// against area_score: 67 cross-set human pairs mean error 0.1037 -> 0.1006 (13 -> 12 flips), every 2nd
  /// pair 0.0915 -> 0.0849 (8 -> 7), 14 SCAPE pairs unchanged (0.0374), TOSCA michael3->michael1 0.269 -> 0.023.
  area_and_confidence_rank,
};

/// Options of blended_matcher (dissertation ch. 3 defaults).
struct blended_matcher_options {
  blended_shape_options shape{};  ///< per-shape precomputation (samples, features, repairs)
  /// Eigenvectors of S~ whose eigenvalue is at least this fraction of the top one are processed ("within 75% of
  /// the top eigenvalue", ch. 3.3.4, read as lambda_k >= 0.75 lambda_1). Measured on SCAPE: 0.25 (the other
  /// reading) recovers the true group where the flip's block dominates (mesh008->068) but lets more flipped groups
  /// win the selection overall (10 flipped pairs of 50 instead of 6 of 65), so 0.75 is the default.
  double eigenvalue_fraction = 0.75;
  index_t max_eigenvectors = 6;  ///< at most this many eigenvectors (the spectral gap usually leaves 1-3)
  /// Maps whose |entry| in an eigenvector is at least this fraction of the eigenvector's largest |entry| are
  /// the "high entries" that are grouped; the others get weight 0.
  double entry_fraction = 0.25;
  index_t min_group_size = 2;  ///< smaller groups are dropped (unless no group is this large)
  index_t max_groups = 8;      ///< blended maps built and scored, largest eigen-weight first
  /// Blended maps are scored on about this many source faces (every k-th face); only the selected one is then
  /// evaluated at every vertex, unless full_maps_for_all_groups. 0 = score on all faces.
  index_t score_faces = 6000;
  bool full_maps_for_all_groups = false;  ///< also fill blended_candidate::map of the groups not selected
  /// How the blended map is selected among the groups' maps (flip disambiguation, see blended_selection).
  blended_selection selection = blended_selection::area_and_confidence_rank;
  /// Optional extrinsic tie-break: the area term of the selection is score - convexity_weight *
  /// convexity_mismatch (blended_candidate). Intrinsic measures cannot tell a map from its intrinsic 180-degree
  /// flip when both are near-isometric; the convexity mismatch (bumps must map to bumps) can, and weight 5 picks
  /// the true map of a dome-versus-dimple creature where area alone picks the flip. On the benchmark's humans
  /// the flip's and the truth's mismatch differ by less than the noise, so it is off (0) by default;
  /// docs/blended_maps.md has the measurements.
  double convexity_weight = 0.0;
  int threads = 0;             ///< std::threads, 0 = all cores; the result does not depend on it
  /// Progress callback (stage name, seconds spent in it); the library never prints.
  std::function<void(const std::string&, double)> on_stage{};
};

/// One group of consistent candidate maps (binary weights) and the blended map it defines.
template <class Scalar = double>
struct blended_candidate {
  std::vector<index_t> maps;   ///< indices into blended_match_result::candidates
  Scalar eigen_weight = 0;     ///< sum of |eigenvector entries| of the group's maps
  Scalar score = 0;            ///< integrated area preservation of the blended map, in [0, 1] (higher is better)
  /// Integrated confidence of the group (ch. 3.3.5): mean over the even samples of the confidence-weighted mean
  /// confidence of the group's maps, in [0, 1].
  Scalar confidence_integral = 0;
  /// Geodesic distortion of the blended map at the even samples: mean over sample pairs of
  /// |d_source(s, t) - d_target(f(s), f(t))| in unit-area units (lower is better). d_target is read from the
  /// target's sample table via the target sample nearest to f(t), so it carries an error up to the sampling's
  /// covering radius, the same for every group.
  Scalar geodesic_distortion = 0;
  /// Mean over the even samples s of |convexity_source(s) - convexity_target(f(s))| (blended_shape::
  /// sample_convexity, averaged over the radii; both values interpolated from their shape's samples). Intrinsic
  /// measures cannot tell a map from its intrinsic flip (front of a human to the back); this extrinsic but
  /// rigid- and pose-robust one can (noses, knee caps and toes are bumps, their flipped images are not).
  Scalar convexity_mismatch = 0;
  /// The selection's area term: score - blended_matcher_options::convexity_weight * convexity_mismatch.
  Scalar selection_score = 0;
  /// Rank sum used by blended_selection::area_and_confidence_rank (0 = best on both); the selected map has the
  /// smallest. With blended_selection::area_score it is the rank by selection_score alone.
  index_t selection_rank = 0;
  /// The blended map (source vertices -> target surface points); empty for unselected groups unless
  /// blended_matcher_options::full_maps_for_all_groups (blended_matcher::blend_group rebuilds it).
  surface_map<Scalar> map;
};

/// Result of blended_matcher::match. Models MatchResult.
template <class Scalar = double>
struct blended_match_result {
  surface_map<Scalar> map;                          ///< the selected blended map (highest score)
  status info = status::ok;                         ///< not_converged if the eigen-solver did not converge
  std::vector<candidate_map<Scalar>> candidates;    ///< all candidate conformal maps m_i
  matrix_x<Scalar> confidence;                      ///< (#candidates x #samples) c_i(p)
  vector_x<Scalar> eigenvalues;                     ///< leading eigenvalues of S~ (descending)
  std::vector<blended_candidate<Scalar>> blended;   ///< every blended map built, with its score
  index_t selected = no_index;                      ///< index of the selected blended map in `blended`
  std::vector<std::pair<std::string, double>> timings;  ///< seconds per stage
};

/// Blended intrinsic maps (Kim, Lipman & Funkhouser 2011; dissertation ch. 3) with swappable policies:
///   Candidates(a, b)                    -> std::vector<candidate_map>          (triplet_candidates)
///   Confidence(a, b, maps, threads)     -> (#maps x #samples) c_i(p)           (area_confidence)
///   Consistency(a, b, maps, c, threads) -> sparse symmetric S~                 (geodesic_consistency)
/// Pipeline: candidates -> confidences -> S~ -> top eigenvectors (Spectra) -> groups of non-conflicting maps
/// with binary weights -> one blended map per group, f(p) = closest point on the target to the confidence-weighted
/// centroid of the candidate images (ch. 3.3.5) -> the blended map that ranks best by its own area preservation
/// and the chapter's integrated confidence together (blended_selection).
/// Symmetric flips: a flipped near-isometry forms its own group (its maps conflict with the true ones), so it is
/// scored separately; it distorts area more at feet, knees and buttocks (the chapter's cue), and it maps bumps
/// (nose, knee caps, toes) onto flat or hollow places, which the convexity mismatch measures.
/// Models PairwiseMatcher. Per-shape work is in blended_shape: prepare() each shape once and call match() on
/// the prepared shapes to match one shape against many.
template <class Candidates = triplet_candidates, class Confidence = area_confidence,
          class Consistency = geodesic_consistency>
class blended_matcher {
 public:
  using scalar_type = double;

  blended_matcher() = default;
  explicit blended_matcher(blended_matcher_options options, Candidates candidates = {}, Confidence confidence = {},
                           Consistency consistency = {})
      : options_(std::move(options)),
        candidates_(std::move(candidates)),
        confidence_(std::move(confidence)),
        consistency_(std::move(consistency)) {}

  [[nodiscard]] const blended_matcher_options& options() const noexcept { return options_; }

  /// The per-shape precomputation with this matcher's options. \throws invalid_input as blended_shape.
  template <SurfaceMesh Mesh>
  [[nodiscard]] blended_shape<double> prepare(const Mesh& mesh) const {
    auto o = options_.shape;
    o.threads = options_.threads;
    return make_blended_shape(mesh, o);
  }

  /// Matches the vertices of `a` to the surface of `b` (PairwiseMatcher). Prepares both shapes first.
  /// \throws invalid_input as blended_shape (topology, repairs, parameters).
  template <SurfaceMesh Src, SurfaceMesh Tgt>
  [[nodiscard]] blended_match_result<double> match(const Src& a, const Tgt& b) const {
    const auto t0 = clock::now();
    const auto sa = prepare(a);
    const auto sb = prepare(b);
    auto r = match(sa, sb);
    r.timings.insert(r.timings.begin(), {"preprocess", seconds(t0)});
    return r;
  }

  /// Matches two prepared shapes; output maps use the input meshes' vertex numbering.
  /// Complexity: dominated by the consistency matrix, O(pairs * samples * log F / threads).
  [[nodiscard]] blended_match_result<double> match(const blended_shape<double>& a,
                                                   const blended_shape<double>& b) const {
    using Scalar = double;
    blended_match_result<Scalar> out;
    auto stage = [&](const char* name, clock::time_point since) {
      const double s = seconds(since);
      out.timings.emplace_back(name, s);
      if (options_.on_stage) options_.on_stage(name, s);
    };
    auto t = clock::now();
    out.candidates = candidates_(a, b);
    stage("candidates", t);
    const index_t K = static_cast<index_t>(out.candidates.size());
    if (K == 0) {
      // Fewer than three features on a side: no conformal candidate exists. Fall back to the identity of the
      // flattenings, which is still a valid (if poor) conformal map.
      candidate_map<Scalar> c;
      out.candidates.push_back(c);
    }
    t = clock::now();
    out.confidence = confidence_(a, b, out.candidates, options_.threads);
    stage("confidence", t);
    t = clock::now();
    const Eigen::SparseMatrix<Scalar> S = consistency_(a, b, out.candidates, out.confidence, options_.threads);
    stage("consistency", t);
    t = clock::now();
    const index_t n = S.rows();
    const index_t nev = std::min<index_t>(std::max<index_t>(options_.max_eigenvectors, 1), n);
    const auto eig = top_eigenpairs(S, nev);
    out.info = eig.info;
    out.eigenvalues = eig.values;
    std::vector<group> groups = make_groups(out.candidates, eig);
    stage("eigenvectors", t);
    t = clock::now();
    for (const auto& g : groups) {
      blended_candidate<Scalar> bc;
      bc.maps = g.maps;
      bc.eigen_weight = g.weight;
      blend(a, b, out, bc, !options_.full_maps_for_all_groups);
      bc.selection_score = bc.score - options_.convexity_weight * bc.convexity_mismatch;
      out.blended.push_back(std::move(bc));
    }
    const index_t best = select(out.blended);
    out.selected = best;
    auto& chosen = out.blended[static_cast<std::size_t>(best)];
    if (chosen.map.points.empty()) {
      // Re-blending at every vertex: keep the area score of the scored face subset, which the selection used
      // (the sample measures do not change: the samples are blended alike in both passes).
      const Scalar score = chosen.score;
      blend(a, b, out, chosen, false);
      chosen.score = score;
    }
    out.map = chosen.map;
    stage("blending", t);
    return out;
  }

 private:
  using clock = std::chrono::steady_clock;
  static double seconds(clock::time_point since) { return std::chrono::duration<double>(clock::now() - since).count(); }

  struct group {
    std::vector<index_t> maps;
    double weight = 0;
  };

  /// Ch. 3.3.4 "Processing eigenvectors": eigenvectors within the eigenvalue fraction; in each, the high
  /// entries (by |entry|, descending) join the first group they do not conflict with, or start a new one.
  std::vector<group> make_groups(const std::vector<candidate_map<double>>& maps, const eigenpairs_result<double>& eig) const {
    std::vector<group> groups;
    std::vector<char> used(maps.size(), 0);
    const index_t ne = eig.values.size();
    if (ne == 0 || eig.vectors.cols() == 0) {
      groups.push_back({{0}, 1.0});
      return groups;
    }
    const double top = eig.values[0];
    for (index_t e = 0; e < ne && e < eig.vectors.cols(); ++e) {
      if (e > 0 && !(eig.values[e] >= options_.eigenvalue_fraction * top)) break;
      const auto w = eig.vectors.col(e);
      const double wmax = w.cwiseAbs().maxCoeff();
      if (!(wmax > 0)) continue;
      std::vector<index_t> high;
      for (index_t i = 0; i < w.size(); ++i)
        if (std::abs(w[i]) >= options_.entry_fraction * wmax) high.push_back(i);
      std::stable_sort(high.begin(), high.end(), [&](index_t x, index_t y) { return std::abs(w[x]) > std::abs(w[y]); });
      for (index_t i : high) {
        if (used[static_cast<std::size_t>(i)]) continue;
        used[static_cast<std::size_t>(i)] = 1;
        bool placed = false;
        for (auto& g : groups) {
          bool ok = true;
          for (index_t j : g.maps)
            if (maps[static_cast<std::size_t>(i)].conflicts_with(maps[static_cast<std::size_t>(j)])) {
              ok = false;
              break;
            }
          if (ok) {
            g.maps.push_back(i);
            g.weight += std::abs(w[i]);
            placed = true;
            break;
          }
        }
        if (!placed) groups.push_back({{i}, std::abs(w[i])});
      }
    }
    std::stable_sort(groups.begin(), groups.end(), [](const group& x, const group& y) { return x.weight > y.weight; });
    std::vector<group> kept;
    for (const auto& g : groups)
      if (static_cast<index_t>(g.maps.size()) >= options_.min_group_size) kept.push_back(g);
    if (kept.empty() && !groups.empty()) kept.push_back(groups.front());
    if (static_cast<index_t>(kept.size()) > options_.max_groups) kept.resize(static_cast<std::size_t>(options_.max_groups));
    for (auto& g : kept) std::sort(g.maps.begin(), g.maps.end());
    return kept;
  }

  /// Ch. 3.3.5: f(p) = projection onto the target of sum_i c_i(p) m_i(p) / sum_i c_i(p) over the group (binary
  /// weights), c_i interpolated from the samples; then the blended map's own area preservation as its score.
  /// With score_only, the map is evaluated only at the corners of the scored faces and not stored.
  void blend(const blended_shape<double>& a, const blended_shape<double>& b, const blended_match_result<double>& r,
             blended_candidate<double>& bc, bool score_only) const {
    using Scalar = double;
    const auto& Va = a.mesh().V;
    const auto& Fa = a.mesh().F;
    const auto& Vb = b.mesh().V;
    const auto& Fb = b.mesh().F;
    const index_t nv = Va.rows();
    const auto& fa = a.flattening();
    const auto& fb = b.flattening();
    const auto& idx = a.interpolation_index();
    const auto& wts = a.interpolation_weight();
    std::vector<surface_point<Scalar>> pts(static_cast<std::size_t>(nv));
    matrix_x3<Scalar> img = matrix_x3<Scalar>::Zero(nv, 3);
    const index_t face_stride =
        options_.score_faces > 0 ? std::max<index_t>(1, Fa.rows() / std::max<index_t>(options_.score_faces, 1)) : 1;
    std::vector<index_t> todo;
    if (score_only) {
      std::vector<char> need(static_cast<std::size_t>(nv), 0);
      for (index_t f = 0; f < Fa.rows(); f += face_stride)
        for (int k = 0; k < 3; ++k) need[static_cast<std::size_t>(Fa(f, k))] = 1;
      for (index_t s : a.samples()) need[static_cast<std::size_t>(s)] = 1;
      for (index_t v = 0; v < nv; ++v)
        if (need[static_cast<std::size_t>(v)]) todo.push_back(v);
    } else {
      todo.resize(static_cast<std::size_t>(nv));
      std::iota(todo.begin(), todo.end(), index_t(0));
    }
    detail::parallel_for(static_cast<index_t>(todo.size()), detail::resolve_threads(options_.threads, "blended intrinsic maps"), [&](index_t ti) {
      const index_t v = todo[static_cast<std::size_t>(ti)];
      const auto z = fa.coordinate(v);
      vec3<Scalar> acc = vec3<Scalar>::Zero();
      Scalar wsum = 0, best_c = -1;
      vec3<Scalar> best_p = vec3<Scalar>::Zero();
      for (index_t i : bc.maps) {
        Scalar c = 0;
        for (index_t k = 0; k < idx.cols(); ++k) c += wts(v, k) * r.confidence(i, idx(v, k));
        const auto q = fb.locate(r.candidates[static_cast<std::size_t>(i)].transform(z));
        const vec3<Scalar> p = q.position(Vb, Fb);
        if (c > best_c) {
          best_c = c;
          best_p = p;
        }
        acc += c * p;
        wsum += c;
      }
      const vec3<Scalar> centroid = wsum > Scalar(1e-12) ? vec3<Scalar>(acc / wsum) : best_p;
      const auto hit = b.closest_points().query(centroid);
      pts[static_cast<std::size_t>(v)] = hit.location;
      img.row(v) = hit.point.transpose();
    });
    // Score: area-weighted mean of 2 / (r + 1/r) over the source faces, r = image area / face area (both unit).
    Scalar score = 0, scored_area = 0;
    for (index_t f = 0; f < Fa.rows(); f += face_stride) {
      const vec3<Scalar> a0 = Va.row(Fa(f, 0)), a1 = Va.row(Fa(f, 1)), a2 = Va.row(Fa(f, 2));
      const vec3<Scalar> b0 = img.row(Fa(f, 0)), b1 = img.row(Fa(f, 1)), b2 = img.row(Fa(f, 2));
      const Scalar A = Scalar(0.5) * (a1 - a0).cross(a2 - a0).norm();
      const Scalar B = Scalar(0.5) * (b1 - b0).cross(b2 - b0).norm();
      if (!(A > 0)) continue;
      scored_area += A;
      const Scalar ratio = B / A;
      score += ratio > 0 ? A * Scalar(2) / (ratio + Scalar(1) / ratio) : Scalar(0);
    }
    bc.score = scored_area > 0 ? score / scored_area : Scalar(0);
    sample_measures(a, b, r, bc, pts);
    if (score_only) return;
    // Back to the input numbering (repairs may have renumbered or added vertices).
    const index_t n_out = a.original_size();
    bc.map.points.assign(static_cast<std::size_t>(n_out), surface_point<Scalar>{});
    bc.map.nearest.assign(static_cast<std::size_t>(n_out), no_index);
    for (index_t v = 0; v < n_out; ++v) {
      const index_t iv = a.internal_vertex(v);
      if (iv == no_index) continue;
      const auto& p = pts[static_cast<std::size_t>(iv)];
      if (!p.valid()) continue;
      // Report the nearest ORIGINAL target vertex (a hole-filling vertex has no original id).
      index_t best = no_index;
      Scalar bw = -1;
      for (int k = 0; k < 3; ++k) {
        const index_t tv = b.original_vertex(Fb(p.face, k));
        if (tv != no_index && p.bary[k] > bw) {
          bw = p.bary[k];
          best = tv;
        }
      }
      bc.map.points[static_cast<std::size_t>(v)] = p;
      bc.map.nearest[static_cast<std::size_t>(v)] = best;
    }
  }

  /// Ranks the groups' blended maps (blended_candidate::selection_rank) and returns the selected one.
  index_t select(std::vector<blended_candidate<double>>& maps) const {
    const index_t n = static_cast<index_t>(maps.size());
    std::vector<index_t> order(static_cast<std::size_t>(n));
    const auto rank_by = [&](auto better) {
      std::iota(order.begin(), order.end(), index_t(0));
      std::stable_sort(order.begin(), order.end(), better);
      for (index_t r = 0; r < n; ++r) maps[static_cast<std::size_t>(order[static_cast<std::size_t>(r)])].selection_rank += r;
    };
    for (auto& m : maps) m.selection_rank = 0;
    rank_by([&](index_t x, index_t y) {
      return maps[static_cast<std::size_t>(x)].selection_score > maps[static_cast<std::size_t>(y)].selection_score;
    });
    if (options_.selection == blended_selection::area_and_confidence_rank)
      rank_by([&](index_t x, index_t y) {
        return maps[static_cast<std::size_t>(x)].confidence_integral > maps[static_cast<std::size_t>(y)].confidence_integral;
      });
    index_t best = 0;
    for (index_t g = 1; g < n; ++g) {
      const auto& c = maps[static_cast<std::size_t>(g)];
      const auto& b = maps[static_cast<std::size_t>(best)];
      if (c.selection_rank < b.selection_rank || (c.selection_rank == b.selection_rank && c.selection_score > b.selection_score))
        best = g;
    }
    return best;
  }

  /// Integrated confidence, geodesic distortion and convexity mismatch of a blended map (see blended_candidate).
  static void sample_measures(const blended_shape<double>& a, const blended_shape<double>& b,
                              const blended_match_result<double>& r, blended_candidate<double>& bc,
                              const std::vector<surface_point<double>>& pts) {
    const auto& samples = a.samples();
    const index_t ns = static_cast<index_t>(samples.size());
    if (ns == 0) return;
    double conf = 0;
    for (index_t s = 0; s < ns; ++s) {
      double c1 = 0, c2 = 0;
      for (index_t i : bc.maps) {
        const double c = r.confidence(i, s);
        c1 += c;
        c2 += c * c;
      }
      conf += c1 > 0 ? c2 / c1 : 0.0;
    }
    bc.confidence_integral = conf / static_cast<double>(ns);
    // Image of every sample as a target vertex, and the target sample nearest to it.
    const auto& Fb = b.mesh().F;
    const auto& Tb = b.sample_distances();
    std::vector<index_t> image(static_cast<std::size_t>(ns), no_index), image_sample(static_cast<std::size_t>(ns), 0);
    for (index_t s = 0; s < ns; ++s) {
      const auto& p = pts[static_cast<std::size_t>(samples[static_cast<std::size_t>(s)])];
      if (!p.valid()) continue;
      int k = 0;
      for (int c = 1; c < 3; ++c)
        if (p.bary[c] > p.bary[k]) k = c;
      const index_t v = Fb(p.face, k);
      image[static_cast<std::size_t>(s)] = v;
      Tb.row(v).minCoeff(&image_sample[static_cast<std::size_t>(s)]);
    }
    const auto& Ta = a.sample_distances();
    double sum = 0;
    std::size_t count = 0;
    for (index_t s = 0; s < ns; ++s) {
      const index_t vs = image[static_cast<std::size_t>(s)];
      if (vs == no_index) continue;
      for (index_t t = 0; t < ns; ++t) {
        if (t == s || image[static_cast<std::size_t>(t)] == no_index) continue;
        const double da = Ta(samples[static_cast<std::size_t>(s)], t);
        const double db = Tb(vs, image_sample[static_cast<std::size_t>(t)]);
        sum += std::abs(da - db);
        ++count;
      }
    }
    bc.geodesic_distortion = count > 0 ? sum / static_cast<double>(count) : 0.0;
    const auto& Ca = a.sample_convexity();
    const auto& Cb = b.sample_convexity();
    double mismatch = 0;
    std::size_t mapped = 0;
    // Both descriptors interpolated from their shape's samples (like the confidences), so that both sides are
    // smoothed alike and a perfect map has no mismatch.
    const auto interpolated = [](const blended_shape<double>& shape, const matrix_x<double>& C, index_t v) {
      Eigen::RowVectorXd c = Eigen::RowVectorXd::Zero(C.cols());
      for (index_t k = 0; k < shape.interpolation_index().cols(); ++k)
        c += shape.interpolation_weight()(v, k) * C.row(shape.interpolation_index()(v, k));
      return c;
    };
    if (Ca.cols() > 0 && Ca.cols() == Cb.cols()) {
      for (index_t s = 0; s < ns; ++s) {
        if (image[static_cast<std::size_t>(s)] == no_index) continue;
        const Eigen::RowVectorXd ca = interpolated(a, Ca, samples[static_cast<std::size_t>(s)]);
        const Eigen::RowVectorXd cb = interpolated(b, Cb, image[static_cast<std::size_t>(s)]);
        mismatch += (ca - cb).cwiseAbs().mean();
        ++mapped;
      }
    }
    bc.convexity_mismatch = mapped > 0 ? mismatch / static_cast<double>(mapped) : 0.0;
  }

  blended_matcher_options options_{};
  Candidates candidates_{};
  Confidence confidence_{};
  Consistency consistency_{};
};

}  // namespace shapestruct
