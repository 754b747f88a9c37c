// SPDX-License-Identifier: MIT
// refinement_move_check: the sample-table lower bound of geodesic distances, and putting back the images a
// refinement moved far where the map agrees better with them.
#include <algorithm>
#include <limits>
#include <numeric>
#include <vector>

#include <doctest/doctest.h>

#include "blended_fixtures.hpp"
#include "shapestruct/blended/blended_matcher.hpp"
#include "shapestruct/blended/refinement_move_check.hpp"
#include "shapestruct/maps/surface_map.hpp"
#include "support/fixtures.hpp"

using namespace shapestruct;

namespace {
blended_matcher_options small_options() {
  blended_matcher_options o;
  o.shape.num_samples = 128;
  o.threads = 2;
  return o;
}

/// The vertex of `shape` geodesically farthest from v.
index_t farthest_from(const blended_shape<double>& shape, index_t v) {
  index_t far = 0;
  shape.geodesics().distances_from(v).maxCoeff(&far);
  return far;
}
}  // namespace

TEST_CASE("sample-table lower bound: never above the geodesic distance, close to it for far-apart points") {
  const blended_matcher<> matcher(small_options());
  const auto shape = matcher.prepare(test::armed_sphere(3));
  const index_t n = shape.mesh().V.rows();
  std::vector<index_t> x, y;
  for (index_t v = 0; v < n; v += 37) {
    x.push_back(v);
    y.push_back((v * 7 + 11) % n);
  }
  x.push_back(0);
  y.push_back(farthest_from(shape, 0));
  x.push_back(no_index);
  y.push_back(0);
  const auto bound = sample_distance_lower_bounds(shape, x, y);
  REQUIRE(bound.size() == x.size());
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double exact = shape.geodesics().geodesic_distance(x[i], y[i]);
    CHECK(bound[i] <= exact + 1e-12);
    CHECK(bound[i] >= exact - 2.5 * shape.sample_spacing());
  }
  CHECK(bound.back() == std::numeric_limits<double>::infinity());  // an unmapped end
}

TEST_CASE("check_refinement_moves puts back the long moves the map disagrees with, and keeps repairs") {
  const blended_matcher<> matcher(small_options());
  const auto shape = matcher.prepare(test::armed_sphere(3));
  const auto& mesh = shape.mesh();
  std::vector<index_t> identity(static_cast<std::size_t>(mesh.V.rows()));
  std::iota(identity.begin(), identity.end(), index_t(0));
  // The map before: right (the identity) except at vertices 20-29, sent to the far side of the shape.
  std::vector<index_t> wrong = identity;
  for (index_t v = 20; v < 30; ++v) wrong[static_cast<std::size_t>(v)] = farthest_from(shape, v);
  const auto before = surface_map_at_vertices(mesh, wrong);
  // The refinement: vertices 0-9 jump to the far side (wrong), 10-19 move to a neighbour (a short move), 20-29
  // are repaired (a long move back to the truth).
  std::vector<index_t> moved = identity;
  for (index_t v = 0; v < 10; ++v) moved[static_cast<std::size_t>(v)] = farthest_from(shape, v);
  for (index_t f = 0; f < mesh.F.rows(); ++f) {
    const index_t v = mesh.F(f, 0);
    if (v >= 10 && v < 20) moved[static_cast<std::size_t>(v)] = mesh.F(f, 1);
  }
  const auto refined = surface_map_at_vertices(mesh, moved);

  auto checked = refined;
  CHECK(check_refinement_moves(shape, shape, before, checked, 0.1, 1.5) == 10);
  for (index_t v = 0; v < mesh.V.rows(); ++v) {
    const auto i = static_cast<std::size_t>(v);
    const auto& expected = v < 10 ? before : refined;  // only the wrong jumps go back
    CHECK(checked.nearest[i] == expected.nearest[i]);
    CHECK(checked.points[i].face == expected.points[i].face);
  }
  // Moves shorter than the check's length are never questioned.
  auto unchecked = refined;
  CHECK(check_refinement_moves(shape, shape, before, unchecked, 10.0, 1.5) == 0);
  CHECK(unchecked.nearest == refined.nearest);
}

namespace {
/// A MapRefiner that jumps at every tenth source vertex: its image becomes that of the vertex at the mirrored place
/// in the numbering; the others stay.
struct jumping_refiner {
  template <class Scalar>
  surface_map<Scalar> refine(const triangle_mesh<Scalar>&, const triangle_mesh<Scalar>&, const surface_map<Scalar>& map,
                             int) const {
    surface_map<Scalar> out = map;
    const std::size_t n = map.points.size();
    for (std::size_t i = 0; i < n; i += 10) {
      out.points[i] = map.points[n - 1 - i];
      out.nearest[i] = map.nearest[n - 1 - i];
    }
    return out;
  }
};
using jumping_matcher = blended_matcher<triplet_candidates, area_confidence, geodesic_consistency, jumping_refiner>;
}  // namespace

