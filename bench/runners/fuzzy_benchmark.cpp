// SPDX-License-Identifier: MIT
// run_fuzzy_benchmark: fuzzy correspondences (dissertation ch. 4) measured on real and generated collections.
//
//   run_fuzzy_benchmark --set shrec --data $SHAPESTRUCT_DATA --out DIR [--classes 1,4,...] [--threads T]
//       Each SHREC'07 class of the benchmark's Corr_SHREC.query is one intrinsic collection of its closed genus-0
//       shapes. On the benchmark's pairs of that class, three maps are scored exactly as run_bim_benchmark scores
//       them (feature points, geodesic / sqrt(area) on the target, raw and with the class's symmetry): the
//       pairwise blended map (the matcher alone), the consistent blended map (4.4.5) and the best fuzzy
//       correspondence (4.4.2); the stored original BIM figure is read beside them.
//   run_fuzzy_benchmark --set scape --data $SHAPESTRUCT_DATA --out DIR [--threads T]
//       The 71 meshes of the benchmark's Corr_Scape.query as one intrinsic collection; its 71 pairs scored at 1,024
//       geodesic farthest-point samples of the source (dense truth: the same vertex id), raw and with the
//       symmetry made dense from the feature points, beside the pairwise blended maps and the stored original.
//   run_fuzzy_benchmark --set humans|animals --data $SHAPESTRUCT_DATA --out DIR [--threads T]
//       The meshes of a cross-set list (Corr_Humans.query: SCAPE, TOSCA and SHREC'07 humans; Corr_Animals.query:
//       TOSCA and SHREC'07 four-legged animals) as one intrinsic collection, each mesh repaired as
//       run_bim_benchmark repairs it; the list's pairs scored as run_bim_benchmark scores them (feature points
//       paired by name, the target class's symmetry for the flips), beside the pairwise blended maps and the
//       stored original.
//   run_fuzzy_benchmark --set chairs|airplanes --count N --out DIR [--threads T] [--seed S]
//       A generated collection of polygon soups with named landmarks, extrinsic: landmark error / bounding-box
//       diagonal of the target, over all ordered pairs, for the best fuzzy correspondence, it refined, the extrinsic
//       matcher alone on every pair, and the least-squares affine alignment of the true landmarks.
//   run_fuzzy_benchmark --set coseg|psb --data $SHAPESTRUCT_DATA --out DIR [--classes chair,table,...] [--threads T]
//       Label transfer on real collections, extrinsic: the 17 consistently labelled COSEG chairs (all but
//       101, 102, 103, 109, 110), or PSB classes of 20 meshes (chair, table, airplane, cup, fourleg by default).
//       Every shape's ground-truth labels are carried to every other shape, face by face: a target face's nearest
//       sample, its best fuzzy correspondence (or, for the baseline, its best-scoring sample under the extrinsic
//       matcher's alignment of that pair), and the label of the source face nearest that sample. COSEG scores
//       the area fraction labelled right (labels are consistent across the class); PSB the area-weighted Rand
//       index against every human segmentation of the target (the source's first human segmentation is carried).
// Options: --aligner truth (generated sets) aligns every pair by the least-squares affine map of the true landmarks,
// the chapter's Figure 4.7 experiment; --sigma / --intrinsic-sigma set the score widths (sigma_fraction of the
// extrinsic and intrinsic aligners); --up the extrinsic aligner's up axis (-1: none, any rotation); --min-gain, --fuzzy-min-gain, --max-fuzzy-distortion and --fuzzy-min-distance
// the consistent blended map's min_consistency_gain, fuzzy_min_gain, max_fuzzy_distortion_ratio and
// fuzzy_min_distance; --no-fuzzy-candidate leaves the refined best fuzzy map out of its
// candidates (by default the runner also scores that choice as consistent_blended_only); --no-refine-axis-scales
// refines the extrinsic fuzzy map with one scale (by default a scale per axis, as `fuzzy-map --refined`);
// --baseline-axis-scales also scores the matcher with a scale per axis on every pair; --axis-scales makes the
// collection's own alignments and the all-pairs matcher fit one (extrinsic_alignment_options::axis_scales); --time, --dims,
// --iterations, --samples, --edges-per-shape (M) the pipeline's.
// Writes <set>_pairs.csv (per pair and method; for shrec also shrec_groups.csv, every candidate blended map of a
// pair with its selection features and errors), <set>_choices.csv (per pair, what the consistent map chose and the
// consistencies, distortions and distances it chose by), <set>_curves.dat (fraction within D, D = 0 .. 0.25) and
// appends a table to summary.md; prints per-stage times.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "shapestruct/eval/error_curve.hpp"
#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/eval/rand_index.hpp"
#include "shapestruct/fuzzy/collection_records.hpp"
#include "shapestruct/fuzzy/extrinsic_alignment.hpp"
#include "shapestruct/fuzzy/fuzzy_collection.hpp"
#include "shapestruct/fuzzy/fuzzy_maps.hpp"
#include "shapestruct/fuzzy/intrinsic_alignment.hpp"
#include "shapestruct/fuzzy/refined_fuzzy_alignment.hpp"
#include "shapestruct/generate/assembly_generator.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/geometry/sphere_repair.hpp"
#include "shapestruct/io/bim_benchmark_files.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "shapestruct/io/write_mesh.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "runner_errors.hpp"

namespace fs = std::filesystem;
using namespace shapestruct;
using clock_type = std::chrono::steady_clock;

namespace {

/// Pipeline settings the runner can change from the command line (defaults: the chapter's).
struct tuning {
  double time = -1;        ///< --time: diffusion time t
  index_t dims = -1;       ///< --dims: embedding dimensions
  index_t iterations = -1; ///< --iterations: graph-optimisation rounds
  index_t samples = 128;   ///< --samples: K
  index_t edges_per_shape = -1;  ///< --edges-per-shape: M
  bool baseline = true;    ///< --no-baseline skips the all-pairs extrinsic baseline (slow: every pair aligned)
  double weak_support = -1;  ///< --weak-support F: fuzzy_collection_options::weak_support_fraction (0 = off)
  std::optional<double> orientation_margin;  ///< --orientation-margin F: fuzzy_collection_options' (negative = off)
  /// --aligner truth: align the generated shapes by the least-squares affine map of their true landmarks (the
  /// chapter's Figure 4.7 experiment: how much the embedding itself loses when every alignment is right).
  std::string aligner = "extrinsic";
  extrinsic_alignment_options extrinsic;  ///< --sigma: its sigma_fraction
  /// --intrinsic-sigma: sigma_intrinsic(S) / sqrt(area(S)) of the intrinsic scores
  double intrinsic_sigma = intrinsic_alignment_options{}.sigma_fraction;
  /// --both-feature-sets: intrinsic_alignment_options::both_feature_sets (every blended map of both feature
  /// sets an alternative of the edge and a candidate of the consistent blended map)
  bool both_feature_sets = false;
  [[nodiscard]] intrinsic_alignment_options intrinsic() const {
    return {.sigma_fraction = intrinsic_sigma, .both_feature_sets = both_feature_sets};
  }
  [[nodiscard]] std::string intrinsic_cache_suffix() const;
  /// --min-gain, --fuzzy-min-gain, --max-fuzzy-distortion, --fuzzy-min-distance, --no-refine-choice. With a chosen
  /// blended map refined (refine_choice, the default) the runner also scores it unrefined ("consistent_unrefined")
  /// and logs the refinement's distortion ratio per pair; the comparison rows (unoriented, blended only) are
  /// chosen the same way but left unrefined.
  consistent_blended_options consistent;
  /// --refined-duel (shrec): also score "consistent_refined", the blended maps' choice refined by ZoomOut against
  /// the refined fuzzy map, the more consistent of the two (both then equally precise), and that refined blended
  /// choice alone ("blended_only_refined").
  bool refined_duel = false;
  /// The refined fuzzy map fits a scale per axis, as `fuzzy-map --refined` does (extrinsic_alignment_options::
  /// axis_scales, upright collections); --no-refine-axis-scales: one scale, the similarity alone.
  bool refine_axis_scales = true;
  /// --baseline-axis-scales: also score the all-pairs matcher with axis_scales (a column beside the chapter's).
  bool baseline_axis_scales = false;
};
tuning knobs;

/// The options with axis_scales on where asked and possible (it needs an up axis).
extrinsic_alignment_options with_axis_scales(extrinsic_alignment_options o, bool on) {
  o.axis_scales = on && o.up_axis != no_up_axis && o.allow_scale;
  return o;
}

void apply(fuzzy_collection_options& fo) {
  if (knobs.time >= 0) fo.embedding.time = knobs.time;
  if (knobs.dims > 0) fo.embedding.dimensions = knobs.dims;
  if (knobs.iterations >= 0) fo.max_iterations = knobs.iterations;
  if (knobs.weak_support >= 0) fo.weak_support_fraction = knobs.weak_support;
  if (knobs.orientation_margin) fo.orientation_margin = *knobs.orientation_margin;
  if (knobs.edges_per_shape > 0) fo.graph.edges_per_shape = knobs.edges_per_shape;
}

double seconds_since(clock_type::time_point t) { return std::chrono::duration<double>(clock_type::now() - t).count(); }

std::string fmt(double x, int prec = 3) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", prec, x);
  return b;
}

/// The intrinsic cache folders' suffix: alignments made with other settings are not read back.
std::string tuning::intrinsic_cache_suffix() const {
  return "_sigma" + fmt(intrinsic_sigma) + (both_feature_sets ? "_both_sets" : "");
}

