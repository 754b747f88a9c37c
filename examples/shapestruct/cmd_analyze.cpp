// SPDX-License-Identifier: MIT
// shapestruct analyze: the structure of a folder of shapes in one command (issue 15): inspect every shape, learn
// part templates (as `shapestruct templates`), score them against ground truth when there is some, compute fuzzy
// correspondences (as `shapestruct fuzzy`) and write a static HTML report, each stage in its own folder of OUT,
// resumable stage by stage. docs/analyze.md documents the layout.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "command.hpp"
#include "feature_point_accuracy.hpp"
#include "file_fingerprint.hpp"
#include "fuzzy_run.hpp"
#include "option_checks.hpp"
#include "process_group.hpp"
#include "progress_display.hpp"
#include "report_fuzzy.hpp"
#include "short_faces_json.hpp"
#include "templates_run.hpp"
#include "thumbnail.hpp"
#include "shapestruct/core/check_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/eval/labeling_accuracy.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/io/file_bytes.hpp"
#include "shapestruct/io/json_file.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/segmentation_file.hpp"

namespace {

using namespace shapestruct;
namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;  // objects keep their keys in insertion order: the files are written in it
using steady = std::chrono::steady_clock;

double since(steady::time_point t) { return std::chrono::duration<double>(steady::now() - t).count(); }

/// Writes text atomically (the library's temporary file + rename), so an interrupted run never leaves half a file.
void write_atomic(const fs::path& path, const std::string& text) { io_detail::write_file_atomically(path, text); }

/// A temporary file an interrupted writer left behind: NAME.tmp (templates, thumbnails) or .NAME.tmp-... (the
/// library's write_file_atomically). Not a result: never listed or counted.
bool is_temporary(const fs::path& p) {
  const std::string name = p.filename().string();
  return p.extension() == ".tmp" || (name.rfind('.', 0) == 0 && name.find(".tmp-") != std::string::npos);
}

void write_json_atomic(const fs::path& path, const ojson& v) { write_atomic(path, format_json(v) + "\n"); }

std::string html_escape(const std::string& s) {
  std::string o;
  for (const char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string percent(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f %%", 100.0 * x);
  return b;
}

const char* stage_names[] = {"inspect", "templates", "fuzzy", "evaluate", "report"};

/// While a phase without progress reports runs (the templates' learning), redraws "STAGE: PHASE, N s" once a
/// second on a terminal, so the display never stands still; stopped by the next phase, progress or stage end.
class phase_ticker {
 public:
  explicit phase_ticker(bool quiet) : enabled_(!quiet && isatty(2) != 0) {}
  ~phase_ticker() { stop(); }
  void start(const std::string& label) {
    stop();
    if (!enabled_) return;
    running_ = true;
    thread_ = std::thread([this, label] {
      const auto t0 = steady::now();
      std::unique_lock<std::mutex> lk(m_);
      while (!cv_.wait_for(lk, std::chrono::seconds(1), [this] { return !running_; })) {
        std::fprintf(stderr, "\r%s, %.0f s spent  ", label.c_str(), since(t0));
        std::fflush(stderr);
        printed_ = true;
      }
    });
  }
  void stop() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard<std::mutex> g(m_);
      running_ = false;
    }
    cv_.notify_all();
    thread_.join();
    if (printed_) std::fprintf(stderr, "\n");
    printed_ = false;
  }

 private:
  bool enabled_;
  bool running_ = false, printed_ = false;
  std::mutex m_;
  std::condition_variable cv_;
  std::thread thread_;
};

/// One analyze run's settings.
struct analyze_settings {
  fs::path input, out, truth;
  bool truth_given = false;
  long long threads = 0;
  std::string mode = "auto";
  bool quiet = false;
  /// The processes sharing the run (MPI ranks of shapestruct-mpi): each takes its share of the shapes and
  /// pairs of every stage; rank 0 alone writes the files that sum up a stage and speaks on the terminal.
  work_share share{};
};

/// What the inspect stage decided about one shape (inspect/summary.json).
struct shape_check {
  std::string name, file;
  bool usable = false;
  std::string reason;  ///< why not usable
  bool closed_genus0 = false;
  std::string topology;  ///< one line: components, boundary, non-manifold, genus
};

// ---------------------------------------------------------------------------------------------------------------
// Stage 1: inspect. Per shape file inspect/FILE.json (the object of `shapestruct inspect --json`), and summary.json.

void run_inspect_stage(const analyze_settings& s, const std::vector<fs::path>& files, cli::progress_line& bar) {
  const fs::path dir = s.out / "inspect";
  fs::create_directories(dir);
  std::vector<shape_check> checks(files.size());
  std::mutex m;
  std::size_t done = 0;
  const check_mesh_options options{.max_examples = 10};
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < files.size(); ++i)
    if (s.share.owns(i)) mine.push_back(i);
  detail::parallel_for(mine.size(), detail::resolve_threads(static_cast<int>(s.threads), "analyze"), [&](std::size_t j) {
    const std::size_t i = mine[j];
    shape_check& c = checks[i];
    c.name = files[i].stem().string();
    c.file = files[i].filename().string();
    std::string error, report_json, short_faces_json;
    try {
      const auto mf = read_mesh(files[i]);
      const mesh_report r = check_mesh(mf.mesh, options);
      report_json = r.to_json();
      short_faces_json = cli::short_faces_json_fields(mf);  // the same keys as `shapestruct inspect --json`
      if (!r.shape_problem.empty()) c.reason = r.shape_problem;
      else if (r.num_faces == 0 || r.num_vertices == 0) c.reason = "empty: no faces";
      else if (r.num_non_finite_vertices > 0) c.reason = std::to_string(r.num_non_finite_vertices) + " non-finite vertices";
      else if (r.num_out_of_range_faces > 0) c.reason = std::to_string(r.num_out_of_range_faces) + " faces index a missing vertex";
      c.usable = c.reason.empty();
      c.closed_genus0 = r.is_closed_genus0_manifold();
      c.topology = std::to_string(r.num_components) + " component(s), " + std::to_string(r.num_boundary_edges) +
                   " boundary edges, " + std::to_string(r.num_non_manifold_edges) + " non-manifold edges, genus " +
                   std::to_string(r.genus);
    } catch (const std::bad_alloc&) {
      error = "out of memory";
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::string text;
    if (!error.empty()) {
      c.reason = "cannot be read: " + error;
      std::string esc;
      detail::json_write_string(esc, error);
      std::string fesc;
      detail::json_write_string(fesc, c.file);
      text = "{\"file\":" + fesc + ",\"ok\":false,\"error\":" + esc + "}\n";
    } else {
      std::string fesc;
      detail::json_write_string(fesc, c.file);
      text = "{\"file\":" + fesc + ",\"ok\":true," + short_faces_json + "\"report\":" + report_json + "}\n";
    }
    write_atomic(dir / (c.file + ".json"), text);  // FILE.json: two files may share a stem
    std::lock_guard<std::mutex> g(m);
    bar.update("shapes", ++done, mine.size());
  });
  bar.finish();
  if (s.share.distributed()) {
    std::vector<std::string> items;
    for (const auto i : mine) {
      const auto& c = checks[i];
      items.insert(items.end(), {std::to_string(i), c.name, c.file, c.usable ? "1" : "0", c.reason,
                                 c.closed_genus0 ? "1" : "0", c.topology});
    }
    for (const auto& message : s.share.all_gather(detail::pack_strings(items))) {
      const auto got = detail::unpack_strings(message);
      for (std::size_t k = 0; k + 6 < got.size(); k += 7) {
        shape_check& c = checks[std::stoul(got[k])];
        c.name = got[k + 1];
        c.file = got[k + 2];
        c.usable = got[k + 3] == "1";
        c.reason = got[k + 4];
        c.closed_genus0 = got[k + 5] == "1";
        c.topology = got[k + 6];
      }
    }
    if (!s.share.leader()) return;
  }
  // The later stages name their outputs by file stem: of several files with one stem, the first is used.
  std::map<std::string, std::string> first_with_stem;
  for (auto& c : checks) {
    const auto [it, fresh] = first_with_stem.emplace(c.name, c.file);
    if (!fresh && c.usable) {
      c.usable = false;
      c.reason = "has the same name as " + it->second + " (the stages name their outputs by file stem)";
    }
  }
  auto shapes = ojson::array();
  for (const auto& c : checks) {
    auto o = ojson::object({{"name", c.name}, {"file", c.file}, {"usable", c.usable}});
    if (!c.usable) o["reason"] = c.reason;
    o["closed_genus0"] = c.closed_genus0;
    o["topology"] = c.topology;
    shapes.push_back(std::move(o));
  }
  write_json_atomic(dir / "summary.json", ojson::object({{"shapes", std::move(shapes)}}));
}

std::vector<shape_check> read_inspect_summary(const fs::path& out) {
  std::vector<shape_check> v;
  const ojson j = read_json_file((out / "inspect" / "summary.json").string());
  for (const auto& e : j.at("shapes")) {
    shape_check c;
    c.name = e.at("name").get<std::string>();
    c.file = e.at("file").get<std::string>();
    c.usable = e.at("usable").get<bool>();
    if (const auto* r = json_member(e, "reason")) c.reason = r->get<std::string>();
    c.closed_genus0 = e.at("closed_genus0").get<bool>();
    c.topology = e.at("topology").get<std::string>();
    v.push_back(std::move(c));
  }
  return v;
}

// ---------------------------------------------------------------------------------------------------------------
// Stage 4: evaluate (when there is ground truth). Part labels (STEM.seg): the labeling accuracy of the templates
// stage, the protocol of bench/runners/template_eval.cpp (area-weighted, one best one-to-one label mapping for
// the whole collection, every shape weighted equally), plus the secondary figure with a mapping per shape.
// Feature points (STEM.vts / STEM.pid, as SHREC'07 and SCAPE give them): the fuzzy correspondences' error.

bool has_part_truth(const analyze_settings& s, const std::vector<shape_check>& checks) {
  for (const auto& c : checks)
    if (c.usable && fs::exists(s.truth / (c.name + ".seg"))) return true;
  return false;
}

bool has_point_truth(const analyze_settings& s, const std::vector<shape_check>& checks) {
  for (const auto& c : checks)
    if (c.usable && !cli::feature_point_file(s.truth, c.name).empty()) return true;
  return false;
}

/// evaluate/correspondence.json: feature points carried by the fuzzy correspondences (feature_point_accuracy).
void run_feature_point_evaluation(const analyze_settings& s, cli::progress_line& bar) {
  ojson o = ojson::object({{"truth", s.truth_given ? s.truth.string() : std::string("beside the shapes (DIR/STEM.vts)")},
                       {"protocol", "every ordered pair (a, b) of shapes with feature points: a's k-th feature point "
                                    "mapped by the best fuzzy correspondence, error = geodesic distance on b to b's "
                                    "k-th feature point / sqrt(area of b) (the BIM benchmark's scale), raw (no "
                                    "symmetry flips)"}});
  if (!fs::exists(s.out / "fuzzy" / "fuzzy.bin")) {
    o["not_scored"] = "the fuzzy stage produced no correspondences";
  } else {
    const auto r = cli::evaluate_feature_points(s.out / "fuzzy", s.truth, static_cast<int>(s.threads),
                                                [&](std::size_t d, std::size_t t) { bar.update("feature points", d, t); });
    bar.finish();
    o["shapes_scored"] = static_cast<long long>(r.shapes_scored);
    o["pairs"] = static_cast<long long>(r.pairs);
    o["points"] = static_cast<long long>(r.points);
    if (r.points > 0) {
      o["within_0.25"] = r.within_025;
      o["within_0.10"] = r.within_010;
      o["within_0.05"] = r.within_005;
      o["mean_error"] = r.mean;
    }
    o["shapes_without_truth"] = r.not_scored;
    auto pairs = ojson::array();
    for (const auto& p : r.per_pair)
      pairs.push_back(ojson::object({{"source", p.source}, {"target", p.target}, {"mean_error", p.mean},
                                     {"within_0.25", p.within_025}}));
    o["per_pair"] = std::move(pairs);
  }
  write_json_atomic(s.out / "evaluate" / "correspondence.json", o);
}

void run_evaluate_stage(const analyze_settings& s, const std::vector<fs::path>& files,
                        const std::vector<shape_check>& checks, cli::progress_line& bar) {
  const fs::path dir = s.out / "evaluate";
  fs::create_directories(dir);
  std::vector<labeled_shape> all;
  auto per_shape = ojson::array(), not_scored = ojson::array();
  double per_shape_sum = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    bar.update("shapes", i + 1, files.size());
    const auto& c = checks[i];
    if (!c.usable) continue;
    const fs::path pred = s.out / "templates" / (c.name + ".seg"), truth = s.truth / (c.name + ".seg");
    if (!fs::exists(truth)) {
      not_scored.push_back(ojson::object({{"name", c.name}, {"reason", "no ground truth file"}}));
      continue;
    }
    if (!fs::exists(pred)) {
      not_scored.push_back(ojson::object({{"name", c.name}, {"reason", "not labelled by the templates stage"}}));
      continue;
    }
    try {
      const auto m = read_mesh(files[i]).mesh;
      labeled_shape l;
      l.predicted = read_segmentation(pred, m.F.rows());
      l.truth = read_segmentation(truth, m.F.rows());
      const auto A = face_areas<double>(m.V, m.F, validation_level::trust);
      l.weight.assign(A.data(), A.data() + A.size());
      const double a = labeling_accuracy({l}).accuracy;
      per_shape_sum += a;
      per_shape.push_back(ojson::object({{"name", c.name}, {"accuracy_own_mapping", a}}));
      all.push_back(std::move(l));
    } catch (const std::exception& e) {
      not_scored.push_back(ojson::object({{"name", c.name}, {"reason", std::string(e.what())}}));
    }
  }
  bar.finish();
  auto o = ojson::object({{"truth", s.truth_given ? s.truth.string() : std::string("beside the shapes (DIR/STEM.seg)")},
                       {"protocol", "fraction of surface area labelled correctly after one best one-to-one mapping of "
                                    "output labels to true labels for the whole collection, every shape weighted "
                                    "equally (as bench/runners/template_eval.cpp)"},
                       {"shapes_scored", static_cast<long long>(all.size())}});
  if (!all.empty()) {
    const auto acc = labeling_accuracy(all);
    o["accuracy"] = acc.accuracy;
    o["accuracy_mapping_per_shape"] = per_shape_sum / double(all.size());
    auto mapping = ojson::array();
    for (const auto t : acc.mapping.to_truth) mapping.push_back(static_cast<long long>(t));
    o["mapping_output_to_true_label"] = std::move(mapping);
    for (std::size_t k = 0; k < per_shape.size(); ++k) per_shape[k]["accuracy"] = acc.per_shape[k];
  }
  o["per_shape"] = std::move(per_shape);
  o["not_scored"] = std::move(not_scored);
  write_json_atomic(dir / "accuracy.json", o);
}

