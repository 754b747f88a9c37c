// SPDX-License-Identifier: MIT
// shapestruct fuzzy / fuzzy-map: fuzzy correspondences of a folder of shapes (dissertation chapter 4) and the
// maps between two of its shapes.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include "command.hpp"
#include "file_fingerprint.hpp"
#include "fuzzy_run.hpp"
#include "option_checks.hpp"
#include "shapestruct/fuzzy/collection_records.hpp"
#include "shapestruct/fuzzy/extrinsic_alignment.hpp"
#include "shapestruct/fuzzy/fuzzy_collection.hpp"
#include "shapestruct/fuzzy/fuzzy_files.hpp"
#include "shapestruct/fuzzy/fuzzy_maps.hpp"
#include "shapestruct/fuzzy/fuzzy_output.hpp"
#include "shapestruct/fuzzy/intrinsic_alignment.hpp"
#include "shapestruct/fuzzy/refined_fuzzy_alignment.hpp"
#include "shapestruct/io/json_file.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/vertex_map_file.hpp"
#include "shapestruct/templates/collection_runner.hpp"

namespace {

using namespace shapestruct;
namespace fs = std::filesystem;
using steady = std::chrono::steady_clock;
using ojson = nlohmann::ordered_json;

using cli::progress_line;

double since(steady::time_point t) { return std::chrono::duration<double>(steady::now() - t).count(); }

/// The command line of `shapestruct fuzzy`.
struct fuzzy_command_line {
  std::string input, out;
  cli::fuzzy_cli_options options;
};

int run_fuzzy(const fuzzy_command_line& c) {
  const std::string& out = c.out;
  const cli::fuzzy_cli_options& o = c.options;
  const auto files = list_shape_files(c.input);
  if (files.empty()) throw cli::usage_error("no .off/.obj/.ply/.stl files in " + c.input);
  progress_line bar(o.quiet);
  return cli::run_fuzzy_folder(files, out, o, bar, c.input).exit_code;
}

/// OUT/cache.json records what the resume caches were made with: records/ (samples and their metric) and pairs/
/// (alignment mode, up axis), and every shape file's fingerprint (size, content hash): the caches are keyed by
/// file name, so an edited file would otherwise keep its old record and alignments. A rerun into the same folder with other settings would mix old records or
/// alignments into the new run without a word, so it is refused, naming the option.
class cache_settings {
 public:
  explicit cache_settings(fs::path file) : file_(std::move(file)) {
    if (fs::exists(file_)) stored_ = read_json_file(file_.string());
  }
  /// Throws cli::usage_error when `part` was stored with other values; otherwise records `wanted` for it.
  void require(const std::string& part, const std::string& folder, const nlohmann::ordered_json& wanted) {
    if (stored_.is_object() && stored_.contains(part) && stored_[part] != wanted) {
      const auto& stored = stored_[part];
      auto differs = [&](const std::string& key, const nlohmann::ordered_json& old, const nlohmann::ordered_json& now) {
        if (old == now) return;
        const std::string made = old.is_null() ? " was made without " + key : " was made with " + key + " " + old.dump();
        const std::string asked = now.is_null() ? "this run does not ask for it" : "this run asks for " + now.dump();
        throw cli::usage_error((file_.parent_path() / folder).string() + made + "; " + asked + " (option " +
                               flag_of(key) + "). Use another output folder, or delete " + folder +
                               "/ there to make it again");
      };
      for (const auto& [key, value] : wanted.items())
        differs(key, stored.contains(key) ? stored[key] : nlohmann::ordered_json(), value);
      // A setting stored but not asked for now (an option left out this time).
      if (stored.is_object())
        for (const auto& [key, value] : stored.items())
          if (!wanted.contains(key)) differs(key, value, nlohmann::ordered_json());
    }
    if (!stored_.is_object()) stored_ = nlohmann::ordered_json::object();
    stored_[part] = wanted;
  }
  /// Throws cli::usage_error when a shape file changed since its record (records/STEM.rec) or an alignment naming
  /// it (pairs/A__B.align) was made; otherwise records every file's fingerprint under "shapes".
  void require_shapes(const std::vector<fs::path>& files) {
    if (!stored_.is_object()) stored_ = nlohmann::ordered_json::object();
    if (!stored_.contains("shapes") || !stored_["shapes"].is_object()) stored_["shapes"] = nlohmann::ordered_json::object();
    auto& known = stored_["shapes"];
    const fs::path out = file_.parent_path();
    std::set<std::string> aligned;  // the shapes some cached alignment was made from
    if (fs::is_directory(out / "pairs"))
      for (const auto& e : fs::directory_iterator(out / "pairs")) {
        const std::string n = e.path().stem().string();
        const auto cut = n.find("__");
        if (e.path().extension() != ".align" || cut == std::string::npos) continue;
        aligned.insert(n.substr(0, cut));
        aligned.insert(n.substr(cut + 2));
      }
    for (const auto& f : files) {
      const std::string stem = f.stem().string();
      std::string now;
      try {
        now = cli::file_fingerprint(f);
      } catch (const io_error&) {
        continue;  // unreadable: the records step reports it and skips the shape
      }
      const bool cached = fs::exists(out / "records" / (stem + ".rec")) || aligned.count(stem) != 0;
      if (cached && known.contains(stem) && known[stem] != now)
        throw cli::usage_error((out / "records").string() + " and pairs/ hold results made from another version of " +
                               f.string() + " (" + known[stem].get<std::string>() + " then, " + now +
                               " now). Use another output folder, or delete records/" + stem +
                               ".rec and the pairs/ files naming " + stem + " there to make them again");
      known[stem] = now;
    }
  }
  void write() const { write_json_file(file_.string(), stored_); }
  /// What was recorded for `part` ("records", "pairs"); an empty object when the file or the part is absent
  /// (an older folder, whose readers then keep the defaults of that time).
  [[nodiscard]] nlohmann::ordered_json stored(const std::string& part) const {
    const auto* found = stored_.is_object() ? json_member(stored_, part) : nullptr;
    return found != nullptr && found->is_object() ? *found : nlohmann::ordered_json::object();
  }