/// The cache folder's mark of a non-default up axis (none for +y, so that older caches stay valid).
std::string up_suffix(const extrinsic_alignment_options& o) {
  return (o.up_axis == extrinsic_alignment_options{}.up_axis ? std::string() : "_up" + std::to_string(o.up_axis)) +
         (o.axis_scales ? "_axis_scales" : "");
}

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / double(v.size());
}

double within(const std::vector<double>& v, double d) {
  if (v.empty()) return 0;
  return double(std::count_if(v.begin(), v.end(), [&](double x) { return x <= d; })) / double(v.size());
}

/// Errors of one method, raw and with flips (per pair: the better of the truth and its symmetric image).
struct method_errors {
  std::vector<double> raw, flip;
  int flipped_pairs = 0, pairs = 0;
  void add(const std::vector<double>& e_raw, const std::vector<double>& e_sym) {
    raw.insert(raw.end(), e_raw.begin(), e_raw.end());
    const bool flipped = mean_of(e_sym) < mean_of(e_raw);
    const auto& f = flipped ? e_sym : e_raw;
    flip.insert(flip.end(), f.begin(), f.end());
    flipped_pairs += flipped ? 1 : 0;
    ++pairs;
  }
};

void write_curves(const fs::path& file, const std::vector<std::pair<std::string, const std::vector<double>*>>& cols,
                  const std::string& comment) {
  std::ofstream out(file);
  out << "# " << comment << "\n# D";
  for (const auto& c : cols) out << "  " << c.first;
  out << "\n";
  for (int i = 0; i <= 50; ++i) {
    const double d = 0.005 * i;
    out << fmt(d, 3);
    for (const auto& c : cols) out << "  " << fmt(within(*c.second, d), 4);
    out << "\n";
  }
}

std::vector<int> parse_list(const std::string& s) {
  std::vector<int> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(std::stoi(item));
  return out;
}

void print_log(const fuzzy_collection_result& r, const std::vector<shape_record>* records = nullptr) {
  const auto& ev = r.fuzzy.embedding().eigenvalues;
  std::cout << "    eigenvalues (index: lambda):";
  for (const index_t i : {0, 7, 15, 31, 63, 127})
    if (i < ev.size()) std::cout << " " << i + 1 << ": " << fmt(ev[i], 4);
  std::cout << "\n";
  for (const auto& it : r.log)
    std::cout << "    iteration " << it.iteration << ": edges " << it.edges << ", switched " << it.alternatives_changed
              << ", pruned " << it.pruned << ", added " << it.added << " (reinforcing weak shapes " << it.reinforced
              << "), reconnected " << it.reconnected
              << ", pairs aligned " << it.pairs_aligned << ", mean consistency " << fmt(it.mean_consistency, 4)
              << ", align " << fmt(it.align_seconds, 1) << " s, embed " << fmt(it.embed_seconds, 2) << " s, optimise "
              << fmt(it.optimize_seconds, 2) << " s\n";
  if (!r.orientation.empty()) {
    std::cout << "    orientation: " << r.orientation_votes << " edges voted; opposite the rest (votes agreeing / against):";
    const auto votes = detail::orientation_votes_of(r.edges, knobs.orientation_margin.value_or(fuzzy_collection_options{}.orientation_margin));
    index_t opposite = 0;
    for (std::size_t k = 0; k < r.orientation.size(); ++k) {
      if (r.orientation[k] > 0) continue;
      int agree = 0, against = 0;
      for (const auto& v : votes)
        if (std::size_t(v.a) == k || std::size_t(v.b) == k) ++(v.sign > 0 ? agree : against);
      std::cout << " " << (records ? (*records)[k].name : std::to_string(k)) << " (" << agree << " / " << against << ")";
      ++opposite;
    }
    std::cout << (opposite == 0 ? " none" : "") << "\n";
  }
}

/// The header and one line of <set>_choices.csv: which map the consistent blended map chose for a pair (the
/// matcher's own choice, another blended map, or the refined fuzzy map), the consistencies (eq. 4.10) it chose by,
/// the geodesic distortions of the refined fuzzy map and of the most consistent blended map, and the mean distance
/// between their images, so that other selection rules can be studied from one run.
constexpr const char* choices_header =
    "matcher_consistency,best_blended_consistency,fuzzy_consistency,chosen,opposite_orientation,fuzzy_distortion,"
    "most_consistent_distortion,fuzzy_distance\n";
void write_choice(std::ostream& out, const std::string& pair_columns, const consistent_blended_map& cb) {
  double matcher = -1, best = -1;
  for (std::size_t k = 0; k < cb.groups.size(); ++k) {
    best = std::max(best, cb.consistency[k]);
    if (cb.groups[k] == cb.pairwise_group) matcher = cb.consistency[k];
  }
  out << pair_columns << fmt(matcher, 4) << "," << fmt(best, 4) << "," << fmt(cb.fuzzy_consistency, 4) << ","
      << (cb.fuzzy_chosen ? "fuzzy" : cb.group == cb.pairwise_group ? "matcher" : "blended") << ","
      << (cb.opposite_orientation ? 1 : 0) << "," << fmt(cb.fuzzy_distortion, 5) << ","
      << fmt(cb.most_consistent_distortion, 5) << "," << fmt(cb.fuzzy_distance, 5) << "\n";
}

/// The consistent map before its chosen blended map's refinement (the comparison row "consistent_unrefined"; the
/// map itself where the refined fuzzy map was chosen, so that the row covers every pair), or nothing when the
/// refinement is off; one line on stdout says how much the refinement changed the map's geodesic distortion and
/// whether it was kept, so that other limits can be studied from one run.
std::optional<std::vector<index_t>> unrefined_choice(const blended_match_result<double>& pairwise,
                                                     const consistent_blended_map& cb, const std::string& a,
                                                     const std::string& b) {
  if (!knobs.consistent.refine_choice) return std::nullopt;
  if (cb.fuzzy_chosen) return cb.map.nearest;
  std::cout << "  refinement " << a << " -> " << b << ": group " << cb.group << ", distortion ratio "
            << fmt(cb.refinement_distortion_ratio, 4) << (cb.refinement_accepted ? ", kept\n" : ", undone\n");
  return pairwise.blended[std::size_t(cb.group)].map.nearest;
}

