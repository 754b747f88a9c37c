// SPDX-License-Identifier: MIT
// shapestruct templates: part-based templates for a folder of shapes (dissertation chapter 5).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "option_checks.hpp"
#include "templates_run.hpp"
#include "shapestruct/templates/collection_runner.hpp"

namespace {

using namespace shapestruct;

/// The command line of `shapestruct templates`.
struct templates_command_line {
  std::string input, out;
  cli::templates_cli_options options;
  bool quiet = false;
};

int run_templates(const templates_command_line& c) {
  const std::string& out = c.out;
  const cli::templates_cli_options& o = c.options;
  const bool quiet = c.quiet;
  const auto files = list_shape_files(c.input);
  if (files.empty()) throw cli::usage_error("no .off/.obj/.ply/.stl files in " + c.input);
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
  opt.learning_round = [&](int round, int rounds) {
    if (quiet) return;
    const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - phase_start).count();
    std::cerr << "templates: learning round " << round << " of at most " << rounds << " done, " << std::lround(spent)
              << " s spent, at most " << std::lround(spent / round * (rounds - round)) << " s left\n";
  };
  opt.candidates = [&](std::size_t done, std::size_t total) {
    if (quiet) return;
    const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - phase_start).count();
    std::cerr << "\rtemplates: candidate template " << done << " of " << total << ", " << std::lround(spent)
              << " s spent, ~" << std::lround(spent / double(done) * double(total - done)) << " s left  "
              << (done == total ? "\n" : "") << std::flush;
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
  if (hooks.learning_round && opt.run_learning) {
    // Automatic initialisation learns from learn_best candidates one after the other: rounds count across them.
    const int most = opt.learn.N_iter * (templates.empty() ? std::max(1, opt.init.learn_best) : 1);
    opt.learn.progress = [&hooks, most, done = std::make_shared<int>(0)](int, std::size_t, std::size_t) {
      hooks.learning_round(++*done, most);  // shared: the options may be copied per candidate
    };
  }
  opt.init.progress = hooks.candidates;
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


void add_templates_run_options(CLI::App& app, templates_cli_options& o, const std::string& prefix) {
  app.add_option("--template,-t", o.template_file,
                 prefix + "initial template(s) (hand-authored or from an earlier run);\ndefault: automatic")
      ->type_name("T.json")
      ->check(CLI::ExistingFile.description(""));
  app.add_flag("--no-learn", o.no_learn, prefix + "label with the --template templates as they are");
  app.add_option("--learn-subset", o.learn_subset, prefix + "shapes held in memory for learning (default 200)")
      ->type_name("S")
      ->check(at_least(1LL));
  app.add_option("--learn-best", o.learn_best,
                 prefix + "automatic templates: learn from the B best candidates, keep the best\nset (default 2; chapter 10)")
      ->type_name("B")
      ->check(at_least(1LL));
  app.add_option("--parts", o.parts, prefix + "parts of automatic templates (default 4)")->type_name("K")->check(at_least(1LL));
  app.add_option("--points", o.points, prefix + "samples per shape (default 1500)")->type_name("P")->check(at_least(16LL));
}

}  // namespace shapestruct::cli

namespace {

cli::command_fn setup_templates(CLI::App& app) {
  auto c = std::make_shared<templates_command_line>();
  auto& o = c->options;
  app.add_option("DIR", c->input, "the input folder (its .off .obj .ply .stl files)")->required();
  app.add_option("-o,--output", c->out, "the output folder")->type_name("OUT")->required();
  app.add_option("--threads", o.threads, "worker threads, 0 = all cores (default); results do not depend on N")
      ->type_name("N")
      ->check(cli::at_least(0LL));
  app.add_option("--up", o.up, "up axis of the collection: 0 x, 1 y (default), 2 z")
      ->type_name("0|1|2")
      ->check(cli::in_range(0LL, 2LL));
  cli::add_templates_run_options(app, o, "");
  app.add_flag("--no-ply", o.no_ply, "skip the visualisation outputs (ply/)");
  app.add_flag("--no-points", o.no_points, "skip the per-point outputs (STEM.points.txt)");
  app.add_flag("--quiet", c->quiet, "no progress display");
  app.footer(
      "Fits deformable part templates to every mesh / polygon soup in DIR (.off .obj .ply .stl) and writes to OUT:\n"
      "  templates.json     the learned template set (edit it and pass it back with --template)\n"
      "  STEM.seg           one 0-based part label per face of the input (COSEG/PSB format)\n"
      "  STEM.fit.json      cluster (template), energy, rigid transform, per-part deformation\n"
      "  STEM.points.txt    per sample point: label, template correspondence, co-aligned positions\n"
      "  ply/STEM.ply       faces coloured by part; ply/STEM.boxes.ply the fitted boxes\n"
      "  summary.json       clusters and skipped shapes\n"
      "An interrupted run resumes: finished shapes (STEM.fit.json present) are not redone.");
  return [c] { return run_templates(*c); };
}

const cli::register_command register_templates{
    "templates",
    {"learn part-based templates; segment, correspond and co-align a folder of shapes (chapter 5)", setup_templates}};

}  // namespace
