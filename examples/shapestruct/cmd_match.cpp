// SPDX-License-Identifier: MIT
// shapestruct match: blended intrinsic maps between two closed genus-0 meshes.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <utility>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "huge_pages.hpp"
#include "option_checks.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/detail/side_by_side.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/io/vertex_map_file.hpp"
#include "shapestruct/io/write_mesh.hpp"

namespace {

using namespace shapestruct;
using namespace shapestruct::cli;

/// The names `match --selection` gives the selection rules (blended_selection).
constexpr std::pair<const char*, blended_selection> selection_names[] = {
    {"adaptive", blended_selection::distortion_adaptive},
    {"confidence-distortion", blended_selection::confidence_and_distortion_rank},
    {"confidence", blended_selection::integrated_confidence},
    {"area", blended_selection::area_score},
    {"area-confidence", blended_selection::area_and_confidence_rank},
};

std::string selection_name(blended_selection rule) {
  for (const auto& [name, r] : selection_names)
    if (r == rule) return name;
  return "confidence";
}

blended_selection selection_rule(const std::string& name) {
  for (const auto& [n, r] : selection_names)
    if (name == n) return r;
  return blended_selection::integrated_confidence;  // unreachable: CLI11 checks the name
}

/// The command line of `shapestruct match`.
struct match_options {
  std::string src, tgt, out, precise, candidates, colors;
  long long samples = 256;
  long long features = 10;
  long long min_features = -1;  // not given: the library's default, at most --features
  double feature_radius = blended_matcher_options{}.shape.feature_radius;
  double alternative_persistence = blended_shape_options{}.alternative_feature_persistence;
  std::string selection = selection_name(blended_matcher_options{}.selection);
  long long max_maps = 10000;
  long long max_enumerated = 30000;
  std::string pruning = "distances";
  long long seed = 1;
  bool strict = false;       // refuse defective meshes instead of repairing them
  bool close_holes = false;  // with --strict: allow this one repair
  bool keep_largest = false;
  long long max_hole_edges = 64;
  std::string refine = "zoomout";  // refinement of the blended map
  long long refine_basis = zoomout_options{}.final_size;
  double refinement_move_check = blended_matcher_options{}.refinement_move_check;
  bool both_directions = blended_matcher_options{}.both_directions;  // also match TGT -> SRC, reconcile the two
  long long threads = 0;
  bool verbose = false;
};

/// The tool's own way out of a defect: the switch that repairs it, or why none does.
std::string remedy_of(mesh_defect defect, const match_options& m) {
  const std::string drop_strict = m.strict ? "drop --strict to let match repair it" : "";
  switch (defect) {
    case mesh_defect::collapsed_face:
    case mesh_defect::duplicate_face: return m.strict ? "drop --strict to remove such faces" : "";
    case mesh_defect::non_manifold_edge:
      return m.strict ? "if they repeat one face, drop --strict to remove the repeats; otherwise no repair applies "
                        "('shapestruct inspect FILE' lists them)"
                      : "no repair applies; 'shapestruct inspect FILE' lists them";
    case mesh_defect::non_manifold_vertex: return drop_strict;
    case mesh_defect::several_pieces:
      return m.strict ? "add --keep-largest to keep the largest piece only, or drop --strict"
                      : "add --keep-largest to drop them anyway (by default match drops only pieces holding at most "
                        "5 % of the area)";
    case mesh_defect::hole:
      return m.strict && !m.close_holes ? "add --close-holes (fills holes of up to --max-hole-edges edges, now " +
                                              std::to_string(m.max_hole_edges) + "), or " + drop_strict
                                        : "raise --max-hole-edges (now " + std::to_string(m.max_hole_edges) + ")";
    case mesh_defect::non_orientable:
    case mesh_defect::genus:
      return "blended maps need a sphere-like surface and no repair applies; 'shapestruct fuzzy' (extrinsic mode) "
             "works on any shape";
    case mesh_defect::coordinate_overflow: return "scale the coordinates down";
    case mesh_defect::zero_area: return "";
  }
  return "";
}

/// Prepares one mesh for matching with `threads` threads; a defect is reported with the file, the problem
/// (naming the element) and the tool's switch that repairs it.
blended_shape<double> prepare_or_explain(const blended_matcher<>& matcher, const triangle_mesh<double>& mesh,
                                         const std::string& path, const match_options& m, int threads) {
  try {
    auto o = matcher.options().shape;
    o.threads = threads;
    return make_blended_shape(mesh, o);
  } catch (const mesh_defect_error& e) {
    throw mesh_defect_error(e.reason(), e.defect(), e.element(), path, e.problem(), remedy_of(e.defect(), m));
  } catch (const invalid_input& e) {
    throw invalid_input(e.reason(), e.element(), path + ": " + e.what());
  }
}

/// "5" when every feature is an AGD maximum, else "4 (2 AGD maxima)"; "7, 5 without bumps" with a second set.
std::string feature_count(const blended_shape<double>& shape) {
  std::string text = std::to_string(shape.features().size());
  if (static_cast<std::size_t>(shape.num_agd_maxima()) != shape.features().size())
    text += " (" + std::to_string(shape.num_agd_maxima()) + " AGD maxima)";
  if (shape.alternative()) text += ", " + std::to_string(shape.alternative()->features().size()) + " without bumps";
  return text;
}

/// A source vertex that a repair dropped (on a small piece, or on no face) has no image; it takes the image of
/// the nearest kept source vertex, so the dense map still has one line per vertex. Returns how many did.
index_t map_dropped_vertices(const triangle_mesh<double>& source, surface_map<double>& map) {
  std::vector<index_t> kept, dropped;
  for (index_t v = 0; v < map.source_size(); ++v)
    (map.target_vertex(v) == no_index ? dropped : kept).push_back(v);
  if (dropped.empty() || kept.empty()) return 0;
  Eigen::Matrix<double, Eigen::Dynamic, 3> P(static_cast<index_t>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) P.row(static_cast<index_t>(i)) = source.V.row(kept[i]);
  const knn_index<double, 3> index(P);
  for (const index_t v : dropped) {
    const index_t from = kept[static_cast<std::size_t>(index.nearest(source.V.row(v).transpose()).index)];
    map.points[static_cast<std::size_t>(v)] = map.points[static_cast<std::size_t>(from)];
    map.nearest[static_cast<std::size_t>(v)] = map.nearest[static_cast<std::size_t>(from)];
  }
  return static_cast<index_t>(dropped.size());
}

int run_match(const match_options& m) {
  const std::string& out = m.out;
  const std::string& precise = m.precise;
  const std::string& cand = m.candidates;
  const std::string& colors = m.colors;
  blended_matcher_options o;
  o.shape.num_samples = m.samples;
  if (m.min_features > m.features)
    throw cli::usage_error("--min-features " + std::to_string(m.min_features) + " is more than --features " +
                           std::to_string(m.features) + ": lower it, or raise --features");
  o.shape.max_features = m.features;
  if (m.min_features >= 0) o.shape.min_features = m.min_features;
  o.shape.feature_radius = m.feature_radius;
  o.shape.alternative_feature_persistence = m.alternative_persistence;
  o.selection = selection_rule(m.selection);
  const long long max_enumerated = m.max_enumerated;
  const long long seed = m.seed;
  const std::string& pruning = m.pruning;
  // The tool repairs what is safely repairable unless --strict; the library keeps every repair off by default.
  o.shape.repairs = sphere_repair_options::all(m.max_hole_edges);
  if (m.keep_largest) o.shape.repairs.max_dropped_area_fraction = 1.0;  // asked for: drop whatever is smaller
  if (m.strict) {
    o.shape.repairs.remove_bad_faces = o.shape.repairs.split_non_manifold_vertices = false;
    o.shape.repairs.keep_largest_component = m.keep_largest;
    o.shape.repairs.close_small_holes = m.close_holes;
    o.shape.flattening.accept_pinched_vertices = false;  // a pinch is a defect too: refused, not worked around
  }
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
  o.refine = m.refine == "zoomout";
  o.refinement_move_check = m.refinement_move_check;
  o.both_directions = m.both_directions;
  zoomout_options zoomout;
  zoomout.final_size = m.refine_basis;
  zoomout.initial_size = std::min(zoomout.initial_size, zoomout.final_size);
  const blended_matcher<> matcher(o, cands, {}, {}, zoomout_refiner(zoomout));

  const int threads = static_cast<int>(detail::resolve_threads(o.threads, "match"));
  // Both files are read side by side; notes and errors are reported in argument order.
  const auto note_short_faces = [](const mesh_file<double>& file, const std::string& path) {
    if (file.short_faces > 0) std::fprintf(stderr, "match: %s\n", file.short_faces_note(path).c_str());
  };
  auto files = detail::side_by_side(
      threads > 1,
      [&] {
        auto file = read_mesh(std::filesystem::path(pos[0]));
        note_short_faces(file, pos[0]);
        return file;
      },
      [&] { return read_mesh(std::filesystem::path(pos[1])); });
  note_short_faces(files.second, pos[1]);
  const auto A = std::move(files.first.mesh);
  const auto B = std::move(files.second.mesh);
  if (verbose)
    std::fprintf(stderr, "read %s (%ld vertices) and %s (%ld vertices)\nmemory: %s\n", pos[0].c_str(),
                 long(A.V.rows()), pos[1].c_str(), long(B.V.rows()), huge_pages_status().c_str());
  const auto t0 = std::chrono::steady_clock::now();
  // As blended_matcher::match(a, b) does: side by side, each allowed all the threads; here each failure is
  // explained in the tool's terms first.
  const auto shapes =
      detail::side_by_side(threads > 1, [&] { return prepare_or_explain(matcher, A, pos[0], m, threads); },
                           [&] { return prepare_or_explain(matcher, B, pos[1], m, threads); });
  const auto& sa = shapes.first;
  const auto& sb = shapes.second;
  for (const auto& [shape, path] : {std::pair{&sa, pos[0]}, std::pair{&sb, pos[1]}})
    if (shape->repairs().any())
      std::fprintf(stderr, "match: repaired %s: %s\n", path.c_str(), shape->repairs().to_string().c_str());
  if (verbose)
    std::fprintf(stderr, "  %-12s %8.3f s (features: %s and %s)\n", "preprocess",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                 feature_count(sa).c_str(), feature_count(sb).c_str());
  auto res = matcher.match(sa, sb);
  if (verbose)
    std::fprintf(stderr, "total %.3f s, %zu candidate maps, %zu blended maps, selected score %.4f\n",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), res.candidates.size(),
                 res.blended.size(), res.blended[static_cast<std::size_t>(res.selected)].score);
  if (verbose && (sa.alternative() || sb.alternative()))
    std::fprintf(stderr, "kept the features %s: geodesic distortion %.4f against %.4f %s\n",
                 res.alternative_features ? "without bumps" : "with every AGD maximum",
                 res.blended[static_cast<std::size_t>(res.selected)].geodesic_distortion,
                 res.other_features_distortion, res.alternative_features ? "with every maximum" : "without bumps");
  if (verbose && o.both_directions && !blended_matcher<>::judges_both_directions(o))
    std::fprintf(stderr, "both directions: not used with --selection %s (the two-way rule judges by confidence)\n",
                 m.selection.c_str());
  if (verbose && blended_matcher<>::judges_both_directions(o)) {
    const auto two_way = [&](index_t g) { return res.blended[static_cast<std::size_t>(g)].two_way_confidence; };
    if (res.selected != res.forward_selected)
      std::fprintf(stderr,
                   "both directions: blended map %ld replaced by %ld (two-way confidence %.4f against %.4f)\n",
                   long(res.forward_selected), long(res.selected), two_way(res.selected), two_way(res.forward_selected));
    else
      std::fprintf(stderr, "both directions: blended map %ld kept (two-way confidence %.4f)\n", long(res.selected),
                   two_way(res.selected));
  }
  if (verbose && o.refine)
    std::fprintf(stderr, "refinement %s; the blended image put back at %ld vertices it moved %g or more\n",
                 res.refinement_accepted ? "kept" : "undone (it distorts too much)", long(res.refinement_moves_undone),
                 m.refinement_move_check);
  if (res.info != status::ok)
    std::fprintf(stderr, "warning: eigen-solver status %s; the map is from the last iterate\n", to_string(res.info));

