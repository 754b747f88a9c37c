// SPDX-License-Identifier: MIT
// The glue between `shapestruct templates`' options and the library's run_template_collection, shared with
// `shapestruct analyze` (defined in cmd_templates.cpp, so including this header stays cheap).
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "shapestruct/core/work_share.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace shapestruct::cli {

/// The options of `shapestruct templates` (defaults as documented in its --help; their ranges are checked
/// when the command line is parsed).
struct templates_cli_options {
  std::string template_file;  ///< --template T.json ("" = automatic)
  long long threads = 0;
  long long points = 1500;
  long long learn_subset = 200;
  long long up = 1;
  long long parts = 4;
  long long learn_best = 2;
  bool no_learn = false;
  bool no_ply = false;
  bool no_points = false;
  work_share share{};  ///< not an option: analyze's process group (several MPI ranks share the run)
};

/// Callbacks of a run (any may be empty): as collection_run_options' progress / problem / phase.
struct templates_hooks {
  std::function<void(std::size_t, std::size_t)> progress;
  std::function<void(const std::string&, const std::string&)> problem;
  std::function<void(const std::string&)> phase;
  /// After each learning round: (rounds done, most rounds); learning may converge before the last one.
  std::function<void(int, int)> learning_round;
  /// Automatic initialisation: after each candidate template is made (done, total), before the learning rounds.
  std::function<void(std::size_t, std::size_t)> candidates;
};

/// What a run reports back (collection_run_summary without the templates themselves).
struct templates_run_summary {
  std::vector<std::string> template_ids;
  std::vector<std::size_t> cluster_sizes;
  std::size_t processed = 0, skipped = 0, failed = 0;
};

/// Adds the options that shape a templates run (--template, --no-learn, --learn-subset, --learn-best, --parts,
/// --points) to `app`, each help text after `prefix`: `templates` and `analyze` declare them once, alike.
void add_templates_run_options(CLI::App& app, templates_cli_options& o, const std::string& prefix);

/// The library's list_shape_files(dir): the .off/.obj/.ply/.stl files directly in dir, sorted.
std::vector<std::filesystem::path> shape_files_in(const std::filesystem::path& dir);

/// run_template_collection(files, out, templates read from o.template_file, options built from o): exactly what
/// `shapestruct templates` writes into OUT.
templates_run_summary run_templates_folder(const std::vector<std::filesystem::path>& files,
                                           const std::filesystem::path& out, const templates_cli_options& o,
                                           const templates_hooks& hooks);

}  // namespace shapestruct::cli
