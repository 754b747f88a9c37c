// SPDX-License-Identifier: MIT
// run_template_collection: the streamed, resumable, parallel collection pipeline of chapter 5 (learn templates on
// a bounded subset, then fit every shape file and write its results as soon as they exist).
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/work_share.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/io/json_file.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "shapestruct/io/write_mesh.hpp"
#include "shapestruct/templates/co_alignment.hpp"
#include "shapestruct/templates/face_labels.hpp"
#include "shapestruct/templates/make_shape_samples.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/template_fitter.hpp"
#include "shapestruct/templates/template_initializer.hpp"
#include "shapestruct/templates/template_learner.hpp"

namespace shapestruct {

/// Options of run_template_collection.
struct collection_run_options {
  template_learner_options learn;
  shape_sampling_options sampling;
  template_initializer_options init;
  /// Shapes (a seeded random subset) whose samples are held in memory for learning; the chapter shows that
  /// templates learned on ~1,000 shapes generalise to the rest (5.4.7). Labeling then streams every file.
  std::size_t learn_subset = 200;
  bool run_learning = true;  ///< false: use the given templates as they are
  bool write_ply = true;    ///< coloured PLY of each shape and its fitted boxes, for looking at
  bool write_points = true; ///< per-point labels, correspondences and co-alignments
  int threads = 0;          ///< 0 = all cores (over shapes); every result is independent of it
  std::string summary_name = "summary.json";  ///< distinct names let several processes share one OUT folder
  /// Several processes on one OUT folder: part 0 learns and writes templates.json, each part labels its own
  /// shapes, and part 0 writes the summary of all of them; the files are those of a single process.
  work_share share{};
  /// progress(done, total) after each shape of the labeling pass (called under a lock; may be empty).
  std::function<void(std::size_t, std::size_t)> progress;
  /// problem(file, message) for a shape that could not be processed (skipped, not fatal; may be empty).
  std::function<void(const std::string&, const std::string&)> problem;
  /// phase(message) when a phase starts (sampling the learning subset, learning, labeling; may be empty).
  std::function<void(const std::string&)> phase;
};

/// Summary of a run: per template, the shapes it explains (the clusters), plus counts.
struct collection_run_summary {
  std::vector<part_template> templates;
  std::vector<std::size_t> cluster_sizes;
  std::size_t processed = 0;  ///< shapes fitted in this run
  std::size_t skipped = 0;    ///< shapes already finished by an earlier (interrupted) run
  std::size_t failed = 0;     ///< unreadable / invalid shapes, reported through `problem`
};

/// The mesh files (.off, .obj, .ply, .stl, case-insensitive) directly in `dir`, sorted by name.
/// \throws io_error cannot_open when dir is not a readable folder.
inline std::vector<std::filesystem::path> list_shape_files(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw io_error(file_error::cannot_open, dir.string(), 0, 0, "not a folder of shapes");
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

namespace detail {

/// Writes text to path atomically (temporary file + rename): a crash never leaves a half-written record.
inline void write_text_atomic(const std::filesystem::path& path, const std::string& text) {
  const auto tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw io_error(file_error::cannot_open, tmp, 0, 0, "cannot open for writing");
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    if (!out) throw io_error(file_error::write_failed, tmp, 0, 0, "could not write the whole file");
  }
  std::filesystem::rename(tmp, path);
}

inline std::array<std::uint8_t, 3> label_color(index_t l) {
  static constexpr std::array<std::array<std::uint8_t, 3>, 10> palette = {{{228, 26, 28},
                                                                            {55, 126, 184},
                                                                            {77, 175, 74},
                                                                            {152, 78, 163},
                                                                            {255, 127, 0},
                                                                            {255, 255, 51},
                                                                            {166, 86, 40},
                                                                            {247, 129, 191},
                                                                            {153, 153, 153},
                                                                            {0, 206, 209}}};
  if (l < 0) return {40, 40, 40};
  return palette[static_cast<std::size_t>(l) % palette.size()];
}

/// Mesh of the fitted (deformed) boxes in the input coordinates, coloured by label.
inline std::pair<triangle_mesh<double>, Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3>> boxes_mesh(
    const part_template& t, const template_fit& f, const shape_samples& s) {
  triangle_mesh<double> m;
  const index_t K = t.num_parts();
  m.V.resize(8 * K, 3);
  m.F.resize(12 * K, 3);
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3> col(8 * K, 3);
  static constexpr int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (index_t b = 0; b < K; ++b) {
    const auto& box = t.parts[static_cast<std::size_t>(b)];
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d u((c & 1) ? 0.5 : -0.5, (c & 2) ? 0.5 : -0.5, (c & 4) ? 0.5 : -0.5);
      const Eigen::Vector3d p = f.centers[static_cast<std::size_t>(b)] +
                                box.axes.transpose() * f.sizes[static_cast<std::size_t>(b)].cwiseProduct(u);
      // template frame -> canonical shape frame (q = R^T p) -> input coordinates
      m.V.row(8 * b + c) = (f.rotation.transpose() * p * s.scale + s.center).transpose();
      const auto rgb = label_color(box.label);
      col.row(8 * b + c) << rgb[0], rgb[1], rgb[2];
    }
    for (int q = 0; q < 6; ++q) {
      m.F.row(12 * b + 2 * q) << 8 * b + quads[q][0], 8 * b + quads[q][1], 8 * b + quads[q][2];
      m.F.row(12 * b + 2 * q + 1) << 8 * b + quads[q][0], 8 * b + quads[q][2], 8 * b + quads[q][3];
    }
  }
  return {m, col};
}

/// The input mesh with faces split apart so each face can carry its label's colour.
inline std::pair<triangle_mesh<double>, Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3>> labeled_mesh(
    const triangle_mesh<double>& in, const std::vector<index_t>& face_labels) {
  triangle_mesh<double> m;
  m.V.resize(3 * in.F.rows(), 3);
  m.F.resize(in.F.rows(), 3);
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 3> col(3 * in.F.rows(), 3);
  for (index_t f = 0; f < in.F.rows(); ++f) {
    const auto rgb = label_color(face_labels[static_cast<std::size_t>(f)]);
    for (int k = 0; k < 3; ++k) {
      m.V.row(3 * f + k) = in.V.row(in.F(f, k));
      col.row(3 * f + k) << rgb[0], rgb[1], rgb[2];
    }
    m.F.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  }
  return {m, col};
}

inline nlohmann::ordered_json vec_json(const Eigen::Vector3d& v) { return nlohmann::ordered_json::array({v[0], v[1], v[2]}); }

}  // namespace detail

