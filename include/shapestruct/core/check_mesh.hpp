// SPDX-License-Identifier: MIT
// check_mesh: a never-throwing inventory of a mesh's size, topology and defects (for `shapestruct inspect`).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross product
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"

namespace shapestruct {

/// Options of check_mesh().
struct check_mesh_options {
  /// A face counts as degenerate when its area is <= degenerate_area_epsilon * d^2, d the diagonal of the
  /// bounding box of the finite vertices. 1e-14 is ~100 ulps of double precision in the cross product, so it
  /// catches exactly collinear (or coincident) corners, also of float input, but no real sliver of a scan.
  double degenerate_area_epsilon = 1e-14;
  /// How many offending elements to list per problem (the counts are always complete).
  index_t max_examples = 10;
};

/// Topology of one connected component that has at least one face (isolated vertices are not listed).
struct component_report {
  index_t first_vertex = no_index;  ///< smallest vertex index in the component (components are in this order)
  index_t num_vertices = 0;
  index_t num_faces = 0;  ///< topological faces: indices in range and pairwise distinct
  index_t num_edges = 0;
  index_t num_boundary_loops = 0;
  index_t euler_characteristic = 0;  ///< V - E + F of the component
  bool manifold = true;              ///< no non-manifold edge or vertex and no face repeating a vertex
  bool orientable = true;            ///< faces can be oriented consistently (meaningful when manifold)
  index_t genus = -1;                ///< (2 - chi - b) / 2 for manifold orientable components, else -1
  double area = 0;                   ///< sum of the areas of its faces with finite corners
};

/// Everything check_mesh() found. Counts are complete; the *_examples lists hold at most
/// check_mesh_options::max_examples entries each, in increasing element order.
///
/// Definitions (the independent counter scripts/independent_mesh_count.py follows the same ones):
///  - topological faces: faces whose three indices are in [0, #V) and pairwise distinct; edges, boundary,
///    manifoldness, orientation and Euler characteristic use only these.
///  - edges: distinct unordered vertex pairs of topological faces. boundary edge: 1 incident face;
///    non-manifold edge: more than 2; inconsistently oriented edge: 2 faces traversing it the same way.
///  - non-manifold vertex: its incident faces form more than one fan (faces linked across shared edges
///    at the vertex), e.g. the centre of a bowtie.
///  - boundary loops: connected components of the graph of boundary edges (one per hole on a manifold).
///  - components: classes of vertices linked by faces with in-range indices; an isolated (unreferenced)
///    vertex is a component on its own.
///  - Euler characteristic: #V - #E + #topological faces over ALL vertices (isolated ones add 1 each).
///  - genus: sum over components of (2 - chi_c - b_c) / 2; -1 when a component is non-manifold or
///    non-orientable (genus undefined there) or when there is no face at all (no surface).
///  - duplicate vertices: vertices whose position equals (exactly) that of a lower-indexed vertex.
struct mesh_report {
  index_t num_vertices = 0;
  index_t num_faces = 0;  ///< all rows of F, including defective ones
  index_t num_edges = 0;
  index_t num_components = 0;  ///< including isolated vertices
  index_t num_boundary_edges = 0;
  index_t num_boundary_loops = 0;
  index_t num_non_manifold_edges = 0;
  index_t num_non_manifold_vertices = 0;
  index_t num_degenerate_faces = 0;      ///< zero area (see check_mesh_options) or a repeated vertex index
  index_t num_repeated_index_faces = 0;  ///< faces with a repeated vertex index (a subset of the degenerate ones)
  index_t num_duplicate_vertices = 0;
  index_t num_non_finite_vertices = 0;
  index_t num_out_of_range_faces = 0;
  index_t num_unreferenced_vertices = 0;
  index_t num_inconsistent_edges = 0;
  index_t euler_characteristic = 0;
  index_t genus = -1;
  bool orientable = true;
  double bbox_diagonal = 0;
  /// Non-empty when the input matrices do not have 3 columns; nothing else is then filled in.
  std::string shape_problem;