// ---------------------------------------------------------------------------------------------- SHREC'07
int run_shrec(const fs::path& data, const fs::path& out_dir, const std::string& classes_arg, int threads) {
  const auto pairs = read_bim_query((data / "Results" / "Corr_SHREC.query").string());
  std::map<int, std::vector<bim_pair>> by_class;
  for (const auto& p : pairs) by_class[std::stoi(p.source.cls)].push_back(p);
  std::vector<int> classes = parse_list(classes_arg);
  if (classes.empty())
    for (const auto& [c, v] : by_class) classes.push_back(c);
  std::ofstream csv(out_dir / "shrec_pairs.csv");
  csv << "class,source,target,method,mean,w025,mean_flip,flipped,w005,w010,w025_flip,points\n";
  std::ofstream groups_csv(out_dir / "shrec_groups.csv");
  groups_csv << "class,source,target,group,pairwise_selected,most_consistent,consistent_selected,consistency,area_score,"
                "confidence_integral,convexity_mismatch,geodesic_distortion,selection_rank,w025,mean,flipped\n";
  std::ofstream choices_csv(out_dir / "shrec_choices.csv");
  choices_csv << "class,source,target," << choices_header;
  std::map<std::string, method_errors> total;
  std::ofstream summary(out_dir / "summary.md", std::ios::app);
  summary << "\n## SHREC'07, one intrinsic collection per class (run_fuzzy_benchmark --set shrec)\n\n"
          << "| class | shapes | pairs aligned | of | iterations | time (s) | pairwise w025 raw / flips (flipped) | "
             "consistent blended | best fuzzy | stored original raw |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const int cls : classes) {
    if (!by_class.count(cls)) {
      std::cerr << "class " << cls << " has no benchmark pairs\n";
      continue;
    }
    const auto t0 = clock_type::now();
    std::vector<fs::path> files;
    for (int id = 1; id <= 20; ++id) files.push_back(data / "watertight_shrec07/Meshes" / (std::to_string(20 * (cls - 1) + id) + ".off"));
    collection_records_options ro;
    ro.threads = threads;
    ro.record.metric = sample_metric::automatic;
    auto col = make_collection_records(files, ro);
    keep_intrinsic_shapes(col);  // the class's intrinsic collection: its closed genus-0 shapes
    const std::vector<shape_record>& records = col.records;
    const std::vector<fs::path>& kept = col.files;
    auto index_of = index_by_name(records);
    const double t_records = seconds_since(t0);
    for (const auto& s : col.skipped) std::cout << "  class " << cls << ": left out " << s.file.filename().string() << ": " << s.reason << "\n";
    intrinsic_aligner aligner(records, [&](index_t k) { return read_mesh(kept[std::size_t(k)]).mesh; },
                            knobs.intrinsic());
    fuzzy_collection_options fo;
    fo.threads = threads;
    fo.cache_folder = out_dir / "cache" / ("shrec_class" + std::to_string(cls) + knobs.intrinsic_cache_suffix());
    apply(fo);
    const auto t1 = clock_type::now();
    const auto r = compute_fuzzy_correspondences(records, aligner, fo);
    const double t_fuzzy = seconds_since(t1);
    std::cout << "class " << cls << ": " << records.size() << " shapes, records " << fmt(t_records, 1) << " s, fuzzy "
              << fmt(t_fuzzy, 1) << " s, pairs aligned " << r.pairs_aligned << " of "
              << records.size() * (records.size() - 1) / 2 << "\n";
    print_log(r, &records);
    std::map<std::string, method_errors> here;
    std::vector<double> stored;
    for (const auto& pr : by_class[cls]) {
      const std::string a = pr.source.global_id(), b = pr.target.global_id();
      if (!index_of.count(a) || !index_of.count(b)) {
        std::cout << "  pair " << a << " -> " << b << ": not in the collection (not genus 0), not scored\n";
        continue;
      }
      const index_t ia = index_of[a], ib = index_of[b];
      const auto B = read_mesh(kept[std::size_t(ib)]).mesh;
      const dijkstra_geodesics<double> geo(B.V, B.F);
      // Feature points of both shapes and the class symmetry (as run_bim_benchmark).
      const std::vector<index_t> fa = read_bim_feature_points(data, pr.source).vertices;
      const bim_feature_points target_points = read_bim_feature_points(data, pr.target);
      const std::vector<index_t>& fb = target_points.vertices;
      const std::vector<index_t>& perm = target_points.symmetry;
      const std::size_t n = std::min(fa.size(), fb.size());
      std::vector<index_t> truth, truth_sym;
      for (std::size_t k = 0; k < n; ++k) {
        truth.push_back(fb[k]);
        truth_sym.push_back(fb[std::size_t(perm[k])]);
      }
      auto errors = [&](const std::vector<index_t>& predicted_of_vertex) {
        std::vector<index_t> pred;
        for (std::size_t k = 0; k < n; ++k) pred.push_back(predicted_of_vertex[std::size_t(fa[k])]);
        return std::pair{benchmark_geodesic_errors<double>(B.V, B.F, geo, std::span<const index_t>(pred),
                                                           std::span<const index_t>(truth), threads),
                         benchmark_geodesic_errors<double>(B.V, B.F, geo, std::span<const index_t>(pred),
                                                           std::span<const index_t>(truth_sym), threads)};
      };
      auto score = [&](const std::string& method, const std::vector<index_t>& predicted_of_vertex) {
        const auto [e_raw, e_sym] = errors(predicted_of_vertex);
        here[method].add(e_raw, e_sym);
        total[method].add(e_raw, e_sym);
        csv << cls << "," << a << "," << b << "," << method << "," << fmt(mean_of(e_raw), 4) << ","
            << fmt(within(e_raw, 0.25), 3) << "," << fmt(std::min(mean_of(e_raw), mean_of(e_sym)), 4) << ","
            << (mean_of(e_sym) < mean_of(e_raw) ? 1 : 0) << "," << fmt(within(e_raw, 0.05), 3) << ","
            << fmt(within(e_raw, 0.10), 3) << "," << fmt(within(mean_of(e_sym) < mean_of(e_raw) ? e_sym : e_raw, 0.25), 3) << "," << e_raw.size() << "\n";
      };
      const blended_match_result<double> pairwise = aligner.match(ia, ib);
      consistent_blended_options oriented = knobs.consistent;
      oriented.orientation = r.orientation;
      oriented.threads = threads;
      const auto cb = make_consistent_blended_map(aligner, r.fuzzy, ia, ib, pairwise, oriented);
      score("pairwise", pairwise.map.nearest);
      score("consistent_blended", cb.map.nearest);
      write_choice(choices_csv, std::to_string(cls) + "," + a + "," + b + ",", cb);
      if (const auto unrefined = unrefined_choice(pairwise, cb, a, b)) score("consistent_unrefined", *unrefined);
      consistent_blended_options unrefined_options = knobs.consistent;
      unrefined_options.refine_choice = false;
      if (!r.orientation.empty())  // the same choice without the orientation, for the comparison
        score("consistent_unoriented",
              make_consistent_blended_map(aligner, r.fuzzy, ia, ib, pairwise, unrefined_options).map.nearest);
      std::optional<consistent_blended_map> blended_choice;  // the choice among the blended maps alone
      if (knobs.consistent.fuzzy_candidate || knobs.refined_duel) {
        consistent_blended_options blended_only = oriented;
        blended_only.refine_choice = false;
        blended_only.fuzzy_candidate = false;
        blended_choice = make_consistent_blended_map(aligner, r.fuzzy, ia, ib, pairwise, blended_only);
      }
      if (knobs.consistent.fuzzy_candidate) score("consistent_blended_only", blended_choice->map.nearest);
      score("best_fuzzy", best_fuzzy_vertex_map(r.fuzzy, records, ia, ib));
      if (knobs.refined_duel) {
        const consistent_blended_map& choice = *blended_choice;
        const surface_map<double> refined =
            zoomout_refiner{}.refine(*aligner.mesh(ia), *aligner.mesh(ib), choice.map, threads);
        const Eigen::MatrixXd F = r.fuzzy.block(ia, ib);
        const double refined_consistency = detail::consistency_score(aligner.score_map(ia, ib, refined), F);
        score("blended_only_refined", refined.nearest);
        const bool fuzzy_wins = cb.fuzzy_consistency > refined_consistency;
        std::cout << "  duel " << a << " -> " << b << ": refined blended choice " << fmt(refined_consistency, 4)
                  << ", refined fuzzy " << fmt(cb.fuzzy_consistency, 4) << "\n";
        score("consistent_refined", !fuzzy_wins       ? refined.nearest
                                    : cb.fuzzy_chosen ? cb.map.nearest
                                                      : refined_fuzzy_map(aligner, r.fuzzy, ia, ib, threads).nearest);
      }
      for (std::size_t k = 0; k < cb.groups.size(); ++k) {  // every candidate blended map, to study the selection
        const auto& g = pairwise.blended[std::size_t(cb.groups[k])];
        const auto [e_raw, e_sym] = errors(g.map.nearest);
        groups_csv << cls << "," << a << "," << b << "," << cb.groups[k] << "," << (cb.groups[k] == pairwise.selected)
                   << "," << (cb.groups[k] == cb.most_consistent_group) << "," << (cb.groups[k] == cb.group) << ","
                   << fmt(cb.consistency[k], 4) << "," << fmt(g.score, 4)
                   << "," << fmt(g.confidence_integral, 4) << "," << fmt(g.convexity_mismatch, 4) << ","
                   << fmt(g.geodesic_distortion, 4) << "," << g.selection_rank << "," << fmt(within(e_raw, 0.25), 3)
                   << "," << fmt(mean_of(e_raw), 4) << "," << (mean_of(e_sym) < mean_of(e_raw) ? 1 : 0) << "\n";
      }
      const fs::path st = data / "Results/Results_Corr_SHREC" / ("BenchResult_BlendedMap_" + a + "_to_" + b + ".txt");
      if (fs::exists(st)) {
        const auto blocks = read_bim_result(st.string());
        if (blocks.count("Stats")) {
          const auto& e = blocks.at("Stats").per_sample_errors;
          total["stored_original"].add(e, blocks.count("StatsWithFlip") ? blocks.at("StatsWithFlip").per_sample_errors : e);
          here["stored_original"].add(e, blocks.count("StatsWithFlip") ? blocks.at("StatsWithFlip").per_sample_errors : e);
        }
      }
    }
    auto cell = [&](const std::string& m) {
      const auto& e = here[m];
      return fmt(within(e.raw, 0.25)) + " / " + fmt(within(e.flip, 0.25)) + " (" + std::to_string(e.flipped_pairs) + ")";
    };
    summary << "| " << cls << " | " << records.size() << " | " << r.pairs_aligned << " | "
            << records.size() * (records.size() - 1) / 2 << " | " << r.log.size() - 1 << " | " << fmt(t_records + t_fuzzy, 0)
            << " | " << cell("pairwise") << " | " << cell("consistent_blended") << " | " << cell("best_fuzzy") << " | "
            << fmt(within(here["stored_original"].raw, 0.25)) << " |\n";
    summary.flush();
    std::cout << "  within 0.25 raw / flips (flipped pairs): pairwise " << cell("pairwise") << ", consistent blended "
              << cell("consistent_blended")
              << (r.orientation.empty() ? std::string() : " (without the orientation " + cell("consistent_unoriented") + ")")
              << (knobs.consistent.fuzzy_candidate ? " (among the blended maps only " + cell("consistent_blended_only") + ")" : std::string())
              << (knobs.consistent.refine_choice ? " (unrefined " + cell("consistent_unrefined") + ")"
                                                 : std::string())
              << ", best fuzzy " << cell("best_fuzzy") << ", stored original "
              << fmt(within(here["stored_original"].raw, 0.25)) << "\n";
  }
  summary << "\n| all classes | within 0.05 | within 0.10 | within 0.25 | mean | with flips: within 0.25 | mean | flipped pairs |\n"
             "|---|---|---|---|---|---|---|---|\n";
  for (const auto& [m, e] : total)
    summary << "| " << m << " | " << fmt(within(e.raw, 0.05)) << " | " << fmt(within(e.raw, 0.10)) << " | "
            << fmt(within(e.raw, 0.25)) << " | " << fmt(mean_of(e.raw), 4) << " | " << fmt(within(e.flip, 0.25)) << " | "
            << fmt(mean_of(e.flip), 4) << " | " << e.flipped_pairs << " of " << e.pairs << " |\n";
  write_curves(out_dir / "shrec_curves.dat",
               {{"pairwise", &total["pairwise"].raw},
                {"consistent_blended", &total["consistent_blended"].raw},
                {"best_fuzzy", &total["best_fuzzy"].raw},
                {"stored_original", &total["stored_original"].raw}},
               "SHREC'07, fraction of feature points within geodesic error D (/ sqrt(area)), raw");
  for (const auto& [m, e] : total)
    std::cout << m << ": within 0.25 raw " << fmt(within(e.raw, 0.25)) << ", flips " << fmt(within(e.flip, 0.25))
              << ", mean " << fmt(mean_of(e.raw), 4) << ", flipped pairs " << e.flipped_pairs << " of " << e.pairs << "\n";
  return 0;
}