// ---------------------------------------------------------------------------------------------------------------
// Stage 5: report. Thumbnails (report/shapes/STEM.png grey, report/parts/STEM.png by part, report/templates/T.png
// the template's boxes) and report/index.html, which needs no server: all data is in the page, except the stage
// times, which it reads from ../timings.js (a script tag) so that the page itself is the same on every run.

/// The co-aligned frame of a fitted shape (templates/STEM.fit.json): p = R (x - c) / s, then the template's up
/// axis moved to +y. Without a fit, the input frame (up axis moved to +y) centred on the bounding box.
Eigen::Matrix<double, Eigen::Dynamic, 3> view_points(const Eigen::Matrix<double, Eigen::Dynamic, 3>& V,
                                                     const fs::path& fit_file, int up) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  double s = 1;
  if (fs::exists(fit_file)) {
    try {
      const ojson j = read_json_file(fit_file.string());
      const auto& cc = j.at("canonical_center");
      for (int k = 0; k < 3; ++k) c[k] = cc.at(std::size_t(k)).get<double>();
      s = j.at("canonical_scale").get<double>();
      const auto& rot = j.at("rotation");
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) R(r, k) = rot.at(std::size_t(r)).at(std::size_t(k)).get<double>();
      if (!(s > 0) || !R.allFinite()) R.setIdentity(), c.setZero(), s = 1;
    } catch (const std::exception&) {
      R.setIdentity();
      c.setZero();
      s = 1;
    }
  }
  // Axis permutation taking the up axis to y (a rotation, so nothing is mirrored).
  Eigen::Matrix3d U = Eigen::Matrix3d::Identity();
  if (up == 2) U << 1, 0, 0, 0, 0, 1, 0, -1, 0;   // z up -> y; y -> -z
  if (up == 0) U << 0, 1, 0, 1, 0, 0, 0, 0, -1;   // x up -> y
  Eigen::Matrix<double, Eigen::Dynamic, 3> P(V.rows(), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) P.row(i) = (U * (R * ((V.row(i).transpose() - c) / s))).transpose();
  return P;
}