  std::vector<component_report> components;                        ///< components with faces, by first_vertex
  std::vector<std::array<index_t, 2>> boundary_edge_examples;      ///< (a, b) as traversed by its face
  std::vector<std::array<index_t, 2>> non_manifold_edge_examples;  ///< (min, max)
  std::vector<std::array<index_t, 2>> inconsistent_edge_examples;  ///< (min, max)
  std::vector<index_t> non_manifold_vertex_examples;
  std::vector<index_t> degenerate_face_examples;
  std::vector<index_t> duplicate_vertex_examples;
  std::vector<index_t> non_finite_vertex_examples;
  std::vector<index_t> out_of_range_face_examples;
  std::vector<index_t> unreferenced_vertex_examples;

  /// Every index in range, every coordinate finite, at least one face, no face repeating a vertex: the
  /// checks of validate_mesh() (zero-area faces are allowed there).
  [[nodiscard]] bool is_valid() const noexcept {
    return shape_problem.empty() && num_faces > 0 && num_vertices > 0 && num_non_finite_vertices == 0 &&
           num_out_of_range_faces == 0 && num_repeated_index_faces == 0;
  }
  /// Valid and neither non-manifold edges nor non-manifold vertices.
  [[nodiscard]] bool is_manifold() const noexcept {
    return is_valid() && num_non_manifold_edges == 0 && num_non_manifold_vertices == 0;
  }
  /// No boundary edge (says nothing about manifoldness).
  [[nodiscard]] bool is_closed() const noexcept { return num_boundary_edges == 0; }
  /// Valid, manifold, without boundary.
  [[nodiscard]] bool is_closed_manifold() const noexcept { return is_manifold() && is_closed(); }
  /// A closed orientable manifold of genus 0 in one piece (no isolated vertices): a topological sphere, the
  /// precondition of mid-edge uniformization.
  [[nodiscard]] bool is_closed_genus0_manifold() const noexcept {
    return is_closed_manifold() && orientable && num_components == 1 && genus == 0;
  }