  const index_t borrowed = map_dropped_vertices(A, res.map);
  if (borrowed > 0)
    std::fprintf(stderr, "match: %ld vertices of %s were on dropped pieces; each takes the image of its nearest kept vertex\n",
                 long(borrowed), pos[0].c_str());
  std::vector<index_t> ids(static_cast<std::size_t>(res.map.source_size()));
  for (index_t v = 0; v < res.map.source_size(); ++v) ids[static_cast<std::size_t>(v)] = res.map.target_vertex(v);
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
      ->check(at_least(3LL));
  app.add_option("--min-features", m->min_features,
                 "a mesh with fewer AGD maxima gets its most central point and then farthest points as\n"
                 "features, up to N (default " + std::to_string(blended_shape_options{}.min_features) +
                     " or --features if fewer; 0 = the maxima alone)")
      ->type_name("N")
      ->check(at_least(0LL));
  app.add_option("--feature-radius", m->feature_radius,
                 "AGD maxima closer than R (units of sqrt(area)) are one feature (default 0.15)")
      ->type_name("R");
  app.add_option("--alternative-persistence", m->alternative_persistence,
                 "also match with the features whose AGD persistence is at least P (units of sqrt(area)):\n"
                 "bumps on an extremity, a dog's eyes beside its head, are dropped; that map is kept\n"
                 "where it distorts geodesic distances at least 5 % less (default " +
                     option_check_detail::number_text(blended_shape_options{}.alternative_feature_persistence) +
                     "; 0 = every maximum only)")
      ->type_name("P")
      ->check(at_least(0.0));
  app.add_option("--selection", m->selection,
                 "how one blended map is chosen among the groups': confidence alone unless the most\n"
                 "confident map distorts geodesic distances clearly (then as confidence-distortion), the\n"
                 "lowest sum of its ranks by integrated confidence and by geodesic distortion, confidence\n"
                 "alone (the chapter's), area preservation alone, or the sum of the ranks by area and\n"
                 "confidence (default " +
                     selection_name(blended_matcher_options{}.selection) + ")")
      ->type_name("adaptive|confidence-distortion|confidence|area|area-confidence")
      ->check(one_of({"adaptive", "confidence-distortion", "confidence", "area", "area-confidence"}));
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
  app.add_flag("--strict", m->strict,
               "refuse a mesh that is not a closed genus-0 manifold instead of repairing it\n"
               "(by default match removes collapsed and duplicate faces, splits non-manifold\n"
               "vertices, keeps the largest piece and fills holes, and says what it changed)");
  app.add_flag("--close-holes", m->close_holes, "with --strict: still fill holes of up to --max-hole-edges edges");
  app.add_flag("--keep-largest", m->keep_largest,
               "keep only the largest connected piece, however large the others (by default\n"
               "only pieces holding at most 5 % of the area are dropped; with --strict, none)");
  app.add_option("--max-hole-edges", m->max_hole_edges, "longest hole (boundary loop, in edges) that is filled (default 64)")
      ->type_name("N")
      ->check(at_least(3LL));
  app.add_option("--refine", m->refine,
                 "refine the blended map with ZoomOut (spectral upsampling of its functional map;\n"
                 "default), or leave it as blended (none)")
      ->type_name("zoomout|none")
      ->check(one_of({"zoomout", "none"}));
  app.add_option("--refine-basis", m->refine_basis,
                 "Laplace-Beltrami eigenfunctions ZoomOut ends with (default " +
                     std::to_string(zoomout_options{}.final_size) + "; more is sharper and slower)")
      ->type_name("K")
      ->check(at_least(2LL));
  app.add_option("--refinement-move-check", m->refinement_move_check,
                 "where the refinement moves an image D or more (units of sqrt(target area)), put\n"
                 "the blended image back if it agrees better with the rest of the map (default " +
                     option_check_detail::number_text(blended_matcher_options{}.refinement_move_check) +
                     "; 0 = keep every refined image)")
      ->type_name("D")
      ->check(at_least(0.0));
  app.add_flag("--both-directions,!--one-direction", m->both_directions,
               "--both-directions (the default) also matches TGT -> SRC and selects by the confidence of each map "
               "and its inverse (with the selections by confidence); --one-direction matches SRC -> TGT only (the "
               "matching stages run once, about a quarter less time)");
  app.add_option("--threads", m->threads, "worker threads, 0 = all cores (default 0)")->type_name("T")->check(at_least(0LL));
  app.add_flag("-v,--verbose", m->verbose, "progress and timings per stage on stderr");
  app.footer(
      "Blended intrinsic maps (dissertation ch. 3) from SRC to TGT (OFF, OBJ, PLY, STL). They need closed genus-0\n"
      "surfaces: by default match repairs what it safely can (collapsed and duplicate faces, non-manifold\n"
      "vertices, pieces holding at most 5 % of the area, holes of up to --max-hole-edges edges) and says\n"
      "on stderr what it changed;\n"
      "--strict refuses instead. A defect no repair removes (a handle, a non-manifold edge) is refused with\n"
      "the file, the element and the reason.\n"
      "The blended map is then refined by ZoomOut (Melzi et al. 2019) unless --refine none.\n"
      "Writes the benchmark's dense map: one line per SRC vertex, the 0-based TGT vertex it maps to (a vertex\n"
      "on a dropped piece takes the image of its nearest kept vertex).");
  return [m] { return run_match(*m); };
}

const register_command register_match{"match", {"blended intrinsic maps between two meshes (writes a dense .map)", setup_match}};

}  // namespace
