// SPDX-License-Identifier: MIT
// run_bim_benchmark: blended intrinsic maps on the exact pairs of the BIM benchmark's .query lists, scored with
// the benchmark's protocol, side by side with the original authors' stored per-pair results.
//
//   run_bim_benchmark --data $SHAPESTRUCT_DATA --set scape --out results/ [--limit N] [--stride K] [--threads T]
//                     [--reverse]
//
// Error = geodesic distance (Dijkstra, on the target) / sqrt(area of the target): the benchmark's scale and that
// of the stored results (see the data README; eval/geodesic_error.hpp, benchmark_geodesic_errors). Dense sets
// (SCAPE, TOSCA) are scored at 1,024 geodesic farthest-point samples of the source (the ground truth is the same
// vertex id); SHREC'07 at the class's .vts feature points.
// "With flips" takes, per pair, the better of the truth and the truth composed with the class's intrinsic
// symmetry (.sym.info; for dense sets the symmetry is made dense from the feature points by geodesic
// descriptors, see eval/geodesic_error.hpp). The cross-set lists (humans: SCAPE/TOSCA/SHREC'07 humans; animals:
// TOSCA/SHREC'07 four-legged animals) have no dense truth: they are scored, as the stored results are (36 resp. 21
// errors per pair), at the source's feature points, whose true image is the target's feature point of the same
// name (.info / c<k>.info, matched by name, not by line), and "with flips" uses the target class's .sym.info.
// --reverse matches every pair the other way round (target -> source; no stored result is compared then), to see
// whether a pair that one direction gets wrong the other gets right; --one-direction turns off the matcher's
// blended_matcher_options::both_directions (on by default; with --groups, each group's reverse partner is written
// too).
// Writes <set>_pairs.csv, <set>_errors.tsv (per-sample errors of
// both methods, for curves), and appends to summary.md.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/detail/side_by_side.hpp"
#include "shapestruct/eval/error_curve.hpp"
#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/io/bim_benchmark_files.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "runner_errors.hpp"

namespace fs = std::filesystem;
using namespace shapestruct;

namespace {

struct set_info {
  std::string query, results;
  bool dense;
  bool cross = false;  ///< pairs across data sets: features matched by name
};

const std::map<std::string, set_info> sets = {
    {"scape", {"Corr_Scape.query", "Results_Corr_Scape", true}},
    {"tosca", {"Corr_NRW.query", "Results_Corr_TOSCA", true}},
    {"shrec", {"Corr_SHREC.query", "Results_Corr_SHREC", false}},
    {"humans", {"Corr_Humans.query", "Results_Corr_Humans", false, true}},
    {"animals", {"Corr_Animals.query", "Results_Corr_Animals", false, true}},
};

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string fmt(double x, int prec = 4) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", prec, x);
  return b;
}

}  // namespace