  /// A multi-line human-readable summary (counts, per-component topology, up to max_examples offenders).
  [[nodiscard]] std::string to_string() const;
  /// The same content as one JSON object (no trailing newline).
  [[nodiscard]] std::string to_json() const;
};

namespace detail {

inline void push_example(std::vector<index_t>& list, index_t value, index_t cap) {
  if (static_cast<index_t>(list.size()) < cap) list.push_back(value);
}
inline void push_example(std::vector<std::array<index_t, 2>>& list, std::array<index_t, 2> value, index_t cap) {
  if (static_cast<index_t>(list.size()) < cap) list.push_back(value);
}

/// One directed edge of a topological face, keyed by its unordered vertex pair.
struct check_half_edge {
  index_t lo, hi, face;
  int from_corner;  ///< corner (0..2) of the face where the edge starts
  bool forward;     ///< traversed lo -> hi
};

}  // namespace detail

/// Checks (V, F) and returns the report; never throws for any content of V and F (only std::bad_alloc can
/// escape if memory runs out). Kernel behind check_mesh(const Mesh&).
/// \param V  #V x 3 positions (any finite or non-finite values)
/// \param F  #F x 3 vertex indices (any values, also negative or >= #V)
/// \returns the mesh_report; see its documentation for the definitions.
/// Complexity: O(V log V + F log F) time (two sorts), O(V + F) memory.
template <class Scalar>
[[nodiscard]] mesh_report check_mesh_kernel(const Eigen::Ref<const matrix_x3<Scalar>>& V,
                                            const Eigen::Ref<const face_matrix>& F,
                                            const check_mesh_options& options = {}) {
  mesh_report r;
  const index_t n = V.rows();
  const index_t m = F.rows();
  const index_t cap = std::max<index_t>(options.max_examples, 0);
  r.num_vertices = n;
  r.num_faces = m;

  // --- vertices: finiteness and bounding box of the finite ones
  std::vector<char> finite(static_cast<std::size_t>(n), 1);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (index_t v = 0; v < n; ++v) {
    const Eigen::Vector3d p = V.row(v).template cast<double>().transpose();
    if (!p.allFinite()) {
      finite[static_cast<std::size_t>(v)] = 0;
      ++r.num_non_finite_vertices;
      detail::push_example(r.non_finite_vertex_examples, v, cap);
      continue;
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  r.bbox_diagonal = (n > r.num_non_finite_vertices) ? (hi - lo).norm() : 0.0;
  const double area_tol = options.degenerate_area_epsilon * r.bbox_diagonal * r.bbox_diagonal;

  // --- faces: range, repeated indices, area
  std::vector<char> topological(static_cast<std::size_t>(m), 0);
  std::vector<char> in_range(static_cast<std::size_t>(m), 0);
  std::vector<char> referenced(static_cast<std::size_t>(n), 0);
  std::vector<double> face_area(static_cast<std::size_t>(m), 0.0);
  for (index_t f = 0; f < m; ++f) {
    const index_t a = F(f, 0), b = F(f, 1), c = F(f, 2);
    if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n) {
      ++r.num_out_of_range_faces;
      detail::push_example(r.out_of_range_face_examples, f, cap);
      continue;
    }
    in_range[static_cast<std::size_t>(f)] = 1;
    referenced[static_cast<std::size_t>(a)] = referenced[static_cast<std::size_t>(b)] =
        referenced[static_cast<std::size_t>(c)] = 1;
    if (a == b || b == c || a == c) {
      ++r.num_repeated_index_faces;
      ++r.num_degenerate_faces;
      detail::push_example(r.degenerate_face_examples, f, cap);
      continue;
    }
    topological[static_cast<std::size_t>(f)] = 1;
    if (finite[static_cast<std::size_t>(a)] && finite[static_cast<std::size_t>(b)] &&
        finite[static_cast<std::size_t>(c)]) {
      const Eigen::Vector3d pa = V.row(a).template cast<double>().transpose();
      const Eigen::Vector3d pb = V.row(b).template cast<double>().transpose();
      const Eigen::Vector3d pc = V.row(c).template cast<double>().transpose();
      const double area = 0.5 * (pb - pa).cross(pc - pa).norm();
      face_area[static_cast<std::size_t>(f)] = area;
      if (area <= area_tol) {
        ++r.num_degenerate_faces;
        detail::push_example(r.degenerate_face_examples, f, cap);
      }
    }
  }
  for (index_t v = 0; v < n; ++v)
    if (!referenced[static_cast<std::size_t>(v)]) {
      ++r.num_unreferenced_vertices;
      detail::push_example(r.unreferenced_vertex_examples, v, cap);
    }

  // --- duplicate positions: sort finite vertices lexicographically (ties by index, so the first of each
  // group of equal positions is the lowest index and all others are its duplicates)
  {
    std::vector<index_t> order;
    order.reserve(static_cast<std::size_t>(n));
    for (index_t v = 0; v < n; ++v)
      if (finite[static_cast<std::size_t>(v)]) order.push_back(v);
    auto key_less = [&](index_t x, index_t y) {
      for (int d = 0; d < 3; ++d) {
        if (V(x, d) < V(y, d)) return true;
        if (V(y, d) < V(x, d)) return false;
      }
      return x < y;
    };
    std::sort(order.begin(), order.end(), key_less);
    std::vector<index_t> dups;
    for (std::size_t i = 1; i < order.size(); ++i)
      if (V.row(order[i]) == V.row(order[i - 1])) dups.push_back(order[i]);
    r.num_duplicate_vertices = static_cast<index_t>(dups.size());
    std::sort(dups.begin(), dups.end());
    for (const index_t v : dups) detail::push_example(r.duplicate_vertex_examples, v, cap);
  }

  // --- vertex components over faces with in-range indices
  detail::disjoint_sets vsets(n);
  for (index_t f = 0; f < m; ++f)
    if (in_range[static_cast<std::size_t>(f)]) {
      vsets.unite(F(f, 0), F(f, 1));
      vsets.unite(F(f, 0), F(f, 2));
    }
  std::vector<index_t> label(static_cast<std::size_t>(n), no_index);
  std::vector<index_t> root_label(static_cast<std::size_t>(n), no_index);
  std::vector<index_t> comp_of_label;  // label -> index into r.components, or no_index for isolated vertices
  for (index_t v = 0; v < n; ++v) {
    const index_t root = vsets.find(v);
    auto& rl = root_label[static_cast<std::size_t>(root)];
    if (rl == no_index) {
      rl = r.num_components++;
      comp_of_label.push_back(no_index);
    }
    label[static_cast<std::size_t>(v)] = rl;
  }
  for (index_t v = 0; v < n; ++v) {
    const index_t l = label[static_cast<std::size_t>(v)];
    if (!referenced[static_cast<std::size_t>(v)]) continue;
    if (comp_of_label[static_cast<std::size_t>(l)] == no_index) {
      comp_of_label[static_cast<std::size_t>(l)] = static_cast<index_t>(r.components.size());
      r.components.push_back(component_report{});
      r.components.back().first_vertex = v;
    }
    ++r.components[static_cast<std::size_t>(comp_of_label[static_cast<std::size_t>(l)])].num_vertices;
  }
  auto comp_of_vertex = [&](index_t v) -> component_report& {
    return r.components[static_cast<std::size_t>(
        comp_of_label[static_cast<std::size_t>(label[static_cast<std::size_t>(v)])])];
  };
  index_t num_topological_faces = 0;
  for (index_t f = 0; f < m; ++f) {
    if (!in_range[static_cast<std::size_t>(f)]) continue;
    auto& c = comp_of_vertex(F(f, 0));
    if (!topological[static_cast<std::size_t>(f)]) {
      c.manifold = false;  // a face repeating a vertex is not a 2-cell
      continue;
    }
    ++c.num_faces;
    c.area += face_area[static_cast<std::size_t>(f)];
    ++num_topological_faces;
  }

  // --- edges: sort the directed edges of topological faces by unordered pair
  std::vector<detail::check_half_edge> he;
  he.reserve(static_cast<std::size_t>(3 * num_topological_faces));
  for (index_t f = 0; f < m; ++f) {
    if (!topological[static_cast<std::size_t>(f)]) continue;
    for (int k = 0; k < 3; ++k) {
      const index_t s = F(f, k), t = F(f, (k + 1) % 3);
      he.push_back({std::min(s, t), std::max(s, t), f, k, s < t});
    }
  }
  std::sort(he.begin(), he.end(), [](const detail::check_half_edge& x, const detail::check_half_edge& y) {
    if (x.lo != y.lo) return x.lo < y.lo;
    if (x.hi != y.hi) return x.hi < y.hi;
    if (x.face != y.face) return x.face < y.face;
    return x.from_corner < y.from_corner;
  });

  // Corners (3 f + k) of the same vertex are linked when their faces share an edge at that vertex; the
  // number of resulting classes per vertex is its number of fans.
  detail::disjoint_sets corners(3 * m);
  detail::disjoint_sets boundary_sets(n);
  std::vector<char> on_boundary(static_cast<std::size_t>(n), 0);
  // Face pairs across manifold edges, with "same direction" = the two faces disagree in orientation.
  std::vector<std::array<index_t, 3>> face_links;
  std::vector<std::array<index_t, 2>> nm_edges, bad_orient_edges;
  auto corner_of = [](const detail::check_half_edge& h, bool at_lo) {
    // The edge runs from corner from_corner to corner from_corner + 1 of its face.
    const bool at_start = (at_lo == h.forward);
    return 3 * h.face + (at_start ? h.from_corner : (h.from_corner + 1) % 3);
  };
  for (std::size_t i = 0; i < he.size();) {
    std::size_t j = i + 1;
    while (j < he.size() && he[j].lo == he[i].lo && he[j].hi == he[i].hi) ++j;
    const std::size_t count = j - i;
    const index_t a = he[i].lo, b = he[i].hi;
    ++r.num_edges;
    ++comp_of_vertex(a).num_edges;
    if (count == 1) {
      ++r.num_boundary_edges;
      const auto& h = he[i];
      detail::push_example(r.boundary_edge_examples,
                           h.forward ? std::array<index_t, 2>{a, b} : std::array<index_t, 2>{b, a}, cap);
      boundary_sets.unite(a, b);
      on_boundary[static_cast<std::size_t>(a)] = on_boundary[static_cast<std::size_t>(b)] = 1;
    } else if (count == 2) {
      const bool same = he[i].forward == he[i + 1].forward;
      if (same) {
        ++r.num_inconsistent_edges;
        bad_orient_edges.push_back({a, b});
      }
      face_links.push_back({he[i].face, he[i + 1].face, same ? 1 : 0});
    } else {
      ++r.num_non_manifold_edges;
      nm_edges.push_back({a, b});
      comp_of_vertex(a).manifold = false;
    }
    for (std::size_t k = i + 1; k < j; ++k) {
      corners.unite(corner_of(he[i], true), corner_of(he[k], true));
      corners.unite(corner_of(he[i], false), corner_of(he[k], false));
    }
    i = j;
  }
  for (const auto& e : nm_edges) detail::push_example(r.non_manifold_edge_examples, e, cap);
  for (const auto& e : bad_orient_edges) detail::push_example(r.inconsistent_edge_examples, e, cap);

  // --- fans per vertex
  {
    std::vector<index_t> fans(static_cast<std::size_t>(n), 0);
    for (index_t f = 0; f < m; ++f) {
      if (!topological[static_cast<std::size_t>(f)]) continue;
      for (int k = 0; k < 3; ++k)
        if (corners.find(3 * f + k) == 3 * f + k) ++fans[static_cast<std::size_t>(F(f, k))];
    }
    for (index_t v = 0; v < n; ++v)
      if (fans[static_cast<std::size_t>(v)] > 1) {
        ++r.num_non_manifold_vertices;
        detail::push_example(r.non_manifold_vertex_examples, v, cap);
        comp_of_vertex(v).manifold = false;
      }
  }

  // --- boundary loops
  for (index_t v = 0; v < n; ++v)
    if (on_boundary[static_cast<std::size_t>(v)] && boundary_sets.find(v) == v) {
      ++r.num_boundary_loops;
      ++comp_of_vertex(v).num_boundary_loops;
    }

  // --- orientability: propagate a flip bit across manifold edges; a contradiction means no consistent
  // orientation exists (e.g. a Moebius strip).
  {
    std::vector<index_t> start(static_cast<std::size_t>(m) + 1, 0);
    for (const auto& l : face_links) {
      ++start[static_cast<std::size_t>(l[0]) + 1];
      ++start[static_cast<std::size_t>(l[1]) + 1];
    }
    for (std::size_t f = 0; f < static_cast<std::size_t>(m); ++f) start[f + 1] += start[f];
    std::vector<std::array<index_t, 2>> adj(static_cast<std::size_t>(start.back()));
    std::vector<index_t> fill(start.begin(), start.end() - 1);
    for (const auto& l : face_links) {
      adj[static_cast<std::size_t>(fill[static_cast<std::size_t>(l[0])]++)] = {l[1], l[2]};
      adj[static_cast<std::size_t>(fill[static_cast<std::size_t>(l[1])]++)] = {l[0], l[2]};
    }
    std::vector<signed char> flip(static_cast<std::size_t>(m), -1);
    std::vector<index_t> stack;
    for (index_t f0 = 0; f0 < m; ++f0) {
      if (!topological[static_cast<std::size_t>(f0)] || flip[static_cast<std::size_t>(f0)] >= 0) continue;
      flip[static_cast<std::size_t>(f0)] = 0;
      stack.push_back(f0);
      while (!stack.empty()) {
        const index_t f = stack.back();
        stack.pop_back();
        for (index_t k = start[static_cast<std::size_t>(f)]; k < start[static_cast<std::size_t>(f) + 1]; ++k) {
          const auto [g, same] = adj[static_cast<std::size_t>(k)];
          const signed char want = static_cast<signed char>(flip[static_cast<std::size_t>(f)] ^ (same ? 1 : 0));
          if (flip[static_cast<std::size_t>(g)] < 0) {
            flip[static_cast<std::size_t>(g)] = want;
            stack.push_back(g);
          } else if (flip[static_cast<std::size_t>(g)] != want) {
            comp_of_vertex(F(f, 0)).orientable = false;
          }
        }
      }
    }
  }

  // --- Euler characteristic and genus
  r.euler_characteristic = n - r.num_edges + num_topological_faces;
  index_t genus_sum = 0;
  bool genus_defined = true;
  for (auto& c : r.components) {
    c.euler_characteristic = c.num_vertices - c.num_edges + c.num_faces;
    const index_t twice = 2 - c.euler_characteristic - c.num_boundary_loops;
    if (c.manifold && c.orientable && twice >= 0 && twice % 2 == 0) c.genus = twice / 2;
    if (c.genus < 0) genus_defined = false;
    genus_sum += std::max<index_t>(c.genus, 0);
    if (!c.orientable) r.orientable = false;
  }
  // Genus belongs to surfaces: vertices without a face (e.g. what is left of a file of 2-corner faces) have none.
  r.genus = genus_defined && num_topological_faces > 0 ? genus_sum : -1;
  return r;
}

/// check_mesh on plain matrices of any Eigen types (e.g. libigl's MatrixXd / MatrixXi). Matrices without 3
/// columns give a report whose shape_problem says so (no exception).
/// Complexity: O(V log V + F log F).
template <class DerivedV, class DerivedF>
[[nodiscard]] mesh_report check_mesh(const Eigen::MatrixBase<DerivedV>& V, const Eigen::MatrixBase<DerivedF>& F,
                                     const check_mesh_options& options = {}) {
  if (V.cols() != 3 || F.cols() != 3) {
    mesh_report r;
    r.num_vertices = V.rows();
    r.num_faces = F.rows();
    r.shape_problem = "V is " + std::to_string(V.rows()) + " x " + std::to_string(V.cols()) + " and F is " +
                      std::to_string(F.rows()) + " x " + std::to_string(F.cols()) + "; both need 3 columns";
    return r;
  }
  using S = std::conditional_t<std::is_floating_point_v<typename DerivedV::Scalar>, typename DerivedV::Scalar, double>;
  const matrix_x3<S> Vc = V.template cast<S>();
  const face_matrix Fc = F.template cast<index_t>();
  return check_mesh_kernel<S>(Vc, Fc, options);
}

/// Inventory of any SurfaceMesh: sizes, components, boundary, manifoldness, orientation, Euler
/// characteristic and genus, degenerate / duplicate / non-finite / unreferenced elements and out-of-range
/// indices, each with up to options.max_examples offending elements. Never throws on defective meshes;
/// use it before an algorithm to find out why validate_mesh() or a topology requirement would reject a mesh.
/// \param mesh any SurfaceMesh (gathered into triangle_mesh form; a triangle_mesh is used in place)
/// \returns the mesh_report (see its definitions)
/// Complexity: O(V log V + F log F) time, O(V + F) memory.
template <SurfaceMesh Mesh>
[[nodiscard]] mesh_report check_mesh(const Mesh& mesh, const check_mesh_options& options = {}) {
  using S = mesh_scalar_t<Mesh>;
  if constexpr (std::is_same_v<std::remove_cvref_t<Mesh>, triangle_mesh<S>>) {
    return check_mesh_kernel<S>(mesh.V, mesh.F, options);
  } else {
    const triangle_mesh<S> m = to_triangle_mesh<S>(mesh);
    return check_mesh_kernel<S>(m.V, m.F, options);
  }
}

// ---------------------------------------------------------------------------------------------- printing

namespace detail {
inline std::string yes_no(bool b) {
  return b ? "yes" : "no";
}

inline void print_examples(std::ostringstream& os, const std::vector<index_t>& list, index_t total) {
  if (list.empty()) return;
  os << "  e.g.";
  for (const index_t x : list) os << ' ' << x;
  if (total > static_cast<index_t>(list.size())) os << " ...";
}
inline void print_examples(std::ostringstream& os, const std::vector<std::array<index_t, 2>>& list, index_t total) {
  if (list.empty()) return;
  os << "  e.g.";
  for (const auto& e : list) os << " (" << e[0] << ',' << e[1] << ')';
  if (total > static_cast<index_t>(list.size())) os << " ...";
}
template <class List>
void json_list(std::ostringstream& os, const char* name, const List& list) {
  os << ",\"" << name << "\":[";
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (i) os << ',';
    if constexpr (std::is_same_v<typename List::value_type, index_t>) {
      os << list[i];
    } else {
      os << '[' << list[i][0] << ',' << list[i][1] << ']';
    }
  }
  os << ']';
}
}  // namespace detail

inline std::string mesh_report::to_string() const {
  std::ostringstream os;
  if (!shape_problem.empty()) {
    os << "bad matrix shape: " << shape_problem << "\n";
    return os.str();
  }
  os << "vertices " << num_vertices << ", faces " << num_faces << ", edges " << num_edges << ", components "
     << num_components << "\n";
  os << "euler characteristic " << euler_characteristic << ", genus "
     << (genus >= 0 ? std::to_string(genus) : std::string("undefined")) << ", orientable " << detail::yes_no(orientable)
     << ", closed manifold " << detail::yes_no(is_closed_manifold()) << ", bbox diagonal " << bbox_diagonal << "\n";
  struct row {
    const char* name;
    index_t count;
    const std::vector<index_t>* list;
    const std::vector<std::array<index_t, 2>>* edges;
  };
  const row rows[] = {
      {"boundary edges", num_boundary_edges, nullptr, &boundary_edge_examples},
      {"boundary loops", num_boundary_loops, nullptr, nullptr},
      {"non-manifold edges", num_non_manifold_edges, nullptr, &non_manifold_edge_examples},
      {"non-manifold vertices", num_non_manifold_vertices, &non_manifold_vertex_examples, nullptr},
      {"inconsistently oriented edges", num_inconsistent_edges, nullptr, &inconsistent_edge_examples},
      {"degenerate faces", num_degenerate_faces, &degenerate_face_examples, nullptr},
      {"duplicate vertices", num_duplicate_vertices, &duplicate_vertex_examples, nullptr},
      {"non-finite vertices", num_non_finite_vertices, &non_finite_vertex_examples, nullptr},
      {"out-of-range faces", num_out_of_range_faces, &out_of_range_face_examples, nullptr},
      {"unreferenced vertices", num_unreferenced_vertices, &unreferenced_vertex_examples, nullptr},
  };
  for (const auto& rw : rows) {
    os << "  " << rw.name << ": " << rw.count;
    if (rw.list) detail::print_examples(os, *rw.list, rw.count);
    if (rw.edges) detail::print_examples(os, *rw.edges, rw.count);
    os << "\n";
  }
  // A scan with thousands of fragments would drown the summary; the counts above stay complete.
  const std::size_t shown = std::min<std::size_t>(components.size(), 10);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto& c = components[i];
    os << "  component " << i << " (from vertex " << c.first_vertex << "): " << c.num_vertices << " vertices, "
       << c.num_faces << " faces, " << c.num_edges << " edges, chi " << c.euler_characteristic << ", "
       << c.num_boundary_loops << " boundary loops, genus "
       << (c.genus >= 0 ? std::to_string(c.genus) : std::string("undefined")) << ", area " << c.area
       << (c.manifold ? "" : ", non-manifold") << (c.orientable ? "" : ", non-orientable") << "\n";
  }
  if (components.size() > shown) os << "  ... and " << components.size() - shown << " more components with faces\n";
  return os.str();
}

