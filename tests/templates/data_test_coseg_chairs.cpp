// SPDX-License-Identifier: MIT
// COSEG chairs with the hand-authored templates (docs/templates/), an automatic candidate, and the fully automatic
// mode (about 40 s), skipped without data.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shapestruct/eval/labeling_accuracy.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "shapestruct/templates/face_labels.hpp"
#include "shapestruct/templates/make_shape_samples.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/template_fitter.hpp"
#include "shapestruct/templates/template_initializer.hpp"
#include "shapestruct/templates/template_learner.hpp"
#include "support/data_path.hpp"

using namespace shapestruct;

namespace {
/// A fitted chair's face labels beside its ground truth (COSEG .seg is 1-based), weighted by face area.
labeled_shape scored_shape(const triangle_mesh<double>& m, const shape_samples& s, const std::vector<index_t>& labels,
                           const std::filesystem::path& seg) {
  labeled_shape ls;
  ls.predicted = project_labels_to_faces(m, s, labels);
  ls.truth = read_segmentation(seg, m.F.rows());
  for (auto& x : ls.truth) x -= 1;
  const auto A = face_areas<double>(m.V, m.F);
  ls.weight.assign(A.data(), A.data() + A.size());
  return ls;
}
}  // namespace

TEST_CASE("COSEG chairs: the hand-authored chair template labels three chairs above 95 %") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "coseg_subset/res/chairs");
  const auto t = read_templates(std::string(SHAPESTRUCT_TEST_SOURCE_DIR) + "/../docs/templates/chair.json").at(0);
  std::vector<labeled_shape> scored;
  for (const char* id : {"12", "13", "15"}) {
    const auto m = read_mesh(dir / "shapes" / (std::string(id) + ".off")).mesh;
    const auto s = make_shape_samples(m);
    const auto f = fit_template(t, s);
    scored.push_back(scored_shape(m, s, f.labels, dir / "gt" / (std::string(id) + ".seg")));
  }
  const auto acc = labeling_accuracy(scored);
  MESSAGE("accuracy " << acc.accuracy);
  CHECK(acc.accuracy > 0.95);
}

TEST_CASE("COSEG chairs: the chair-and-stool set gives each support style its template, with one label mapping") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "coseg_subset/res/chairs");
  const auto set = read_templates(std::string(SHAPESTRUCT_TEST_SOURCE_DIR) + "/../docs/templates/chairs_and_stools.json");
  REQUIRE(set.size() == 5);
  // id -> expected template: a four-legged chair (0), a backless stool on a column (2), a stool on a column with
  // sloping feet (3, its feet typed as 4-decimal axes in the JSON) and a swivel chair (4).
  const std::vector<std::pair<std::string, std::size_t>> cases = {{"12", 0}, {"22", 2}, {"0", 3}, {"23", 4}};
  std::vector<labeled_shape> scored;
  for (const auto& [id, expected] : cases) {
    const auto m = read_mesh(dir / "shapes" / (id + ".off")).mesh;
    const auto s = make_shape_samples(m);
    template_fit best;
    std::size_t which = 0;
    for (std::size_t t = 0; t < set.size(); ++t) {
      auto f = fit_template(set[t], s);
      if (f.energy < best.energy) {
        best = std::move(f);
        which = t;
      }
    }
    // A template with a must-exist back must not win a backless stool, nor four legs a column with feet.
    CHECK_MESSAGE(which == expected, "shape " << id);
    scored.push_back(scored_shape(m, s, best.labels, dir / "gt" / (id + ".seg")));
  }
  // Shared output labels across the set: one mapping serves all four shapes.
  const auto acc = labeling_accuracy(scored);
  MESSAGE("accuracy " << acc.accuracy);
  CHECK(acc.accuracy > 0.95);
}

TEST_CASE("COSEG chairs: the automatic candidate from chair 13 gives its four legs one label, the template fits") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "coseg_subset/res/chairs");
  const auto m = read_mesh(dir / "shapes" / "13.off").mesh;
  const auto s = make_shape_samples(m);
  const auto [t, energy] = template_from_shape(s);
  // One leg's cell also held a strip of the seat, which once gave it a label of its own: seat, back, legs.
  std::set<index_t> labels;
  for (const auto& b : t.parts) labels.insert(b.label);
  CHECK(labels.size() == 3);
  std::vector<std::pair<double, index_t>> by_height;
  for (const auto& b : t.parts) by_height.emplace_back(b.center[t.up_axis], b.label);
  std::sort(by_height.begin(), by_height.end());
  REQUIRE(by_height.size() >= 4);
  for (int k = 1; k < 4; ++k) CHECK(by_height[k].second == by_height[0].second);
  // The candidate labels its own chair as the ground truth does, up to the names of the labels.
  const auto f = fit_template(t, s);
  const auto acc = labeling_accuracy({scored_shape(m, s, f.labels, dir / "gt" / "13.seg")});
  MESSAGE("energy " << energy << ", accuracy " << acc.accuracy);
  CHECK(acc.accuracy > 0.95);
}

TEST_CASE("COSEG chairs: the fully automatic mode labels the consistently labelled chairs above 91.2 %") {
  SHAPESTRUCT_REQUIRE_DATA(dir, "coseg_subset/res/chairs");
  // The protocol (one best one-to-one label mapping for the whole set, accuracy by face area) over the 17
  // chairs whose ground truth numbers back and legs the same way (docs/templates/coseg_chairs_oracle.py finds the
  // other five from label heights). 91.2 % is the chapter's automatic result on the 400 chairs. About 40 s.
  const std::set<std::string> other_convention{"101", "102", "103", "109", "110"};
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir / "shapes"))
    if (e.path().extension() == ".off") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() == 22);
  std::vector<triangle_mesh<double>> meshes;
  std::vector<shape_samples> samples;
  for (const auto& f : files) {
    meshes.push_back(read_mesh(f).mesh);
    samples.push_back(make_shape_samples(meshes.back()));
  }
  template_learner_options lo;
  const auto templates = learn_templates(auto_templates(samples, lo), samples, lo).templates;
  const auto fits = fit_template_set(templates, samples, lo);
  std::vector<labeled_shape> kept;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto id = files[i].stem().string();
    if (other_convention.count(id) == 0)
      kept.push_back(scored_shape(meshes[i], samples[i], fits[i].fit.labels, dir / "gt" / (id + ".seg")));
  }
  REQUIRE(kept.size() == 17);
  const auto acc = labeling_accuracy(kept);
  MESSAGE(templates.size() << " templates, accuracy on the 17 chairs " << acc.accuracy);
  CHECK(acc.accuracy > 0.912);
}