/// An intrinsic collection made of `files` and its fuzzy correspondences (records and pairs cached under
/// out_dir/cache/<name>_records and <name>_pairs_sigma<width>).
struct intrinsic_run {
  collection_records col;  ///< the closed genus-0 shapes kept; the others in col.skipped
  std::map<std::string, index_t> index_of;
  double records_seconds = 0, fuzzy_seconds = 0;
  std::size_t pairs_aligned = 0;

  /// "N shapes, pairs aligned P of A (Z %), records X s, fuzzy Y s"
  [[nodiscard]] std::string counts() const {
    const std::size_t n = col.records.size(), all = n * (n - 1) / 2;
    return std::to_string(n) + " shapes, pairs aligned " + std::to_string(pairs_aligned) + " of " +
           std::to_string(all) + " (" + fmt(100.0 * double(pairs_aligned) / double(std::max<std::size_t>(all, 1)), 1) +
           " %), records " + fmt(records_seconds, 1) + " s, fuzzy " + fmt(fuzzy_seconds, 1) + " s";
  }
};

/// Makes the records of `files`, keeps the closed genus-0 shapes, aligns them with the intrinsic aligner and
/// computes the fuzzy correspondences, prints "<label>: <counts>" and the rounds; then calls
/// `evaluate(run, aligner, result)`.
template <class Evaluate>
void run_intrinsic_collection(const std::vector<fs::path>& files, const std::string& name, const std::string& label,
                              const fs::path& out_dir, int threads, Evaluate&& evaluate) {
  const auto t0 = clock_type::now();
  intrinsic_run run;
  collection_records_options ro;
  ro.threads = threads;
  ro.cache_folder = out_dir / "cache" / (name + "_records");
  run.col = make_collection_records(files, ro);
  keep_intrinsic_shapes(run.col);
  for (const auto& s : run.col.skipped) std::cout << "  left out " << s.file.filename().string() << ": " << s.reason << "\n";
  run.index_of = index_by_name(run.col.records);
  run.records_seconds = seconds_since(t0);
  const std::vector<fs::path>& kept = run.col.files;
  intrinsic_aligner aligner(run.col.records, [&](index_t k) { return read_mesh(kept[std::size_t(k)]).mesh; },
                            knobs.intrinsic());
  fuzzy_collection_options fo;
  fo.threads = threads;
  fo.cache_folder = out_dir / "cache" / (name + "_pairs" + knobs.intrinsic_cache_suffix());
  apply(fo);
  const auto t1 = clock_type::now();
  const auto r = compute_fuzzy_correspondences(run.col.records, aligner, fo);
  run.fuzzy_seconds = seconds_since(t1);
  run.pairs_aligned = r.pairs_aligned;
  std::cout << label << ": " << run.counts() << "\n";
  print_log(r, &run.col.records);
  evaluate(run, aligner, r);
}

/// Scores one benchmark pair of an intrinsic collection: the pairwise blended map, the consistent blended map and
/// the best fuzzy correspondence at the source vertices `points` against their true images on the target B (raw
/// and under the symmetry), and the stored original from `stored` when it exists; one csv line per method.
void score_list_pair(intrinsic_aligner& aligner, const fuzzy_collection_result& r,
                     const std::vector<shape_record>& records, index_t ia, index_t ib, const triangle_mesh<double>& B,
                     const dijkstra_geodesics<double>& geo_b, const std::vector<index_t>& points,
                     const std::vector<index_t>& truth, const std::vector<index_t>& truth_sym, const fs::path& stored,
                     int threads, std::map<std::string, method_errors>& total, std::ostream& csv,
                     std::ostream& choices) {
  const std::string& a = records[std::size_t(ia)].name;
  const std::string& b = records[std::size_t(ib)].name;
  auto score = [&](const std::string& method, const std::vector<index_t>& map_of_vertex) {
    std::vector<index_t> pred;
    for (const index_t v : points) pred.push_back(map_of_vertex[std::size_t(v)]);
    const auto e_raw = benchmark_geodesic_errors<double>(B.V, B.F, geo_b, std::span<const index_t>(pred),
                                                          std::span<const index_t>(truth), threads);
    const auto e_sym = benchmark_geodesic_errors<double>(B.V, B.F, geo_b, std::span<const index_t>(pred),
                                                          std::span<const index_t>(truth_sym), threads);
    total[method].add(e_raw, e_sym);
    csv << a << "," << b << "," << method << "," << fmt(mean_of(e_raw), 4) << "," << fmt(within(e_raw, 0.25), 3) << ","
        << fmt(std::min(mean_of(e_raw), mean_of(e_sym)), 4) << "," << (mean_of(e_sym) < mean_of(e_raw) ? 1 : 0) << ","
        << fmt(within(e_raw, 0.05), 3) << "," << fmt(within(e_raw, 0.10), 3) << "," << fmt(within(mean_of(e_sym) < mean_of(e_raw) ? e_sym : e_raw, 0.25), 3) << ","
        << e_raw.size() << "\n";
  };
  const blended_match_result<double> pairwise = aligner.match(ia, ib);
  consistent_blended_options oriented = knobs.consistent;
  oriented.orientation = r.orientation;
  oriented.threads = threads;
  const auto cb = make_consistent_blended_map(aligner, r.fuzzy, ia, ib, pairwise, oriented);
  score("pairwise", pairwise.map.nearest);
  score("consistent_blended", cb.map.nearest);
  write_choice(choices, a + "," + b + ",", cb);
  if (const auto unrefined = unrefined_choice(pairwise, cb, a, b)) score("consistent_unrefined", *unrefined);
  consistent_blended_options unrefined_options = knobs.consistent;
  unrefined_options.refine_choice = false;
  if (!r.orientation.empty())  // the same choice without the orientation, for the comparison
    score("consistent_unoriented",
          make_consistent_blended_map(aligner, r.fuzzy, ia, ib, pairwise, unrefined_options).map.nearest);
  if (knobs.consistent.fuzzy_candidate) {  // the choice among the blended maps alone, for the comparison
    consistent_blended_options blended_only = oriented;
    blended_only.refine_choice = false;
    blended_only.fuzzy_candidate = false;
    score("consistent_blended_only", make_consistent_blended_map(aligner, r.fuzzy, ia, ib, pairwise, blended_only).map.nearest);
  }
  score("best_fuzzy", best_fuzzy_vertex_map(r.fuzzy, records, ia, ib));
  if (fs::exists(stored)) {
    const auto blocks = read_bim_result(stored.string());
    if (blocks.count("Stats")) {
      const auto& e = blocks.at("Stats").per_sample_errors;
      total["stored_original"].add(e, blocks.count("StatsWithFlip") ? blocks.at("StatsWithFlip").per_sample_errors : e);
    }
  }
}

/// The summary table of every method (and one line each on stdout).
void write_method_table(std::ostream& summary, const std::map<std::string, method_errors>& total) {
  summary << "| method | within 0.05 | within 0.10 | within 0.25 | mean | with flips: within 0.25 | mean | flipped pairs |\n"
             "|---|---|---|---|---|---|---|---|\n";
  for (const auto& [m, e] : total) {
    summary << "| " << m << " | " << fmt(within(e.raw, 0.05)) << " | " << fmt(within(e.raw, 0.10)) << " | "
            << fmt(within(e.raw, 0.25)) << " | " << fmt(mean_of(e.raw), 4) << " | " << fmt(within(e.flip, 0.25)) << " | "
            << fmt(mean_of(e.flip), 4) << " | " << e.flipped_pairs << " of " << e.pairs << " |\n";
    std::cout << m << ": within 0.05 " << fmt(within(e.raw, 0.05)) << ", 0.25 raw " << fmt(within(e.raw, 0.25))
              << ", flips " << fmt(within(e.flip, 0.25)) << ", mean " << fmt(mean_of(e.raw), 4) << ", flipped pairs "
              << e.flipped_pairs << " of " << e.pairs << "\n";
  }
}