 private:
  static std::string flag_of(const std::string& key) {
    if (key == "samples") return "--samples";
    if (key == "up") return "--up";
    if (key == "both_feature_sets") return "--both-feature-sets";
    return "--mode";  // the sampling metric and the alignment mode both follow it
  }
  fs::path file_;
  nlohmann::ordered_json stored_;
};

/// The command line of `shapestruct fuzzy-map`.
struct fuzzy_map_command_line {
  std::string folder, a, b, out;
  bool consistent = false;
  double min_gain = consistent_blended_options{}.min_consistency_gain;
  double fuzzy_min_gain = consistent_blended_options{}.fuzzy_min_gain;
  bool blended_only = false;
  bool unrefined_choice = false;
  bool refined = false;
  bool no_axis_scales = false;
  long long threads = 0;
};

int run_fuzzy_map(const fuzzy_map_command_line& c) {
  const std::string& out = c.out;
  const bool consistent = c.consistent;
  const std::vector<std::string> pos{c.folder, c.a, c.b};
  const fs::path dir(pos[0]);
  for (const char* needed : {"collection.json", "fuzzy.bin"})
    if (!fs::exists(dir / needed))
      throw cli::usage_error(std::string("'") + pos[0] + "' is not the output of `shapestruct fuzzy`: " + needed + " is missing");
  const fuzzy_output collection = read_fuzzy_output(dir);
  const auto& records = collection.records;
  const auto& files = collection.files;
  const fuzzy_correspondence& f = collection.fuzzy;
  std::map<std::string, index_t> index_of;
  for (index_t k = 0; k < collection.shapes(); ++k) index_of[records[std::size_t(k)].name] = k;
  for (const auto& n : {pos[1], pos[2]})
    if (!index_of.count(n)) throw cli::usage_error("shape '" + n + "' is not in the collection (see " + (dir / "collection.json").string() + ")");
  const index_t a = index_of[pos[1]], b = index_of[pos[2]];
  std::vector<index_t> map;
  if (consistent) {
    if (collection.mode != "intrinsic")
      throw cli::usage_error("--consistent-blended needs an intrinsic collection (this one is extrinsic)");
    // The candidates the collection's alignments were made from (cache.json; one feature set when absent).
    intrinsic_alignment_options io;
    const ojson pairs = cache_settings(dir / "cache.json").stored("pairs");
    if (const auto* both = json_member(pairs, "both_feature_sets"); both != nullptr && both->is_boolean())
      io.both_feature_sets = both->get<bool>();
    intrinsic_aligner aligner(records, [&files](index_t k) { return read_mesh(files[std::size_t(k)]).mesh; }, io);
    const auto cb = make_consistent_blended_map(aligner, f, a, b,
                                                {.min_consistency_gain = c.min_gain, .orientation = collection.orientation,
                                                 .fuzzy_candidate = !c.blended_only, .fuzzy_min_gain = c.fuzzy_min_gain,
                                                 .refine_choice = !c.unrefined_choice, .threads = int(c.threads)});
    map = cb.map.nearest;
    if (cb.fuzzy_chosen)
      std::fprintf(stderr, "fuzzy-map: the refined best fuzzy map chosen (consistency %.3g; of the %zu blended maps the "
                   "matcher picks %ld, the most consistent is %ld)\n",
                   cb.fuzzy_consistency, cb.consistency.size(), long(cb.pairwise_group), long(cb.most_consistent_group));
    else {
      char refinement[160] = "";
      if (!c.unrefined_choice)
        std::snprintf(refinement, sizeof refinement,
                      cb.refinement_accepted ? ", refined (its geodesic distortion x%.3g)"
                                             : ", its refinement undone (it multiplied the geodesic distortion by %.3g)",
                      cb.refinement_distortion_ratio);
      std::fprintf(stderr,
                   "fuzzy-map: blended map %ld of %zu chosen (the matcher alone picks %ld, the most consistent is "
                   "%ld%s)%s\n",
                   long(cb.group), cb.consistency.size(), long(cb.pairwise_group), long(cb.most_consistent_group),
                   cb.opposite_orientation
                       ? "; the two shapes sit in f the mirror way round, so the matcher's choice is kept"
                       : "",
                   refinement);
    }
  } else if (c.refined) {
    if (collection.mode != "extrinsic")
      throw cli::usage_error("--refined needs an extrinsic collection (this one is intrinsic: --consistent-blended "
                             "refines the fuzzy map there)");
    extrinsic_alignment_options eo;
    // The collection's up axis, as its alignments were made (cache.json; +y when an older folder lacks it).
    const ojson pairs = cache_settings(dir / "cache.json").stored("pairs");
    if (const auto* up = json_member(pairs, "up"); up != nullptr && up->is_number_integer())
      eo.up_axis = up->get<int>();
    // A scale per axis fits shapes of other proportions closely; it needs the upright frame (docs/fuzzy.md).
    eo.axis_scales = !c.no_axis_scales && eo.up_axis != no_up_axis;
    try {
      map = refined_fuzzy_vertex_map(f, records, a, b, read_mesh(files[std::size_t(a)]).mesh.V,
                                     read_mesh(files[std::size_t(b)]).mesh.V, eo);
    } catch (const invalid_input& e) {
      if (e.reason() != input_error::empty) throw;
      throw invalid_input(e.reason(), e.element(), std::string(e.what()) + ": fuzzy-map without --refined writes it");
    }
  } else {
    const bool on_vertices = !records[std::size_t(b)].sample_vertex.empty() && records[std::size_t(b)].sample_vertex[0] != no_index;
    const Eigen::Matrix<double, Eigen::Dynamic, 3> Vb =
        on_vertices ? Eigen::Matrix<double, Eigen::Dynamic, 3>() : read_mesh(files[std::size_t(b)]).mesh.V;
    map = best_fuzzy_vertex_map(f, records, a, b, Vb);
  }
  write_vertex_map(fs::path(out), std::span<const index_t>(map));
  return 0;
}

}  // namespace

