// SPDX-License-Identifier: MIT
// shapestruct match: blended intrinsic maps between two closed genus-0 meshes.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "option_checks.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/vertex_map_file.hpp"
#include "shapestruct/io/write_mesh.hpp"

namespace {

using namespace shapestruct;
using namespace shapestruct::cli;

/// The command line of `shapestruct match`.
struct match_options {
  std::string src, tgt, out, precise, candidates, colors;
  long long samples = 256;
  long long features = 10;
  double feature_radius = blended_matcher_options{}.shape.feature_radius;
  long long max_maps = 10000;
  long long max_enumerated = 30000;
  std::string pruning = "distances";
  long long seed = 1;
  bool close_holes = false;
  bool keep_largest = false;
  long long threads = 0;
  bool verbose = false;
};

int run_match(const match_options& m) {
  const std::string& out = m.out;
  const std::string& precise = m.precise;
  const std::string& cand = m.candidates;
  const std::string& colors = m.colors;
  blended_matcher_options o;
  o.shape.num_samples = m.samples;
  o.shape.max_features = m.features;
  o.shape.feature_radius = m.feature_radius;
  const long long max_enumerated = m.max_enumerated;
  const long long seed = m.seed;
  const std::string& pruning = m.pruning;
  o.shape.close_small_holes = m.close_holes;
  o.shape.keep_largest_component = m.keep_largest;
  o.threads = static_cast<int>(m.threads);
  const bool verbose = m.verbose;
  const std::vector<std::string> pos{m.src, m.tgt};
  o.max_maps = m.max_maps;
  if (verbose)
    o.on_stage = [](const std::string& stage, double s) { std::fprintf(stderr, "  %-12s %8.3f s\n", stage.c_str(), s); };
  triplet_candidates cands;
  cands.options.max_maps = max_enumerated;
  cands.options.seed = static_cast<std::uint64_t>(seed);
  cands.options.pruning = pruning == "random" ? triplet_pruning::random : triplet_pruning::feature_distances;
  const blended_matcher<> matcher(o, cands);

  const auto A = read_mesh(std::filesystem::path(pos[0])).mesh;
  const auto B = read_mesh(std::filesystem::path(pos[1])).mesh;
  if (verbose) std::fprintf(stderr, "read %s (%ld vertices) and %s (%ld vertices)\n", pos[0].c_str(), long(A.V.rows()),
                            pos[1].c_str(), long(B.V.rows()));
  const auto t0 = std::chrono::steady_clock::now();
  const auto sa = matcher.prepare(A);
  const auto sb = matcher.prepare(B);
  if (verbose)
    std::fprintf(stderr, "  %-12s %8.3f s (features: %zu and %zu)\n", "preprocess",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), sa.features().size(),
                 sb.features().size());
  const auto res = matcher.match(sa, sb);
  if (verbose)
    std::fprintf(stderr, "total %.3f s, %zu candidate maps, %zu blended maps, selected score %.4f\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), res.candidates.size(),
                 res.blended.size(), res.blended[static_cast<std::size_t>(res.selected)].score);
  if (res.info != status::ok)
    std::fprintf(stderr, "warning: eigen-solver status %s; the map is from the last iterate\n", to_string(res.info));