// ---------------------------------------------------------------------------------------------- SCAPE
int run_scape(const fs::path& data, const fs::path& out_dir, int threads) {
  const auto pairs = read_bim_query((data / "Results" / "Corr_Scape.query").string());
  std::set<std::string> names;
  for (const auto& p : pairs) names.insert(p.source.relative_path()), names.insert(p.target.relative_path());
  std::vector<fs::path> files;
  for (const auto& n : names) files.push_back(data / n);
  run_intrinsic_collection(files, "scape", "SCAPE", out_dir, threads, [&](const intrinsic_run& run,
                                                                        intrinsic_aligner& aligner,
                                                                        const fuzzy_collection_result& r) {
    const std::vector<shape_record>& records = run.col.records;
    const std::vector<fs::path>& kept = run.col.files;
    auto index_of = run.index_of;
    const auto feats = read_bim_feature_vertices((data / "SCAPE/Corrs/1.pid").string());
    const auto perm = read_bim_symmetry((data / "SCAPE/Corrs/1.sym.info").string(), static_cast<index_t>(feats.size()));
    std::map<std::string, method_errors> total;
    std::ofstream csv(out_dir / "scape_pairs.csv");
    csv << "source,target,method,mean,w025,mean_flip,flipped,w005,w010,w025_flip,points\n";
    std::ofstream choices(out_dir / "scape_choices.csv");
    choices << "source,target," << choices_header;
    const auto t2 = clock_type::now();
    for (const auto& pr : pairs) {
      const std::string a = pr.source.name(), b = pr.target.name();
      if (!index_of.count(a) || !index_of.count(b)) continue;
      const index_t ia = index_of[a], ib = index_of[b];
      const auto A = read_mesh(kept[std::size_t(ia)]).mesh;
      const auto B = read_mesh(kept[std::size_t(ib)]).mesh;
      if (A.V.rows() != B.V.rows()) continue;  // no dense truth
      const dijkstra_geodesics<double> geo_a(A.V, A.F), geo_b(B.V, B.F);
      const auto fps = geodesic_farthest_point_sampling(geo_a, std::min<index_t>(1024, A.V.rows()), 0);
      const std::vector<index_t>& truth = fps.indices;  // same vertex id = same point
      const auto truth_sym = symmetric_vertices(geo_b, std::span<const index_t>(feats), std::span<const index_t>(perm),
                                                std::span<const index_t>(truth), threads);
      score_list_pair(aligner, r, records, ia, ib, B, geo_b, truth, truth, truth_sym,
                      data / "Results/Results_Corr_Scape" / ("BenchResult_BlendedMap_" + a + "_to_" + b + ".txt"), threads,
                      total, csv, choices);
    }
    std::ofstream summary(out_dir / "summary.md", std::ios::app);
    summary << "\n## SCAPE, the benchmark's 71 meshes as one intrinsic collection (run_fuzzy_benchmark --set scape)\n\n"
            << run.counts() << ", evaluation " << fmt(seconds_since(t2), 1) << " s\n\n";
    write_method_table(summary, total);
  });
  return 0;
}

// ---------------------------------------------------------------------------------------------- cross-set lists
int run_cross(const std::string& set, const fs::path& data, const fs::path& out_dir, int threads) {
  const std::string query = set == "humans" ? "Corr_Humans.query" : "Corr_Animals.query";
  const std::string stored_dir = set == "humans" ? "Results_Corr_Humans" : "Results_Corr_Animals";
  const auto pairs = read_bim_query((data / "Results" / query).string());
  std::map<std::string, bim_mesh_ref> refs;  // by name, in name order
  for (const auto& p : pairs) refs.emplace(p.source.name(), p.source), refs.emplace(p.target.name(), p.target);
  // The lists' TOSCA meshes have small holes and some SHREC'07 meshes stray pieces: each mesh is repaired as
  // run_bim_benchmark repairs it (holes closed, the largest piece kept), written to the output folder, and the
  // collection is made of the repaired files. repaired_of[name][v]: the repaired vertex of input vertex v
  // (no_index when a repair dropped it).
  const fs::path mesh_dir = out_dir / "cache" / (set + "_repaired");
  fs::create_directories(mesh_dir);
  sphere_repair_options repairs;
  repairs.close_small_holes = repairs.keep_largest_component = true;
  std::map<std::string, std::vector<index_t>> repaired_of;
  // SCAPE's 1.pid holds the template's vertex ids: a SCAPE mesh with another vertex count has no feature points.
  const index_t scape_template_rows = read_mesh(data / "SCAPE/Meshes/mesh000.off").mesh.V.rows();
  std::set<std::string> off_template;
  std::vector<fs::path> files;
  std::size_t repaired_count = 0;
  for (const auto& [name, ref] : refs) {
    if (!fs::exists(data / ref.relative_path())) {  // the animals list names dog8 and dog10, not in the data
      std::cout << "  " << ref.relative_path() << ": not in the data folder, its pairs are not scored\n";
      continue;
    }
    const auto M = read_mesh(data / ref.relative_path()).mesh;
    repaired_sphere<double> fixed;
    try {
      fixed = repair_to_sphere<double>(M.V, M.F, repairs, "repair_to_sphere",
                                       blended_shape_options{}.flattening.accept_pinched_vertices);
    } catch (const invalid_input& e) {  // e.g. a SHREC'07 human with a handle: no intrinsic map, as for the matcher
      std::cout << "  left out " << ref.relative_path() << ": " << e.what() << "\n";
      continue;
    }
    if (fixed.report.any()) {
      ++repaired_count;
      std::cout << "  " << ref.relative_path() << ": " << fixed.report.to_string() << "\n";
    }
    const fs::path file = mesh_dir / (name + ".ply");
    write_mesh(file, fixed.mesh, mesh_write_options{.binary = true});  // always: it must agree with repaired_of
    auto& inverse = repaired_of[name];
    inverse.assign(static_cast<std::size_t>(M.V.rows()), no_index);
    for (std::size_t v = fixed.original_vertex.size(); v-- > 0;)  // a split vertex's first copy keeps the input's id
      if (fixed.original_vertex[v] != no_index) inverse[std::size_t(fixed.original_vertex[v])] = static_cast<index_t>(v);
    if (ref.dataset == "SCAPE" && M.V.rows() != scape_template_rows) off_template.insert(name);
    files.push_back(file);
  }
  std::cout << set << ": " << repaired_count << " of " << files.size() << " meshes repaired\n";
  run_intrinsic_collection(files, set, set, out_dir, threads, [&](const intrinsic_run& run, intrinsic_aligner& aligner,
                                                                 const fuzzy_collection_result& r) {
    const std::vector<shape_record>& records = run.col.records;
    const std::vector<fs::path>& kept = run.col.files;
    auto index_of = run.index_of;
    std::map<std::string, method_errors> total;
    std::ofstream csv(out_dir / (set + "_pairs.csv"));
    csv << "source,target,method,mean,w025,mean_flip,flipped,w005,w010,w025_flip,points\n";
    std::ofstream choices(out_dir / (set + "_choices.csv"));
    choices << "source,target," << choices_header;
    const auto t2 = clock_type::now();
    int not_scored = 0;
    for (const auto& pr : pairs) {
      const std::string a = pr.source.name(), b = pr.target.name();
      if (!index_of.count(a) || !index_of.count(b)) {
        std::cout << "  pair " << a << " -> " << b << ": a mesh is not in the collection, not scored\n";
        ++not_scored;
        continue;
      }
      // Feature points paired by name, as run_bim_benchmark scores the list, in the repaired meshes' numbering.
      const auto named = match_bim_features_by_name(read_bim_feature_points(data, pr.source, true),
                                                    read_bim_feature_points(data, pr.target, true));
      const auto& ra = repaired_of[a];
      const auto& rb = repaired_of[b];
      const auto repaired = [](const std::vector<index_t>& inverse, index_t v) {
        return v >= 0 && std::size_t(v) < inverse.size() ? inverse[std::size_t(v)] : no_index;
      };
      std::vector<index_t> src, truth, truth_sym;
      for (std::size_t k = 0; k < named.source.size(); ++k) {
        const index_t s = repaired(ra, named.source[k]), t = repaired(rb, named.target[k]),
                      ts = repaired(rb, named.target_symmetric[k]);
        if (s == no_index || t == no_index) continue;
        src.push_back(s), truth.push_back(t), truth_sym.push_back(ts == no_index ? t : ts);
      }
      if (src.empty() || off_template.count(a) || off_template.count(b)) {
        std::cout << "  pair " << a << " -> " << b << ": no feature points in common, not scored\n";
        ++not_scored;
        continue;
      }
      const index_t ia = index_of[a], ib = index_of[b];
      const auto B = read_mesh(kept[std::size_t(ib)]).mesh;
      const dijkstra_geodesics<double> geo_b(B.V, B.F);
      score_list_pair(aligner, r, records, ia, ib, B, geo_b, src, truth, truth_sym,
                      data / "Results" / stored_dir / ("BenchResult_BlendedMap_" + a + "_to_" + b + ".txt"), threads,
                      total, csv, choices);
    }
    std::ofstream summary(out_dir / "summary.md", std::ios::app);
    summary << "\n## The " << set << " cross-set list (" << query << ") as one intrinsic collection (run_fuzzy_benchmark --set "
            << set << ")\n\n"
            << run.counts() << ", evaluation " << fmt(seconds_since(t2), 1) << " s; " << not_scored << " of "
            << pairs.size() << " list pairs not scored\n\n";
    write_method_table(summary, total);
    write_curves(out_dir / (set + "_curves.dat"),
                 {{"pairwise", &total["pairwise"].raw},
                  {"consistent_blended", &total["consistent_blended"].raw},
                  {"best_fuzzy", &total["best_fuzzy"].raw},
                  {"stored_original", &total["stored_original"].raw}},
                 "The " + set + " cross-set list, fraction of feature points within geodesic error D (/ sqrt(area)), raw");
  });
  return 0;
}

