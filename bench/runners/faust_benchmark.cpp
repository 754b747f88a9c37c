// SPDX-License-Identifier: MIT
// run_faust_benchmark: blended intrinsic maps, with and without the ZoomOut refinement, on a fixed list of
// MPI-FAUST registration pairs, scored at every vertex.
//
//   run_faust_benchmark --data $SHAPESTRUCT_DATA --out results/ [--threads T] [--limit N]
//
// The registrations share one vertex numbering, so the true image of source vertex v is target vertex v. Error =
// geodesic distance (Dijkstra on the target's edge graph) / sqrt(area of the target), averaged over all 6,890
// vertices of every pair (the ZoomOut paper's measure, there on remeshed shapes with exact geodesics).
// The pairs (subject = id / 10, pose = id % 10), 40 in all:
//   intra-subject: for every subject s, pose 0 -> pose 1 and pose 2 -> pose 5;
//   inter-subject: for every subject s, pose p of s -> pose p of subject s + 1 (mod 10), p in {0, 5}.
// Writes faust_pairs.csv and appends to summary.md.
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
#include "shapestruct/eval/geodesic_error.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "runner_errors.hpp"

namespace fs = std::filesystem;
using namespace shapestruct;

namespace {

struct faust_pair {
  int source, target;
  const char* kind;
};

std::vector<faust_pair> faust_pairs() {
  std::vector<faust_pair> out;
  for (int s = 0; s < 10; ++s) {
    out.push_back({10 * s + 0, 10 * s + 1, "intra"});
    out.push_back({10 * s + 2, 10 * s + 5, "intra"});
  }
  for (int s = 0; s < 10; ++s)
    for (int p : {0, 5}) out.push_back({10 * s + p, 10 * ((s + 1) % 10) + p, "inter"});
  return out;
}

std::string fmt(double x, int prec = 4) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", prec, x);
  return b;
}

std::string mesh_path(const fs::path& data, int id) {
  char name[32];
  std::snprintf(name, sizeof name, "tr_reg_%03d.ply", id);
  return (data / "faust_registrations/registrations" / name).string();
}

}  // namespace

static int run(int argc, char** argv) {
  std::string data_dir = std::getenv("SHAPESTRUCT_DATA") ? std::getenv("SHAPESTRUCT_DATA") : "";
  std::string out_dir = "faust_results";
  int threads = 0, limit = -1;
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
    else if (a == "--out") out_dir = next();
    else if (a == "--threads") threads = std::stoi(next());
    else if (a == "--limit") limit = std::stoi(next());
    else {
      std::cerr << "usage: run_faust_benchmark --data DIR --out DIR [--threads T] [--limit N]\n";
      return 2;
    }
  }
  if (data_dir.empty()) {
    std::cerr << "need --data (or $SHAPESTRUCT_DATA)\n";
    return 2;
  }
  const fs::path data(data_dir);
  fs::create_directories(out_dir);
  blended_matcher_options options;
  options.threads = threads;
  const blended_matcher<> matcher(options);

  std::ofstream csv(fs::path(out_dir) / "faust_pairs.csv");
  csv << "source,target,kind,blended_mean,blended_w005,refined_mean,refined_w005,time_total,time_refinement\n";
  struct totals {
    double blended = 0, refined = 0, blended_w005 = 0, refined_w005 = 0;
    int pairs = 0;
  };
  std::map<std::string, totals> by_kind;
  int done = 0;
  for (const auto& pr : faust_pairs()) {
    if (limit >= 0 && done >= limit) break;
    const auto A = read_mesh(fs::path(mesh_path(data, pr.source))).mesh;
    const auto B = read_mesh(fs::path(mesh_path(data, pr.target))).mesh;
    if (A.V.rows() != B.V.rows()) {
      std::cerr << "FAUST " << pr.source << " and " << pr.target << " differ in vertex count\n";
      return 1;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const auto r = matcher.match(A, B);
    const double t_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    double t_refine = 0;
    for (const auto& [stage, s] : r.timings)
      if (stage == "refinement") t_refine = s;
    // Scored on the target as read (errors / sqrt(its area)), every vertex against the same vertex id.
    const dijkstra_geodesics<double> geo(B.V, B.F);
    std::vector<index_t> truth(static_cast<std::size_t>(A.V.rows()));
    for (index_t v = 0; v < A.V.rows(); ++v) truth[static_cast<std::size_t>(v)] = v;
    const auto score = [&](const surface_map<double>& m) {
      std::vector<index_t> pred(truth.size());
      for (index_t v = 0; v < A.V.rows(); ++v) pred[static_cast<std::size_t>(v)] = m.target_vertex(v);
      return summarize_errors(std::span<const double>(benchmark_geodesic_errors(
          B.V, B.F, geo, std::span<const index_t>(pred), std::span<const index_t>(truth), threads)));
    };
    const auto blended = score(r.blended[static_cast<std::size_t>(r.selected)].map);
    const auto refined = score(r.map);
    auto& t = by_kind[pr.kind];
    t.blended += blended.mean;
    t.refined += refined.mean;
    t.blended_w005 += blended.within_005;
    t.refined_w005 += refined.within_005;
    ++t.pairs;
    csv << pr.source << "," << pr.target << "," << pr.kind << "," << fmt(blended.mean) << "," << fmt(blended.within_005)
        << "," << fmt(refined.mean) << "," << fmt(refined.within_005) << "," << fmt(t_total, 3) << "," << fmt(t_refine, 3)
        << "\n";
    csv.flush();
    std::cerr << "faust " << pr.source << "->" << pr.target << " (" << pr.kind << "): blended " << fmt(blended.mean)
              << ", refined " << fmt(refined.mean) << ", " << fmt(t_total, 2) << " s\n";
    ++done;
  }
  std::ofstream md(fs::path(out_dir) / "summary.md", std::ios::app);
  md << "\n### FAUST registrations: " << done << " pairs, mean geodesic error / sqrt(area) over all vertices\n\n"
     << "| pairs | blended | blended <=0.05 | refined (ZoomOut) | refined <=0.05 |\n|---|---|---|---|---|\n";
  totals all;
  for (const auto& [kind, t] : by_kind) {
    md << "| " << kind << " (" << t.pairs << ") | " << fmt(t.blended / t.pairs) << " | " << fmt(t.blended_w005 / t.pairs, 3)
       << " | " << fmt(t.refined / t.pairs) << " | " << fmt(t.refined_w005 / t.pairs, 3) << " |\n";
    all.blended += t.blended;
    all.refined += t.refined;
    all.blended_w005 += t.blended_w005;
    all.refined_w005 += t.refined_w005;
    all.pairs += t.pairs;
  }
  if (all.pairs > 0) {
    md << "| all (" << all.pairs << ") | " << fmt(all.blended / all.pairs) << " | " << fmt(all.blended_w005 / all.pairs, 3)
       << " | " << fmt(all.refined / all.pairs) << " | " << fmt(all.refined_w005 / all.pairs, 3) << " |\n";
    std::cout << "faust: " << all.pairs << " pairs, mean error blended " << fmt(all.blended / all.pairs) << ", refined "
              << fmt(all.refined / all.pairs) << "\n";
  }
  return 0;
}

int main(int argc, char** argv) {
  return shapestruct::bench::run_reporting_errors("run_faust_benchmark", [&] { return run(argc, argv); });
}
