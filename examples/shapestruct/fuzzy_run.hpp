// SPDX-License-Identifier: MIT
// The glue between `shapestruct fuzzy`'s options and the library's fuzzy pipeline, shared with
// `shapestruct analyze` (defined in cmd_fuzzy.cpp, so including this header stays cheap).
#pragma once

#include <filesystem>
#include <string>
#include <array>
#include <utility>
#include <vector>

#include "progress_display.hpp"
#include "shapestruct/core/work_share.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace shapestruct::cli {

/// The options of `shapestruct fuzzy` (defaults as documented in its --help; their ranges are checked when
/// the command line is parsed).
struct fuzzy_cli_options {
  std::string mode = "auto";  ///< auto | extrinsic | intrinsic
  long long samples = 128;
  long long threads = 0;
  long long edges_per_shape = 5;
  long long up = 1;
  double diffusion_time = 10.0;
  long long dimensions = 64;
  double weak_support = 0.8;  ///< fuzzy_collection_options::weak_support_fraction (0 = the chapter's graph)
  bool alignments_in_memory = false;  ///< keep the alignments' scores in memory rather than re-reading OUT/pairs
  long long cache_memory_mb = 2048;   ///< intrinsic_alignment_options::cache_bytes, in MiB
  bool both_feature_sets = false;     ///< intrinsic_alignment_options::both_feature_sets
  bool quiet = false;
  /// true (`shapestruct fuzzy`): collection.json holds "seconds" and iterations.tsv the seconds per step.
  /// false (`shapestruct analyze`): neither does, so the files are the same on every run; the times are
  /// returned in fuzzy_run_report instead.
  bool timings_in_results = true;
  /// Not an option: analyze's process group. Each MPI rank makes its share of the records and alignments
  /// (exchanged through OUT/records and OUT/pairs); every rank computes the rest alike; rank 0 writes.
  work_share share{};
};

/// Adds the options of a fuzzy run's graph and embedding (--samples, --edges-per-shape, --diffusion-time,
/// --dimensions, --alignments-in-memory) to `app`, each help text after `prefix`: `fuzzy` and `analyze` declare
/// them once, alike.
void add_fuzzy_run_options(CLI::App& app, fuzzy_cli_options& o, const std::string& prefix);

/// What a run reports back.
struct fuzzy_run_report {
  int exit_code = 0;  ///< 0, or 1 when fewer than two usable shapes were left
  std::string mode;   ///< "intrinsic" or "extrinsic" (empty when the run stopped before choosing)
  std::size_t shapes = 0;
  std::vector<std::pair<std::string, std::string>> skipped;  ///< (file, reason)
  double seconds_records = 0, seconds_fuzzy = 0, seconds_total = 0;
  std::vector<std::array<double, 3>> iteration_seconds;  ///< per round: align, embed, optimize
};

/// The pipeline of `shapestruct fuzzy` on `files`, writing exactly its files into `out` (see
/// timings_in_results); `input_name` only names the folder in messages.
fuzzy_run_report run_fuzzy_folder(const std::vector<std::filesystem::path>& files, const std::filesystem::path& out,
                                  const fuzzy_cli_options& o, progress_line& bar, const std::string& input_name);

}  // namespace shapestruct::cli
