// SPDX-License-Identifier: MIT
// repair_to_sphere: the repairs that make a real-world mesh (a scan with holes, an export with duplicate faces or
// stray pieces) a closed genus-0 manifold, as blended intrinsic maps need, with a report of what they changed.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/connected_components.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/geometry/mesh_repair.hpp"
#include "shapestruct/geometry/mesh_topology.hpp"

namespace shapestruct {

/// Which repairs repair_to_sphere applies; all off by default, so that nothing is changed unasked.
struct sphere_repair_options {
  bool remove_bad_faces = false;             ///< faces with a repeated corner, repeats of a face
  bool split_non_manifold_vertices = false;  ///< give every fan of a bowtie vertex its own vertex
  bool keep_largest_component = false;       ///< drop all but the largest piece (and vertices on no face)
  /// keep_largest_component refuses (several_pieces) when the pieces it would drop hold more than this fraction
  /// of the area (then they are parts of the shape rather than debris). 1 = drop whatever is not the largest.
  double max_dropped_area_fraction = 1.0;
  bool close_small_holes = false;            ///< fill boundary loops of at most max_hole_edges edges
  index_t max_hole_edges = 64;

  /// Every repair on, dropping only pieces that hold at most 5 % of the area: the safe repairs `shapestruct
  /// match` makes unless --strict.
  [[nodiscard]] static sphere_repair_options all(index_t max_hole_edges = 64) {
    sphere_repair_options o;
    o.remove_bad_faces = o.split_non_manifold_vertices = o.keep_largest_component = o.close_small_holes = true;
    o.max_hole_edges = max_hole_edges;
    o.max_dropped_area_fraction = 0.05;
    return o;
  }
};

/// What repair_to_sphere changed in one mesh (all zero when no repair was enabled or needed).
struct sphere_repair_report {
  index_t collapsed_faces_removed = 0;   ///< faces with a repeated corner
  index_t duplicate_faces_removed = 0;   ///< repeats of a face on the same three vertices
  index_t non_manifold_vertices_split = 0;
  index_t pieces_dropped = 0;            ///< connected components with faces, other than the largest
  index_t stray_vertices_dropped = 0;    ///< vertices on no face
  index_t vertices_dropped = 0;          ///< all vertices dropped with the pieces and the stray vertices
  index_t faces_dropped = 0;             ///< faces dropped with the pieces
  std::vector<index_t> holes_filled;     ///< the length (edges) of each hole filled

