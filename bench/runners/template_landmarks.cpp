// SPDX-License-Identifier: MIT
// run_template_landmarks: landmark correspondence error of part-based templates on a generated collection
// (issue 4 acceptance: "landmark correspondence error as a curve, Euclidean / bounding-box diagonal").
//   run_template_landmarks SHAPES_DIR [--template T.json] [--shapes N] [--pairs P] [--points N] [--threads N]
//                          [--learn] [--seed S] [--curve FILE]
// SHAPES_DIR is the output of `shapestruct generate chairs ...`: STEM.off with named landmarks in STEM.pts
// ("name x y z" per line). Every shape is sampled and fitted with the template set (the given one, learned on the
// collection with --learn; without --template the fully automatic initialisation + learning). For P seeded random
// ordered pairs (A, B) fitted to the SAME template, each landmark of A is snapped to its nearest sample, mapped to
// B through the canonical space (canonical_correspondence, 5.4.5), and compared with B's landmark of the same name.
// The error is the Euclidean distance divided by B's bounding-box diagonal, i.e. the distance in B's canonical
// frame. Landmarks named base_foot_* are skipped: the generator numbers a pedestal's feet from a random phase, so
// equal names are not corresponding points. Also reported: the sampling floor (the error of snapping B's own
// landmark to its nearest sample), which no sample-to-sample map can beat, and a no-template baseline: A's
// landmark sample mapped to the nearest sample of B in the bounding-box-normalised frame (no rotation search,
// no parts; the generator writes every chair upright and facing -Z, which favours this baseline).
// Prints the curve (fraction of landmark pairs within D, D = 0 .. 0.25) and writes it to FILE for gnuplot.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/eval/error_curve.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/templates/co_alignment.hpp"
#include "shapestruct/templates/collection_runner.hpp"
#include "shapestruct/templates/make_shape_samples.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/template_initializer.hpp"
#include "shapestruct/templates/template_learner.hpp"
#include "runner_errors.hpp"

namespace fs = std::filesystem;
using namespace shapestruct;

