// SPDX-License-Identifier: MIT
// shapestruct templates: part-based templates for a folder of shapes (dissertation chapter 5).
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "command.hpp"
#include "templates_run.hpp"
#include "shapestruct/templates/collection_runner.hpp"

namespace {

using namespace shapestruct;

int run_templates(const std::vector<std::string>& args) {
  cli::arg_reader reader(args);
  const std::string out = reader.option({"-o", "--output"});
  cli::templates_cli_options o;
  o.template_file = reader.option({"--template", "-t"});
  o.threads = reader.integer({"--threads"}, 0);
  o.points = reader.integer({"--points"}, 1500);
  o.learn_subset = reader.integer({"--learn-subset"}, 200);
  o.up = reader.integer({"--up"}, 1);
  o.parts = reader.integer({"--parts"}, 4);
  o.learn_best = reader.integer({"--learn-best"}, 2);
  o.no_learn = reader.flag("--no-learn");
  o.no_ply = reader.flag("--no-ply");
  o.no_points = reader.flag("--no-points");
  const bool quiet = reader.flag("--quiet");
  const auto pos = reader.positionals();
  if (pos.size() != 1) throw cli::usage_error("expected one input folder DIR");
  if (out.empty()) throw cli::usage_error("-o OUT is required");
  cli::check_templates_options(o);
  const auto files = list_shape_files(pos[0]);
  if (files.empty()) throw cli::usage_error("no .off/.obj/.ply/.stl files in " + pos[0]);
  cli::templates_hooks opt;
  const auto start = std::chrono::steady_clock::now();
  auto phase_start = start;
  std::size_t first_done = 0;
  bool first_seen = false;
  opt.phase = [&](const std::string& m) {
    phase_start = std::chrono::steady_clock::now();
    if (!quiet) std::cerr << "templates: " << m << "\n";
  };
  opt.problem = [&](const std::string& f, const std::string& m) {
    std::cerr << "\rtemplates: skipped " << f << ": " << m << "\n";
  };
  opt.progress = [&](std::size_t done, std::size_t total) {
    if (quiet) return;
    if (!first_seen) {
      first_seen = true;
      first_done = done - 1;  // shapes finished by an earlier run are skipped at once; do not count them
    }
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - phase_start).count();
    const double rate = done > first_done ? el / double(done - first_done) : 0;
    const double left = rate * double(total - done);
    const int width = 30, filled = static_cast<int>(width * double(done) / double(total));
    char line[160];
    std::snprintf(line, sizeof line, "\r[%s%s] %zu/%zu  %.0fs elapsed, ~%.0fs left  ",
                  std::string(static_cast<std::size_t>(filled), '#').c_str(),
                  std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done, total, el, left);
    std::cerr << line << (done == total ? "\n" : "") << std::flush;
  };
  const auto sum = cli::run_templates_folder(files, out, o, opt);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "templates: " << sum.template_ids.size() << " template(s), " << sum.processed << " shapes fitted, "
            << sum.skipped << " already done, " << sum.failed << " failed, " << secs << " s\n";
  for (std::size_t t = 0; t < sum.template_ids.size(); ++t)
    std::cout << "  cluster " << t << " (" << sum.template_ids[t] << "): " << sum.cluster_sizes[t] << " shapes\n";
  std::cout << "results in " << out << " (templates.json, STEM.seg, STEM.fit.json, summary.json)\n";
  return sum.failed > 0 && sum.processed + sum.skipped == 0 ? 1 : 0;
}

}  // namespace

namespace shapestruct::cli {

std::vector<std::filesystem::path> shape_files_in(const std::filesystem::path& dir) { return list_shape_files(dir); }

void check_templates_options(const templates_cli_options& o) {
  if (o.threads < 0 || o.points < 16 || o.learn_subset < 1 || o.up < 0 || o.up > 2 || o.parts < 1 || o.learn_best < 1)
    throw cli::usage_error(
        "--threads >= 0, --points >= 16, --learn-subset >= 1, --up 0|1|2, --parts >= 1, --learn-best >= 1");
}

templates_run_summary run_templates_folder(const std::vector<std::filesystem::path>& files,
                                           const std::filesystem::path& out, const templates_cli_options& o,
                                           const templates_hooks& hooks) {
  std::vector<part_template> templates;
  if (!o.template_file.empty()) templates = read_templates(o.template_file);
  collection_run_options opt;
  opt.threads = static_cast<int>(o.threads);
  opt.learn.threads = static_cast<int>(o.threads);
  opt.sampling.points = static_cast<index_t>(o.points);
  opt.sampling.up_axis = static_cast<int>(o.up);
  opt.init.up_axis = static_cast<int>(o.up);
  opt.init.parts = static_cast<int>(o.parts);
  opt.init.learn_best = static_cast<int>(o.learn_best);
  opt.learn_subset = static_cast<std::size_t>(o.learn_subset);
  opt.run_learning = !o.no_learn;
  opt.write_ply = !o.no_ply;
  opt.write_points = !o.no_points;
  opt.phase = hooks.phase;
  opt.problem = hooks.problem;
  opt.progress = hooks.progress;
  opt.share = o.share;
  const auto sum = run_template_collection(files, out, templates, opt);
  templates_run_summary r;
  for (const auto& t : sum.templates) r.template_ids.push_back(t.id);
  r.cluster_sizes = sum.cluster_sizes;
  r.processed = sum.processed;
  r.skipped = sum.skipped;
  r.failed = sum.failed;
  return r;
}

}  // namespace shapestruct::cli

namespace {

const cli::register_command reg{
    "templates",
    {"learn part-based templates; segment, correspond and co-align a folder of shapes (chapter 5)",
     "usage: shapestruct templates DIR -o OUT [--template T.json] [--threads N] [--points P] [--learn-subset S]\n"
     "                            [--up 0|1|2] [--parts K] [--learn-best B] [--no-learn] [--no-ply] [--no-points]\n"
     "                            [--quiet]\n"
     "\n"
     "Fits deformable part templates to every mesh / polygon soup in DIR (.off .obj .ply .stl) and writes to OUT:\n"
     "  templates.json     the learned template set (edit it and pass it back with --template)\n"
     "  STEM.seg           one 0-based part label per face of the input (COSEG/PSB format)\n"
     "  STEM.fit.json      cluster (template), energy, rigid transform, per-part deformation\n"
     "  STEM.points.txt    per sample point: label, template correspondence, co-aligned positions\n"
     "  ply/STEM.ply       faces coloured by part; ply/STEM.boxes.ply the fitted boxes\n"
     "  summary.json       clusters and skipped shapes\n"
     "An interrupted run resumes: finished shapes (STEM.fit.json present) are not redone.\n"
     "\n"
     "options:\n"
     "  --template T.json  initial template(s) (hand-authored or from an earlier run); default: automatic\n"
     "  --threads N        worker threads, 0 = all cores (default); results do not depend on N\n"
     "  --points P         samples per shape (default 1500)\n"
     "  --learn-subset S   shapes held in memory for learning (default 200)\n"
     "  --up A             up axis of the collection: 0 x, 1 y (default), 2 z\n"
     "  --parts K          parts of automatic templates (default 4)\n"
     "  --learn-best B     automatic mode: learn from the B best candidates, keep the best set (default 2; chapter 10)\n"
     "  --no-learn         label with the given templates as they are\n"
     "  --no-ply, --no-points  skip the visualisation / per-point outputs",
     run_templates}};

}  // namespace
