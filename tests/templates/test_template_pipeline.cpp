// SPDX-License-Identifier: MIT
// Learner, initializer, collection runner (resume, bad shapes), co-alignment, on two mesh models.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "shapestruct/generate/assembly_generator.hpp"
#include "shapestruct/io/write_mesh.hpp"
#include "shapestruct/templates/collection_runner.hpp"
#include "support/fixtures.hpp"
#include "support/legacy_mesh.hpp"
#include "support/thread_exchange.hpp"

using namespace shapestruct;
namespace fs = std::filesystem;

namespace {

/// A hand-written template for the generator's chairs (+Y up, seat ~0.45 high): seat, back, four legs.
part_template synthetic_chair_template() {
  part_template t;
  t.id = "test chair";
  auto box = [](const char* n, index_t l, Eigen::Vector3d c, Eigen::Vector3d s) {
    part_box b;
    b.name = n;
    b.label = l;
    b.center = c;
    b.size = s;
    b.sigma_center = Eigen::Vector3d::Constant(0.05);
    b.sigma_size = Eigen::Vector3d::Constant(0.06);
    return b;
  };
  // Canonical frame: bbox centre, unit diagonal; a generated chair is about 0.48 x 0.95 x 0.45.
  t.parts = {box("seat", 0, {0, -0.05, 0.02}, {0.40, 0.04, 0.38}), box("back", 1, {0, 0.2, -0.19}, {0.38, 0.40, 0.04}),
             box("leg", 2, {-0.17, -0.27, 0.16}, {0.03, 0.34, 0.03}), box("leg", 2, {0.17, -0.27, 0.16}, {0.03, 0.34, 0.03}),
             box("leg", 2, {-0.17, -0.27, -0.16}, {0.03, 0.34, 0.03}), box("leg", 2, {0.17, -0.27, -0.16}, {0.03, 0.34, 0.03})};
  return t;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("make_shape_samples and fit_template agree on triangle_mesh and legacy_mesh") {
  const assembly_generator<double> gen(assembly_kind::chair, 5);
  const auto a = gen.generate(0);
  const auto legacy = test::to_legacy(a.mesh);
  const auto s1 = make_shape_samples(a.mesh, {.points = 600});
  const auto s2 = make_shape_samples(legacy, {.points = 600});
  REQUIRE(s1.size() == 600);
  REQUIRE(s2.size() == 600);
  CHECK((s1.points - s2.points).cwiseAbs().maxCoeff() < 1e-5);  // float storage of the legacy model
  CHECK(s1.features.cols() == 4);
  CHECK(!s1.edges.empty());
  const auto t = synthetic_chair_template();
  const auto f1 = fit_template(t, s1);
  const auto f2 = fit_template(t, s2);
  index_t same = 0;
  for (std::size_t i = 0; i < f1.labels.size(); ++i) same += f1.labels[i] == f2.labels[i] ? 1 : 0;
  CHECK(static_cast<double>(same) / 600.0 > 0.95);
  // Co-alignment: deformation-aware co-aligned points are closer to the mean template than rigid ones.
  const auto rigid = co_aligned_points(t, s1, f1, false);
  const auto def = co_aligned_points(t, s1, f1, true);
  CHECK(rigid.rows() == 600);
  CHECK(def.allFinite());
  const auto corr = canonical_correspondence(t, s1, f1, s1, f1);
  index_t self = 0;
  for (std::size_t i = 0; i < corr.size(); ++i) self += corr[i] == static_cast<index_t>(i) ? 1 : 0;
  CHECK(self == 600);  // a shape maps onto itself through the canonical space
}

TEST_CASE("canonical_correspondence across two templates goes through parts with the same output label") {
  const assembly_generator<double> gen(assembly_kind::chair, 5);
  const auto m = gen.generate(0).mesh;
  const auto s1 = make_shape_samples(m, {.points = 500});
  const auto s2 = make_shape_samples(test::to_legacy(m), {.points = 500});
  const auto t = synthetic_chair_template();
  // t2: the same boxes in another order, and the back relabelled so it has no counterpart in t.
  part_template t2 = t;
  std::reverse(t2.parts.begin(), t2.parts.end());
  t2.parts.back().label = 1;  // was the seat (label 0) -> now shares the back's label 1
  t2.parts[t2.parts.size() - 2].label = 7;  // the back: a label t does not have
  const auto pm = template_part_map(t, t2);
  REQUIRE(pm.size() == 6);
  CHECK(pm[0] == -1);  // t's seat (label 0): t2 has no part labelled 0
  CHECK(pm[1] == 5);   // t's back (label 1) -> t2's only label-1 part
  for (index_t b = 2; b < 6; ++b) CHECK(pm[static_cast<std::size_t>(b)] == 5 - b);  // legs: nearest same-label box
  const auto same = template_part_map(t, t);
  for (index_t b = 0; b < 6; ++b) CHECK(same[static_cast<std::size_t>(b)] == b);
  // A shape fitted with t (triangle_mesh) and the same shape fitted with t reordered (legacy_mesh): leg points
  // map onto the same (or an adjacent) sample position.
  part_template t3 = t;
  std::reverse(t3.parts.begin(), t3.parts.end());
  const auto f1 = fit_template(t, s1);
  const auto f3 = fit_template(t3, s2);
  const auto corr = canonical_correspondence(t, s1, f1, t3, s2, f3);
  REQUIRE(corr.size() == 500);
  index_t close = 0, legs = 0, on_leg = 0;
  for (std::size_t i = 0; i < corr.size(); ++i) {
    if (f1.labels[i] != 2) continue;
    ++legs;
    on_leg += f3.labels[static_cast<std::size_t>(corr[i])] == 2 ? 1 : 0;
    close += (s1.points.row(static_cast<index_t>(i)) - s2.points.row(corr[i])).norm() < 0.05 ? 1 : 0;
  }
  REQUIRE(legs > 20);
  CHECK(static_cast<double>(on_leg) / static_cast<double>(legs) > 0.95);
  CHECK(static_cast<double>(close) / static_cast<double>(legs) > 0.9);
}

TEST_CASE("make_shape_samples bad input") {
  auto m = test::octahedron<double>();
  m.V(1, 0) = std::nan("");
  CHECK_THROWS_AS(make_shape_samples(m), invalid_input);
  CHECK_THROWS_AS(make_shape_samples(triangle_mesh<double>{}), invalid_input);
  CHECK_THROWS_AS(make_shape_samples(test::octahedron<double>(), {.points = 1}), invalid_input);
}

TEST_CASE("learn_templates moves the template towards the collection, initializer builds valid templates") {
  const assembly_generator<double> gen(assembly_kind::chair, 11);
  std::vector<shape_samples> shapes;
  for (int i = 0; i < 8; ++i) shapes.push_back(make_shape_samples(gen.generate(static_cast<std::uint64_t>(i)).mesh, {.points = 500}));
  auto t = synthetic_chair_template();
  template_learner_options lo;
  lo.N_iter = 2;
  lo.K_L = 4;
  lo.e_min = 1e9;  // learn from every shape
  const auto before = fit_template_set({t}, shapes, lo);
  const auto learned = learn_templates({t}, shapes, lo);
  REQUIRE(!learned.templates.empty());
  CHECK(learned.learned_shapes == 8);
  const auto after = fit_template_set(learned.templates, shapes, lo);
  double eb = 0, ea = 0;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    eb += before[i].fit.terms[0];  // the distance term: how well the boxes fit the surfaces
    ea += after[i].fit.terms[0];
  }
  // Learned means fit the collection's surfaces better than the hand-made guess (the total energy is not
  // comparable: learning adds feature Gaussians, and so a feature cost the untrained template does not have).
  CHECK(ea < eb);
  CHECK(learned.templates[0].parts[0].feature_mean.size() == 4);
  // Same result with one thread and with two.
  lo.threads = 1;
  const auto one = learn_templates({t}, shapes, lo);
  lo.threads = 2;
  const auto two = learn_templates({t}, shapes, lo);
  CHECK(format_json(template_to_json(one.templates[0])) == format_json(template_to_json(two.templates[0])));
  const auto [auto_t, e] = template_from_shape(shapes[0], {.parts = 4});
  // One box per merged cell; congruent cells (legs) share a label, so at most 4 labels.
  CHECK(auto_t.num_parts() >= 1);
  std::vector<index_t> auto_labels;
  for (const auto& p : auto_t.parts) auto_labels.push_back(p.label);
  std::sort(auto_labels.begin(), auto_labels.end());
  CHECK(std::unique(auto_labels.begin(), auto_labels.end()) - auto_labels.begin() <= 4);
  CHECK(template_from_shape(shapes[0], {.parts = 4, .oversegment = 0}).first.num_parts() == 4);  // plain Voronoi
  CHECK(std::isfinite(e));
  validate_template(auto_t);
  CHECK_THROWS_AS(learn_templates({}, shapes, lo), invalid_input);
  CHECK_THROWS_AS(template_from_shape(shapes[0], {.parts = 0}), invalid_input);
}

TEST_CASE("auto_templates reports each candidate template once, in order, and the result does not depend on it") {
  const assembly_generator<double> gen(assembly_kind::chair, 11);
  std::vector<shape_samples> shapes;
  for (int i = 0; i < 4; ++i) shapes.push_back(make_shape_samples(gen.generate(static_cast<std::uint64_t>(i)).mesh, {.points = 400}));
  template_learner_options lo;
  lo.N_iter = 1;
  lo.threads = 2;
  template_initializer_options io;
  io.learn_best = 1;
  const auto quiet = auto_templates(shapes, lo, io);
  std::vector<std::pair<std::size_t, std::size_t>> calls;
  io.progress = [&calls](std::size_t done, std::size_t total) { calls.emplace_back(done, total); };
  const auto reported = auto_templates(shapes, lo, io);
  REQUIRE(calls.size() == shapes.size());
  for (std::size_t c = 0; c < calls.size(); ++c) CHECK(calls[c] == std::pair<std::size_t, std::size_t>(c + 1, shapes.size()));
  REQUIRE(quiet.size() == reported.size());
  for (std::size_t t = 0; t < quiet.size(); ++t)
    CHECK(format_json(template_to_json(quiet[t])) == format_json(template_to_json(reported[t])));
}

TEST_CASE("learning set admits energies below max(tau x best or e_max) and its non-re-estimating shapes spawn (5.3.3)") {
  // Half triangle_mesh, half legacy_mesh: the learner sees only samples, both models must behave alike.
  const assembly_generator<double> gen(assembly_kind::chair, 11);
  std::vector<shape_samples> shapes;
  for (int i = 0; i < 8; ++i) {
    const auto m = gen.generate(static_cast<std::uint64_t>(i)).mesh;
    shapes.push_back(i % 2 == 0 ? make_shape_samples(m, {.points = 400})
                                : make_shape_samples(test::to_legacy(m), {.points = 400}));
  }
  template_learner_options lo;
  lo.N_iter = 1;
  lo.e_min = 0;             // no fit is "almost certainly good": nothing re-estimates the template ...
  lo.tau = 1e-9;            // ... tau x best is below every energy ...
  lo.e_max = 1e9;           // ... but every energy is below e_max, so all 8 form the Learning Set
  lo.cluster_distance = 1e9;  // one cluster of 8 > 5% of the Learning Set: it spawns a template
  const auto r = learn_templates({synthetic_chair_template()}, shapes, lo);
  CHECK(r.learned_shapes == 8);
  REQUIRE(r.templates.size() == 2);
  CHECK(r.outliers == 0);
  // The spawned template keeps the parent's parts and output labels (so one label mapping serves both) and is
  // estimated from the cluster: its seat moved from the hand-made guess.
  const auto& parent = r.templates[0];
  const auto& child = r.templates[1];
  REQUIRE(child.num_parts() == parent.num_parts());
  for (index_t b = 0; b < parent.num_parts(); ++b)
    CHECK(child.parts[static_cast<std::size_t>(b)].label == parent.parts[static_cast<std::size_t>(b)].label);
  CHECK((child.parts[0].center - parent.parts[0].center).norm() > 1e-4);
  // With no window (e_max below every energy too) nothing is learned and nothing spawns.
  lo.e_max = 0;
  const auto none = learn_templates({synthetic_chair_template()}, shapes, lo);
  CHECK(none.learned_shapes == 0);
  CHECK(none.templates.size() == 1);
}

TEST_CASE("run_template_collection writes per-shape results, skips a bad file, resumes identically") {
  const fs::path dir = fs::temp_directory_path() / "shapestruct_tpl_pipeline";
  fs::remove_all(dir);
  fs::create_directories(dir / "in");
  const assembly_generator<double> gen(assembly_kind::chair, 2);
  for (int i = 0; i < 5; ++i) write_mesh(dir / "in" / ("c" + std::to_string(i) + ".off"), gen.generate(static_cast<std::uint64_t>(i)).mesh);
  { std::ofstream(dir / "in" / "broken.off") << "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"; }
  { std::ofstream(dir / "in" / "empty.off") << ""; }
  collection_run_options opt;
  opt.sampling.points = 400;
  opt.run_learning = false;
  opt.write_ply = true;
  std::vector<std::string> problems;
  opt.problem = [&](const std::string& f, const std::string&) { problems.push_back(fs::path(f).filename().string()); };
  const auto files = list_shape_files(dir / "in");
  REQUIRE(files.size() == 7);
  const auto s1 = run_template_collection(files, dir / "out", {synthetic_chair_template()}, opt);
  CHECK(s1.processed == 5);
  CHECK(s1.failed == 2);
  std::sort(problems.begin(), problems.end());
  CHECK(problems == std::vector<std::string>{"broken.off", "empty.off"});
  for (int i = 0; i < 5; ++i) {
    const std::string st = "c" + std::to_string(i);
    CHECK(fs::exists(dir / "out" / (st + ".seg")));
    CHECK(fs::exists(dir / "out" / (st + ".fit.json")));
    CHECK(fs::exists(dir / "out" / (st + ".points.txt")));
    CHECK(fs::exists(dir / "out" / "ply" / (st + ".boxes.ply")));
  }
  CHECK(fs::exists(dir / "out" / "summary.json"));
  const std::string seg2 = slurp(dir / "out" / "c2.seg"), rec2 = slurp(dir / "out" / "c2.fit.json");
  // Interrupt: lose two shapes' results, run again with another thread count.
  fs::remove(dir / "out" / "c2.fit.json");
  fs::remove(dir / "out" / "c2.seg");
  fs::remove(dir / "out" / "c4.fit.json");
  opt.threads = 1;
  problems.clear();
  const auto s2 = run_template_collection(files, dir / "out", {synthetic_chair_template()}, opt);
  CHECK(s2.processed == 2);
  CHECK(s2.skipped == 3);
  CHECK(slurp(dir / "out" / "c2.seg") == seg2);
  CHECK(slurp(dir / "out" / "c2.fit.json") == rec2);
  fs::remove_all(dir);
}

TEST_CASE("run_template_collection: two processes sharing one folder write one process's files, byte for byte") {
  const fs::path dir = fs::temp_directory_path() / "shapestruct_tpl_shared";
  fs::remove_all(dir);
  fs::create_directories(dir / "in");
  const assembly_generator<double> gen(assembly_kind::chair, 2);
  for (int i = 0; i < 5; ++i) write_mesh(dir / "in" / ("c" + std::to_string(i) + ".off"), gen.generate(static_cast<std::uint64_t>(i)).mesh);
  { std::ofstream(dir / "in" / "broken.off") << "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"; }
  collection_run_options opt;
  opt.sampling.points = 400;
  opt.learn_subset = 4;
  opt.threads = 1;
  const auto files = list_shape_files(dir / "in");
  const auto alone = run_template_collection(files, dir / "alone", {synthetic_chair_template()}, opt);
  const auto parts = test::run_parts(2, [&](const work_share& share) {
    auto own = opt;
    own.share = share;
    return run_template_collection(files, dir / "shared", {synthetic_chair_template()}, own);
  });
  for (const auto& s : parts) {
    CHECK(s.cluster_sizes == alone.cluster_sizes);
    CHECK(s.failed == 1);
    CHECK(s.processed == alone.processed);
  }
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir / "alone"))
    if (e.is_regular_file()) names.push_back(fs::relative(e.path(), dir / "alone").string());
  std::sort(names.begin(), names.end());
  std::size_t shared_files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir / "shared")) shared_files += e.is_regular_file() ? 1 : 0;
  CHECK(shared_files == names.size());
  REQUIRE(names.size() > 10);
  for (const auto& n : names) {
    INFO(n);
    CHECK(slurp(dir / "shared" / n) == slurp(dir / "alone" / n));
  }
  fs::remove_all(dir);
}