namespace {

std::map<std::string, Eigen::Vector3d> read_landmarks(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw io_error(file_error::cannot_open, p.string(), 0, 0, "cannot open the landmark file");
  std::map<std::string, Eigen::Vector3d> out;
  std::string line;
  std::size_t ln = 0;
  while (std::getline(in, line)) {
    ++ln;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream is(line);
    std::string name;
    Eigen::Vector3d x;
    if (!(is >> name >> x[0] >> x[1] >> x[2]) || !x.allFinite())
      throw io_error(file_error::syntax, p.string(), ln, 0, "expected 'name x y z'");
    out[name] = x;
  }
  return out;
}

index_t nearest_sample(const shape_samples& s, const Eigen::Vector3d& q) {
  index_t best = 0;
  (s.points.rowwise() - q.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return best;
}

}  // namespace

static int run(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: run_template_landmarks SHAPES_DIR [--template T.json] [--shapes N] [--pairs P] "
                 "[--points N] [--threads N] [--learn] [--seed S] [--curve FILE]\n";
    return 2;
  }
  const fs::path dir = argv[1];
  std::string tpl_path, curve_path;
  index_t points = 1000;
  std::size_t max_shapes = 200, pairs = 2000;
  int threads = 1;
  bool learn = false;
  std::uint64_t seed = 1;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--template" && i + 1 < argc) tpl_path = argv[++i];
    else if (a == "--shapes" && i + 1 < argc) max_shapes = std::stoul(argv[++i]);
    else if (a == "--pairs" && i + 1 < argc) pairs = std::stoul(argv[++i]);
    else if (a == "--points" && i + 1 < argc) points = std::stol(argv[++i]);
    else if (a == "--threads" && i + 1 < argc) threads = std::stoi(argv[++i]);
    else if (a == "--seed" && i + 1 < argc) seed = std::stoull(argv[++i]);
    else if (a == "--curve" && i + 1 < argc) curve_path = argv[++i];
    else if (a == "--learn") learn = true;
    else {
      std::cerr << "run_template_landmarks: unknown option " << a << "\n";
      return 2;
    }
  }
  auto files = list_shape_files(dir);
  if (files.size() > max_shapes) files.resize(max_shapes);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<shape_samples> samples(files.size());
  std::vector<std::map<std::string, Eigen::Vector3d>> marks(files.size());  // canonical coordinates
  shape_sampling_options so;
  so.points = points;
  detail::parallel_for(files.size(), detail::resolve_threads(threads, "run_template_landmarks"), [&](std::size_t i) {
    const auto m = read_mesh(files[i]).mesh;
    samples[i] = make_shape_samples(m, so);
    fs::path p = files[i];
    for (const auto& [name, x] : read_landmarks(p.replace_extension(".pts")))
      marks[i][name] = (x - samples[i].center) / samples[i].scale;
  });
  template_learner_options lo;
  lo.threads = threads;
  std::vector<part_template> templates;
  if (!tpl_path.empty()) {
    templates = read_templates(tpl_path);
    if (learn) templates = learn_templates(templates, samples, lo).templates;
  } else {
    templates = auto_templates(samples, lo);
    templates = learn_templates(templates, samples, lo).templates;
  }
  const auto fits = fit_template_set(templates, samples, lo);
  const auto t1 = std::chrono::steady_clock::now();

  // Seeded random ordered pairs of distinct shapes (pairs on different templates are scored too, see above).
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, files.size() - 1);
  std::vector<double> errors, floor_errors, baseline_errors;
  std::map<std::string, std::pair<double, int>> per_name;
  std::size_t scored_pairs = 0, cross_template = 0;
  double same_sum = 0, cross_sum = 0;
  std::size_t same_n = 0, cross_n = 0;
  for (std::size_t k = 0; k < pairs && files.size() > 1; ++k) {
    const std::size_t a = pick(rng);
    std::size_t b = pick(rng);
    while (b == a) b = pick(rng);
    const bool cross = fits[a].template_index != fits[b].template_index;
    const auto& ta = templates[static_cast<std::size_t>(fits[a].template_index)];
    const auto& tb = templates[static_cast<std::size_t>(fits[b].template_index)];
    const auto map = canonical_correspondence(ta, samples[a], fits[a].fit, tb, samples[b], fits[b].fit);
    ++scored_pairs;
    cross_template += cross ? 1 : 0;
    for (const auto& [name, qa] : marks[a]) {
      if (name.rfind("base_foot_", 0) == 0) continue;
      const auto it = marks[b].find(name);
      if (it == marks[b].end()) continue;
      const index_t ia = nearest_sample(samples[a], qa);
      const Eigen::Vector3d pred = samples[b].points.row(map[static_cast<std::size_t>(ia)]).transpose();
      const double e = (pred - it->second).norm();
      errors.push_back(e);
      (cross ? cross_sum : same_sum) += e;
      (cross ? cross_n : same_n) += 1;
      const Eigen::Vector3d qa_s = samples[a].points.row(ia).transpose();
      const Eigen::Vector3d base = samples[b].points.row(nearest_sample(samples[b], qa_s)).transpose();
      baseline_errors.push_back((base - it->second).norm());
      floor_errors.push_back((samples[b].points.row(nearest_sample(samples[b], it->second)).transpose() - it->second).norm());
      auto& pn = per_name[name];
      pn.first += e;
      pn.second += 1;
    }
  }
  if (errors.empty()) {
    std::cerr << "run_template_landmarks: no landmark pair was scored\n";
    return 1;
  }
  std::vector<double> D;
  for (int i = 0; i <= 50; ++i) D.push_back(0.005 * i);
  const auto curve = error_curve(errors, D);
  const auto floor_curve = error_curve(floor_errors, D);
  const auto base_curve = error_curve(baseline_errors, D);
  double mean = 0, fmean = 0, bmean = 0;
  for (const double e : baseline_errors) bmean += e;
  bmean /= static_cast<double>(baseline_errors.size());
  for (const double e : errors) mean += e;
  for (const double e : floor_errors) fmean += e;
  mean /= static_cast<double>(errors.size());
  fmean /= static_cast<double>(floor_errors.size());
  std::cout << "shapes: " << files.size() << ", templates: " << templates.size() << ", points: " << points << "\n";
  std::cout << "pairs scored: " << scored_pairs << " (" << cross_template
            << " across two templates, through template_part_map), landmark pairs: " << errors.size() << "\n";
  std::cout << "mean error, same template: " << (same_n ? same_sum / double(same_n) : 0.0)
            << ", across templates: " << (cross_n ? cross_sum / double(cross_n) : 0.0) << "\n";
  std::cout << "mean error / bbox diagonal: " << mean << " (sampling floor " << fmean << ", no-template baseline "
            << bmean << ")\n";
  for (const double d : {0.025, 0.05, 0.1, 0.25})
    std::cout << "within " << d << ": " << 100 * error_curve(errors, {d}).front() << " % (baseline "
              << 100 * error_curve(baseline_errors, {d}).front() << " %)\n";
  std::cout << "per landmark (mean error):";
  for (const auto& [name, v] : per_name) std::cout << " " << name << " " << std::setprecision(3) << v.first / v.second;
  std::cout << std::setprecision(6) << "\n";
  std::cout << "time: sampling + fitting " << std::chrono::duration<double>(t1 - t0).count() << " s\n";
  if (!curve_path.empty()) {
    std::ofstream out(curve_path);
    out << "# D  templates  sampling_floor  no_template_baseline   (fraction of landmark pairs within D; "
        << "run_template_landmarks " << dir.string() << ")\n";
    for (std::size_t i = 0; i < D.size(); ++i)
      out << D[i] << ' ' << curve[i] << ' ' << floor_curve[i] << ' ' << base_curve[i] << "\n";
  }
  return 0;
}

int main(int argc, char** argv) {
  return shapestruct::bench::run_reporting_errors("run_template_landmarks", [&] { return run(argc, argv); });
}