struct template_info {
  std::string id;
  std::vector<std::string> part_names;
  std::vector<long> labels;
  std::vector<Eigen::Vector3d> centers, sizes;
  std::vector<Eigen::Matrix3d> axes;
  int up = 1;
};

std::vector<template_info> read_template_infos(const fs::path& file) {
  std::vector<template_info> out;
  const ojson j = read_json_file(file.string());
  auto vec = [](const ojson& v) {
    return Eigen::Vector3d(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>());
  };
  for (const auto& t : j.at("templates")) {
    template_info ti;
    if (const auto* id = json_member(t, "id")) ti.id = id->get<std::string>();
    if (const auto* up = json_member(t, "up_axis")) ti.up = static_cast<int>(up->get<double>());
    for (const auto& p : t.at("parts")) {
      ti.part_names.push_back(json_member(p, "name") ? p.at("name").get<std::string>() : std::string());
      ti.labels.push_back(json_member(p, "label") ? static_cast<long>(p.at("label").get<double>()) : -1);
      ti.centers.push_back(vec(p.at("center")));
      ti.sizes.push_back(vec(p.at("size")));
      Eigen::Matrix3d ax = Eigen::Matrix3d::Identity();
      if (const auto* a = json_member(p, "axes"))
        for (int r = 0; r < 3; ++r) ax.row(r) = vec(a->at(std::size_t(r))).transpose();
      ti.axes.push_back(ax);
    }
    out.push_back(std::move(ti));
  }
  return out;
}

cli::rgb_image render_boxes(const template_info& t) {
  const std::size_t K = t.centers.size();
  Eigen::Matrix<double, Eigen::Dynamic, 3> V(Eigen::Index(8 * K), 3);
  Eigen::Matrix<long, Eigen::Dynamic, 3> F(Eigen::Index(12 * K), 3);
  std::vector<cli::rgb> colors;
  static constexpr int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (std::size_t b = 0; b < K; ++b) {
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d u((c & 1) ? 0.5 : -0.5, (c & 2) ? 0.5 : -0.5, (c & 4) ? 0.5 : -0.5);
      V.row(Eigen::Index(8 * b) + c) = (t.centers[b] + t.axes[b].transpose() * t.sizes[b].cwiseProduct(u)).transpose();
    }
    for (int q = 0; q < 6; ++q) {
      const long o = long(8 * b);
      F.row(Eigen::Index(12 * b) + 2 * q) << o + quads[q][0], o + quads[q][1], o + quads[q][2];
      F.row(Eigen::Index(12 * b) + 2 * q + 1) << o + quads[q][0], o + quads[q][2], o + quads[q][3];
      colors.push_back(cli::part_color(t.labels[b]));
      colors.push_back(cli::part_color(t.labels[b]));
    }
  }
  Eigen::Matrix3d U = Eigen::Matrix3d::Identity();
  if (t.up == 2) U << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  if (t.up == 0) U << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  for (Eigen::Index i = 0; i < V.rows(); ++i) V.row(i) = (U * V.row(i).transpose()).transpose();
  return cli::render_thumbnail(V, F, colors);
}

ojson read_json_or_null(const fs::path& p) {
  if (!fs::exists(p)) return nullptr;
  try {
    return read_json_file(p.string());
  } catch (const std::exception&) {
    return nullptr;
  }
}

/// The skipped shapes of every stage: (name or file, stage, reason).
struct skipped_shape {
  std::string shape, stage, reason;
};

std::vector<skipped_shape> collect_skipped(const analyze_settings& s, const std::vector<shape_check>& checks) {
  std::vector<skipped_shape> v;
  for (const auto& c : checks)
    if (!c.usable) v.push_back({c.file, "inspect", c.reason});
  const ojson sum = read_json_or_null(s.out / "templates" / "summary.json");
  if (sum.is_object())
    if (const auto* f = json_member(sum, "failed"))
      for (const auto& e : *f)
        v.push_back({fs::path(e.get<std::string>()).stem().string(), "templates", "could not be fitted (see the run's messages)"});
  const ojson col = read_json_or_null(s.out / "fuzzy" / "collection.json");
  if (col.is_object()) {
    if (const auto* f = json_member(col, "skipped"))
      for (const auto& e : *f)
        v.push_back({fs::path(e.at("file").get<std::string>()).stem().string(), "fuzzy", e.at("reason").get<std::string>()});
    if (const auto* d = json_member(col, "disconnected"))
      for (const auto& e : *d)
        v.push_back({e.get<std::string>(), "fuzzy", "not connected to the rest of the collection (every alignment to it was rejected)"});
  }
  return v;
}

/// Which fuzzy mode and why, from the inspect stage and (when it ran) the fuzzy stage.
std::pair<std::string, std::string> mode_and_reason(const analyze_settings& s, const std::vector<shape_check>& checks) {
  std::size_t usable = 0, not_g0 = 0;
  std::string example;
  for (const auto& c : checks) {
    if (!c.usable) continue;
    ++usable;
    if (!c.closed_genus0) {
      if (not_g0++ == 0) example = c.name + ": " + c.topology;
    }
  }
  std::string mode;
  const ojson col = read_json_or_null(s.out / "fuzzy" / "collection.json");
  if (col.is_object()) mode = col.at("mode").get<std::string>();
  std::string why;
  if (s.mode != "auto") why = "--mode " + s.mode + " was given";
  else if (not_g0 == 0) why = "--mode auto: every one of the " + std::to_string(usable) + " usable shapes is a closed genus-0 manifold";
  else
    why = "--mode auto: " + std::to_string(not_g0) + " of the " + std::to_string(usable) +
          " usable shapes are not closed genus-0 manifolds (e.g. " + example + ")";
  if (mode.empty()) mode = s.mode != "auto" ? s.mode : (not_g0 == 0 ? "intrinsic" : "extrinsic");
  return {mode, why};
}

/// Blue (0) - grey (0.5) - red (1): the variance colour map.
cli::rgb variance_color(float v) {
  const float t = std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f);
  const float lo[3] = {59, 76, 192}, mid[3] = {221, 221, 221}, hi[3] = {180, 4, 38};
  cli::rgb c;
  for (int k = 0; k < 3; ++k) {
    const float x = t < 0.5f ? lo[k] + (mid[k] - lo[k]) * (2 * t) : mid[k] + (hi[k] - mid[k]) * (2 * t - 1);
    c[std::size_t(k)] = static_cast<std::uint8_t>(std::lround(x));
  }
  return c;
}

/// For every face, the sample nearest its centroid (brute force: K is small).
std::vector<long> nearest_sample_of_faces(const triangle_mesh<double>& m, const Eigen::Matrix<double, Eigen::Dynamic, 3>& S) {
  std::vector<long> out(std::size_t(m.F.rows()), 0);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::RowVector3d c = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3.0;
    Eigen::Index best = 0;
    (S.rowwise() - c).rowwise().squaredNorm().minCoeff(&best);
    out[std::size_t(f)] = long(best);
  }
  return out;
}

/// Shapes whose colour-transfer thumbnails the report shows: the reference (shape 0 of the fuzzy collection) and
/// the next ones, up to this many in all.
constexpr std::size_t transfer_examples = 12;