// ---------------------------------------------------------------------------------------------- generated
/// The matcher alone: each source sample's best-scoring target sample under the pair's initial alternative.
std::vector<index_t> best_scoring_samples(const alignment_alternative& alternative) {
  const auto& scores = alternative.scores;
  std::vector<index_t> best(std::size_t(scores.rows()), 0);
  for (index_t i = 0; i < scores.rows(); ++i) {
    float top = -1;
    for (Eigen::SparseMatrix<float, Eigen::RowMajor, std::int32_t>::InnerIterator it(scores, i); it; ++it)
      if (it.value() > top) top = it.value(), best[std::size_t(i)] = it.col();
  }
  return best;
}

std::vector<index_t> best_scoring_samples(const pair_alignment& pa) {
  return best_scoring_samples(pa.alternatives[std::size_t(pa.initial)]);
}

/// Least-squares affine map of the target's true landmarks onto the source's, as the one alternative of a pair.
Eigen::Matrix<double, 3, 4> landmark_affine(const assembly<double>& source, const assembly<double>& target) {
  std::map<std::string, Eigen::Vector3d> ls, lt;
  for (const auto& f : source.features) ls[f.name] = f.position;
  for (const auto& f : target.features) lt[f.name] = f.position;
  std::vector<std::string> common;
  for (const auto& [name, x] : ls)
    if (lt.count(name)) common.push_back(name);
  Eigen::MatrixXd X(common.size(), 4), Y(common.size(), 3);
  for (std::size_t k = 0; k < common.size(); ++k) {
    X.row(Eigen::Index(k)) << lt.at(common[k]).transpose(), 1.0;
    Y.row(Eigen::Index(k)) = ls.at(common[k]).transpose();
  }
  return X.colPivHouseholderQr().solve(Y).transpose();  // 3 x 4: target -> source
}

struct true_landmark_aligner {
  const std::vector<assembly<double>>* shapes;
  const std::vector<shape_record>* records;
  pair_alignment align(index_t source, index_t target) const {
    pair_alignment out;
    out.source = source;
    out.target = target;
    out.alternatives.push_back(score_extrinsic_alignment((*records)[std::size_t(source)], (*records)[std::size_t(target)],
                                                         landmark_affine((*shapes)[std::size_t(source)],
                                                                         (*shapes)[std::size_t(target)]),
                                                         knobs.extrinsic));
    return out;
  }
};

int run_generated(const std::string& set, int count, const fs::path& out_dir, int threads, std::uint64_t seed) {
  const assembly_kind kind = set == "chairs" ? assembly_kind::chair : assembly_kind::airplane;
  const assembly_generator<double> gen(kind, seed);
  const auto t0 = clock_type::now();
  std::vector<assembly<double>> shapes(static_cast<std::size_t>(count));
  std::vector<shape_record> records(static_cast<std::size_t>(count));
  const spherical_harmonic_descriptor describe;
  detail::parallel_for(count, detail::resolve_threads(threads), [&](int i) {
    shapes[std::size_t(i)] = gen.generate(std::uint64_t(i));
    shape_record_options o;
    o.metric = sample_metric::euclidean;
    o.samples = knobs.samples;
    records[std::size_t(i)] = make_shape_record(shapes[std::size_t(i)].mesh, set + std::to_string(i), describe, o);
  });
  const double t_records = seconds_since(t0);
  fuzzy_collection_options fo;
  fo.threads = threads;
  fo.cache_folder = out_dir / "cache" / (set + std::to_string(count) + "_seed" + std::to_string(seed) + "_k" +
                                         std::to_string(knobs.samples) + (knobs.aligner == "truth" ? "_truth" : "") +
                                         "_sigma" + fmt(knobs.extrinsic.sigma_fraction) + up_suffix(knobs.extrinsic));
  apply(fo);
  const auto t1 = clock_type::now();
  const auto r = knobs.aligner == "truth"
                     ? compute_fuzzy_correspondences(records, true_landmark_aligner{&shapes, &records}, fo)
                     : compute_fuzzy_correspondences(
                           records, extrinsic_aligner(records, knobs.extrinsic), fo);
  const double t_fuzzy = seconds_since(t1);
  const std::size_t all_pairs = std::size_t(count) * std::size_t(count - 1) / 2;
  std::cout << set << " " << count << ": records " << fmt(t_records, 1) << " s, fuzzy " << fmt(t_fuzzy, 1)
            << " s, pairs aligned " << r.pairs_aligned << " of " << all_pairs << " ("
            << fmt(100.0 * double(r.pairs_aligned) / double(all_pairs), 1) << " %)\n";
  print_log(r);
  // Landmarks of every shape by name, with the sample nearest to each.
  auto landmarks = [&](int i) {
    std::map<std::string, Eigen::Vector3d> m;
    for (const auto& f : shapes[std::size_t(i)].features) m[f.name] = f.position;
    return m;
  };
  auto nearest_sample = [&](const shape_record& rec, const Eigen::Vector3d& x) {
    index_t best = 0;
    (rec.samples.rowwise() - x.transpose()).rowwise().squaredNorm().minCoeff(&best);
    return best;
  };
  std::vector<double> e_fuzzy, e_refined, e_pairwise, e_affine, e_pairwise_axes;
  const auto t2 = clock_type::now();
  std::vector<std::vector<double>> ef(static_cast<std::size_t>(count)), er(ef), ep(ef), ea(ef), epa(ef);
  detail::parallel_for(count, detail::resolve_threads(threads), [&](int a) {
    const auto la = landmarks(a);
    for (int b = 0; b < count; ++b) {
      if (a == b) continue;
      const auto lb = landmarks(b);
      const shape_record& ra = records[std::size_t(a)];
      const shape_record& rb = records[std::size_t(b)];
      const auto& Vb = shapes[std::size_t(b)].mesh.V;
      const double diag = (Vb.colwise().maxCoeff() - Vb.colwise().minCoeff()).norm();
      const auto fuzzy_match = r.fuzzy.best_matches(a, b);
      const auto refined = best_scoring_samples(refined_fuzzy_alignment(r.fuzzy, records, a, b, with_axis_scales(knobs.extrinsic, knobs.refine_axis_scales)));
      const std::vector<index_t> baseline = knobs.baseline ? best_scoring_samples(align_extrinsic(ra, rb, knobs.extrinsic)) : std::vector<index_t>{};
      const std::vector<index_t> baseline_axes = knobs.baseline && knobs.baseline_axis_scales
          ? best_scoring_samples(align_extrinsic(ra, rb, with_axis_scales(knobs.extrinsic, true))) : std::vector<index_t>{};
      // Least-squares affine map of b's true landmarks onto a's (both directions share the landmark names).
      std::vector<std::string> common;
      for (const auto& [name, x] : la)
        if (lb.count(name)) common.push_back(name);
      const Eigen::Matrix<double, 3, 4> T = landmark_affine(shapes[std::size_t(a)], shapes[std::size_t(b)]);  // b -> a
      const Eigen::MatrixXd Bt = (rb.samples * T.leftCols<3>().transpose()).rowwise() + T.col(3).transpose();
      for (const auto& name : common) {
        const index_t s = nearest_sample(ra, la.at(name));
        const Eigen::Vector3d truth = lb.at(name);
        ef[std::size_t(a)].push_back((rb.samples.row(fuzzy_match[std::size_t(s)]).transpose() - truth).norm() / diag);
        er[std::size_t(a)].push_back((rb.samples.row(refined[std::size_t(s)]).transpose() - truth).norm() / diag);
        if (knobs.baseline)
          ep[std::size_t(a)].push_back((rb.samples.row(baseline[std::size_t(s)]).transpose() - truth).norm() / diag);
        if (!baseline_axes.empty())
          epa[std::size_t(a)].push_back((rb.samples.row(baseline_axes[std::size_t(s)]).transpose() - truth).norm() / diag);
        index_t aff = 0;
        (Bt.rowwise() - ra.samples.row(s)).rowwise().squaredNorm().minCoeff(&aff);
        ea[std::size_t(a)].push_back((rb.samples.row(aff).transpose() - truth).norm() / diag);
      }
    }
  });
  for (int a = 0; a < count; ++a) {
    e_fuzzy.insert(e_fuzzy.end(), ef[std::size_t(a)].begin(), ef[std::size_t(a)].end());
    e_refined.insert(e_refined.end(), er[std::size_t(a)].begin(), er[std::size_t(a)].end());
    e_pairwise.insert(e_pairwise.end(), ep[std::size_t(a)].begin(), ep[std::size_t(a)].end());
    e_affine.insert(e_affine.end(), ea[std::size_t(a)].begin(), ea[std::size_t(a)].end());
    e_pairwise_axes.insert(e_pairwise_axes.end(), epa[std::size_t(a)].begin(), epa[std::size_t(a)].end());
  }
  const double t_eval = seconds_since(t2);
  std::vector<std::pair<std::string, const std::vector<double>*>> curves = {
      {"best_fuzzy", &e_fuzzy}, {"refined_fuzzy", &e_refined}, {"extrinsic_all_pairs", &e_pairwise}};
  if (!e_pairwise_axes.empty()) curves.emplace_back("extrinsic_axis_scales_all_pairs", &e_pairwise_axes);
  curves.emplace_back("true_landmark_affine", &e_affine);
  write_curves(out_dir / (set + std::to_string(count) + "_curves.dat"), curves,
               set + " x " + std::to_string(count) + ": fraction of landmark pairs within D (Euclidean / bbox diagonal)");
  std::ofstream summary(out_dir / "summary.md", std::ios::app);
  summary << "\n## " << count << " generated " << set << " (run_fuzzy_benchmark --set " << set << " --count " << count
          << "), extrinsic\n\n" << "pairs aligned " << r.pairs_aligned << " of " << all_pairs << ", records "
          << fmt(t_records, 1) << " s, fuzzy " << fmt(t_fuzzy, 1) << " s\n\n"
          << "| method | within 0.05 | within 0.10 | within 0.25 | mean |\n|---|---|---|---|---|\n";
  for (const auto& [m, e] : std::vector<std::pair<std::string, const std::vector<double>*>>{
           {"best fuzzy", &e_fuzzy}, {"refined fuzzy (ICP from it)", &e_refined},
           {"extrinsic matcher, all pairs", &e_pairwise},
           {"extrinsic matcher with axis scales, all pairs", &e_pairwise_axes},
           {"true-landmark affine, all pairs", &e_affine}})
    if (!e->empty())
    summary << "| " << m << " | " << fmt(within(*e, 0.05)) << " | " << fmt(within(*e, 0.10)) << " | "
            << fmt(within(*e, 0.25)) << " | " << fmt(mean_of(*e), 4) << " |\n";
  std::cout << "landmark pairs " << e_fuzzy.size() << " (evaluation " << fmt(t_eval, 1) << " s)\n"
            << "  within 0.05 / 0.10 / 0.25, mean: best fuzzy " << fmt(within(e_fuzzy, 0.05)) << " / "
            << fmt(within(e_fuzzy, 0.10)) << " / " << fmt(within(e_fuzzy, 0.25)) << ", " << fmt(mean_of(e_fuzzy), 4)
            << "\n  refined fuzzy " << fmt(within(e_refined, 0.05)) << " / " << fmt(within(e_refined, 0.10)) << " / "
            << fmt(within(e_refined, 0.25)) << ", " << fmt(mean_of(e_refined), 4)
            << "\n  extrinsic all pairs " << fmt(within(e_pairwise, 0.05)) << " / " << fmt(within(e_pairwise, 0.10)) << " / "
            << fmt(within(e_pairwise, 0.25)) << ", " << fmt(mean_of(e_pairwise), 4)
            << (e_pairwise_axes.empty() ? std::string()
                                        : "\n  extrinsic all pairs, axis scales " + fmt(within(e_pairwise_axes, 0.05)) + " / " +
                                              fmt(within(e_pairwise_axes, 0.10)) + " / " + fmt(within(e_pairwise_axes, 0.25)) +
                                              ", " + fmt(mean_of(e_pairwise_axes), 4))
            << "\n  true-landmark affine "
            << fmt(within(e_affine, 0.05)) << " / " << fmt(within(e_affine, 0.10)) << " / " << fmt(within(e_affine, 0.25))
            << ", " << fmt(mean_of(e_affine), 4) << "\n";
  return 0;
}