namespace shapestruct::cli {

fuzzy_run_report run_fuzzy_folder(const std::vector<std::filesystem::path>& files, const std::filesystem::path& out,
                                  const fuzzy_cli_options& o, progress_line& bar, const std::string& input_name) {
  fuzzy_run_report report;
  const fs::path out_dir(out);
  fs::create_directories(out_dir);
  const auto t_start = steady::now();

  // 1. Records (cached in OUT/records): intrinsic collections sample geodesically, extrinsic ones on the surface.
  collection_records_options ro;
  ro.threads = static_cast<int>(o.threads);
  ro.record.samples = static_cast<index_t>(o.samples);
  ro.record.metric = o.mode == "extrinsic" ? sample_metric::euclidean : sample_metric::automatic;
  ro.cache_folder = out_dir / "records";
  ro.on_progress = [&](std::size_t d, std::size_t t) { bar.update("records", d, t); };
  ro.share = o.share;
  const bool writer = o.share.leader();  // with several ranks, rank 0 alone writes the results and speaks
  cache_settings cache(out_dir / "cache.json");
  cache.require("records", "records",
                {{"samples", o.samples}, {"metric", o.mode == "extrinsic" ? "euclidean" : "geodesic where possible"}});
  cache.require_shapes(files);
  if (writer) cache.write();  // before any record is made: an interrupted run still knows what its records came from
  auto col = make_collection_records(files, ro);
  bar.finish();
  const double t_records = since(t_start);
  if (writer)
    for (const auto& s : col.skipped) std::fprintf(stderr, "fuzzy: skipped %s: %s\n", s.file.string().c_str(), s.reason.c_str());
  bool all_genus0 = !col.records.empty();
  for (const auto& r : col.records) all_genus0 = all_genus0 && r.closed_genus0;
  const bool intrinsic = o.mode == "intrinsic" || (o.mode == "auto" && all_genus0);
  if (intrinsic) {
    // Intrinsic alignment needs closed genus-0 surfaces: the others are left out, by name.
    const std::size_t before = col.skipped.size();
    keep_intrinsic_shapes(col, "not a closed genus-0 surface (intrinsic mode needs one; --mode extrinsic keeps it)");
    for (std::size_t i = before; i < col.skipped.size() && writer; ++i)
      std::fprintf(stderr, "fuzzy: left out %s: %s\n", col.skipped[i].file.string().c_str(), col.skipped[i].reason.c_str());
  }
  if (col.records.size() < 2) {
    if (writer) std::fprintf(stderr, "fuzzy: fewer than two usable shapes in %s; nothing to correspond\n", input_name.c_str());
    for (const auto& s : col.skipped) report.skipped.emplace_back(s.file.string(), s.reason);
    report.exit_code = 1;
    return report;
  }
  if (!o.quiet)
    std::fprintf(stderr, "fuzzy: %zu shapes, %s mode, %lld samples each (records %.1f s)\n", col.records.size(),
                 intrinsic ? "intrinsic" : "extrinsic", o.samples, t_records);

  // 2. The pipeline, with the pairwise alignments cached in OUT/pairs.
  nlohmann::ordered_json alignment_settings{{"mode", intrinsic ? "intrinsic" : "extrinsic"}};
  if (!intrinsic) alignment_settings["up"] = o.up;
  if (intrinsic && o.both_feature_sets) alignment_settings["both_feature_sets"] = true;  // absent: one set, as before
  cache.require("pairs", "pairs", alignment_settings);
  if (writer) cache.write();
  fuzzy_collection_options fo;
  fo.threads = static_cast<int>(o.threads);
  fo.graph.edges_per_shape = static_cast<index_t>(o.edges_per_shape);
  fo.alignments_in_memory = o.alignments_in_memory;
  fo.embedding.time = o.diffusion_time;
  fo.embedding.dimensions = static_cast<index_t>(o.dimensions);
  fo.weak_support_fraction = o.weak_support;
  fo.cache_folder = out_dir / "pairs";
  fo.share = o.share;
  fo.on_progress = [&](const std::string& stage, std::size_t d, std::size_t t) { bar.update(stage, d, t); };
  const auto t_fuzzy = steady::now();
  fuzzy_collection_result r;
  std::size_t preparations = 0;
  if (intrinsic) {
    const auto& f = col.files;
    intrinsic_alignment_options io;
    io.cache_bytes = static_cast<std::size_t>(o.cache_memory_mb) << 20;
    io.both_feature_sets = o.both_feature_sets;
    intrinsic_aligner aligner(col.records, [&f](index_t k) { return read_mesh(f[std::size_t(k)]).mesh; }, io);
    r = compute_fuzzy_correspondences(col.records, aligner, fo);
    preparations = aligner.preparations();
  } else {
    extrinsic_alignment_options eo;
    eo.up_axis = static_cast<int>(o.up);
    const extrinsic_aligner aligner(col.records, eo);
    r = compute_fuzzy_correspondences(col.records, aligner, fo);
  }
  bar.finish();
  if (preparations > 0 && !o.quiet && writer)  // says whether --cache-memory is too small
    std::fprintf(stderr, "fuzzy: %zu shapes prepared %zu times for intrinsic alignment (--cache-memory %lld MB)\n",
                 col.records.size(), preparations, o.cache_memory_mb);
  const double seconds_fuzzy = since(t_fuzzy);
  auto disconnected = nlohmann::ordered_json::array();
  for (const index_t k : r.disconnected) {
    if (writer) std::fprintf(stderr, "fuzzy: %s is not connected to the rest of the collection: every alignment to it was "
                 "rejected, so its correspondences to the others mean nothing\n", col.files[std::size_t(k)].string().c_str());
    disconnected.push_back(col.records[std::size_t(k)].name);
  }

  // 3. Outputs.
  report.mode = intrinsic ? "intrinsic" : "extrinsic";
  report.shapes = col.records.size();
  if (!writer) return report;
  write_fuzzy_correspondence(out_dir / "fuzzy.bin", r.fuzzy);
  {
    std::string s = "# shape sample x y z vertex  (vertex -1: a surface point of a soup)\n";
    char line[256];
    for (std::size_t k = 0; k < col.records.size(); ++k) {
      const auto& rec = col.records[k];
      for (index_t i = 0; i < rec.sample_count(); ++i) {
        std::snprintf(line, sizeof line, "%s %ld %.9g %.9g %.9g %ld\n", rec.name.c_str(), long(i), rec.samples(i, 0),
                      rec.samples(i, 1), rec.samples(i, 2), long(rec.sample_vertex[std::size_t(i)]));
        s += line;
      }
    }
    io_detail::write_file_atomically(out_dir / "samples.txt", s);
  }
  {
    std::string s = "# source target alternative alternatives consistency global_score (the final alignment graph)\n";
    char line[512];
    for (const auto& e : r.edges) {
      const auto file = out_dir / "pairs" / (col.records[std::size_t(e.source)].name + "__" + col.records[std::size_t(e.target)].name + ".align");
      const auto pa = read_pair_alignment(file);
      std::snprintf(line, sizeof line, "%s %s %ld %zu %.6g %.6g\n", col.records[std::size_t(e.source)].name.c_str(),
                    col.records[std::size_t(e.target)].name.c_str(), long(e.alternative), pa.alternatives.size(),
                    e.consistency, pa.alternatives[std::size_t(e.alternative)].global_score);
      s += line;
    }
    io_detail::write_file_atomically(out_dir / "graph.txt", s);
  }
  {
    // analyze (timings_in_results false) leaves the seconds out, so the file is the same on every run.
    const bool t = o.timings_in_results;
    std::string s = std::string("iteration\tedges\tswitched\tpruned\tadded\treinforced\treconnected\tpairs_aligned\tmean_consistency\t") +
                    (t ? "align_s\tembed_s\toptimize_s\t" : "") + "embedding_status\n";
    for (const auto& it : r.log)
      s += std::to_string(it.iteration) + "\t" + std::to_string(it.edges) + "\t" + std::to_string(it.alternatives_changed) +
           "\t" + std::to_string(it.pruned) + "\t" + std::to_string(it.added) + "\t" + std::to_string(it.reinforced) +
           "\t" + std::to_string(it.reconnected) +
           "\t" + std::to_string(it.pairs_aligned) + "\t" + std::to_string(it.mean_consistency) + "\t" +
           (t ? std::to_string(it.align_seconds) + "\t" + std::to_string(it.embed_seconds) + "\t" +
                    std::to_string(it.optimize_seconds) + "\t"
              : std::string()) +
           to_string(it.embedding_info) + "\n";
    io_detail::write_file_atomically(out_dir / "iterations.tsv", s);
  }
  auto shapes = ojson::array(), skipped = ojson::array();
  for (std::size_t k = 0; k < col.records.size(); ++k) {
    shapes.push_back(ojson::object({{"name", col.records[k].name},
                                    {"file", fs::absolute(col.files[k]).string()},
                                    {"vertices", static_cast<long long>(col.records[k].vertex_count)},
                                    {"closed_genus0", col.records[k].closed_genus0}}));
    if (!r.orientation.empty()) shapes.back()["orientation"] = int(r.orientation[k]);
  }
  for (const auto& s : col.skipped) skipped.push_back(ojson::object({{"file", s.file.string()}, {"reason", s.reason}}));
  const std::size_t N = col.records.size();
  ojson manifest = ojson::object({
      {"mode", intrinsic ? "intrinsic" : "extrinsic"},
      {"samples", static_cast<long long>(o.samples)},
      {"shapes", shapes},
      {"skipped", skipped},
      {"disconnected", disconnected},
      {"pairs_aligned", static_cast<long long>(r.pairs_aligned)},
      {"pairs_total", static_cast<long long>(N * (N - 1) / 2)},
      {"iterations", static_cast<long long>(r.log.size() - 1)},
      {"converged", r.converged}});
  if (o.timings_in_results)
    manifest["seconds"] = ojson::object({{"records", t_records}, {"fuzzy", seconds_fuzzy}, {"total", since(t_start)}});
  write_json_file((out_dir / "collection.json").string(), manifest);
  if (!o.quiet)
    std::fprintf(stderr,
                 "fuzzy: %zu shapes, %zu of %zu pairs aligned (%.1f %%), %zu iterations%s, %.1f s; wrote %s\n", N,
                 r.pairs_aligned, N * (N - 1) / 2, 100.0 * double(r.pairs_aligned) / double(N * (N - 1) / 2),
                 r.log.size() - 1, r.converged ? " (converged)" : "", since(t_start), out_dir.string().c_str());
  report.mode = intrinsic ? "intrinsic" : "extrinsic";
  report.shapes = N;
  for (const auto& s : col.skipped) report.skipped.emplace_back(s.file.string(), s.reason);
  report.seconds_records = t_records;
  report.seconds_fuzzy = seconds_fuzzy;
  report.seconds_total = since(t_start);
  for (const auto& it : r.log) report.iteration_seconds.push_back({it.align_seconds, it.embed_seconds, it.optimize_seconds});
  return report;
}

void add_fuzzy_run_options(CLI::App& app, fuzzy_cli_options& o, const std::string& prefix) {
  app.add_option("--samples", o.samples, prefix + "farthest-point samples per shape (default 128)")
      ->type_name("K")
      ->check(at_least(3LL));
  app.add_option("--edges-per-shape", o.edges_per_shape,
                 prefix + "edges per shape of the initial alignment graph (default 5)")
      ->type_name("M")
      ->check(at_least(1LL));
  app.add_option("--diffusion-time", o.diffusion_time, prefix + "time of the diffusion embedding (default 10)")
      ->type_name("T")
      ->check(at_least(0.0));
  app.add_option("--dimensions", o.dimensions, prefix + "dimensions of the diffusion embedding (default 64)")
      ->type_name("D")
      ->check(at_least(1LL));
  app.add_option("--weak-support", o.weak_support,
                 prefix + "a shape whose alignments' mean consistency is below this fraction of\n"
                          "the median shape's is aligned with up to 2 more shapes (default 0.8;\n"
                          "0 = only the chapter's pruned-for-new edge swaps)")
      ->type_name("F")
      ->check(in_range(0.0, 1.0));
  app.add_flag("--alignments-in-memory", o.alignments_in_memory,
               prefix + "keep every pairwise alignment's scores in memory instead of reading\n"
                        "them back from the pair cache each round: a little faster, memory grows\n"
                        "with the pairs; the results are the same");
  app.add_option("--cache-memory", o.cache_memory_mb,
                 prefix + "memory for the shapes prepared for intrinsic alignment, kept for\n"
                          "reuse (about 5 KB per vertex each; default 2048): a smaller cache\n"
                          "prepares shapes again more often; the results are the same")
      ->type_name("MB")
      ->check(in_range(64LL, 1048576LL));  // 64 MB .. 1 TB
  app.add_flag("--both-feature-sets", o.both_feature_sets,
               prefix + "intrinsic mode: a shape with small bumps among its extremities is also\n"
                        "matched without them, and every map of both matches is an alternative\n"
                        "of the pair (slower for those pairs; off by default)");
}

}  // namespace shapestruct::cli

