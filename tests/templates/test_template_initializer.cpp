// SPDX-License-Identifier: MIT
// Automatic initialisation (5.3.4): the structure-following segmentation separates the parts of an assembly of
// boxes (seat, back, four legs) where the plain farthest-point Voronoi cells cut across them; on two mesh models.
#include <doctest/doctest.h>

#include <map>
#include <set>

#include "shapestruct/templates/make_shape_samples.hpp"
#include "shapestruct/templates/template_initializer.hpp"
#include "support/legacy_mesh.hpp"

using namespace shapestruct;

namespace {

/// A chair made of six closed boxes (+Y up): seat (part 0), back (1), four legs (2). face_part gets the part of
/// every face.
triangle_mesh<double> box_chair(std::vector<int>& face_part) {
  triangle_mesh<double> m;
  std::vector<Eigen::RowVector3d> V;
  std::vector<Eigen::RowVector3i> F;
  face_part.clear();
  const auto add_box = [&](Eigen::Vector3d lo, Eigen::Vector3d hi, int part) {
    const int base = static_cast<int>(V.size());
    for (int c = 0; c < 8; ++c)
      V.emplace_back((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
    // Two triangles per side (vertex index bits: 1 = x, 2 = y, 4 = z).
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      F.emplace_back(base + q[0], base + q[1], base + q[2]);
      F.emplace_back(base + q[0], base + q[2], base + q[3]);
      face_part.push_back(part);
      face_part.push_back(part);
    }
  };
  add_box({-0.22, 0.40, -0.22}, {0.22, 0.45, 0.22}, 0);   // seat
  add_box({-0.22, 0.45, -0.22}, {0.22, 0.95, -0.18}, 1);  // back, standing on the seat's rear edge
  for (const double x : {-0.2, 0.17})
    for (const double z : {-0.2, 0.17}) add_box({x, 0.0, z}, {x + 0.03, 0.40, z + 0.03}, 2);  // legs
  m.V.resize(static_cast<index_t>(V.size()), 3);
  m.F.resize(static_cast<index_t>(F.size()), 3);
  for (std::size_t i = 0; i < V.size(); ++i) m.V.row(static_cast<index_t>(i)) = V[i];
  for (std::size_t f = 0; f < F.size(); ++f) m.F.row(static_cast<index_t>(f)) = F[f].cast<index_t>();
  return m;
}

/// Fraction of samples whose label maps to their true part, under the best one-to-one map of labels to parts
/// (brute force over the few labels), and the label of each true part (majority).
double agreement(const std::vector<index_t>& label, const std::vector<int>& truth, index_t num_labels) {
  std::map<std::pair<index_t, int>, int> count;
  for (std::size_t i = 0; i < label.size(); ++i) ++count[{label[i], truth[i]}];
  // One-to-one: try every assignment of the 3 parts to distinct labels.
  int best = 0;
  for (index_t a = 0; a < num_labels; ++a)
    for (index_t b = 0; b < num_labels; ++b)
      for (index_t c = 0; c < num_labels; ++c)
        if (a != b && b != c && a != c) best = std::max(best, count[{a, 0}] + count[{b, 1}] + count[{c, 2}]);
  return static_cast<double>(best) / static_cast<double>(label.size());
}

template <class Mesh>
void check_segmentation(const Mesh& mesh, const std::vector<int>& face_part) {
  const auto s = make_shape_samples(mesh, {.points = 1200, .seed = 3});
  std::vector<int> truth(static_cast<std::size_t>(s.size()));
  for (index_t i = 0; i < s.size(); ++i)
    truth[static_cast<std::size_t>(i)] = face_part[static_cast<std::size_t>(s.faces[static_cast<std::size_t>(i)])];

  const auto seg = segment_into_boxes(s, 3, 64, 1);
  REQUIRE(seg.cell.size() == static_cast<std::size_t>(s.size()));
  std::vector<index_t> label(seg.cell.size());
  std::set<index_t> labels;
  for (std::size_t i = 0; i < label.size(); ++i) {
    REQUIRE(seg.cell[i] >= 0);
    REQUIRE(seg.cell[i] < seg.num_cells());
    label[i] = seg.cell_label[static_cast<std::size_t>(seg.cell[i])];
    labels.insert(label[i]);
  }
  CHECK(labels.size() <= 3);
  // Seat, back and legs come out as separate labels, the four legs as four cells sharing one label.
  const double merged = agreement(label, truth, 3);
  CHECK(merged > 0.93);  // a few samples at the creases go to the neighbouring part
  std::map<index_t, int> leg_votes;
  int legs = 0;
  for (std::size_t i = 0; i < label.size(); ++i)
    if (truth[i] == 2) {
      ++leg_votes[label[i]];
      ++legs;
    }
  const auto leg_label =
      std::max_element(leg_votes.begin(), leg_votes.end(), [](auto& x, auto& y) { return x.second < y.second; })->first;
  CHECK(leg_votes[leg_label] > 0.9 * legs);
  index_t leg_cells = 0;
  for (const auto l : seg.cell_label) leg_cells += l == leg_label ? 1 : 0;
  CHECK(leg_cells == 4);

  // The chapter's plain Voronoi cells of 3 farthest points cut across the parts.
  const auto plain = segment_into_boxes(s, 3, 0, 1);
  CHECK(plain.num_cells() == 3);
  const double voronoi = agreement(plain.cell, truth, 3);
  CHECK(voronoi < merged - 0.1);

  // The candidate template built from it has one box per cell and the shared labels.
  const auto [t, e] = template_from_shape(s, {.parts = 3});
  CHECK(t.num_parts() == seg.num_cells());
  CHECK(std::isfinite(e));
  validate_template(t);
}

}  // namespace

TEST_CASE("segment_into_boxes separates seat, back and legs of a box chair (triangle_mesh and legacy_mesh)") {
  std::vector<int> face_part;
  const auto m = box_chair(face_part);
  SUBCASE("triangle_mesh") {
    check_segmentation(m, face_part);
  }
  SUBCASE("legacy_mesh") {
    check_segmentation(test::to_legacy(m), face_part);
  }
}

TEST_CASE("segment_into_boxes is deterministic and rejects bad parameters") {
  std::vector<int> face_part;
  const auto s = make_shape_samples(box_chair(face_part), {.points = 600});
  const auto a = segment_into_boxes(s, 4, 32, 1), b = segment_into_boxes(s, 4, 32, 1);
  CHECK(a.cell == b.cell);
  CHECK(a.cell_label == b.cell_label);
  CHECK_THROWS_AS(segment_into_boxes(s, 0, 32, 1), invalid_input);
  CHECK_THROWS_AS(segment_into_boxes(s, 3, 32, 3), invalid_input);
  CHECK_THROWS_AS(segment_into_boxes(s, 3, 32, 1, -1.0), invalid_input);
  shape_samples tiny = s;
  tiny.points.conservativeResize(2, 3);
  tiny.normals.conservativeResize(2, 3);
  tiny.features.resize(0, 0);
  tiny.faces.clear();
  tiny.edges.clear();
  CHECK_THROWS_AS(segment_into_boxes(tiny, 3, 32, 1), invalid_input);
}

TEST_CASE("congruent fitted boxes share an output label, different parts keep theirs") {
  part_template t;
  t.up_axis = 1;
  const auto add = [&](Eigen::Vector3d c, Eigen::Vector3d size, index_t label) {
    part_box b;
    b.center = c;
    b.size = size;
    b.label = label;
    t.parts.push_back(b);
  };
  add({0, 0, 0}, {0.4, 0.05, 0.4}, 0);          // seat
  add({0, 0.2, -0.2}, {0.4, 0.4, 0.05}, 1);     // back
  add({-0.18, -0.2, 0.18}, {0.03, 0.3, 0.03}, 2);  // three legs the segmentation grouped
  add({0.18, -0.2, 0.18}, {0.03, 0.3, 0.03}, 2);
  add({-0.18, -0.2, -0.18}, {0.03, 0.3, 0.03}, 2);
  add({0.18, -0.2, -0.18}, {0.045, 0.28, 0.04}, 3);  // a fourth whose cell also held a strip of the seat
  add({0.2, 0.1, 0}, {0.04, 0.04, 0.3}, 4);          // an arm: horizontal, not a copy of a leg
  add({0, 0.45, -0.2}, {0.03, 0.3, 0.03}, 5);        // a finial on the back: a leg's extents, not its height
  detail::share_labels_of_congruent_boxes(t);
  CHECK(t.parts[0].label == 0);
  CHECK(t.parts[1].label == 1);
  for (std::size_t b = 2; b < 6; ++b) CHECK(t.parts[b].label == 2);
  CHECK(t.parts[6].label == 3);  // labels stay numbered 0, 1, ... by first appearance
  CHECK(t.parts[7].label == 4);
  // A leg turned a quarter turn about the up axis is still a copy (upright extents do not depend on it).
  t.parts[5].axes = Eigen::AngleAxisd(0.5 * 3.14159265358979, Eigen::Vector3d::UnitY()).toRotationMatrix();
  t.parts[5].label = 7;
  detail::share_labels_of_congruent_boxes(t);
  CHECK(t.parts[5].label == 2);
}