  std::vector<index_t> ids(static_cast<std::size_t>(res.map.source_size()));
  for (index_t v = 0; v < res.map.source_size(); ++v) {
    ids[static_cast<std::size_t>(v)] = res.map.target_vertex(v);
    if (ids[static_cast<std::size_t>(v)] == no_index)
      throw std::runtime_error("source vertex " + std::to_string(v) +
                               " is unmapped (dropped by --keep-largest); a dense .map needs every vertex");
  }
  write_vertex_map(std::filesystem::path(out), std::span<const index_t>(ids));
  if (!precise.empty()) {
    std::ofstream f(precise);
    f.precision(9);
    for (const auto& p : res.map.points) f << p.face << " " << p.bary[0] << " " << p.bary[1] << " " << p.bary[2] << "\n";
    if (!f) throw io_error(file_error::write_failed, precise, 0, 0, "cannot write the precise map");
  }
  if (!cand.empty()) {
    std::ofstream f(cand);
    f << "# group_size eigen_weight score selected\n";
    for (std::size_t g = 0; g < res.blended.size(); ++g)
      f << res.blended[g].maps.size() << " " << res.blended[g].eigen_weight << " " << res.blended[g].score << " "
        << (static_cast<index_t>(g) == res.selected ? 1 : 0) << "\n";
    if (!f) throw io_error(file_error::write_failed, cand, 0, 0, "cannot write the candidate list");
  }
  if (!colors.empty()) {
    // Target coloured by normalised position; source vertices take the colour of their image.
    const Eigen::RowVector3d lo = B.V.colwise().minCoeff(), hi = B.V.colwise().maxCoeff();
    auto color_of = [&](const vec3<double>& p) {
      Eigen::Matrix<std::uint8_t, 1, 3> c;
      for (int k = 0; k < 3; ++k) {
        const double t = hi[k] > lo[k] ? (p[k] - lo[k]) / (hi[k] - lo[k]) : 0.5;
        c[k] = static_cast<std::uint8_t>(std::lround(255 * std::clamp(t, 0.0, 1.0)));
      }
      return c;
    };
    mesh_write_options wt, ws;
    wt.vertex_colors.resize(B.V.rows(), 3);
    for (index_t v = 0; v < B.V.rows(); ++v) wt.vertex_colors.row(v) = color_of(B.V.row(v).transpose());
    ws.vertex_colors.resize(A.V.rows(), 3);
    for (index_t v = 0; v < A.V.rows(); ++v) {
      const auto& p = res.map.point(v);
      ws.vertex_colors.row(v) = p.valid() ? color_of(p.position(sb.mesh().V, sb.mesh().F) * sb.scale())
                                          : Eigen::Matrix<std::uint8_t, 1, 3>(128, 128, 128);
    }
    write_mesh(std::filesystem::path(colors + "_target.ply"), B, wt);
    write_mesh(std::filesystem::path(colors + "_source.ply"), A, ws);
  }
  return 0;
}

command_fn setup_match(CLI::App& app) {
  auto m = std::make_shared<match_options>();
  app.add_option("SRC", m->src, "source mesh")->required();
  app.add_option("TGT", m->tgt, "target mesh")->required();
  app.add_option("-o,--output", m->out, "the dense vertex map")->type_name("OUT.map")->required();
  app.add_option("--precise", m->precise, "per SRC vertex: target face and barycentric weights, 'face b0 b1 b2'")
      ->type_name("OUT.txt");
  app.add_option("--candidates", m->candidates,
                 "every blended map considered: group size, eigen-weight, score (selected first)")
      ->type_name("OUT.txt");
  app.add_option("--colors", m->colors,
                 "colour-transfer PLY pair: PREFIX_target.ply coloured by position,\n"
                 "PREFIX_source.ply coloured through the map")
      ->type_name("PREFIX");
  app.add_option("--samples", m->samples, "even samples for confidence/consistency (default 256)")
      ->type_name("N")
      ->check(integer());
  app.add_option("--features", m->features, "at most N AGD-maxima feature points per mesh (default 10)")
      ->type_name("N")
      ->check(integer());
  app.add_option("--feature-radius", m->feature_radius,
                 "AGD maxima closer than R (units of sqrt(area)) are one feature (default 0.15)")
      ->type_name("R");
  app.add_option("--max-maps", m->max_maps, "candidate conformal maps kept, the most confident (default 10000)")
      ->type_name("N")
      ->check(at_least(1LL));
  app.add_option("--max-enumerated", m->max_enumerated, "cap on enumerated triplet maps before that (default 30000)")
      ->type_name("N")
      ->check(at_least(1LL));
  app.add_option("--pruning", m->pruning,
                 "how that cap prunes: keep the triplets that preserve feature-to-feature\n"
                 "geodesic distances best (default), or a seeded random choice (the chapter's)")
      ->type_name("distances|random")
      ->check(one_of({"distances", "random"}));
  app.add_option("--seed", m->seed, "seed of the random pruning (default 1)")->type_name("S")->check(integer());
  app.add_flag("--close-holes", m->close_holes, "fill boundary loops of up to 64 edges before matching (off by default)");
  app.add_flag("--keep-largest", m->keep_largest, "keep only the largest connected component (off by default)");
  app.add_option("--threads", m->threads, "worker threads, 0 = all cores (default 0)")->type_name("T")->check(at_least(0LL));
  app.add_flag("-v,--verbose", m->verbose, "progress and timings per stage on stderr");
  app.footer(
      "Blended intrinsic maps (dissertation ch. 3) from SRC to TGT (closed genus-0 meshes: OFF, OBJ, PLY, STL).\n"
      "Writes the benchmark's dense map: one line per SRC vertex, the 0-based TGT vertex it maps to.");
  return [m] { return run_match(*m); };
}

const register_command reg{"match", {"blended intrinsic maps between two meshes (writes a dense .map)", setup_match}};

}  // namespace