void run_report_stage(const analyze_settings& s, const std::vector<fs::path>& files,
                      const std::vector<shape_check>& checks, cli::progress_line& bar) {
  const fs::path dir = s.out / "report";
  for (const char* sub : {"shapes", "parts", "templates"}) fs::create_directories(dir / sub);
  const std::vector<template_info> templates = fs::exists(s.out / "templates" / "templates.json")
                                                   ? read_template_infos(s.out / "templates" / "templates.json")
                                                   : std::vector<template_info>{};
  const int up = templates.empty() ? 1 : templates.front().up;
  // Variance and colour transfer from the fuzzy stage, when it succeeded.
  std::optional<cli::fuzzy_colours> fz;
  std::map<std::string, std::size_t> fuzzy_index;
  std::vector<cli::rgb> reference_colors;
  if (fs::exists(s.out / "fuzzy" / "fuzzy.bin")) {
    try {
      fz = cli::read_fuzzy_colours(s.out / "fuzzy", static_cast<int>(s.threads));
      for (std::size_t k = 0; k < fz->names.size(); ++k) fuzzy_index[fz->names[k]] = k;
      // The reference's samples coloured by where they lie in its bounding box (x -> red, y -> green, z -> blue).
      const auto& S = fz->samples.front();
      const Eigen::RowVector3d lo = S.colwise().minCoeff(), ext = (S.colwise().maxCoeff() - lo).cwiseMax(1e-12);
      for (Eigen::Index i = 0; i < S.rows(); ++i) {
        const Eigen::RowVector3d t = (S.row(i) - lo).cwiseQuotient(ext);
        reference_colors.push_back({static_cast<std::uint8_t>(std::lround(30 + 210 * t[0])),
                                    static_cast<std::uint8_t>(std::lround(30 + 210 * t[1])),
                                    static_cast<std::uint8_t>(std::lround(30 + 210 * t[2]))});
      }
      fs::create_directories(dir / "variance");
      fs::create_directories(dir / "transfer");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "analyze: report: no variance or correspondences: %s\n", e.what());
      fz.reset();
    }
  }
  std::vector<char> has_variance(files.size(), 0), has_transfer(files.size(), 0);
  // Thumbnails, in parallel.
  std::vector<char> has_parts(files.size(), 0), has_shape(files.size(), 0);
  std::mutex m;
  std::size_t done = 0;
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < files.size(); ++i)
    if (s.share.owns(i)) mine.push_back(i);
  detail::parallel_for(mine.size(), detail::resolve_threads(static_cast<int>(s.threads), "analyze"), [&](std::size_t j) {
    const std::size_t i = mine[j];
    const auto& c = checks[i];
    if (c.usable) {
      try {
        const auto mesh = read_mesh(files[i]).mesh;
        const auto P = view_points(mesh.V, s.out / "templates" / (c.name + ".fit.json"), up);
        const Eigen::Matrix<long, Eigen::Dynamic, 3> F = mesh.F.cast<long>();
        cli::write_png(dir / "shapes" / (c.name + ".png"),
                       cli::render_thumbnail(P, F, std::vector<cli::rgb>(std::size_t(F.rows()), cli::rgb{200, 200, 205})));
        has_shape[i] = 1;
        const fs::path seg = s.out / "templates" / (c.name + ".seg");
        if (fs::exists(seg)) {
          const auto labels = read_segmentation(seg, mesh.F.rows());
          std::vector<cli::rgb> colors;
          colors.reserve(labels.size());
          for (const auto l : labels) colors.push_back(cli::part_color(long(l)));
          cli::write_png(dir / "parts" / (c.name + ".png"), cli::render_thumbnail(P, F, colors));
          has_parts[i] = 1;
        }
        if (fz && fuzzy_index.count(c.name)) {
          const std::size_t k = fuzzy_index.at(c.name);
          const auto near = nearest_sample_of_faces(mesh, fz->samples[k]);
          std::vector<cli::rgb> vc(near.size());
          for (std::size_t f = 0; f < near.size(); ++f) vc[f] = variance_color(fz->variance[k][std::size_t(near[f])]);
          cli::write_png(dir / "variance" / (c.name + ".png"), cli::render_thumbnail(P, F, vc));
          has_variance[i] = 1;
          if (k < transfer_examples) {
            for (std::size_t f = 0; f < near.size(); ++f)
              vc[f] = reference_colors[std::size_t(fz->to_reference[k][std::size_t(near[f])])];
            cli::write_png(dir / "transfer" / (c.name + ".png"), cli::render_thumbnail(P, F, vc));
            has_transfer[i] = 1;
          }
        }
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> g(m);
        std::fprintf(stderr, "\ranalyze: report: no thumbnail of %s: %s\n", c.name.c_str(), e.what());
      }
    }
    std::lock_guard<std::mutex> g(m);
    bar.update("thumbnails", ++done, mine.size());
  });
  bar.finish();
  if (s.share.distributed()) {
    std::vector<std::string> items;
    for (const auto i : mine)
      items.push_back(std::to_string(i) + " " + char('0' + has_shape[i]) + char('0' + has_parts[i]) +
                      char('0' + has_variance[i]) + char('0' + has_transfer[i]));
    for (const auto& message : s.share.all_gather(detail::pack_strings(items)))
      for (const auto& item : detail::unpack_strings(message)) {
        const std::size_t space = item.find(' ');
        const std::size_t i = std::stoul(item.substr(0, space));
        has_shape[i] = char(item[space + 1] - '0');
        has_parts[i] = char(item[space + 2] - '0');
        has_variance[i] = char(item[space + 3] - '0');
        has_transfer[i] = char(item[space + 4] - '0');
      }
    if (!s.share.leader()) return;
  }
  for (std::size_t t = 0; t < templates.size(); ++t)
    cli::write_png(dir / "templates" / ("template_" + std::to_string(t) + ".png"), render_boxes(templates[t]));

  // Data for the page.
  std::map<std::string, long> cluster_of;
  const ojson sum = read_json_or_null(s.out / "templates" / "summary.json");
  std::vector<std::vector<std::string>> members(templates.size());
  if (sum.is_object())
    for (const auto& cl : sum.at("clusters")) {
      const auto t = static_cast<std::size_t>(cl.at("template").get<double>());
      for (const auto& mname : cl.at("members")) {
        cluster_of[mname.get<std::string>()] = long(t);
        if (t < members.size()) members[t].push_back(mname.get<std::string>());
      }
    }
  const ojson acc = read_json_or_null(s.out / "evaluate" / "accuracy.json");
  std::map<std::string, double> shape_acc;
  if (acc.is_object())
    for (const auto& e : acc.at("per_shape"))
      if (const auto* a = json_member(e, "accuracy")) shape_acc[e.at("name").get<std::string>()] = a->get<double>();
  const auto [mode, why] = mode_and_reason(s, checks);
  const ojson col = read_json_or_null(s.out / "fuzzy" / "collection.json");
  const auto skipped = collect_skipped(s, checks);
  std::set<long> labels_used;
  for (const auto& t : templates)
    for (const auto l : t.labels) labels_used.insert(l);

  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<title>shapestruct analyze: " << html_escape(s.input.filename().string()) << "</title>\n"
    << "<style>\nbody{font-family:sans-serif;margin:1.5em;color:#222}\nh2{border-bottom:1px solid #ccc;padding-bottom:.2em}\n"
    << ".grid{display:flex;flex-wrap:wrap;gap:10px}\n.card{border:1px solid #ddd;border-radius:4px;padding:4px;text-align:center;font-size:12px;width:330px}\n"
    << ".card img{width:160px;height:160px}\n.tpl{width:auto}\n.tpl img{width:160px;height:160px}\n"
    << "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:3px 8px;text-align:left}\n"
    << ".sw{display:inline-block;width:12px;height:12px;margin-right:4px;vertical-align:middle}\n.members{max-width:1000px}\n"
    << ".big{font-size:1.3em}\n</style>\n</head>\n<body>\n";
  std::size_t usable = 0;
  for (const auto& c : checks) usable += c.usable ? 1 : 0;
  h << "<h1>Structure of <code>" << html_escape(s.input.string()) << "</code></h1>\n";
  h << "<p>" << checks.size() << " shape files, " << usable << " usable; " << templates.size()
    << " learned template(s); fuzzy correspondences in <b>" << mode << "</b> mode (" << html_escape(why) << ").</p>\n";
  if (acc.is_object() && json_member(acc, "accuracy")) {
    h << "<p class=\"big\" id=\"accuracy\">Part-labeling accuracy against the ground truth: <b>"
      << percent(acc.at("accuracy").get<double>()) << "</b> (" << static_cast<long long>(acc.at("shapes_scored").get<double>())
      << " shapes; " << html_escape(acc.at("protocol").get<std::string>()) << "; with a mapping per shape: "
      << percent(acc.at("accuracy_mapping_per_shape").get<double>()) << ").</p>\n";
  } else {
    h << "<p id=\"accuracy\">No part-label ground truth (no <code>STEM.seg</code> beside the shapes and no "
         "<code>--truth</code>): part-labeling accuracy not measured.</p>\n";
  }
  const ojson corr = read_json_or_null(s.out / "evaluate" / "correspondence.json");
  if (corr.is_object() && json_member(corr, "within_0.25")) {
    h << "<p class=\"big\" id=\"correspondence-accuracy\">Correspondence accuracy against the ground-truth feature "
         "points: <b>" << percent(corr.at("within_0.25").get<double>()) << "</b> within 0.25 &radic;area (within 0.10: "
      << percent(corr.at("within_0.10").get<double>()) << "; mean error " << corr.at("mean_error").get<double>()
      << "; " << corr.at("pairs").get<long long>() << " ordered pairs; "
      << html_escape(corr.at("protocol").get<std::string>()) << ").</p>\n";
  }
  h << "<p>Files: <a href=\"../manifest.json\">manifest.json</a> (what every file is), "
    << "<a href=\"../templates/templates.json\">templates.json</a>";
  if (col.is_object()) h << ", <a href=\"../fuzzy/collection.json\">fuzzy/collection.json</a>";
  h << ". Explore the correspondences interactively with <code>shapestruct explore " << html_escape((s.out / "fuzzy").string())
    << "</code>.</p>\n";

  h << "<h2>Time of each stage</h2>\n<table id=\"timings\"><tr><th>stage</th><th>seconds</th></tr></table>\n"
    << "<p id=\"timings-note\">Seconds of the run that finished each stage (a stage resumed after an interruption "
       "counts its last run only), from <code>../timings.json</code> (loaded from <code>../timings.js</code>).</p>\n";

  h << "<h2>Part labels</h2>\n<p>";
  for (const long l : labels_used) {
    const auto c = cli::part_color(l);
    std::string names;
    for (const auto& t : templates)
      for (std::size_t b = 0; b < t.labels.size(); ++b)
        if (t.labels[b] == l && names.find(t.part_names[b]) == std::string::npos)
          names += (names.empty() ? "" : ", ") + t.part_names[b];
    char sw[64];
    std::snprintf(sw, sizeof sw, "#%02x%02x%02x", c[0], c[1], c[2]);
    h << "<span class=\"sw\" style=\"background:" << sw << "\"></span>label " << l << " (" << html_escape(names) << ") &nbsp; ";
  }
  h << "</p>\n";

  h << "<h2>Learned templates and their clusters</h2>\n";
  for (std::size_t t = 0; t < templates.size(); ++t) {
    h << "<h3>Template " << t << ": " << html_escape(templates[t].id) << " (" << members[t].size() << " shapes)</h3>\n";
    h << "<div class=\"grid\"><div class=\"card tpl\"><img src=\"templates/template_" << t
      << ".png\" alt=\"template " << t << " boxes\"><br>the template's boxes<br>" << templates[t].centers.size()
      << " parts</div>\n<div class=\"members\">";
    for (const auto& mname : members[t]) {
      if (fs::exists(dir / "parts" / (mname + ".png")))
        h << "<img src=\"parts/" << html_escape(mname) << ".png\" width=\"80\" height=\"80\" title=\"" << html_escape(mname)
          << "\" alt=\"" << html_escape(mname) << "\">";
    }
    h << "</div></div>\n";
  }

  h << "<h2>The collection</h2>\n<p>Each shape in the co-aligned frame of its template: as it is, and coloured by "
       "the part labels of the templates stage (<code>templates/STEM.seg</code>).</p>\n<div class=\"grid\">\n";
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto& c = checks[i];
    if (!c.usable) continue;
    h << "<div class=\"card\" id=\"shape-" << html_escape(c.name) << "\">";
    if (has_shape[i]) h << "<img src=\"shapes/" << html_escape(c.name) << ".png\" alt=\"" << html_escape(c.name) << "\">";
    if (has_parts[i]) h << "<img src=\"parts/" << html_escape(c.name) << ".png\" alt=\"" << html_escape(c.name) << " by part\">";
    h << "<br><b>" << html_escape(c.name) << "</b>";
    if (cluster_of.count(c.name)) h << " &middot; template " << cluster_of[c.name];
    if (shape_acc.count(c.name)) h << " &middot; accuracy " << percent(shape_acc[c.name]);
    h << "</div>\n";
  }
  h << "</div>\n";

  if (fz) {
    h << "<h2>Where the collection varies</h2>\n<p>Every shape coloured by the variance of its fuzzy-correspondence "
         "samples (chapter 4.5.1, <code>sample_variance</code>): blue where its points have close counterparts on the "
         "other shapes, red where it differs most from them (1 = the shape's largest value).</p>\n<div class=\"grid\">";
    for (std::size_t i = 0; i < files.size(); ++i)
      if (has_variance[i])
        h << "<img src=\"variance/" << html_escape(checks[i].name) << ".png\" width=\"110\" height=\"110\" title=\""
          << html_escape(checks[i].name) << "\" alt=\"" << html_escape(checks[i].name) << " by variance\">";
    h << "</div>\n<h2>Correspondences by colour transfer</h2>\n<p>The reference shape <b>"
      << html_escape(fz->names.front()) << "</b> is coloured by position (x red, y green, z blue); every other shape "
      << "takes, at each point, the colour of its best fuzzy correspondence on the reference. The first "
      << transfer_examples << " shapes of the fuzzy collection.</p>\n<div class=\"grid\">";
    for (std::size_t i = 0; i < files.size(); ++i)
      if (has_transfer[i])
        h << "<div class=\"card tpl\"><img src=\"transfer/" << html_escape(checks[i].name) << ".png\" alt=\""
          << html_escape(checks[i].name) << " colour transfer\"><br>" << html_escape(checks[i].name)
          << (fuzzy_index.count(checks[i].name) && fuzzy_index.at(checks[i].name) == 0 ? " (reference)" : "") << "</div>";
    h << "</div>\n";
  }
  h << "<h2>Skipped shapes</h2>\n";
  if (skipped.empty()) {
    h << "<p id=\"skipped\">None: every shape went through every stage.</p>\n";
  } else {
    h << "<table id=\"skipped\"><tr><th>shape</th><th>stage</th><th>reason</th></tr>\n";
    for (const auto& k : skipped)
      h << "<tr><td>" << html_escape(k.shape) << "</td><td>" << k.stage << "</td><td>" << html_escape(k.reason) << "</td></tr>\n";
    h << "</table>\n";
  }
  if (col.is_object()) {
    h << "<h2>Fuzzy correspondences</h2>\n<p>" << static_cast<long long>(col.at("shapes").size())
      << " shapes, " << static_cast<long long>(col.at("pairs_aligned").get<double>()) << " of "
      << static_cast<long long>(col.at("pairs_total").get<double>()) << " pairs aligned, "
      << static_cast<long long>(col.at("iterations").get<double>()) << " graph optimisation round(s)"
      << (col.at("converged").get<bool>() ? " (converged)" : "") << ". Regions of interest, other reference shapes "
      << "and maps between any two shapes: <code>shapestruct explore</code>.</p>\n";
  }
  h << "<script src=\"../timings.js\"></script>\n<script>\n"
    << "(function(){var t=window.SHAPESTRUCT_TIMINGS;if(!t)return;var tb=document.getElementById('timings');\n"
    << "var total=0;for(var i=0;i<t.stages.length;i++){var s=t.stages[i];var r=tb.insertRow();r.insertCell().textContent=s.stage;\n"
    << "r.insertCell().textContent=(s.seconds===null?'not run':s.seconds.toFixed(1));if(s.seconds)total+=s.seconds;}\n"
    << "var r=tb.insertRow();r.insertCell().innerHTML='<b>total</b>';r.insertCell().innerHTML='<b>'+total.toFixed(1)+'</b>';})();\n"
    // A self-check a headless browser can read back (tests/cli/analyze_smoke.cmake): images loaded and broken.
    << "window.addEventListener('load',function(){var im=document.images,bad=0;for(var i=0;i<im.length;i++)\n"
    << "if(!im[i].complete||im[i].naturalWidth===0)bad++;document.body.setAttribute('data-images',im.length);\n"
    << "document.body.setAttribute('data-broken-images',bad);});\n"
    << "</script>\n</body>\n</html>\n";
  write_atomic(dir / "index.html", h.str());
}