TEST_CASE("blended_matcher puts back the wrong long moves of its refiner, and none with the check off") {
  const auto source = test::armed_sphere(3);
  std::vector<index_t> perm;
  const auto target = test::moved_and_permuted(source, perm);
  auto o = small_options();
  o.max_refined_distortion_ratio = 0;  // keep the refinement whatever it does, to see the move check alone
  o.refinement_move_check = 0;
  const auto unchecked = jumping_matcher(o).match(source, target);
  const auto& blended = unchecked.blended[static_cast<std::size_t>(unchecked.selected)].map;
  CHECK(unchecked.refinement_moves_undone == 0);
  CHECK(unchecked.refined_map.nearest == jumping_refiner{}.refine(target, target, blended, 1).nearest);

  o.refinement_move_check = blended_matcher_options{}.refinement_move_check;
  const auto checked = jumping_matcher(o).match(source, target);
  REQUIRE(checked.blended[static_cast<std::size_t>(checked.selected)].map.nearest == blended.nearest);
  // The blended map of a rigid copy is right, and so are nine images in ten after the jumps: an image that jumped
  // far disagrees with the rest of the map and goes back; short jumps and the untouched images stay.
  const auto jumped = unchecked.refined_map.nearest;
  const auto b = blended_matcher<>(small_options()).prepare(target);
  std::vector<index_t> x, y;
  for (std::size_t i = 0; i < blended.nearest.size(); ++i) {
    x.push_back(b.internal_vertex(blended.nearest[i]));
    y.push_back(b.internal_vertex(jumped[i]));
  }
  const auto bound = sample_distance_lower_bounds(b, x, y);
  index_t long_moves = 0, put_back = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const bool is_long = bound[i] >= o.refinement_move_check;
    const bool back = checked.refined_map.nearest[i] == blended.nearest[i] && blended.nearest[i] != jumped[i];
    long_moves += is_long;
    put_back += back;
    if (!is_long) CHECK(checked.refined_map.nearest[i] == jumped[i]);
    else CHECK((back || checked.refined_map.nearest[i] == jumped[i]));
  }
  MESSAGE(long_moves << " of " << x.size() << " images jumped far, " << put_back << " put back");
  CHECK(long_moves > static_cast<index_t>(x.size()) / 20);
  CHECK(put_back >= 0.95 * static_cast<double>(long_moves));
  CHECK(checked.refinement_moves_undone == put_back);
  CHECK(checked.map.nearest == checked.refined_map.nearest);
}

namespace {
/// `m` after a small closed tetrahedron far away, numbered first: keep_largest_component drops it, so the
/// internal numbering of the shape is the input's shifted by four.
triangle_mesh<double> after_a_stray_tetrahedron(const triangle_mesh<double>& m) {
  triangle_mesh<double> out;
  out.V.resize(m.V.rows() + 4, 3);
  out.F.resize(m.F.rows() + 4, 3);
  out.V.topRows(4) << 10, 0, 0, 10.1, 0, 0, 10, 0.1, 0, 10, 0, 0.1;
  out.F.topRows(4) << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  out.V.bottomRows(m.V.rows()) = m.V;
  out.F.bottomRows(m.F.rows()) = m.F.array() + 4;
  return out;
}
}  // namespace

TEST_CASE("refine_checked refines a blended map as match refines its selection, across a renumbering repair") {
  const auto source = after_a_stray_tetrahedron(test::armed_sphere(3));
  std::vector<index_t> perm;
  const auto target = test::moved_and_permuted(test::armed_sphere(3), perm);
  auto o = small_options();
  o.shape.repairs.keep_largest_component = true;
  const jumping_matcher matcher(o);
  const auto a = matcher.prepare(source);
  const auto b = matcher.prepare(target);
  REQUIRE(a.internal_vertex(0) == no_index);
  REQUIRE(a.internal_vertex(4) == 0);
  const auto r = matcher.match(a, b);
  REQUIRE(r.refinement_moves_undone > 0);  // the jumps are there to be checked
  const auto again = matcher.refine_checked(a, b, r.blended[static_cast<std::size_t>(r.selected)]);
  CHECK(again.map.nearest == r.refined_map.nearest);
  CHECK(again.moves_undone == r.refinement_moves_undone);
  CHECK(again.accepted == r.refinement_accepted);
  CHECK(again.distortion == doctest::Approx(r.refined_distortion));
  for (index_t v = 0; v < 4; ++v) CHECK_FALSE(again.map.points[static_cast<std::size_t>(v)].valid());

  auto cut = r.blended[static_cast<std::size_t>(r.selected)];
  cut.map.points.pop_back();
  CHECK_THROWS_AS((void)matcher.refine_checked(a, b, cut), invalid_input);
}