namespace {

cli::command_fn setup_fuzzy(CLI::App& app) {
  auto c = std::make_shared<fuzzy_command_line>();
  auto& o = c->options;
  app.add_option("DIR", c->input, "the input folder (its .off .obj .ply .stl files)")->required();
  app.add_option("-o,--output", c->out, "the output folder")->type_name("OUT")->required();
  app.add_option("--mode", o.mode,
                 "auto (the default): intrinsic when every shape is a closed genus-0 surface,\n"
                 "else extrinsic; in intrinsic mode a shape that is not is left out and named")
      ->type_name("extrinsic|intrinsic|auto")
      ->check(cli::one_of({"extrinsic", "intrinsic", "auto"}));
  app.add_option("--threads", o.threads, "worker threads, 0 = all cores (default)")->type_name("N")->check(cli::at_least(0LL));
  app.add_option("--up", o.up,
                 "up axis of the collection (extrinsic mode): 0 x, 1 y (default), 2 z, or none\n"
                 "when the shapes are not consistently oriented (any rotation; 6x the alignment time)")
      ->type_name("0|1|2|none")
      ->transform(cli::up_axis_or_none());
  cli::add_fuzzy_run_options(app, o, "");
  app.add_flag("--quiet", o.quiet, "no progress display");
  app.footer(
      "Fuzzy correspondences of every shape file (.off .obj .ply .stl) in DIR (chapter 4): K farthest-point samples\n"
      "per shape, an initial alignment graph from spherical-harmonic descriptors, pairwise alignments along its\n"
      "edges (extrinsic: ICP, upright unless --up none; intrinsic: blended intrinsic maps), the diffusion\n"
      "embedding of the correspondence matrix (time T = 10, D = 64 dimensions) and the graph optimisation of\n"
      "Algorithm 1.\n"
      "OUT holds (docs/fuzzy.md): collection.json, samples.txt, graph.txt, iterations.tsv, fuzzy.bin, and the\n"
      "resume caches records/ and pairs/: run the same command again after an interruption and finished work is\n"
      "not redone. Unreadable, empty or non-finite shapes are reported and skipped.");
  return [c] { return run_fuzzy(*c); };
}

cli::command_fn setup_fuzzy_map(CLI::App& app) {
  auto c = std::make_shared<fuzzy_map_command_line>();
  app.add_option("OUT", c->folder, "the output folder of `shapestruct fuzzy`")->required();
  app.add_option("A", c->a, "the source shape (its name in OUT/collection.json, i.e. its file stem)")->required();
  app.add_option("B", c->b, "the target shape")->required();
  app.add_option("-o,--output", c->out, "the dense vertex map")->type_name("A_B.map")->required();
  auto* consistent = app.add_flag("--consistent-blended", c->consistent,
                                  "(intrinsic collections) the blended map of the pair most consistent\nwith the fuzzy correspondences");
  app.add_option("--min-gain", c->min_gain,
                 "with --consistent-blended: how much more consistent (a fraction) the\ncollection's choice must be to overrule the matcher's own (default 0.1;\n0 = always the most consistent)")
      ->type_name("F")
      ->check(cli::at_least(0.0))
      ->needs(consistent);  // alone it would be silently ignored
  auto* blended_only = app.add_flag("--blended-only", c->blended_only,
               "with --consistent-blended: choose among the blended maps only (by default\nthe best fuzzy map, refined by ZoomOut, competes with them)")
      ->needs(consistent);
  app.add_flag("--unrefined-choice", c->unrefined_choice,
               "with --consistent-blended: keep a chosen blended map as blended (by default\n"
               "it is refined as `shapestruct match` refines its own: ZoomOut, long moves\n"
               "checked, undone if it distorts 1.5 times as much)")
      ->needs(consistent);
  app.add_option("--fuzzy-min-gain", c->fuzzy_min_gain,
                 "with --consistent-blended: how much more consistent (a fraction) the refined\nfuzzy map must be than every blended map to be chosen (default 0: whenever\nit is the most consistent)")
      ->type_name("F")
      ->check(cli::at_least(0.0))
      ->needs(consistent)
      ->excludes(blended_only);
  auto* refined = app.add_flag("--refined", c->refined,
                               "(extrinsic collections) the best fuzzy correspondence made precise: the\n"
                               "similarity fitted to it (upright, unless made with --up none), refined by\n"
                               "one ICP, then by one more that also fits a scale per axis (upright\n"
                               "collections); each vertex goes to the nearest vertex of B")
      ->excludes(consistent);
  app.add_flag("--no-axis-scales", c->no_axis_scales,
               "with --refined: stop after the similarity ICP (one scale for all axes)")
      ->needs(refined);
  app.add_option("--threads", c->threads, "worker threads, 0 = all cores (default)")->type_name("N")->check(cli::at_least(0LL));
  app.footer(
      "Dense vertex map from shape A to shape B of a collection computed by `shapestruct fuzzy`: by default the\n"
      "best fuzzy correspondence (each vertex goes where its nearest sample's closest sample in the embedding\n"
      "lies); --refined (extrinsic collections) that correspondence made precise by one ICP started from it;\n"
      "--consistent-blended (intrinsic) the map of the pair most consistent with the fuzzy correspondences among\n"
      "the blended maps and the best fuzzy map refined by ZoomOut, unless it is less than --min-gain more\n"
      "consistent than the blended matcher's own choice.\n"
      "One 0-based target vertex id per line.");
  return [c] { return run_fuzzy_map(*c); };
}

const cli::register_command reg_fuzzy{"fuzzy", {"fuzzy correspondences of a folder of shapes (chapter 4)", setup_fuzzy}};
const cli::register_command reg_fuzzy_map{"fuzzy-map", {"a dense .map between two shapes of a fuzzy collection", setup_fuzzy_map}};

}  // namespace