// ---------------------------------------------------------------------------------------------------------------
// Manifest, timings.

std::string describe(const std::string& rel) {
  auto ends = [&](const std::string& suf) { return rel.size() >= suf.size() && rel.compare(rel.size() - suf.size(), suf.size(), suf) == 0; };
  auto starts = [&](const std::string& pre) { return rel.rfind(pre, 0) == 0; };
  if (ends("/.settings.json")) return "what the stage was made with (shape files, options): a rerun with others is refused";
  if (rel == "inspect/summary.json") return "per shape: usable or not (and why), closed genus-0 or not, topology in one line";
  if (starts("inspect/")) return "check_mesh report of one shape: the object `shapestruct inspect --json` prints for it";
  if (rel == "templates/templates.json") return "the learned template set (`shapestruct templates --template` reads it)";
  if (rel == "templates/summary.json") return "clusters (members of each template) and shapes that could not be fitted";
  if (starts("templates/") && ends(".fit.json")) return "template (cluster), energy, rigid transform, per-part deformation of one shape";
  if (starts("templates/") && ends(".points.txt")) return "per sample point: label, template correspondence, co-aligned positions";
  if (starts("templates/") && ends(".seg")) return "one 0-based part label per face of the input shape";
  if (rel == "templates/ply") return "faces coloured by part (STEM.ply) and the fitted boxes (STEM.boxes.ply) per shape";
  if (rel == "evaluate/accuracy.json") return "part-labeling accuracy of the templates stage against the ground truth";
  if (rel == "evaluate/correspondence.json")
    return "feature-point error of the fuzzy correspondences against the ground truth (geodesic / sqrt(area))";
  if (rel == "fuzzy/collection.json") return "fuzzy collection: mode, samples, shapes, skipped, pairs aligned, rounds";
  if (rel == "fuzzy/samples.txt") return "the K samples of every shape";
  if (rel == "fuzzy/graph.txt") return "the final alignment graph";
  if (rel == "fuzzy/iterations.tsv") return "per graph optimisation round: edges, switches, pruned, added (of which for weakly supported shapes), consistency";
  if (rel == "fuzzy/fuzzy.bin") return "the diffusion embedding and widths tau defining the fuzzy correspondences";
  if (rel == "fuzzy/cache.json") return "what the resume caches were made with (a rerun with other settings is refused)";
  if (rel == "fuzzy/records") return "resume cache: one shape record per shape (NAME.rec)";
  if (rel == "fuzzy/pairs") return "resume cache: one pairwise alignment per aligned pair (A__B.align)";
  if (rel == "report/index.html") return "the report: open it in a browser from disk";
  if (starts("report/shapes/")) return "thumbnail of one shape (co-aligned frame)";
  if (starts("report/parts/")) return "thumbnail of one shape coloured by its part labels";
  if (starts("report/templates/")) return "thumbnail of one template's boxes coloured by label";
  if (starts("report/variance/")) return "thumbnail of one shape coloured by the variance of its fuzzy samples";
  if (starts("report/transfer/")) return "thumbnail of one shape coloured by colour transfer from the reference shape";
  if (ends("/.done")) return "stage completion marker (written last, atomically): a rerun skips the stage";
  return "written by the stage";
}