static int run(int argc, char** argv) {
  std::string data_dir = std::getenv("SHAPESTRUCT_DATA") ? std::getenv("SHAPESTRUCT_DATA") : "";
  std::string set = "scape", out_dir = "bim_results";
  int limit = -1, stride = 1, offset = 0, threads = 0;
  bool diagnose_groups = false;
  double eigenvalue_fraction = -1, feature_radius = -1;
  int min_features = -1;
  double feature_persistence = -1, alternative_persistence = -1, alternative_margin = -1;
  std::string selection;  // empty: the library default (blended_matcher_options::selection)
  int max_eigenvectors = -1, max_groups = -1;
  bool refine = true, check_refinement = true, reverse = false,
       both_directions = blended_matcher_options{}.both_directions;
  double refinement_move_check = -1;
  zoomout_options zoomout;
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
    else if (a == "--out") out_dir = next();
    else if (a == "--limit") limit = std::stoi(next());
    else if (a == "--stride") stride = std::max(1, std::stoi(next()));
    else if (a == "--offset") offset = std::stoi(next());
    else if (a == "--threads") threads = std::stoi(next());
    else if (a == "--groups") diagnose_groups = true;
    else if (a == "--reverse") reverse = true;
    else if (a == "--both-directions") both_directions = true;
    else if (a == "--one-direction") both_directions = false;
    else if (a == "--eigenvalue-fraction") eigenvalue_fraction = std::stod(next());
    else if (a == "--feature-radius") feature_radius = std::stod(next());
    else if (a == "--min-features") min_features = std::stoi(next());
    else if (a == "--feature-persistence") feature_persistence = std::stod(next());
    else if (a == "--alternative-persistence") alternative_persistence = std::stod(next());
    else if (a == "--alternative-margin") alternative_margin = std::stod(next());
    else if (a == "--selection") selection = next();
    else if (a == "--max-eigenvectors") max_eigenvectors = std::stoi(next());
    else if (a == "--max-groups") max_groups = std::stoi(next());
    else if (a == "--no-refine") refine = false;
    else if (a == "--refinement-move-check") refinement_move_check = std::stod(next());
    else if (a == "--zoomout-sizes") {  // k0,kmax,step
      const std::string v = next();
      if (std::sscanf(v.c_str(), "%td,%td,%td", &zoomout.initial_size, &zoomout.final_size, &zoomout.step) != 3) {
        std::cerr << "--zoomout-sizes needs k0,kmax,step\n";
        return 2;
      }
    } else if (a == "--zoomout-samples") zoomout.samples = std::stoi(next());
    else if (a == "--zoomout-exact") zoomout.dense_search = zoomout_dense_search::exact;
    else if (a == "--zoomout-radius") zoomout.local_radius = std::stod(next());
    else if (a == "--zoomout-basis") {  // lanczos | galerkin[,coarse functions[,refinement steps]]
      const std::string v = next();
      zoomout.basis.solver = v.rfind("lanczos", 0) == 0 ? laplace_beltrami_solver::lanczos : laplace_beltrami_solver::galerkin;
      if (v.rfind("lanczos", 0) != 0 && v.rfind("galerkin", 0) != 0) {
        std::cerr << "--zoomout-basis needs lanczos or galerkin[,M[,S]]\n";
        return 2;
      }
      std::sscanf(v.c_str(), "galerkin,%td,%td", &zoomout.basis.coarse_functions, &zoomout.basis.subspace_iterations);
    }
    else if (a == "--no-refinement-check") check_refinement = false;
    else {
      std::cerr << "usage: run_bim_benchmark --data DIR --set scape|tosca|shrec|humans|animals --out DIR [--limit N] [--stride K] "
                   "[--offset O] [--threads T] [--groups] [--reverse] [--both-directions|--one-direction]\n"
                   "  [--eigenvalue-fraction F] [--max-eigenvectors K] [--max-groups G] [--feature-radius R] [--min-features N]\n"
                   "  [--feature-persistence P] [--alternative-persistence P] (0: one feature set) [--alternative-margin M]\n"
                   "  [--selection adaptive|confidence-distortion|confidence|area|area-confidence] (as `shapestruct match`; default: the library's)\n"
                   "  [--no-refine] [--no-refinement-check] [--refinement-move-check D] (0: off)\n"
                   "  [--zoomout-sizes k0,kmax,step] [--zoomout-samples N] [--zoomout-exact] [--zoomout-radius R]\n"
                   "  [--zoomout-basis lanczos|galerkin[,M[,S]]] (default galerkin,600,1)\n";
      return 2;
    }
  }
  if (data_dir.empty() || !sets.count(set)) {
    std::cerr << "need --data (or $SHAPESTRUCT_DATA) and --set scape|tosca|shrec|humans|animals\n";
    return 2;
  }
  blended_matcher_options options;
  options.threads = threads;
  // The benchmark's TOSCA meshes have small holes and SHREC'07 some stray pieces: the runner turns the repairs on
  // (the library leaves them off by default).
  options.shape.repairs.close_small_holes = true;
  options.shape.repairs.keep_largest_component = true;
  // --groups: build every blended map in full and score each one against the truth (<set>_groups.csv), to see
  // whether the selection picked the best group and what each group's measures were.
  options.full_maps_for_all_groups = diagnose_groups;
  options.both_directions = both_directions;
  if (eigenvalue_fraction >= 0) options.eigenvalue_fraction = eigenvalue_fraction;
  if (feature_radius > 0) options.shape.feature_radius = feature_radius;
  if (min_features >= 0) options.shape.min_features = min_features;
  if (feature_persistence >= 0) options.shape.min_feature_persistence = feature_persistence;
  if (alternative_persistence >= 0) options.shape.alternative_feature_persistence = alternative_persistence;
  if (alternative_margin >= 0) options.alternative_distortion_margin = alternative_margin;
  if (selection == "area") options.selection = blended_selection::area_score;
  else if (selection == "confidence") options.selection = blended_selection::integrated_confidence;
  else if (selection == "area-confidence") options.selection = blended_selection::area_and_confidence_rank;
  else if (selection == "confidence-distortion") options.selection = blended_selection::confidence_and_distortion_rank;
  else if (selection == "adaptive") options.selection = blended_selection::distortion_adaptive;
  else if (!selection.empty()) {
    std::cerr << "--selection must be adaptive, confidence-distortion, confidence, area or area-confidence\n";
    return 2;
  }
  const fs::path data(data_dir);
  const set_info info = sets.at(set);
  fs::create_directories(out_dir);
  auto pairs = read_bim_query((data / "Results" / info.query).string());
  if (reverse)
    for (auto& pr : pairs) std::swap(pr.source, pr.target);
  if (max_eigenvectors > 0) options.max_eigenvectors = max_eigenvectors;
  if (max_groups > 0) options.max_groups = max_groups;
  options.refine = refine;
  if (!check_refinement) options.max_refined_distortion_ratio = 0;
  if (refinement_move_check >= 0) options.refinement_move_check = refinement_move_check;
  const blended_matcher<triplet_candidates, area_confidence, geodesic_consistency, zoomout_refiner> matcher(
      options, {}, {}, {}, zoomout_refiner(zoomout));
  std::ofstream groups_csv;
  if (diagnose_groups) {
    groups_csv.open(fs::path(out_dir) / (set + "_groups.csv"));
    groups_csv << "source,target,group,maps,eigen_weight,score,confidence_integral,geodesic_distortion,convexity_mismatch,"
                  "mean,mean_sym,w025,w025_sym,points,selection_rank,selected,forward_selected,reverse_partner,"
                  "reverse_cycle_error,partner_rank,partner_confidence,partner_distortion,reverse_selected,"
                  "cycle_errors,reverse_ranks,reverse_confidences,reverse_distortions\n";
  }

  std::ofstream csv(fs::path(out_dir) / (set + "_pairs.csv"));
  csv << "source,target,src_vertices,tgt_vertices,src_features,tgt_features,candidates,groups,time_total,time_prep,"
         "time_confidence,time_consistency,time_blending,time_refinement,mean,w005,w010,w025,mean_flip,w025_flip,flipped,"
         "blended_mean,blended_w005,blended_w025,blended_distortion,refined_distortion,refinement_accepted,"
         "alternative_features,other_features_distortion,zoomout_mean,zoomout_w005,zoomout_w025,"
         "stored_mean,stored_w025,stored_mean_flip,stored_w025_flip,stored_time,moves_undone,status\n";
  std::ofstream errs(fs::path(out_dir) / (set + "_errors.tsv"));
  errs << "# method\tkind\terror\n";
  std::vector<double> all_raw, all_flip, st_raw, st_flip, times;
  std::vector<std::pair<double, std::string>> slow;
  int done = 0, failed = 0;
  std::map<std::string, triangle_mesh<double>> mesh_cache;
  auto load = [&](const bim_mesh_ref& m) -> triangle_mesh<double> {
    const std::string p = (data / m.relative_path()).string();
    auto it = mesh_cache.find(p);
    if (it == mesh_cache.end()) {
      if (mesh_cache.size() > 8) mesh_cache.clear();
      it = mesh_cache.emplace(p, read_mesh(fs::path(p)).mesh).first;
    }
    return it->second;
  };
  for (int pi = offset; pi < static_cast<int>(pairs.size()); pi += stride) {
    if (limit >= 0 && done + failed >= limit) break;
    const auto& pr = pairs[static_cast<std::size_t>(pi)];
    const std::string name = pr.source.name() + "_to_" + pr.target.name();
    std::string status = "ok";
    try {
      const auto A = load(pr.source);
      const auto B = load(pr.target);
      if (info.dense && A.V.rows() != B.V.rows())
        throw std::runtime_error("no dense ground truth: the meshes are not template-aligned (" +
                                 std::to_string(A.V.rows()) + " and " + std::to_string(B.V.rows()) + " vertices)");
      const auto t0 = std::chrono::steady_clock::now();
      // Name the mesh a precondition failure is about (the library's message names the element only).
      auto prepare = [&](const triangle_mesh<double>& M, const bim_mesh_ref& ref) {
        try {
          return matcher.prepare(M);
        } catch (const invalid_input& e) {
          throw std::runtime_error(ref.relative_path() + ": " + e.what());
        }
      };
      // Side by side, as `shapestruct match` and blended_matcher::match(a, b) prepare them; the source's error first.
      const auto shapes = detail::side_by_side(detail::resolve_threads(threads, "run_bim_benchmark") > 1,
                                               [&] { return prepare(A, pr.source); },
                                               [&] { return prepare(B, pr.target); });
      const auto& sa = shapes.first;
      const auto& sb = shapes.second;
      const double t_prep = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const auto r = matcher.match(sa, sb);
      const double t_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      double t_conf = 0, t_cons = 0, t_blend = 0, t_refine = 0;
      for (const auto& [stage, s] : r.timings) {  // with both feature sets, both runs' stages
        if (stage.starts_with("confidence")) t_conf += s;
        if (stage.starts_with("consistency")) t_cons += s;
        if (stage.starts_with("blending")) t_blend += s;
        if (stage.starts_with("refinement")) t_refine += s;
      }
      // Evaluation points (input numbering) and their true images (target input numbering).
      std::vector<index_t> src_pts, truth, truth_sym;
      if (info.dense) {
        const auto fps = geodesic_farthest_point_sampling(sa.geodesics(), std::min<index_t>(1024, sa.mesh().V.rows()), 0);
        for (index_t v : fps.indices) {
          const index_t orig = sa.original_vertex(v);
          if (orig == no_index || orig >= B.V.rows()) continue;
          src_pts.push_back(orig);
          truth.push_back(orig);
        }
        const auto fb = read_bim_feature_points(data, pr.target);
        std::vector<index_t> feat_internal, truth_internal;
        for (index_t f : fb.vertices) feat_internal.push_back(sb.internal_vertex(f));
        for (index_t t : truth) truth_internal.push_back(sb.internal_vertex(t));
        const auto sym_internal = symmetric_vertices(sb.geodesics(), std::span<const index_t>(feat_internal),
                                                     std::span<const index_t>(fb.symmetry),
                                                     std::span<const index_t>(truth_internal), threads);
        for (index_t s : sym_internal) truth_sym.push_back(sb.original_vertex(s));
      } else if (info.cross) {
        // Across data sets the feature lists are matched by name: source point k -> the target point of the same
        // name; the symmetric truth is that target point's partner under the target class's symmetry.
        const auto fa = read_bim_feature_points(data, pr.source, true);
        const auto fb = read_bim_feature_points(data, pr.target, true);
        // SCAPE's single 1.pid holds template vertex ids: it does not apply to the meshes that are not
        // template-aligned (mesh051, mesh071, mesh073 have other vertex counts), and no feature id may be out of range.
        const auto check = [&](const bim_mesh_ref& m, const triangle_mesh<double>& M, const bim_feature_points& f) {
          if (m.dataset == "SCAPE") {
            const index_t template_rows = load(bim_mesh_ref{"SCAPE", m.cls, "0"}).V.rows();
            if (M.V.rows() != template_rows)
              throw std::runtime_error("no feature points: " + m.name() + " is not aligned with the SCAPE template (" +
                                       std::to_string(M.V.rows()) + " vs " + std::to_string(template_rows) +
                                       " vertices)");
          }
          for (index_t v : f.vertices)
            if (v >= M.V.rows())
              throw std::runtime_error("feature vertex " + std::to_string(v) + " out of range for " + m.name());
        };
        check(pr.source, A, fa);
        check(pr.target, B, fb);
        const auto named = match_bim_features_by_name(fa, fb);
        src_pts = named.source, truth = named.target, truth_sym = named.target_symmetric;
        if (src_pts.empty()) throw std::runtime_error("no feature point names in common");
      } else {
        const auto fa = read_bim_feature_points(data, pr.source);
        const auto fb = read_bim_feature_points(data, pr.target);
        const std::size_t n = std::min(fa.vertices.size(), fb.vertices.size());
        for (std::size_t k = 0; k < n; ++k) {
          src_pts.push_back(fa.vertices[k]);
          truth.push_back(fb.vertices[k]);
          truth_sym.push_back(fb.vertices[static_cast<std::size_t>(fb.symmetry[k])]);
        }
      }
      // Scores on the prepared (unit-area) target, d / sqrt(area), the area taken from the mesh itself.
      const auto score = [&](const std::vector<index_t>& predicted, const std::vector<index_t>& true_images) {
        return benchmark_geodesic_errors(sb.mesh().V, sb.mesh().F, sb.geodesics(), std::span<const index_t>(predicted),
                                         std::span<const index_t>(true_images), threads);
      };
      std::vector<index_t> pred_i, truth_i, sym_i;
      for (std::size_t k = 0; k < src_pts.size(); ++k) {
        const index_t p = r.map.target_vertex(src_pts[k]);
        pred_i.push_back(p == no_index ? no_index : sb.internal_vertex(p));
        truth_i.push_back(sb.internal_vertex(truth[k]));
        sym_i.push_back(truth_sym[k] == no_index ? truth_i.back() : sb.internal_vertex(truth_sym[k]));
      }
      const auto e_raw = score(pred_i, truth_i);
      const auto e_sym = score(pred_i, sym_i);
      // The blended map before refinement (the selected group's), for the refinement's gain per pair.
      std::vector<index_t> blended_i;
      const auto& unrefined = r.blended[static_cast<std::size_t>(r.selected)].map;
      for (index_t sp : src_pts) {
        const index_t p = unrefined.target_vertex(sp);
        blended_i.push_back(p == no_index ? no_index : sb.internal_vertex(p));
      }
      const auto s_blended = summarize_errors(std::span<const double>(score(blended_i, truth_i)));
      // The refiner's own map, whether or not the matcher kept it.
      std::vector<index_t> zoomout_i;
      for (index_t sp : src_pts) {
        const index_t p = r.refined_map.points.empty() ? no_index : r.refined_map.target_vertex(sp);
        zoomout_i.push_back(p == no_index ? no_index : sb.internal_vertex(p));
      }
      const auto s_zoomout = summarize_errors(std::span<const double>(score(zoomout_i, truth_i)));
      if (diagnose_groups) {
        for (std::size_t g = 0; g < r.blended.size(); ++g) {
          const auto& bc = r.blended[g];
          std::vector<index_t> gi;
          for (index_t sp : src_pts) {
            const index_t p = bc.map.nearest.empty() ? no_index : bc.map.nearest[static_cast<std::size_t>(sp)];
            gi.push_back(p == no_index ? no_index : sb.internal_vertex(p));
          }
          const auto g_raw = summarize_errors(std::span<const double>(score(gi, truth_i)));
          const auto g_sym = summarize_errors(std::span<const double>(score(gi, sym_i)));
          groups_csv << pr.source.name() << "," << pr.target.name() << "," << g << "," << bc.maps.size() << ","
                     << fmt(bc.eigen_weight) << "," << fmt(bc.score) << "," << fmt(bc.confidence_integral) << ","
                     << fmt(bc.geodesic_distortion) << "," << fmt(bc.convexity_mismatch) << "," << fmt(g_raw.mean) << "," << fmt(g_sym.mean) << ","
                     << fmt(g_raw.within_025) << "," << fmt(g_sym.within_025) << "," << gi.size() << "," << bc.selection_rank << ","
                     << (static_cast<index_t>(g) == r.selected ? 1 : 0) << ","
                     << (static_cast<index_t>(g) == r.forward_selected ? 1 : 0) << ",";
          if (bc.reverse_partner != no_index) {
            const auto& h = r.reverse_blended[static_cast<std::size_t>(bc.reverse_partner)];
            groups_csv << bc.reverse_partner << "," << fmt(bc.reverse_cycle_error) << "," << h.selection_rank << ","
                       << fmt(h.confidence_integral) << "," << fmt(h.geodesic_distortion) << ","
                       << (bc.reverse_partner == r.reverse_selected ? 1 : 0) << ",";
            // Every reverse map: the cycle error with this map, and its rank, confidence and distortion (';').
            const auto joined = [&](auto value) {
              std::string cell;
              for (std::size_t h = 0; h < r.reverse_blended.size(); ++h) {
                if (h > 0) cell += ';';
                cell += fmt(value(h));
              }
              return cell;
            };
            groups_csv << joined([&](std::size_t h) { return bc.reverse_cycle_errors[h]; }) << ","
                       << joined([&](std::size_t h) { return double(r.reverse_blended[h].selection_rank); }) << ","
                       << joined([&](std::size_t h) { return r.reverse_blended[h].confidence_integral; }) << ","
                       << joined([&](std::size_t h) { return r.reverse_blended[h].geodesic_distortion; }) << "\n";
          } else {
            groups_csv << ",,,,,,,,,\n";
          }
        }
        groups_csv.flush();
      }
      const auto s_raw = summarize_errors(std::span<const double>(e_raw));
      const auto s_sym = summarize_errors(std::span<const double>(e_sym));
      const bool flipped = s_sym.mean < s_raw.mean;
      const auto& e_flip = flipped ? e_sym : e_raw;
      const auto s_flip = flipped ? s_sym : s_raw;
      all_raw.insert(all_raw.end(), e_raw.begin(), e_raw.end());
      all_flip.insert(all_flip.end(), e_flip.begin(), e_flip.end());
      for (double e : e_raw) errs << "ours\traw\t" << e << "\n";
      for (double e : e_flip) errs << "ours\tflip\t" << e << "\n";
      // Stored results of the original method.
      double st_mean = -1, st_w025 = -1, st_mean_f = -1, st_w025_f = -1, st_time = -1;
      const fs::path stored = data / "Results" / info.results / ("BenchResult_BlendedMap_" + name + ".txt");
      if (fs::exists(stored)) {
        const auto blocks = read_bim_result(stored.string());
        if (blocks.count("Stats")) {
          const auto& b = blocks.at("Stats");
          const auto s = summarize_errors(std::span<const double>(b.per_sample_errors));
          st_mean = s.mean;
          st_w025 = s.within_025;
          st_time = b.time;
          st_raw.insert(st_raw.end(), b.per_sample_errors.begin(), b.per_sample_errors.end());
          for (double e : b.per_sample_errors) errs << "stored\traw\t" << e << "\n";
        }
        if (blocks.count("StatsWithFlip")) {
          const auto& b = blocks.at("StatsWithFlip");
          const auto s = summarize_errors(std::span<const double>(b.per_sample_errors));
          st_mean_f = s.mean;
          st_w025_f = s.within_025;
          st_flip.insert(st_flip.end(), b.per_sample_errors.begin(), b.per_sample_errors.end());
          for (double e : b.per_sample_errors) errs << "stored\tflip\t" << e << "\n";
        }
      }
      times.push_back(t_total);
      slow.emplace_back(t_total, name);
      std::size_t groups = r.blended.size();
      csv << pr.source.name() << "," << pr.target.name() << "," << A.V.rows() << "," << B.V.rows() << ","
          << sa.features().size() << "," << sb.features().size() << "," << r.candidates.size() << "," << groups << ","
          << fmt(t_total, 3) << "," << fmt(t_prep, 3) << "," << fmt(t_conf, 3) << "," << fmt(t_cons, 3) << ","
          << fmt(t_blend, 3) << "," << fmt(t_refine, 3) << "," << fmt(s_raw.mean) << "," << fmt(s_raw.within_005) << "," << fmt(s_raw.within_010)
          << "," << fmt(s_raw.within_025) << "," << fmt(s_flip.mean) << "," << fmt(s_flip.within_025) << ","
          << (flipped ? 1 : 0) << "," << fmt(s_blended.mean) << "," << fmt(s_blended.within_005) << ","
          << fmt(s_blended.within_025) << "," << fmt(r.blended[static_cast<std::size_t>(r.selected)].geodesic_distortion)
          << "," << fmt(r.refined_distortion) << "," << (r.refinement_accepted ? 1 : 0) << ","
          << (r.alternative_features ? 1 : 0) << "," << fmt(r.other_features_distortion) << "," << fmt(s_zoomout.mean) << ","
          << fmt(s_zoomout.within_005) << "," << fmt(s_zoomout.within_025) << "," << fmt(st_mean) << "," << fmt(st_w025) << "," << fmt(st_mean_f) << ","
          << fmt(st_w025_f) << "," << st_time << "," << r.refinement_moves_undone << "," << status << "\n";
      csv.flush();
      errs.flush();
      std::cerr << set << " " << name << ": mean " << fmt(s_raw.mean) << " (stored " << fmt(st_mean) << "), <=0.25 "
                << fmt(s_raw.within_025, 3) << ", <=0.05 " << fmt(s_raw.within_005, 3) << " (blended "
                << fmt(s_blended.mean) << ", " << fmt(s_blended.within_005, 3) << (r.refinement_accepted ? "" : ", refinement undone")
                << "), flip mean " << fmt(s_flip.mean) << ", " << fmt(t_total, 2) << " s\n";
      ++done;
    } catch (const std::exception& e) {
      ++failed;
      csv << pr.source.name() << "," << pr.target.name() << ",,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,\"failed: " << e.what() << "\"\n";
      std::cerr << set << " " << name << ": FAILED " << e.what() << "\n";
    }
  }
  // Summary (pooled over all evaluated points of all pairs, as the benchmark's curves are).
  const auto o_raw = summarize_errors(std::span<const double>(all_raw));
  const auto o_flip = summarize_errors(std::span<const double>(all_flip));
  const auto p_raw = summarize_errors(std::span<const double>(st_raw));
  const auto p_flip = summarize_errors(std::span<const double>(st_flip));
  // Accuracy curves: fraction of points with error <= D, D in [0, 0.25] (plot with scripts/plot_bim_curves.gnuplot).
  {
    std::vector<double> th;
    for (int k = 0; k <= 50; ++k) th.push_back(0.005 * k);
    // A set where every pair failed, or without stored results, has no errors: its curve is all zeros.
    auto curve = [&](const std::vector<double>& e) { return e.empty() ? std::vector<double>(th.size(), 0.0) : error_curve(e, th); };
    const auto c1 = curve(all_raw), c2 = curve(all_flip), c3 = curve(st_raw), c4 = curve(st_flip);
    std::ofstream cd(fs::path(out_dir) / (set + "_curves.dat"));
    cd << "# D ours_raw ours_flip stored_raw stored_flip  (" << done << " pairs)\n";
    for (std::size_t k = 0; k < th.size(); ++k)
      cd << th[k] << " " << c1[k] << " " << c2[k] << " " << c3[k] << " " << c4[k] << "\n";
  }
  std::sort(slow.rbegin(), slow.rend());
  std::ofstream md(fs::path(out_dir) / "summary.md", std::ios::app);
  md << "\n### " << set << ": " << done << " pairs (" << failed << " failed) of " << pairs.size() << "\n\n";
  md << "| method | <=0.05 | <=0.10 | <=0.25 | mean | <=0.25 flip | mean flip |\n|---|---|---|---|---|---|---|\n";
  md << "| shapestruct BIM | " << fmt(o_raw.within_005, 3) << " | " << fmt(o_raw.within_010, 3) << " | "
     << fmt(o_raw.within_025, 3) << " | " << fmt(o_raw.mean) << " | " << fmt(o_flip.within_025, 3) << " | "
     << fmt(o_flip.mean) << " |\n";
  md << "| original BIM (stored, same pairs) | " << fmt(p_raw.within_005, 3) << " | " << fmt(p_raw.within_010, 3) << " | "
     << fmt(p_raw.within_025, 3) << " | " << fmt(p_raw.mean) << " | " << fmt(p_flip.within_025, 3) << " | "
     << fmt(p_flip.mean) << " |\n\n";
  md << "Median wall time per pair (both meshes preprocessed): " << fmt(median(times), 2) << " s; slowest:";
  for (std::size_t k = 0; k < std::min<std::size_t>(3, slow.size()); ++k) md << " " << slow[k].second << " " << fmt(slow[k].first, 1) << " s;";
  md << "\n";
  std::cout << set << ": " << done << " pairs, ours <=0.25 " << fmt(o_raw.within_025, 3) << " mean " << fmt(o_raw.mean)
            << " | stored <=0.25 " << fmt(p_raw.within_025, 3) << " mean " << fmt(p_raw.mean) << " | flips ours "
            << fmt(o_flip.within_025, 3) << "/" << fmt(o_flip.mean) << " stored " << fmt(p_flip.within_025, 3) << "/"
            << fmt(p_flip.mean) << " | median time " << fmt(median(times), 2) << " s\n";
  return failed > 0 && done == 0 ? 1 : 0;
}

int main(int argc, char** argv) {
  return shapestruct::bench::run_reporting_errors("run_bim_benchmark", [&] { return run(argc, argv); });
}