// ---------------------------------------------------------------------------------------------- label transfer
/// One shape of a labelled collection: its faces' labels, areas, nearest sample per face, and a label per sample.
struct labelled_shape {
  std::vector<index_t> truth;               ///< per face (COSEG: the class's labels; PSB: first human segmentation)
  std::vector<std::vector<index_t>> humans; ///< PSB: every human segmentation
  std::vector<double> area;                 ///< per face
  std::vector<index_t> face_sample;         ///< nearest sample to each face's centroid
  std::vector<index_t> sample_label;        ///< label of the face whose centroid is nearest each sample
};

labelled_shape label_shape(const fs::path& mesh_file, const std::vector<fs::path>& seg_files, const shape_record& rec) {
  const auto m = read_mesh(mesh_file).mesh;
  labelled_shape out;
  for (const auto& f : seg_files) out.humans.push_back(read_segmentation(f, m.F.rows()));
  out.truth = out.humans.front();
  const Eigen::VectorXd A = face_areas<double>(m.V, m.F, validation_level::trust);
  out.area.assign(A.data(), A.data() + A.size());
  Eigen::Matrix<double, Eigen::Dynamic, 3> C(m.F.rows(), 3);
  for (index_t f = 0; f < m.F.rows(); ++f) C.row(f) = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3.0;
  const knn_index<double, 3> samples(rec.samples), centroids(C);
  out.face_sample.resize(std::size_t(m.F.rows()));
  for (index_t f = 0; f < m.F.rows(); ++f) out.face_sample[std::size_t(f)] = samples.nearest(C.row(f)).index;
  out.sample_label.resize(std::size_t(rec.samples.rows()));
  for (index_t i = 0; i < rec.samples.rows(); ++i)
    out.sample_label[std::size_t(i)] = out.truth[std::size_t(centroids.nearest(rec.samples.row(i)).index)];
  return out;
}

/// The target's faces labelled through a sample map target sample -> source sample.
std::vector<index_t> transfer(const labelled_shape& source, const labelled_shape& target, const std::vector<index_t>& to_source) {
  std::vector<index_t> out(target.face_sample.size());
  for (std::size_t f = 0; f < out.size(); ++f)
    out[f] = source.sample_label[std::size_t(to_source[std::size_t(target.face_sample[f])])];
  return out;
}

/// Area fraction of faces whose label equals the truth, or the mean area-weighted Rand index over the humans.
double label_score(const labelled_shape& target, const std::vector<index_t>& labels, bool rand) {
  if (rand) {
    double s = 0;
    for (const auto& h : target.humans) s += rand_index(labels, h, target.area);
    return s / double(target.humans.size());
  }
  double right = 0, all = 0;
  for (std::size_t f = 0; f < labels.size(); ++f) {
    all += target.area[f];
    if (labels[f] == target.truth[f]) right += target.area[f];
  }
  return all > 0 ? right / all : 0;
}