/// Every file and folder under OUT (sorted), except the resume caches' and PLY files (listed as folders with a
/// count), temporaries, manifest.json and the timing files.
ojson list_outputs(const fs::path& out) {
  std::vector<std::string> files;
  std::map<std::string, long long> folders;
  const std::set<std::string> collapsed = {"fuzzy/records", "fuzzy/pairs", "templates/ply"};
  for (auto it = fs::recursive_directory_iterator(out); it != fs::recursive_directory_iterator(); ++it) {
    const std::string rel = fs::relative(it->path(), out).generic_string();
    if (it->is_directory()) {
      if (collapsed.count(rel)) {
        long long n = 0;
        for (const auto& e : fs::directory_iterator(it->path()))
          if (e.is_regular_file() && !is_temporary(e.path())) ++n;
        folders[rel] = n;
        it.disable_recursion_pending();
      }
      continue;
    }
    if (rel == "manifest.json" || rel == "timings.json" || rel == "timings.js" || is_temporary(it->path())) continue;
    files.push_back(rel);
  }
  std::sort(files.begin(), files.end());
  auto a = ojson::array();
  for (const auto& f : files) a.push_back(ojson::object({{"path", f}, {"what", describe(f)}}));
  for (const auto& [f, n] : folders) a.push_back(ojson::object({{"folder", f}, {"files", n}, {"what", describe(f)}}));
  return a;
}

/// timings.json: {"stages": [{"stage", "seconds" (null: not run yet)}]}; the seconds of the run that finished a
/// stage are kept by later runs that skip it. timings.js holds the same for the report page.
struct timings_file {
  std::map<std::string, double> seconds;
  void load(const fs::path& out) {
    const ojson j = read_json_or_null(out / "timings.json");
    if (!j.is_object()) return;
    for (const auto& e : j.at("stages"))
      if (json_member(e, "seconds") && json_member(e, "seconds")->is_number()) seconds[e.at("stage").get<std::string>()] = e.at("seconds").get<double>();
  }
  void save(const fs::path& out) const {
    auto a = ojson::array();
    for (const char* st : stage_names) {
      const auto it = seconds.find(st);
      a.push_back(ojson::object({{"stage", st}, {"seconds", it == seconds.end() ? ojson(nullptr) : ojson(it->second)}}));
    }
    const ojson j = ojson::object({{"stages", std::move(a)}});
    write_json_atomic(out / "timings.json", j);
    write_atomic(out / "timings.js", "window.SHAPESTRUCT_TIMINGS = " + format_json(j, 0) + ";\n");
  }
};

/// What each stage's results depend on, recorded in OUT/STAGE/.settings.json when the stage starts. A rerun into
/// the same OUT with other shapes or options would otherwise skip finished stages (or resume half-done ones) and
/// mix old results with new ones without a word, so it is refused before anything is written, naming the option.
/// The values are fingerprints (file names, sizes and content hashes), not paths: the same input moved or named
/// by another relative path is the same input.
class stage_settings {
 public:
  stage_settings(const analyze_settings& s, const std::vector<fs::path>& shape_files,
                 const cli::templates_cli_options& t, const cli::fuzzy_cli_options& f) {
    const ojson shapes = files_fingerprint(shape_files);
    const ojson templ = t.template_file.empty() ? ojson("automatic") : ojson(fingerprint(t.template_file));
    std::vector<fs::path> truth_files;
    if (fs::is_directory(s.truth))
      for (const auto& e : fs::directory_iterator(s.truth))
        if (e.is_regular_file() && (e.path().extension() == ".seg" || e.path().extension() == ".vts" ||
                                    e.path().extension() == ".pid"))
          truth_files.push_back(e.path());
    std::sort(truth_files.begin(), truth_files.end());
    auto templates = ojson::object({{"shapes", shapes},
                                    {"template", templ},
                                    {"learn_subset", t.learn_subset},
                                    {"learn_best", t.learn_best},
                                    {"no_learn", t.no_learn},
                                    {"parts", t.parts},
                                    {"points", t.points},
                                    {"up", t.up}});
    auto fuzzy = ojson::object({{"shapes", shapes},
                                {"mode", f.mode},
                                {"samples", f.samples},
                                {"edges_per_shape", f.edges_per_shape},
                                {"diffusion_time", f.diffusion_time},
                                {"dimensions", f.dimensions},
                                {"weak_support", f.weak_support},
                                {"up", f.up}});
    wanted_["inspect"] = ojson::object({{"shapes", shapes}});
    wanted_["templates"] = templates;
    wanted_["fuzzy"] = fuzzy;
    ojson all = templates;
    for (const auto& [k, v] : fuzzy.items()) all[k] = v;
    all["truth"] = files_fingerprint(truth_files);
    wanted_["evaluate"] = all;
    wanted_["report"] = all;
  }

  /// Throws cli::usage_error at the first setting a stage folder of `out` was made with that this run changes.
  void check(const fs::path& out) const {
    for (const char* st : stage_names) {
      const ojson stored = read_json_or_null(out / st / ".settings.json");
      if (!stored.is_object()) continue;
      for (const auto& [key, value] : wanted_.at(st).items()) {
        const ojson* old = json_member(stored, key);
        if (old && *old == value) continue;
        std::string stale;
        for (const char* later : stage_names) {
          const ojson o = read_json_or_null(out / later / ".settings.json");
          const ojson* v = o.is_object() ? json_member(o, key) : nullptr;
          if (v && *v != value) stale += std::string(stale.empty() ? "" : ", ") + later + "/";
        }
        throw cli::usage_error((out / st).string() + " was made with " + what_differs(key, old, value) +
                               ". Use another output folder, or delete " + stale + " there to make " +
                               (stale.find(',') == std::string::npos ? "it" : "them") + " again");
      }
    }
  }