/// Runs the chapter-5 pipeline over a folder of shape files, writing into `out_dir`:
///   templates.json            the template set used for labeling (learned unless options.learn is false)
///   STEM.seg                  one 0-based output label per face of the input mesh (COSEG/PSB format)
///   STEM.fit.json             template (cluster), energy, rigid transform, per-part deformation; written last,
///                             atomically: its presence marks the shape finished
///   STEM.points.txt           per sample: input xyz, part, label, unit-box correspondence on the template,
///                             rigidly co-aligned xyz, rigid+deformation co-aligned xyz
///   ply/STEM.ply, ply/STEM.boxes.ply   faces coloured by label; the fitted boxes
///   summary.json              clusters (shapes per template) and the list of failed shapes
/// Learning (unless disabled or templates.json already exists from an interrupted run) uses a seeded random
/// subset of at most learn_subset shapes; given templates (may be empty: automatic initialisation) start it.
/// Labeling then streams the files: each worker reads, samples, fits all templates, writes and forgets its
/// shape, so memory is O(learn_subset + threads) shapes plus one small record per shape. Shapes whose
/// STEM.fit.json exists are skipped (resume); since every result depends only on the shape, the templates and
/// fixed seeds, a resumed run produces the same files as an uninterrupted one. A shape that cannot be read or
/// fails validation is reported through `problem` and listed in summary.json, never fatal.
/// \throws io_error if out_dir cannot be created or written; invalid_input for a bad template set.
inline collection_run_summary run_template_collection(const std::vector<std::filesystem::path>& files,
                                                      const std::filesystem::path& out_dir,
                                                      std::vector<part_template> templates,
                                                      const collection_run_options& opt = {}) {
  namespace fs = std::filesystem;
  fs::create_directories(out_dir);
  if (opt.write_ply) fs::create_directories(out_dir / "ply");
  const unsigned threads = detail::resolve_threads(opt.threads, "run_template_collection");
  collection_run_summary sum;
  std::mutex lock;
  auto report = [&](const std::string& file, const std::string& msg) {
    std::lock_guard<std::mutex> g(lock);
    ++sum.failed;
    if (opt.problem) opt.problem(file, msg);
  };
  const work_share& share = opt.share;
  share.validate("run_template_collection");
  const fs::path tpl_file = out_dir / "templates.json";
  // With several processes, part 0 learns (or reads templates.json) while the others wait, then they read it.
  std::exception_ptr learn_failure;
  std::string learn_error;
  if (share.leader()) try {
    if (fs::exists(tpl_file)) {
      templates = read_templates(tpl_file.string());  // resume: never re-learn, results must not change
    } else {
      if (opt.run_learning || templates.empty()) {
        // Learning subset: seeded shuffle of the file list, samples held in memory.
        std::vector<std::size_t> order(files.size());
        std::iota(order.begin(), order.end(), std::size_t{0});
        std::mt19937_64 rng(opt.learn.seed);
        std::shuffle(order.begin(), order.end(), rng);
        order.resize(std::min(order.size(), opt.learn_subset));
        std::sort(order.begin(), order.end());
        if (opt.phase) opt.phase("sampling " + std::to_string(order.size()) + " shapes for learning");
        std::vector<std::optional<shape_samples>> slots(order.size());
        detail::parallel_for(order.size(), threads, [&](std::size_t k) {
          try {
            const auto mf = read_mesh(files[order[k]]);
            slots[k] = make_shape_samples(mf.mesh, opt.sampling);
          } catch (const std::exception&) {
            // reported in the labeling pass, which reads every file again
          }
        });
        std::vector<shape_samples> subset;
        for (auto& s : slots)
          if (s) subset.push_back(std::move(*s));
        if (subset.empty())
          throw invalid_input(input_error::empty, no_index,
                              "run_template_collection: no readable shape to learn from in the collection");
        if (templates.empty()) {
          if (opt.phase) opt.phase("automatic template initialisation");
          templates = auto_templates(subset, opt.learn, opt.init);
        } else if (opt.run_learning) {
          if (opt.phase) opt.phase("learning templates");
          templates = learn_templates(templates, subset, opt.learn).templates;
        }
      }
      for (const auto& t : templates) validate_template(t, tpl_file.string());
      write_templates(tpl_file.string(), templates);
    }
  } catch (const std::exception& e) {
    if (!share.distributed()) throw;
    learn_failure = std::current_exception();
    learn_error = e.what();
  }
  if (share.distributed()) {
    const auto messages = share.all_gather(learn_error);
    if (learn_failure) std::rethrow_exception(learn_failure);
    if (!messages.front().empty())
      throw std::runtime_error("run_template_collection: learning failed in process 0: " + messages.front());
    if (!share.leader()) templates = read_templates(tpl_file.string());
  }
  sum.templates = templates;
  std::vector<index_t> cluster(files.size(), no_index);
  std::vector<char> failed(files.size(), 0);
  std::vector<std::string> failure(files.size());
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < files.size(); ++i)
    if (share.owns(i)) mine.push_back(i);
  if (opt.phase) opt.phase("labeling " + std::to_string(mine.size()) + " shapes");
  std::atomic<std::size_t> done{0};
  detail::parallel_for(mine.size(), threads, [&](std::size_t j) {
    const std::size_t i = mine[j];
    const fs::path& file = files[i];
    const std::string stem = file.stem().string();
    const fs::path rec = out_dir / (stem + ".fit.json");
    if (fs::exists(rec)) {
      try {
        cluster[i] = json_required<index_t>(read_json_file(rec.string()), "template", rec.string());
      } catch (const std::exception&) {
        cluster[i] = no_index;
      }
      std::lock_guard<std::mutex> g(lock);
      ++sum.skipped;
      ++done;
      if (opt.progress) opt.progress(done, mine.size());
      return;
    }
    try {
      const auto mf = read_mesh(file);
      const auto s = make_shape_samples(mf.mesh, opt.sampling);
      template_assignment best;
      for (std::size_t t = 0; t < templates.size(); ++t) {
        auto f = fit_template(templates[t], s, opt.learn.fit);
        if (best.template_index == no_index || f.energy < best.fit.energy) {
          best.template_index = static_cast<index_t>(t);
          best.fit = std::move(f);
        }
      }
      const auto& tp = templates[static_cast<std::size_t>(best.template_index)];
      const auto& f = best.fit;
      bool any = false;
      for (const auto l : f.labels) any = any || l >= 0;
      std::vector<index_t> face_labels =
          any ? project_labels_to_faces(mf.mesh, s, f.labels)
              : std::vector<index_t>(static_cast<std::size_t>(mf.mesh.F.rows()), 0);
      write_segmentation(out_dir / (stem + ".seg"), face_labels);
      if (opt.write_points) {
        const auto rigid = co_aligned_points(tp, s, f, false);
        const auto deformed = co_aligned_points(tp, s, f, true);
        std::ostringstream os;
        os.precision(7);
        os << "# x y z part label u0 u1 u2 rigid_x rigid_y rigid_z coaligned_x coaligned_y coaligned_z\n";
        for (index_t k = 0; k < s.size(); ++k) {
          const Eigen::Vector3d x = s.points.row(k).transpose() * s.scale + s.center;
          const auto& c = f.correspondence[static_cast<std::size_t>(k)];
          os << x[0] << ' ' << x[1] << ' ' << x[2] << ' ' << f.parts[static_cast<std::size_t>(k)] << ' '
             << f.labels[static_cast<std::size_t>(k)] << ' ' << c.u[0] << ' ' << c.u[1] << ' ' << c.u[2] << ' '
             << rigid(k, 0) << ' ' << rigid(k, 1) << ' ' << rigid(k, 2) << ' ' << deformed(k, 0) << ' '
             << deformed(k, 1) << ' ' << deformed(k, 2) << '\n';
        }
        detail::write_text_atomic(out_dir / (stem + ".points.txt"), os.str());
      }
      if (opt.write_ply) {
        const auto [lm, lc] = detail::labeled_mesh(mf.mesh, face_labels);
        write_mesh(out_dir / "ply" / (stem + ".ply"), lm, {.vertex_colors = lc, .binary = true});
        const auto [bm, bc] = detail::boxes_mesh(tp, f, s);
        write_mesh(out_dir / "ply" / (stem + ".boxes.ply"), bm, {.vertex_colors = bc, .binary = true});
      }
      using ojson = nlohmann::ordered_json;
      auto parts = ojson::array();
      for (std::size_t b = 0; b < tp.parts.size(); ++b)
        parts.push_back(ojson::object({{"name", tp.parts[b].name},
                                       {"center", detail::vec_json(f.centers[b])},
                                       {"size", detail::vec_json(f.sizes[b])}}));
      auto rot = ojson::array();
      for (int r = 0; r < 3; ++r) rot.push_back(detail::vec_json(f.rotation.row(r).transpose()));
      const ojson record = ojson::object({
          {"file", file.filename().string()},
          {"template", static_cast<long long>(best.template_index)},
          {"template_id", tp.id},
          {"energy", std::isfinite(f.energy) ? ojson(f.energy) : ojson(nullptr)},
          {"status", to_string(f.info)},
          {"canonical_center", detail::vec_json(s.center)},
          {"canonical_scale", s.scale},
          {"rotation", std::move(rot)},
          {"parts", std::move(parts)}});
      detail::write_text_atomic(rec, format_json(record) + "\n");
      cluster[i] = best.template_index;
      std::lock_guard<std::mutex> g(lock);
      ++sum.processed;
    } catch (const std::exception& e) {
      failed[i] = 1;
      failure[i] = e.what();
      report(file.string(), e.what());
    }
    std::lock_guard<std::mutex> g(lock);
    ++done;
    if (opt.progress) opt.progress(done, mine.size());
  });
  if (share.distributed()) {
    // Every part learns every shape's cluster and failure, and the counts of all parts.
    std::vector<std::string> items{std::to_string(sum.processed), std::to_string(sum.skipped)};
    for (const auto i : mine) items.insert(items.end(), {std::to_string(i), std::to_string(cluster[i]), failure[i]});
    const auto messages = share.all_gather(detail::pack_strings(items));
    for (std::size_t p = 0; p < messages.size(); ++p) {
      if (p == share.part) continue;
      const auto got = detail::unpack_strings(messages[p]);
      sum.processed += std::stoul(got.at(0));
      sum.skipped += std::stoul(got.at(1));
      for (std::size_t k = 2; k + 2 < got.size(); k += 3) {
        const std::size_t i = std::stoul(got[k]);
        cluster[i] = static_cast<index_t>(std::stol(got[k + 1]));
        if (!got[k + 2].empty()) {
          failed[i] = 1;
          report(files[i].string(), got[k + 2]);
        }
      }
    }
  }
  sum.cluster_sizes.assign(templates.size(), 0);
  using ojson = nlohmann::ordered_json;
  auto clusters = ojson::array(), bad = ojson::array();
  std::vector<ojson> members(templates.size(), ojson::array());
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (failed[i]) bad.push_back(files[i].filename().string());
    if (cluster[i] >= 0 && static_cast<std::size_t>(cluster[i]) < templates.size()) {
      ++sum.cluster_sizes[static_cast<std::size_t>(cluster[i])];
      members[static_cast<std::size_t>(cluster[i])].push_back(files[i].stem().string());
    }
  }
  for (std::size_t t = 0; t < templates.size(); ++t)
    clusters.push_back(ojson::object({{"template", static_cast<long long>(t)},
                                      {"id", templates[t].id},
                                      {"shapes", static_cast<long long>(sum.cluster_sizes[t])},
                                      {"members", std::move(members[t])}}));
  const ojson summary = ojson::object({{"clusters", std::move(clusters)}, {"failed", std::move(bad)}});
  if (share.leader()) detail::write_text_atomic(out_dir / opt.summary_name, format_json(summary) + "\n");
  return sum;
}

}  // namespace shapestruct