int run_labels(const std::string& set, const fs::path& data, const fs::path& out_dir, const std::string& classes_arg,
               int threads) {
  struct collection_spec {
    std::string name;
    std::vector<fs::path> meshes;
    std::vector<std::vector<fs::path>> segs;  // per mesh
  };
  std::vector<collection_spec> specs;
  if (set == "coseg") {
    const fs::path dir = data / "coseg_subset/res/chairs";
    collection_spec c{"coseg_chairs17", {}, {}};
    for (const int id : {0, 1, 2, 4, 9, 12, 13, 14, 15, 16, 17, 18, 19, 20, 22, 23, 24}) {
      c.meshes.push_back(dir / "shapes" / (std::to_string(id) + ".off"));
      c.segs.push_back({dir / "gt" / (std::to_string(id) + ".seg")});
    }
    specs.push_back(std::move(c));
  } else {
    const std::map<std::string, int> first = {{"human", 1},  {"cup", 21},     {"glasses", 41}, {"airplane", 61},
                                              {"ant", 81},   {"chair", 101},  {"octopus", 121}, {"table", 141},
                                              {"teddy", 161}, {"hand", 181},  {"plier", 201},  {"fish", 221},
                                              {"bird", 241}, {"armadillo", 281}, {"bust", 301}, {"mech", 321},
                                              {"bearing", 341}, {"vase", 361}, {"fourleg", 381}};
    std::vector<std::string> names;
    std::stringstream ss(classes_arg.empty() ? "chair,table,airplane,cup,fourleg" : classes_arg);
    for (std::string item; std::getline(ss, item, ',');)
      if (!item.empty()) names.push_back(item);
    for (const auto& n : names) {
      if (!first.count(n)) throw std::runtime_error("unknown PSB class '" + n + "' (--classes)");
      collection_spec c{"psb_" + n, {}, {}};
      for (int id = first.at(n); id < first.at(n) + 20; ++id) {
        const std::string s = std::to_string(id);
        c.meshes.push_back(data / "psb/data/off" / (s + ".off"));
        std::vector<fs::path> segs;
        for (const auto& e : fs::directory_iterator(data / "psb/data/seg/Benchmark" / s))
          if (e.path().extension() == ".seg") segs.push_back(e.path());
        std::sort(segs.begin(), segs.end());
        c.segs.push_back(std::move(segs));
      }
      specs.push_back(std::move(c));
    }
  }
  const bool rand = set == "psb";
  std::ofstream summary(out_dir / "summary.md", std::ios::app);
  summary << "\n## Label transfer, " << set << " (run_fuzzy_benchmark --set " << set << "), extrinsic\n\n"
          << "Mean over ordered pairs of the " << (rand ? "area-weighted Rand index (higher is better)" : "labelled area fraction")
          << " of the target with the source's ground truth carried over.\n\n"
          << "| collection | shapes | pairs aligned | best fuzzy | refined fuzzy | extrinsic matcher, all pairs | fuzzy better on | fuzzy s |\n|---|---|---|---|---|---|---|---|\n";
  std::ofstream csv(out_dir / (set + "_labels.csv"));
  csv << "collection,source,target,best_fuzzy,refined_fuzzy,extrinsic_all_pairs\n";
  for (const auto& spec : specs) {
    const auto t0 = clock_type::now();
    collection_records_options ro;
    ro.threads = threads;
    ro.record.metric = sample_metric::euclidean;
    ro.record.samples = knobs.samples;
    const auto col = make_collection_records(spec.meshes, ro);
    for (const auto& sk : col.skipped) std::cout << "  " << spec.name << ": left out " << sk.file.string() << ": " << sk.reason << "\n";
    const auto& records = col.records;
    const index_t n = index_t(records.size());
    std::vector<labelled_shape> shapes(records.size());
    detail::parallel_for(n, detail::resolve_threads(threads), [&](index_t k) {
      const auto at = std::size_t(std::find(spec.meshes.begin(), spec.meshes.end(), col.files[std::size_t(k)]) - spec.meshes.begin());
      shapes[std::size_t(k)] = label_shape(spec.meshes[at], spec.segs[at], records[std::size_t(k)]);
    });
    const extrinsic_alignment_options eo = knobs.extrinsic;
    fuzzy_collection_options fo;
    fo.threads = threads;
    fo.cache_folder = out_dir / "cache" / (spec.name + "_sigma" + fmt(knobs.extrinsic.sigma_fraction) + up_suffix(eo));
    apply(fo);
    const auto t1 = clock_type::now();
    const auto r = compute_fuzzy_correspondences(records, extrinsic_aligner(records, eo), fo);
    const double t_fuzzy = seconds_since(t1);
    std::vector<std::vector<double>> sf(records.size()), sr(records.size()), sp(records.size()), spa(records.size());
    detail::parallel_for(n, detail::resolve_threads(threads), [&](index_t t) {
      for (index_t s = 0; s < n; ++s) {
        if (s == t) continue;
        const auto& T = shapes[std::size_t(t)];
        const auto& S = shapes[std::size_t(s)];
        sf[std::size_t(t)].push_back(label_score(T, transfer(S, T, r.fuzzy.best_matches(t, s)), rand));
        const auto refined = best_scoring_samples(refined_fuzzy_alignment(r.fuzzy, records, t, s, with_axis_scales(eo, knobs.refine_axis_scales)));
        sr[std::size_t(t)].push_back(label_score(T, transfer(S, T, refined), rand));
        // The matcher alone: target t aligned to source s, each target sample to its best-scoring source sample.
        const auto best = best_scoring_samples(align_extrinsic(records[std::size_t(t)], records[std::size_t(s)], eo));
        sp[std::size_t(t)].push_back(label_score(T, transfer(S, T, best), rand));
        if (knobs.baseline_axis_scales) {
          const auto stretched = best_scoring_samples(
              align_extrinsic(records[std::size_t(t)], records[std::size_t(s)], with_axis_scales(eo, true)));
          spa[std::size_t(t)].push_back(label_score(T, transfer(S, T, stretched), rand));
        }
      }
    });
    std::vector<double> f_all, r_all, p_all, pa_all;
    for (const auto& row : spa) pa_all.insert(pa_all.end(), row.begin(), row.end());
    int better = 0;
    for (index_t t = 0; t < n; ++t) {
      index_t j = 0;
      for (index_t s = 0; s < n; ++s) {
        if (s == t) continue;
        const double a = sf[std::size_t(t)][std::size_t(j)], b = sp[std::size_t(t)][std::size_t(j)];
        const double c = sr[std::size_t(t)][std::size_t(j)];
        csv << spec.name << "," << records[std::size_t(s)].name << "," << records[std::size_t(t)].name << "," << fmt(a, 4)
            << "," << fmt(c, 4) << "," << fmt(b, 4) << "\n";
        f_all.push_back(a), r_all.push_back(c), p_all.push_back(b);
        better += a > b ? 1 : 0;
        ++j;
      }
    }
    const std::size_t all_pairs = std::size_t(n) * std::size_t(n - 1) / 2;
    summary << "| " << spec.name << " | " << n << " | " << r.pairs_aligned << " of " << all_pairs << " | "
            << fmt(mean_of(f_all)) << " | " << fmt(mean_of(r_all)) << " | " << fmt(mean_of(p_all)) << " | " << better << " of " << f_all.size() << " | "
            << fmt(t_fuzzy, 1) << " |\n";
    std::cout << spec.name << ": " << n << " shapes (records " << fmt(seconds_since(t0) - t_fuzzy, 1) << " s), fuzzy "
              << fmt(t_fuzzy, 1) << " s, pairs aligned " << r.pairs_aligned << " of " << all_pairs << ", rounds "
              << r.log.size() << "\n  " << (rand ? "Rand index" : "labelled area") << ": best fuzzy " << fmt(mean_of(f_all))
              << ", refined fuzzy " << fmt(mean_of(r_all)) << ", extrinsic matcher all pairs " << fmt(mean_of(p_all))
              << (pa_all.empty() ? std::string() : ", with axis scales " + fmt(mean_of(pa_all))) << " (fuzzy better on " << better << " of "
              << f_all.size() << " ordered pairs)\n";
  }
  return 0;
}

}  // namespace

static int run(int argc, char** argv) {
  std::string data_dir = std::getenv("SHAPESTRUCT_DATA") ? std::getenv("SHAPESTRUCT_DATA") : "";
  std::string set, out = "fuzzy_results", classes;
  int threads = 0, count = 111;
  std::uint64_t seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--data") data_dir = next();
    else if (a == "--set") set = next();
    else if (a == "--out") out = next();
    else if (a == "--classes") classes = next();
    else if (a == "--threads") threads = std::stoi(next());
    else if (a == "--count") count = std::stoi(next());
    else if (a == "--seed") seed = std::stoull(next());
    else if (a == "--time") knobs.time = std::stod(next());
    else if (a == "--dims") knobs.dims = std::stoi(next());
    else if (a == "--iterations") knobs.iterations = std::stoi(next());
    else if (a == "--samples") knobs.samples = std::stoi(next());
    else if (a == "--edges-per-shape") knobs.edges_per_shape = std::stoi(next());
    else if (a == "--no-baseline") knobs.baseline = false;
    else if (a == "--weak-support") knobs.weak_support = std::stod(next());
    else if (a == "--orientation-margin") knobs.orientation_margin = std::stod(next());
    else if (a == "--aligner") knobs.aligner = next();
    else if (a == "--sigma") knobs.extrinsic.sigma_fraction = std::stod(next());
    else if (a == "--up") knobs.extrinsic.up_axis = std::stoi(next());
    else if (a == "--no-refine-axis-scales") knobs.refine_axis_scales = false;
    else if (a == "--axis-scales") knobs.extrinsic.axis_scales = true;
    else if (a == "--baseline-axis-scales") knobs.baseline_axis_scales = true;
    else if (a == "--intrinsic-sigma") knobs.intrinsic_sigma = std::stod(next());
    else if (a == "--both-feature-sets") knobs.both_feature_sets = true;
    else if (a == "--min-gain") knobs.consistent.min_consistency_gain = std::stod(next());
    else if (a == "--fuzzy-min-gain") knobs.consistent.fuzzy_min_gain = std::stod(next());
    else if (a == "--max-fuzzy-distortion") knobs.consistent.max_fuzzy_distortion_ratio = std::stod(next());
    else if (a == "--fuzzy-min-distance") knobs.consistent.fuzzy_min_distance = std::stod(next());
    else if (a == "--refined-duel") knobs.refined_duel = true;
    else if (a == "--no-refine-choice") knobs.consistent.refine_choice = false;
    else if (a == "--no-fuzzy-candidate") knobs.consistent.fuzzy_candidate = false;
    else {
      std::cerr << "usage: run_fuzzy_benchmark --set shrec|scape|humans|animals|chairs|airplanes|coseg|psb --out DIR [--data DIR] [--classes 1,4] "
                   "[--count N] [--seed S] [--threads T]\n"
                   "  [--time t] [--dims d] [--iterations I] [--samples K] [--edges-per-shape M] [--no-baseline] [--weak-support F]\n"
                   "  [--orientation-margin F]\n"
                   "  [--aligner extrinsic|truth] [--sigma F] [--up 0|1|2|-1] [--intrinsic-sigma F] [--both-feature-sets] [--min-gain F] [--fuzzy-min-gain F]\n"
                   "  [--max-fuzzy-distortion R] [--fuzzy-min-distance D] [--no-fuzzy-candidate] [--refined-duel]\n"
                   "  [--no-refine-choice]\n"
                   "  [--no-refine-axis-scales] [--baseline-axis-scales] [--axis-scales]\n";
      return 2;
    }
  }
  fs::create_directories(out);
  if (knobs.aligner != "extrinsic" && !(knobs.aligner == "truth" && (set == "chairs" || set == "airplanes"))) {
    std::cerr << "--aligner must be extrinsic, or truth with --set chairs|airplanes (the only sets with true "
                 "landmarks on every shape)\n";
    return 2;
  }
  if (set == "shrec") {
    if (data_dir.empty()) {
      std::cerr << "--set shrec needs --data DIR or $SHAPESTRUCT_DATA\n";
      return 2;
    }
    return run_shrec(data_dir, out, classes, threads);
  }
  if (set == "scape") {
    if (data_dir.empty()) {
      std::cerr << "--set scape needs --data DIR or $SHAPESTRUCT_DATA\n";
      return 2;
    }
    return run_scape(data_dir, out, threads);
  }
  if (set == "humans" || set == "animals") {
    if (data_dir.empty()) {
      std::cerr << "--set " << set << " needs --data DIR or $SHAPESTRUCT_DATA\n";
      return 2;
    }
    return run_cross(set, data_dir, out, threads);
  }
  if (set == "chairs" || set == "airplanes") return run_generated(set, count, out, threads, seed);
  if (set == "coseg" || set == "psb") {
    if (data_dir.empty()) {
      std::cerr << "--set " << set << " needs --data DIR or $SHAPESTRUCT_DATA\n";
      return 2;
    }
    return run_labels(set, data_dir, out, classes, threads);
  }
  std::cerr << "--set must be shrec, scape, humans, animals, chairs, airplanes, coseg or psb\n";
  return 2;
}

int main(int argc, char** argv) {
  return shapestruct::bench::run_reporting_errors("run_fuzzy_benchmark", [&] { return run(argc, argv); });
}