  /// Records what `stage` is made with (before its body runs, so that a half-done stage is covered too).
  void record(const fs::path& out, const std::string& stage) const {
    if (!fs::exists(out / stage / ".settings.json")) write_json_atomic(out / stage / ".settings.json", wanted_.at(stage));
  }

 private:
  static ojson files_fingerprint(const std::vector<fs::path>& files) {
    auto a = ojson::array();
    for (const auto& f : files) a.push_back(ojson::object({{"file", f.filename().string()}, {"is", fingerprint(f)}}));
    return a;
  }
  static std::string fingerprint(const fs::path& f) {
    try {
      return cli::file_fingerprint(f);
    } catch (const io_error&) {
      return "unreadable";  // the inspect stage reports it and skips the shape
    }
  }
  static std::string what_differs(const std::string& key, const ojson* old, const ojson& now) {
    if (key == "shapes") {
      std::map<std::string, std::string> then, here;
      for (const auto& e : old ? *old : ojson::array()) then[e.at("file").get<std::string>()] = e.at("is").get<std::string>();
      for (const auto& e : now) here[e.at("file").get<std::string>()] = e.at("is").get<std::string>();
      for (const auto& [f, b] : here) {
        const auto it = then.find(f);
        if (it == then.end()) return "other shape files (" + f + " is new in DIR)";
        if (it->second != b) return "other shape files (" + f + " was " + it->second + ", is now " + b + ")";
      }
      for (const auto& [f, b] : then)
        if (!here.count(f)) return "other shape files (" + f + " is no longer in DIR)";
      return "other shape files";
    }
    if (key == "truth") return "other ground truth (STEM.seg / STEM.vts / STEM.pid files, option --truth)";
    std::string flag = "--" + key;  // the option's name: the key with dashes
    std::replace(flag.begin(), flag.end(), '_', '-');
    const std::string was = old ? old->dump() : std::string("(not recorded)");
    return flag + " " + was + "; this run asks for " + now.dump() + " (option " + flag + ")";
  }
  std::map<std::string, ojson> wanted_;
};

/// The command line of `shapestruct analyze`.
struct analyze_command_line {
  std::string input, out, truth, mode = "auto";
  long long threads = 0;
  long long up = 1;
  cli::templates_cli_options templates;  // the templates stage's options analyze passes on
  cli::fuzzy_cli_options fuzzy;          // the fuzzy stage's
  bool quiet = false;
};

int run_analyze(const analyze_command_line& c) {
  analyze_settings s;
  s.out = c.out;
  s.threads = c.threads;
  s.mode = c.mode;
  const std::string& truth = c.truth;
  cli::templates_cli_options topt = c.templates;
  topt.up = c.up;
  s.quiet = c.quiet;
  s.input = c.input;
  s.share = cli::run_share();
  s.quiet = s.quiet || !s.share.leader();  // one progress display: rank 0's
  s.truth_given = !truth.empty();
  s.truth = s.truth_given ? fs::path(truth) : s.input;
  if (s.truth_given && !fs::is_directory(s.truth)) throw cli::usage_error("--truth " + truth + " is not a folder");
  topt.threads = s.threads;
  topt.share = s.share;
  cli::fuzzy_cli_options fopt = c.fuzzy;
  fopt.up = c.up;
  fopt.mode = s.mode;
  fopt.threads = s.threads;
  fopt.quiet = s.quiet;
  fopt.timings_in_results = false;
  fopt.share = s.share;
  const auto all_files = cli::shape_files_in(s.input);
  if (all_files.empty()) throw cli::usage_error("no .off/.obj/.ply/.stl files in " + c.input);
  if (topt.no_learn && topt.template_file.empty())
    throw cli::usage_error("--no-learn labels with the given templates as they are: it needs --template T.json");
  const stage_settings settings(s, all_files, topt, fopt);
  if (fs::is_directory(s.out)) settings.check(s.out);  // before anything in OUT is touched
  fs::create_directories(s.out);
  // Temporaries of writes cut short by an interruption (never listed, never read): cleared before any rank writes.
  if (s.share.leader())
    for (auto it = fs::recursive_directory_iterator(s.out); it != fs::recursive_directory_iterator(); ++it)
      if (it->is_regular_file() && is_temporary(it->path())) fs::remove(it->path());
  timings_file timings;
  timings.load(s.out);
  const auto t_run = steady::now();
  auto say = [&](const std::string& m) {
    if (!s.quiet) std::fprintf(stderr, "analyze: %s\n", m.c_str());
  };
  int stage_no = 0;
  // Runs a stage unless OUT/<stage>/.done exists; .done is written last, atomically, with the stage's status.
  // With several processes, rank 0's view of .done decides for all, and every rank finishes the body (the
  // exchange below) before rank 0 marks the stage done.
  const bool leader = s.share.leader();
  auto stage = [&](const std::string& name, const std::function<std::string()>& body) {
    ++stage_no;
    const fs::path done = s.out / name / ".done";
    if (s.share.all_gather(fs::exists(done) ? "done" : "").front() == "done") {
      say("stage " + std::to_string(stage_no) + "/5 " + name + ": already done (" + (s.out / name).string() + "), skipped");
      return;
    }
    say("stage " + std::to_string(stage_no) + "/5 " + name);
    const auto t0 = steady::now();
    fs::create_directories(s.out / name);
    if (leader) settings.record(s.out, name);
    const std::string status = body();
    (void)s.share.all_gather({});
    if (!leader) return;
    write_atomic(done, status + "\n");
    timings.seconds[name] = since(t0);
    timings.save(s.out);
    say(name + ": " + status + " (" + std::to_string(static_cast<long long>(std::lround(timings.seconds[name]))) + " s)");
  };

  // 1. inspect
  stage("inspect", [&] {
    cli::progress_line bar(s.quiet, "inspect/");
    run_inspect_stage(s, all_files, bar);
    return std::string("done");
  });
  const auto checks = read_inspect_summary(s.out);
  if (checks.size() != all_files.size())
    throw io_error(file_error::bad_value, (s.out / "inspect" / "summary.json").string(), 0, 0,
                   "lists " + std::to_string(checks.size()) + " shapes but the input folder has " +
                       std::to_string(all_files.size()) + " (the input changed: analyze into a new OUT)");
  std::vector<fs::path> usable;
  for (std::size_t i = 0; i < all_files.size(); ++i)
    if (checks[i].usable) usable.push_back(all_files[i]);
    else if (leader) std::fprintf(stderr, "analyze: skipped %s: %s\n", checks[i].file.c_str(), checks[i].reason.c_str());
  if (usable.empty()) {
    if (leader) std::fprintf(stderr, "analyze: no usable shape in %s\n", c.input.c_str());
    return 1;
  }

  // 2. templates
  stage("templates", [&] {
    cli::progress_line bar(s.quiet, "templates/");
    phase_ticker ticker(s.quiet);
    cli::templates_hooks hooks;
    hooks.phase = [&](const std::string& m) {
      ticker.stop();
      bar.finish();
      say("templates: " + m);
      if (m.rfind("labeling", 0) != 0) ticker.start("templates: " + m);  // labeling reports its own progress
    };
    hooks.problem = [&](const std::string& f, const std::string& m) { if (leader) std::fprintf(stderr, "\ranalyze: templates: skipped %s: %s\n", f.c_str(), m.c_str()); };
    hooks.progress = [&](std::size_t d, std::size_t t) { bar.update("labeling", d, t); };
    hooks.candidates = [&](std::size_t d, std::size_t t) {
      ticker.stop();
      bar.update("candidate templates", d, t);
      if (d == t) {
        bar.finish();
        ticker.start("templates: learning from the best candidates");
      }
    };
    hooks.learning_round = [&](int round, int rounds) {  // time left: an upper bound, learning may converge early
      ticker.stop();
      bar.update("learning rounds (at most)", static_cast<std::size_t>(round), static_cast<std::size_t>(rounds));
    };
    const auto sum = cli::run_templates_folder(usable, s.out / "templates", topt, hooks);
    ticker.stop();
    bar.finish();
    return std::to_string(sum.template_ids.size()) + " template(s), " + std::to_string(sum.processed + sum.skipped) +
           " shapes labelled, " + std::to_string(sum.failed) + " failed";
  });

  // 3. fuzzy
  stage("fuzzy", [&] {
    const auto [mode, why] = mode_and_reason(s, checks);
    say("fuzzy: " + (s.mode == "auto" ? std::string("expecting ") + mode + " mode: " : std::string()) + why);
    cli::progress_line bar(s.quiet, "fuzzy/");
    const auto r = cli::run_fuzzy_folder(usable, s.out / "fuzzy", fopt, bar, c.input);
    if (r.exit_code != 0) return std::string("failed: fewer than two usable shapes, no correspondences");
    return r.mode + " mode, " + std::to_string(r.shapes) + " shapes";
  });

  // 4. evaluate (only with ground truth; small: one process)
  const bool part_truth = has_part_truth(s, checks), point_truth = has_point_truth(s, checks);
  if (part_truth || point_truth) {
    stage("evaluate", [&] {
      cli::progress_line bar(s.quiet, "evaluate/");
      if (leader && part_truth) run_evaluate_stage(s, all_files, checks, bar);
      if (leader && point_truth) run_feature_point_evaluation(s, bar);
      return std::string(part_truth && point_truth ? "part labels and feature points"
                         : part_truth              ? "part labels"
                                                   : "feature points");
    });
  } else {
    ++stage_no;
    say("stage 4/5 evaluate: no ground truth (no STEM.seg or STEM.vts beside the shapes, no --truth): accuracy not "
        "measured");
  }

  // 5. report
  stage("report", [&] {
    cli::progress_line bar(s.quiet, "report/");
    run_report_stage(s, all_files, checks, bar);
    return std::string("done");
  });

  if (!leader) return 0;
  // Manifest (the same on every run: no times in it) and the summary on the terminal.
  const auto [mode, why] = mode_and_reason(s, checks);
  const auto skipped = collect_skipped(s, checks);
  const ojson acc = read_json_or_null(s.out / "evaluate" / "accuracy.json");
  auto stages = ojson::array();
  for (const char* st : stage_names) {
    std::string status = "not run (no ground truth)";
    std::ifstream in(s.out / st / ".done");
    if (in) std::getline(in, status);
    stages.push_back(ojson::object({{"stage", st}, {"folder", std::string(st) + "/"}, {"status", status}}));
  }
  auto skipped_json = ojson::array();
  for (const auto& k : skipped)
    skipped_json.push_back(ojson::object({{"shape", k.shape}, {"stage", k.stage}, {"reason", k.reason}}));
  auto manifest = ojson::object({
      {"tool", "shapestruct analyze"},
      {"input", s.input.string()},
      {"shape_files", static_cast<long long>(all_files.size())},
      {"usable_shapes", static_cast<long long>(usable.size())},
      {"stages", std::move(stages)},
      {"stage_seconds", "in timings.json (kept apart so that every other file is the same on every run)"},
      {"fuzzy_mode", mode},
      {"fuzzy_mode_reason", why},
      {"skipped", std::move(skipped_json)}});
  if (acc.is_object() && json_member(acc, "accuracy"))
    manifest["accuracy"] = ojson::object({{"value", acc.at("accuracy").get<double>()},
                                          {"shapes", acc.at("shapes_scored")},
                                          {"truth", acc.at("truth").get<std::string>()},
                                          {"protocol", acc.at("protocol").get<std::string>()},
                                          {"details", "evaluate/accuracy.json"}});
  else
    manifest["accuracy"] = nullptr;
  const ojson corr = read_json_or_null(s.out / "evaluate" / "correspondence.json");
  const bool corr_scored = corr.is_object() && json_member(corr, "within_0.25");
  if (corr_scored)
    manifest["correspondence_accuracy"] = ojson::object({{"within_0.25", corr.at("within_0.25").get<double>()},
                                                         {"mean_error", corr.at("mean_error").get<double>()},
                                                         {"pairs", corr.at("pairs")},
                                                         {"details", "evaluate/correspondence.json"}});
  else
    manifest["correspondence_accuracy"] = nullptr;
  manifest["report"] = "report/index.html";
  manifest["files"] = list_outputs(s.out);
  write_json_atomic(s.out / "manifest.json", manifest);
  if (!fs::exists(s.out / "timings.json")) timings.save(s.out);

  std::printf("analyze: %zu shapes (%zu usable), fuzzy mode %s; %.1f s this run\n", all_files.size(), usable.size(),
              mode.c_str(), since(t_run));
  if (acc.is_object() && json_member(acc, "accuracy"))
    std::printf("accuracy: %.2f %% part-labeling accuracy against the ground truth (%lld shapes)\n",
                100.0 * acc.at("accuracy").get<double>(), static_cast<long long>(acc.at("shapes_scored").get<double>()));
  else if (!corr_scored)
    std::printf("accuracy: not measured (no ground truth)\n");
  if (corr_scored)
    std::printf("accuracy: %.1f %% of feature points carried within 0.25 sqrt(area) by the fuzzy correspondences, "
                "mean error %.3f (%lld ordered pairs)\n",
                100.0 * corr.at("within_0.25").get<double>(), corr.at("mean_error").get<double>(),
                corr.at("pairs").get<long long>());
  std::printf("report: %s\n", (s.out / "report" / "index.html").string().c_str());
  std::printf("manifest: %s\n", (s.out / "manifest.json").string().c_str());
  std::printf("explore: shapestruct explore %s\n", (s.out / "fuzzy").string().c_str());
  return 0;
}