inline std::string mesh_report::to_json() const {
  std::ostringstream os;
  os.precision(17);
  auto num = [&](const char* k, index_t v) { os << ",\"" << k << "\":" << v; };
  os << "{\"vertices\":" << num_vertices;
  num("faces", num_faces);
  if (!shape_problem.empty()) {
    std::string escaped;
    for (const char ch : shape_problem) {
      if (ch == '"' || ch == '\\') escaped += '\\';
      escaped += ch;
    }
    os << ",\"shape_problem\":\"" << escaped << "\"}";
    return os.str();
  }
  num("edges", num_edges);
  num("components", num_components);
  num("boundary_edges", num_boundary_edges);
  num("boundary_loops", num_boundary_loops);
  num("non_manifold_edges", num_non_manifold_edges);
  num("non_manifold_vertices", num_non_manifold_vertices);
  num("inconsistent_edges", num_inconsistent_edges);
  num("degenerate_faces", num_degenerate_faces);
  num("repeated_index_faces", num_repeated_index_faces);
  num("duplicate_vertices", num_duplicate_vertices);
  num("non_finite_vertices", num_non_finite_vertices);
  num("out_of_range_faces", num_out_of_range_faces);
  num("unreferenced_vertices", num_unreferenced_vertices);
  num("euler_characteristic", euler_characteristic);
  num("genus", genus);
  os << ",\"orientable\":" << (orientable ? "true" : "false");
  os << ",\"closed_manifold\":" << (is_closed_manifold() ? "true" : "false");
  os << ",\"bbox_diagonal\":" << (std::isfinite(bbox_diagonal) ? bbox_diagonal : 0.0);
  detail::json_list(os, "boundary_edge_examples", boundary_edge_examples);
  detail::json_list(os, "non_manifold_edge_examples", non_manifold_edge_examples);
  detail::json_list(os, "non_manifold_vertex_examples", non_manifold_vertex_examples);
  detail::json_list(os, "inconsistent_edge_examples", inconsistent_edge_examples);
  detail::json_list(os, "degenerate_face_examples", degenerate_face_examples);
  detail::json_list(os, "duplicate_vertex_examples", duplicate_vertex_examples);
  detail::json_list(os, "non_finite_vertex_examples", non_finite_vertex_examples);
  detail::json_list(os, "out_of_range_face_examples", out_of_range_face_examples);
  detail::json_list(os, "unreferenced_vertex_examples", unreferenced_vertex_examples);
  os << ",\"component_list\":[";
  for (std::size_t i = 0; i < components.size(); ++i) {
    const auto& c = components[i];
    if (i) os << ',';
    os << "{\"first_vertex\":" << c.first_vertex << ",\"vertices\":" << c.num_vertices << ",\"faces\":" << c.num_faces
       << ",\"edges\":" << c.num_edges << ",\"boundary_loops\":" << c.num_boundary_loops
       << ",\"euler_characteristic\":" << c.euler_characteristic << ",\"genus\":" << c.genus
       << ",\"manifold\":" << (c.manifold ? "true" : "false") << ",\"orientable\":" << (c.orientable ? "true" : "false")
       << ",\"area\":" << (std::isfinite(c.area) ? c.area : 0.0) << "}";
  }
  os << "]}";
  return os.str();
}

}  // namespace shapestruct