  [[nodiscard]] bool any() const noexcept {
    return collapsed_faces_removed + duplicate_faces_removed + non_manifold_vertices_split + pieces_dropped +
               stray_vertices_dropped > 0 || !holes_filled.empty();
  }
  /// One line for a person, e.g. "filled 2 holes (5 and 17 edges); removed 3 duplicate faces"; empty if nothing.
  [[nodiscard]] std::string to_string() const {
    std::string out;
    const auto add = [&](const std::string& part) { out += (out.empty() ? "" : "; ") + part; };
    const auto count = [](index_t n, const char* one, const char* many) {
      return std::to_string(n) + " " + (n == 1 ? one : many);
    };
    if (!holes_filled.empty()) {
      std::vector<index_t> sizes = holes_filled;
      std::sort(sizes.begin(), sizes.end());
      std::string list;
      const std::size_t shown = std::min<std::size_t>(sizes.size(), 8);
      for (std::size_t i = 0; i < shown; ++i)
        list += (i == 0 ? "" : (i + 1 == sizes.size() ? " and " : ", ")) + std::to_string(sizes[i]);
      if (sizes.size() > shown) list += ", ... up to " + std::to_string(sizes.back());
      add("filled " + count(static_cast<index_t>(sizes.size()), "hole", "holes") + " (" + list + " edges)");
    }
    if (collapsed_faces_removed) add("removed " + count(collapsed_faces_removed, "collapsed face", "collapsed faces") + " (a corner repeated)");
    if (duplicate_faces_removed) add("removed " + count(duplicate_faces_removed, "duplicate face", "duplicate faces"));
    if (non_manifold_vertices_split) add("split " + count(non_manifold_vertices_split, "non-manifold vertex", "non-manifold vertices"));
    if (pieces_dropped)
      add("dropped " + count(pieces_dropped, "smaller piece", "smaller pieces") + " (" +
          count(vertices_dropped - stray_vertices_dropped, "vertex", "vertices") + ", " + count(faces_dropped, "face", "faces") + ")");
    if (stray_vertices_dropped) add("dropped " + count(stray_vertices_dropped, "vertex on no face", "vertices on no face"));
    return out;
  }
};

/// A repaired mesh and where its vertices came from.
template <class Scalar>
struct repaired_sphere {
  triangle_mesh<Scalar> mesh;
  /// For each vertex of `mesh`, the input vertex it stands for (a split copy: the vertex it copies), or
  /// no_index for a vertex a repair added (a filled hole's centre).
  std::vector<index_t> original_vertex;
  sphere_repair_report report;
};

namespace detail {

/// A number as a person writes it in a message: 3 significant digits, "1e+200" style for the huge ones.
inline std::string short_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace detail

/// Applies the enabled repairs, in this order: remove collapsed and duplicate faces, split non-manifold vertices,
/// keep the largest piece, close small holes; then requires a closed, connected, orientable genus-0 manifold of
/// positive, finite area. Existing vertices keep their relative order.
/// \param V #V x 3 \param F #F x 3 \param who names the caller at the start of every message
/// \param accept_pinched_vertices accept a non-manifold vertex whose fans belong to one sphere (SCAPE's
///        template pinch), as mid_edge_flattening does by default, without splitting it
/// \throws invalid_input empty / non_finite / bad_face (validate_mesh, after the face removal when enabled);
///         bad_parameter (max_hole_edges < 3); mesh_defect_error for what is left: the defect, an element, the
///         problem and the remedy in terms of sphere_repair_options (a hole longer than max_hole_edges says how
///         long), coordinate_overflow when the area is not finite, zero_area.
/// Complexity: O(V log V + F log F).
template <class Scalar>
[[nodiscard]] repaired_sphere<Scalar> repair_to_sphere(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                                      const Eigen::Ref<const face_matrix>& F,
                                                      const sphere_repair_options& options, const char* who,
                                                      bool accept_pinched_vertices = false) {
  if (options.max_hole_edges < 3)
    throw invalid_input(input_error::bad_parameter, no_index,
                        std::string(who) + ": max_hole_edges must be at least 3, got " + std::to_string(options.max_hole_edges));
  repaired_sphere<Scalar> out;
  sphere_repair_report& rep = out.report;
  triangle_mesh<Scalar> m;
  m.V = V;
  m.F = F;
  std::vector<index_t>& origin = out.original_vertex;
  origin.resize(static_cast<std::size_t>(V.rows()));
  std::iota(origin.begin(), origin.end(), index_t(0));
  if (options.remove_bad_faces && V.rows() > 0 && F.rows() > 0 && F.cols() == 3) {
    auto r = remove_collapsed_and_duplicate_faces(m);
    rep.collapsed_faces_removed = r.collapsed_faces;
    rep.duplicate_faces_removed = r.duplicate_faces;
    m = std::move(r.mesh);
  }
  if (!options.remove_bad_faces)  // the same check validate_mesh makes, typed so that callers can name the repair
    for (index_t f = 0; f < m.F.rows() && m.F.cols() == 3; ++f)
      if (m.F(f, 0) == m.F(f, 1) || m.F(f, 1) == m.F(f, 2) || m.F(f, 0) == m.F(f, 2))
        throw mesh_defect_error(input_error::bad_face, mesh_defect::collapsed_face, f, who,
                                "face " + std::to_string(f) + " repeats a vertex (it has no area)",
                                "the repair remove_bad_faces removes such faces");
  validate_mesh(m.V, m.F, who);
  // Coordinates whose squares overflow make every length and area infinite: say so, not "zero area".
  if (!std::isfinite(total_area<Scalar>(m.V, m.F, validation_level::trust)))
    throw mesh_defect_error(input_error::non_finite, mesh_defect::coordinate_overflow, no_index, who,
                            "the mesh's area overflows the floating-point range (coordinates as large as " +
                                detail::short_number(double(m.V.cwiseAbs().maxCoeff())) + ")",
                            "scale the coordinates down");
  if (options.split_non_manifold_vertices) {
    auto r = split_non_manifold_vertices(m);
    rep.non_manifold_vertices_split = r.split_vertices;
    for (index_t i = 0; i < r.copied_from.size(); ++i) origin.push_back(origin[static_cast<std::size_t>(r.copied_from(i))]);
    m = std::move(r.mesh);
  }
  if (options.keep_largest_component) {
    const component_labels cc = connected_components(m.F, m.V.rows());
    std::vector<char> has_face(static_cast<std::size_t>(cc.count), 0);
    for (index_t f = 0; f < m.F.rows(); ++f) has_face[static_cast<std::size_t>(cc.face_label(f))] = 1;
    const index_t pieces = static_cast<index_t>(std::count(has_face.begin(), has_face.end(), char(1)));
    auto r = keep_largest_component(m);
    const double before = double(total_area<Scalar>(m.V, m.F, validation_level::trust));
    const double dropped = 1.0 - double(total_area<Scalar>(r.mesh.V, r.mesh.F, validation_level::trust)) / before;
    if (dropped > options.max_dropped_area_fraction)
      throw mesh_defect_error(input_error::unsupported_topology, mesh_defect::several_pieces, no_index, who,
                              "the mesh has " + std::to_string(pieces) + " pieces and those other than the largest hold " +
                                  std::to_string(int(std::lround(100 * dropped))) +
                                  " % of its area, so they are parts of the shape rather than debris",
                              "dropping them needs max_dropped_area_fraction >= " + detail::short_number(dropped));
    rep.pieces_dropped = pieces - 1;
    rep.stray_vertices_dropped = cc.count - pieces;
    rep.vertices_dropped = r.removed_vertices;
    rep.faces_dropped = r.removed_faces;
    std::vector<index_t> kept(static_cast<std::size_t>(r.mesh.V.rows()), no_index);
    for (index_t v = 0; v < r.old_to_new.size(); ++v)
      if (r.old_to_new(v) != no_index) kept[static_cast<std::size_t>(r.old_to_new(v))] = origin[static_cast<std::size_t>(v)];
    origin = std::move(kept);
    m = std::move(r.mesh);
  }
  index_t longest_hole_left = 0;
  if (options.close_small_holes) {
    std::optional<hole_filling_result<Scalar>> r;
    try {
      r = close_small_holes(m, options.max_hole_edges);
    } catch (const invalid_input& e) {
      // Holes meeting at a non-manifold edge or vertex have no well-defined loops: none is filled, and the
      // check below names the non-manifold element.
      if (e.reason() != input_error::non_manifold) throw;
    }
    if (r) {
      rep.holes_filled = r->filled_loop_lengths;
      longest_hole_left = r->longest_loop_left;
      origin.resize(static_cast<std::size_t>(r->mesh.V.rows()), no_index);  // new vertices are appended
      m = std::move(r->mesh);
    }
  }
  try {
    if (accept_pinched_vertices && !options.split_non_manifold_vertices) {
      // A pinch (fans of one sphere touching at a vertex) is a sphere to the caller: check the split mesh,
      // whose existing vertices keep their numbers, so any element named is the input's.
      const auto split = split_non_manifold_vertices(m);
      require_closed_genus0_manifold(split.mesh.V, split.mesh.F, who);
    } else {
      require_closed_genus0_manifold(m.V, m.F, who);
    }
  } catch (const mesh_defect_error& e) {
    // The same problem, with the remedy in terms of these options.
    std::string problem = e.problem(), remedy;
    switch (e.defect()) {
      case mesh_defect::non_manifold_edge:
        remedy = options.remove_bad_faces ? "they are not repeats of one face, so no repair applies"
                                          : "if they repeat one face, the repair remove_bad_faces removes the repeats";
        break;
      case mesh_defect::non_manifold_vertex: remedy = "the repair split_non_manifold_vertices gives each fan its own vertex"; break;
      case mesh_defect::several_pieces: remedy = "the repair keep_largest_component keeps the largest piece"; break;
      case mesh_defect::hole:
        if (longest_hole_left > 0)
          problem += ", longer than the " + std::to_string(options.max_hole_edges) +
                     " edges the hole filling closes (the longest has " + std::to_string(longest_hole_left) + " edges)";
        remedy = options.close_small_holes ? "raise max_hole_edges to fill it"
                                           : "the repair close_small_holes fills holes of up to max_hole_edges edges";
        break;
      default: remedy = e.remedy();
    }
    throw mesh_defect_error(e.reason(), e.defect(), e.element(), who, problem, remedy);
  }
  if (!(total_area<Scalar>(m.V, m.F, validation_level::trust) > 0))
    throw mesh_defect_error(input_error::degenerate_face, mesh_defect::zero_area, no_index, who,
                            "the mesh has zero total area (every face is degenerate)", "");
  out.mesh = std::move(m);
  return out;
}

}  // namespace shapestruct