cli::command_fn setup_analyze(CLI::App& app) {
  auto c = std::make_shared<analyze_command_line>();
  app.add_option("DIR", c->input, "the input folder (its .off .obj .ply .stl files)")->required();
  app.add_option("-o,--output", c->out, "the output folder")->type_name("OUT")->required();
  app.add_option("--threads", c->threads, "worker threads, 0 = all cores (default); results do not depend on N")
      ->type_name("N")
      ->check(cli::at_least(0LL));
  app.add_option("--mode", c->mode,
                 "fuzzy correspondences: auto (default: intrinsic when every shape is a\n"
                 "closed genus-0 manifold, else extrinsic), intrinsic or extrinsic")
      ->type_name("auto|intrinsic|extrinsic")
      ->check(cli::one_of({"auto", "intrinsic", "extrinsic"}));
  app.add_option("--truth", c->truth, "ground-truth labels STEM.seg (one 0-based label per face) in DIR")->type_name("DIR");
  app.add_option("--up", c->up, "up axis of the collection (templates; fuzzy in extrinsic mode): 0 x, 1 y (default), 2 z")
      ->type_name("0|1|2")
      ->check(cli::in_range(0LL, 2LL));
  cli::add_templates_run_options(app, c->templates, "templates stage: ");
  cli::add_fuzzy_run_options(app, c->fuzzy, "fuzzy stage: ");
  app.add_flag("--quiet", c->quiet, "no progress display");
  app.footer(
      "Runs five stages on every shape file in DIR (.off .obj .ply .stl), each into its own folder of OUT:\n"
      "  inspect/    check_mesh's report per shape file (FILE.json) and summary.json; an unreadable, empty or\n"
      "              non-finite shape is reported and skipped by the later stages\n"
      "  templates/  exactly what `shapestruct templates` writes (learned templates, STEM.seg, co-alignment)\n"
      "  fuzzy/      what `shapestruct fuzzy` writes (its timings go to OUT/timings.json instead)\n"
      "  evaluate/   with ground truth beside the shapes or in --truth DIR: per-face labels STEM.seg (the\n"
      "              generator's) give accuracy.json, the part-labeling accuracy of the templates; feature\n"
      "              points STEM.vts / STEM.pid (SHREC'07, SCAPE) give correspondence.json, the error of the\n"
      "              fuzzy correspondences (geodesic / sqrt(area)); both printed\n"
      "  report/     index.html: opens from disk without a server; PNG thumbnails rendered by the tool\n"
      "and OUT/manifest.json (every file and what it is, stages, mode, skipped shapes, accuracy) and\n"
      "OUT/timings.json (seconds per stage). Each stage ends by writing OUT/STAGE/.done: run the same command\n"
      "again after an interruption and finished stages (and finished shapes and pairs) are not redone; the\n"
      "result files are the same as those of an uninterrupted run. A rerun with other shape files or options\n"
      "is refused, naming them (OUT/STAGE/.settings.json records them). Across MPI ranks: mpirun -np R\n"
      "shapestruct-mpi analyze ... (docs/cluster.md). See docs/analyze.md.");
  return [c] { return run_analyze(*c); };
}

const cli::register_command register_analyze{
    "analyze",
    {"the structure of a folder of shapes in one command: check, templates, fuzzy correspondences, accuracy, report",
     setup_analyze}};

}  // namespace
