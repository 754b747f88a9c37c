// SPDX-License-Identifier: MIT
// mid_edge_flattening: discrete conformal map of a closed genus-0 mesh to the extended complex plane.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <complex>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "shapestruct/config.hpp"
#include "shapestruct/conformal/planar_triangle_locator.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/heap_bytes.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/surface_point.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"
#include "shapestruct/detail/sorted_half_edges.hpp"
#include "shapestruct/geometry/cotan_laplacian.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/knn/knn_index.hpp"

namespace shapestruct {

/// Options of mid_edge_flattening.
struct mid_edge_flattening_options {
  /// The face cut out of the sphere (it goes to the neighbourhood of infinity). no_index: the largest face,
  /// because a well-shaped cut face makes the two Dirichlet values a well-resolved dipole.
  index_t cut_face = no_index;
  /// Accept vertices where several face fans of the same sphere touch ("pinches"; SCAPE's template has one, at
  /// vertex 419). The mid-edge construction only uses edges, so the surface is still a sphere for it; with
  /// false such a vertex is an invalid_input (non_manifold). Non-manifold edges are always rejected.
  bool accept_pinched_vertices = true;
};

/// Mid-edge uniformization (Pinkall & Polthier 1993, Polthier 2005; used by Lipman & Funkhouser 2009 and
/// dissertation ch. 3.3.2). One face is cut out; the discrete harmonic function u with u = -1 and u = +1 at two
/// corners of the cut face (a discrete dipole) is found with one sparse solve; its conjugate u* is integrated on
/// the mid-edges (non-conforming elements, where it is single-valued because u is discrete harmonic); the mid-edge
/// point of edge e then goes to z_e = u(mid e) + i u*(e). The cut face's neighbourhood goes to the outer boundary
/// of the image, the "point at infinity" of the extended complex plane; Möbius transforms act on the result.
///
/// For mapping in both directions the flattening also stores a planar triangulation that covers the mesh
/// exactly: each face is split into its mid-edge triangle and three corner triangles (the vertex is placed at
/// the mean of its incident mid-edge images), and an AABB tree over it answers "which surface point has this
/// complex coordinate".
template <class Scalar = double>
class mid_edge_flattening {
 public:
  using complex = std::complex<Scalar>;

  mid_edge_flattening() = default;

  /// Flattens (V, F). O(V + F) plus one sparse Cholesky factorisation (O(V^1.5) typical for surfaces).
  /// \param V (#V x 3) positions  \param F (#F x 3) faces of a closed, connected, genus-0, manifold mesh
  /// \throws invalid_input: empty / non_finite / bad_face (validate_mesh); non_manifold (an edge with more than
  ///         two faces, element = a face on it); unsupported_topology (a boundary edge, several components or
  ///         genus > 0; element = an offending face or no_index); bad_parameter (cut_face out of range).
  mid_edge_flattening(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                      const mid_edge_flattening_options& options = {},
                      validation_level level = validation_level::full) {
    validate_mesh(V, F, "mid_edge_flattening", level);
    build_edges(V, F, options.accept_pinched_vertices);
    const vector_x<Scalar> area3 = face_areas<Scalar>(V, F, validation_level::trust);
    cut_ = options.cut_face;
    if (cut_ == no_index) area3.maxCoeff(&cut_);
    if (cut_ < 0 || cut_ >= F.rows())
      throw invalid_input(input_error::bad_parameter, cut_,
                          "mid_edge_flattening: options.cut_face = " + std::to_string(cut_) + " is not a face index");
    solve_harmonic(V, F);
    integrate_conjugate(V, F);
    build_plane(V, F, area3);
  }

  /// Numerical outcome of the harmonic solve.
  [[nodiscard]] status info() const noexcept { return info_; }
  /// The face that was cut out.
  [[nodiscard]] index_t cut_face() const noexcept { return cut_; }
  /// Bytes held on the heap (core/heap_bytes.hpp), the planar locator and the vertex kd-tree included.
  [[nodiscard]] std::size_t heap_bytes() const noexcept {
    using shapestruct::heap_bytes;
    return heap_bytes(faces_) + heap_bytes(face_edges_) + heap_bytes(edges_) + heap_bytes(edge_faces_) +
           heap_bytes(used_) + heap_bytes(u_) + heap_bytes(edge_z_) + heap_bytes(vertex_z_) + heap_bytes(density_) +
           heap_bytes(log_density_) + heap_bytes(sub_face_) + heap_bytes(sub_bary_) + locator_.heap_bytes() +
           (vertex_index_ ? sizeof(*vertex_index_) + vertex_index_->heap_bytes() : 0);
  }
  /// Complex coordinate of every vertex (#V).
  [[nodiscard]] const std::vector<complex>& vertex_coordinates() const noexcept { return vertex_z_; }
  /// Complex coordinate of every edge's mid-point (#E) and the edges' vertex pairs (#E x 2).
  [[nodiscard]] const std::vector<complex>& midedge_coordinates() const noexcept { return edge_z_; }
  [[nodiscard]] const Eigen::Matrix<index_t, Eigen::Dynamic, 2>& edges() const noexcept { return edges_; }
  /// Edge opposite corner k of face f.
  [[nodiscard]] index_t face_edge(index_t f, int k) const noexcept { return face_edges_(f, k); }
  /// The discrete harmonic function u (#V).
  [[nodiscard]] const vector_x<Scalar>& harmonic() const noexcept { return u_; }

  /// Complex coordinate of a surface point (barycentric interpolation of the face's split triangulation, so it
  /// is exact for the mid-edge points and the vertices).
  [[nodiscard]] complex coordinate(const surface_point<Scalar>& p) const {
    // Corner k weight b_k; write the point in the split triangulation: the mid-edge triangle carries the part
    // sum_k min-weight structure; simplest exact form: z = sum_k b_k z(v_k) corrected to the mid-edge image.
    const index_t f = p.face;
    const Scalar b0 = p.bary[0], b1 = p.bary[1], b2 = p.bary[2];
    // Sub-triangle selection: corner k's triangle holds b_k >= 1/2.
    const complex m0 = edge_z_[static_cast<std::size_t>(face_edges_(f, 0))],
                  m1 = edge_z_[static_cast<std::size_t>(face_edges_(f, 1))],
                  m2 = edge_z_[static_cast<std::size_t>(face_edges_(f, 2))];
    const Scalar b[3] = {b0, b1, b2};
    const complex m[3] = {m0, m1, m2};
    for (int k = 0; k < 3; ++k) {
      if (b[k] >= Scalar(0.5)) {
        // corner triangle (v_k, m_{k+1}, m_{k+2}): v_k = e_k, m_{k+1} = (e_k + e_{k+2})/2, m_{k+2} = (e_k + e_{k+1})/2
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        const Scalar l1 = 2 * b[k2], l2 = 2 * b[k1];
        const Scalar l0 = Scalar(1) - l1 - l2;
        return l0 * vertex_z_[static_cast<std::size_t>(faces_(f, k))] + l1 * m[k1] + l2 * m[k2];
      }
    }
    // central triangle (m0, m1, m2): m_k = (sum of the other two corners)/2 -> b_k = (1 - l_k)/2
    return (Scalar(1) - 2 * b0) * m0 + (Scalar(1) - 2 * b1) * m1 + (Scalar(1) - 2 * b2) * m2;
  }

  /// Complex coordinate of vertex v.
  [[nodiscard]] complex coordinate(index_t v) const { return vertex_z_[static_cast<std::size_t>(v)]; }

  /// The surface point whose coordinate is z; points outside the image (near infinity) are clamped to the
  /// nearest triangle. `distance` (optional) receives the planar distance of the clamp (0 inside). O(log F).
  [[nodiscard]] surface_point<Scalar> locate(complex z, Scalar* distance = nullptr) const {
    return to_surface(locator_.locate(z), distance);
  }

  /// locate(z), the search started at `hint` (a triangle of the split triangulation: no_index the first time) and
  /// set to where z was found; the same answer as locate, in a few steps when consecutive queries lie close.
  [[nodiscard]] surface_point<Scalar> locate(complex z, index_t& hint, Scalar* distance = nullptr) const {
    return to_surface(locator_.locate_from(z, hint), distance);
  }

  /// The vertex whose planar image is nearest to z (a kd-tree query, O(log V)): a cheaper, vertex-accurate
  /// stand-in for locate() where one ring of accuracy is enough (consistency and confidence at samples).
  [[nodiscard]] index_t nearest_vertex(complex z) const {
    if (!std::isfinite(z.real()) || !std::isfinite(z.imag())) z = complex(Scalar(1e30), Scalar(1e30));
    const Eigen::Matrix<Scalar, 1, 2> q(z.real(), z.imag());
    return vertex_index_->nearest(q).index;
  }

  /// Surface-area density of the flattening at each vertex: (3-D area) / (planar area) over the vertex's
  /// incident faces. |T'(z)|^2 times the densities' ratio is the area distortion of a conformal map (eq. 3.2).
  [[nodiscard]] const vector_x<Scalar>& vertex_density() const noexcept { return density_; }

  /// Density at a surface point (log-linear interpolation, since densities span orders of magnitude).
  [[nodiscard]] Scalar density(const surface_point<Scalar>& p) const {
    Scalar s = 0;
    for (int k = 0; k < 3; ++k) s += p.bary[k] * log_density_[faces_(p.face, k)];
    return std::exp(s);
  }

  /// Number of mid-edge triangles whose orientation disagrees with the majority (fold-overs); 0 on Delaunay
  /// meshes, where the mid-edge map is provably an embedding.
  [[nodiscard]] index_t count_foldovers() const {
    index_t pos = 0, neg = 0;
    for (index_t f = 0; f < faces_.rows(); ++f) {
      if (f == cut_) continue;
      const complex a = edge_z_[static_cast<std::size_t>(face_edges_(f, 0))],
                    b = edge_z_[static_cast<std::size_t>(face_edges_(f, 1))],
                    c = edge_z_[static_cast<std::size_t>(face_edges_(f, 2))];
      const Scalar s = cross(b - a, c - a);
      if (s > 0) ++pos;
      else if (s < 0) ++neg;
    }
    return std::min(pos, neg);
  }

 private:
  [[nodiscard]] surface_point<Scalar> to_surface(const typename planar_triangle_locator<Scalar>::hit& h,
                                                 Scalar* distance) const {
    surface_point<Scalar> out;
    if (h.triangle == no_index) return out;
    const index_t t = h.triangle;
    out.face = sub_face_[static_cast<std::size_t>(t)];
    out.bary = sub_bary_[static_cast<std::size_t>(t)] * h.bary;
    if (distance) *distance = h.distance;
    return out;
  }

  static Scalar cross(complex u, complex v) { return u.real() * v.imag() - u.imag() * v.real(); }

  void build_edges(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                   bool accept_pinches) {
    faces_ = F;
    const index_t nf = F.rows();
    const std::vector<detail::half_edge> hs = detail::sorted_half_edges(F);
    face_edges_.resize(nf, 3);
    edge_faces_.clear();
    std::vector<std::pair<index_t, index_t>> ev;
    for (std::size_t s = 0; s < hs.size();) {
      std::size_t e = s;
      while (e < hs.size() && hs[e].lo == hs[s].lo && hs[e].hi == hs[s].hi) ++e;
      if (e - s == 1)
        throw invalid_input(input_error::unsupported_topology, hs[s].face,
                            "mid_edge_flattening: edge (" + std::to_string(hs[s].lo) + ", " + std::to_string(hs[s].hi) +
                                ") of face " + std::to_string(hs[s].face) +
                                " is on a boundary (the mesh has a hole); a closed genus-0 surface is required: fill "
                                "small holes first (blended_shape_options::close_small_holes, off by default, or "
                                "geometry/mesh_repair.hpp close_small_holes)");
      if (e - s > 2)
        throw invalid_input(input_error::non_manifold, hs[s].face,
                            "mid_edge_flattening: edge (" + std::to_string(hs[s].lo) + ", " + std::to_string(hs[s].hi) +
                                ") has " + std::to_string(e - s) + " faces; a manifold surface is required");
      const index_t id = static_cast<index_t>(ev.size());
      ev.emplace_back(hs[s].lo, hs[s].hi);
      edge_faces_.push_back({hs[s].face, hs[s + 1].face});
      for (std::size_t t = s; t < e; ++t) face_edges_(hs[t].face, hs[t].corner) = id;
      s = e;
    }
    edges_.resize(static_cast<index_t>(ev.size()), 2);
    for (std::size_t i = 0; i < ev.size(); ++i) {
      edges_(static_cast<index_t>(i), 0) = ev[i].first;
      edges_(static_cast<index_t>(i), 1) = ev[i].second;
    }
    // Connectivity (faces reachable across edges) and Euler characteristic V - E + F = 2 of a sphere.
    std::vector<char> seen(static_cast<std::size_t>(nf), 0);
    std::vector<index_t> stack{0};
    seen[0] = 1;
    index_t reached = 1;
    while (!stack.empty()) {
      const index_t f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const auto& ef = edge_faces_[static_cast<std::size_t>(face_edges_(f, k))];
        const index_t g = ef[0] == f ? ef[1] : ef[0];
        if (!seen[static_cast<std::size_t>(g)]) {
          seen[static_cast<std::size_t>(g)] = 1;
          ++reached;
          stack.push_back(g);
        }
      }
    }
    if (reached != nf) {
      index_t first_unreached = 0;
      while (seen[static_cast<std::size_t>(first_unreached)]) ++first_unreached;
      throw invalid_input(input_error::unsupported_topology, first_unreached,
                          "mid_edge_flattening: the mesh has several connected components (face " +
                              std::to_string(first_unreached) +
                              " is not connected to face 0 across edges); keep the largest component first "
                              "(blended_shape_options::keep_largest_component, off by default, or "
                              "geometry/mesh_repair.hpp keep_largest_component)");
    }
    std::vector<char> used(static_cast<std::size_t>(V.rows()), 0);
    for (index_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(F(f, k))] = 1;
    index_t nv = 0;
    for (char c : used) nv += c;
    // Fans per vertex: corners (3f + k) linked across the edges they share. A pinched vertex with n fans is
    // n vertices of the underlying sphere, so it adds n - 1 to the Euler characteristic.
    detail::disjoint_sets fans(3 * nf);
    for (std::size_t e = 0; e < edge_faces_.size(); ++e) {
      const index_t f = edge_faces_[e][0], g = edge_faces_[e][1];
      for (int s = 0; s < 2; ++s) {
        const index_t v = edges_(static_cast<index_t>(e), s);
        int cf = 0, cg = 0;
        for (int k = 0; k < 3; ++k) {
          if (F(f, k) == v) cf = k;
          if (F(g, k) == v) cg = k;
        }
        fans.unite(3 * f + cf, 3 * g + cg);
      }
    }
    std::vector<index_t> first_root(static_cast<std::size_t>(V.rows()), no_index);
    std::vector<index_t> nfans(static_cast<std::size_t>(V.rows()), 0);
    std::vector<std::vector<index_t>> roots(static_cast<std::size_t>(V.rows()));
    index_t extra = 0;
    for (index_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const index_t r = fans.find(3 * f + k);
        auto& list = roots[static_cast<std::size_t>(F(f, k))];
        if (std::find(list.begin(), list.end(), r) == list.end()) {
          list.push_back(r);
          if (list.size() > 1) {
            if (!accept_pinches)
              throw invalid_input(input_error::non_manifold, F(f, k),
                                  "mid_edge_flattening: vertex " + std::to_string(F(f, k)) +
                                      " joins several face fans (a non-manifold vertex); set "
                                      "mid_edge_flattening_options::accept_pinched_vertices to accept pinches");
            ++extra;
          }
        }
      }
    const index_t chi = nv + extra - edges_.rows() + nf;
    if (chi != 2)
      throw invalid_input(input_error::unsupported_topology, no_index,
                          "mid_edge_flattening: Euler characteristic " + std::to_string(chi) + " (genus " +
                              std::to_string((2 - chi) / 2) + "); a genus-0 (sphere-like) surface is required");
    used_ = std::move(used);
  }

  void solve_harmonic(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F) {
    const index_t nv = V.rows(), nf = F.rows();
    face_matrix Fc(nf - 1, 3);
    for (index_t f = 0, r = 0; f < nf; ++f)
      if (f != cut_) Fc.row(r++) = F.row(f);
    const Eigen::SparseMatrix<Scalar> L = cotan_laplacian<Scalar>(V, Fc, {}, validation_level::trust);
    // Dirichlet values: a dipole across the cut face's first edge (u = -1, +1); every other vertex, including the
    // cut face's third corner, is free (natural boundary condition on the cut).
    const index_t a = F(cut_, 0), b = F(cut_, 1);
    std::vector<index_t> free_id(static_cast<std::size_t>(nv), no_index);
    index_t nfree = 0;
    for (index_t v = 0; v < nv; ++v)
      if (v != a && v != b && used_[static_cast<std::size_t>(v)]) free_id[static_cast<std::size_t>(v)] = nfree++;
    u_ = vector_x<Scalar>::Zero(nv);
    u_[a] = -1;
    u_[b] = 1;
    std::vector<Eigen::Triplet<Scalar, index_t>> trip;
    trip.reserve(static_cast<std::size_t>(L.nonZeros()));
    vector_x<Scalar> rhs = vector_x<Scalar>::Zero(nfree);
    for (index_t c = 0; c < L.outerSize(); ++c)
      for (typename Eigen::SparseMatrix<Scalar>::InnerIterator it(L, c); it; ++it) {
        const index_t r = free_id[static_cast<std::size_t>(it.row())];
        if (r == no_index) continue;
        const index_t cc = free_id[static_cast<std::size_t>(it.col())];
        if (cc != no_index) trip.emplace_back(r, cc, it.value());
        else rhs[r] -= it.value() * u_[it.col()];
      }
    Eigen::SparseMatrix<Scalar> A(nfree, nfree);
    A.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<Scalar>> solver(A);
    info_ = status::ok;
    if (solver.info() != Eigen::Success) {
      info_ = status::numerical_issue;
      return;
    }
    const vector_x<Scalar> x = solver.solve(rhs);
    if (solver.info() != Eigen::Success || !x.allFinite()) {
      info_ = status::numerical_issue;
      return;
    }
    for (index_t v = 0; v < nv; ++v)
      if (free_id[static_cast<std::size_t>(v)] != no_index) u_[v] = x[free_id[static_cast<std::size_t>(v)]];
  }

  /// Walks the faces (not crossing the cut) and sets u* on mid-edges: inside a face, u* is linear with
  /// gradient n x grad u (the 90-degree rotation that makes u + i u* holomorphic), so
  /// u*(m_j) - u*(m_i) = (n x grad u) . (m_j - m_i).
  void integrate_conjugate(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F) {
    const index_t nf = F.rows(), ne = edges_.rows();
    std::vector<Scalar> ustar(static_cast<std::size_t>(ne), 0);
    std::vector<char> known(static_cast<std::size_t>(ne), 0);
    std::vector<char> done(static_cast<std::size_t>(nf), 0);
    const index_t start = cut_ == 0 ? 1 : 0;
    known[static_cast<std::size_t>(face_edges_(start, 0))] = 1;
    std::vector<index_t> queue{start};
    done[static_cast<std::size_t>(start)] = 1;
    done[static_cast<std::size_t>(cut_)] = 1;
    for (std::size_t qi = 0; qi < queue.size(); ++qi) {
      const index_t f = queue[qi];
      vec3<Scalar> p[3];
      Scalar u[3];
      for (int k = 0; k < 3; ++k) {
        p[k] = V.row(F(f, k)).transpose();
        u[k] = u_[F(f, k)];
      }
      const vec3<Scalar> nrm = (p[1] - p[0]).cross(p[2] - p[0]);
      const Scalar twice_area = nrm.norm();
      const Scalar scale = (p[1] - p[0]).squaredNorm() + (p[2] - p[0]).squaredNorm() + (p[2] - p[1]).squaredNorm();
      vec3<Scalar> rot_grad = vec3<Scalar>::Zero();
      // Degenerate faces carry no gradient (their cotan weights are clamped too): skip rather than divide by 0.
      if (twice_area > Scalar(1e-12) * scale && scale > 0) {
        const vec3<Scalar> n = nrm / twice_area;
        vec3<Scalar> grad = vec3<Scalar>::Zero();
        for (int k = 0; k < 3; ++k) grad += u[k] * n.cross(p[(k + 2) % 3] - p[(k + 1) % 3]) / twice_area;
        rot_grad = n.cross(grad);
      }
      vec3<Scalar> mid[3];
      for (int k = 0; k < 3; ++k) mid[k] = (p[(k + 1) % 3] + p[(k + 2) % 3]) / 2;
      int ref = -1;
      for (int k = 0; k < 3; ++k)
        if (known[static_cast<std::size_t>(face_edges_(f, k))]) {
          ref = k;
          break;
        }
      SHAPESTRUCT_ASSERT(ref >= 0, "BFS reaches a face through a known mid-edge");
      if (ref < 0) ref = 0;
      const Scalar base = ustar[static_cast<std::size_t>(face_edges_(f, ref))];
      for (int k = 0; k < 3; ++k) {
        const index_t e = face_edges_(f, k);
        if (!known[static_cast<std::size_t>(e)]) {
          ustar[static_cast<std::size_t>(e)] = base + rot_grad.dot(mid[k] - mid[ref]);
          known[static_cast<std::size_t>(e)] = 1;
        }
        const auto& ef = edge_faces_[static_cast<std::size_t>(e)];
        const index_t g = ef[0] == f ? ef[1] : ef[0];
        if (!done[static_cast<std::size_t>(g)]) {
          done[static_cast<std::size_t>(g)] = 1;
          queue.push_back(g);
        }
      }
    }
    edge_z_.resize(static_cast<std::size_t>(ne));
    for (index_t e = 0; e < ne; ++e)
      edge_z_[static_cast<std::size_t>(e)] =
          complex((u_[edges_(e, 0)] + u_[edges_(e, 1)]) / 2, ustar[static_cast<std::size_t>(e)]);
  }

  void build_plane(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                   const vector_x<Scalar>& area3) {
    const index_t nv = V.rows(), nf = F.rows();
    // Vertex images: the mean of the images of the vertex's mid-edges (the centre of its polygon in the
    // mid-edge mesh). The mid-edge map is non-conforming, so the corner triangles built on this point can
    // overlap a neighbour's near the cut or a sliver; point location then returns a point within one ring.
    vertex_z_.assign(static_cast<std::size_t>(nv), complex(0));
    std::vector<Scalar> cnt(static_cast<std::size_t>(nv), 0);
    for (index_t e = 0; e < edges_.rows(); ++e)
      for (int s = 0; s < 2; ++s) {
        vertex_z_[static_cast<std::size_t>(edges_(e, s))] += edge_z_[static_cast<std::size_t>(e)];
        cnt[static_cast<std::size_t>(edges_(e, s))] += 1;
      }
    for (index_t v = 0; v < nv; ++v)
      if (cnt[static_cast<std::size_t>(v)] > 0) vertex_z_[static_cast<std::size_t>(v)] /= cnt[static_cast<std::size_t>(v)];
    // Planar points: vertices [0, nv), mid-edges [nv, nv + ne).
    std::vector<complex> pts(vertex_z_);
    pts.insert(pts.end(), edge_z_.begin(), edge_z_.end());
    Eigen::Matrix<index_t, Eigen::Dynamic, 3> tris(4 * (nf - 1), 3);
    sub_face_.assign(static_cast<std::size_t>(4 * (nf - 1)), no_index);
    sub_bary_.assign(static_cast<std::size_t>(4 * (nf - 1)), Eigen::Matrix<Scalar, 3, 3>::Zero());
    density_ = vector_x<Scalar>::Zero(nv);
    vector_x<Scalar> planar_sum = vector_x<Scalar>::Zero(nv), area_sum = vector_x<Scalar>::Zero(nv);
    vector_x<Scalar> face_planar = vector_x<Scalar>::Zero(nf), face_area = area3;
    index_t t = 0;
    const Scalar h = Scalar(0.5);
    for (index_t f = 0; f < nf; ++f) {
      if (f == cut_) continue;
      const index_t me[3] = {nv + face_edges_(f, 0), nv + face_edges_(f, 1), nv + face_edges_(f, 2)};
      // central triangle: columns are the face barycentrics of the sub-triangle's corners m0, m1, m2
      tris.row(t) << me[0], me[1], me[2];
      Eigen::Matrix<Scalar, 3, 3> B;
      B << 0, h, h, h, 0, h, h, h, 0;
      sub_face_[static_cast<std::size_t>(t)] = f;
      sub_bary_[static_cast<std::size_t>(t)] = B;
      ++t;
      for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        tris.row(t) << F(f, k), me[k1], me[k2];
        Eigen::Matrix<Scalar, 3, 3> C = Eigen::Matrix<Scalar, 3, 3>::Zero();
        C(k, 0) = 1;
        C(k, 1) = h;  // m_{k1} lies on the edge (v_k, v_{k2})
        C(k2, 1) = h;
        C(k, 2) = h;  // m_{k2} lies on the edge (v_k, v_{k1})
        C(k1, 2) = h;
        sub_face_[static_cast<std::size_t>(t)] = f;
        sub_bary_[static_cast<std::size_t>(t)] = C;
        ++t;
      }
      // The mid-edge triangle is a quarter of the face in 3-D; its planar image is the robust measure of the
      // face's planar area (the vertex positions are averages and can fold on slivers).
      const complex a = edge_z_[static_cast<std::size_t>(face_edges_(f, 0))],
                    b = edge_z_[static_cast<std::size_t>(face_edges_(f, 1))],
                    c = edge_z_[static_cast<std::size_t>(face_edges_(f, 2))];
      const Scalar planar = Scalar(4) * std::abs(cross(b - a, c - a)) / 2;
      face_planar[f] = planar;
    }
    // Density = 3-D area / planar area over a two-ring neighbourhood (vertex -> incident faces -> their
    // vertices): single faces are too noisy on scans with slivers (SCAPE), where a mid-edge triangle can
    // collapse to zero planar area.
    for (int pass = 0; pass < 2; ++pass) {
      planar_sum.setZero();
      area_sum.setZero();
      for (index_t f = 0; f < nf; ++f) {
        if (f == cut_) continue;
        for (int k = 0; k < 3; ++k) {
          planar_sum[F(f, k)] += face_planar[f];
          area_sum[F(f, k)] += face_area[f];
        }
      }
      if (pass == 1) break;
      for (index_t f = 0; f < nf; ++f) {
        if (f == cut_) continue;
        face_planar[f] = planar_sum[F(f, 0)] + planar_sum[F(f, 1)] + planar_sum[F(f, 2)];
        face_area[f] = area_sum[F(f, 0)] + area_sum[F(f, 1)] + area_sum[F(f, 2)];
      }
    }
    log_density_ = vector_x<Scalar>::Zero(nv);
    const Scalar tiny = std::numeric_limits<Scalar>::min() * Scalar(1e20);
    for (index_t v = 0; v < nv; ++v) {
      const Scalar ratio = std::max(area_sum[v], tiny) / std::max(planar_sum[v], tiny);
      density_[v] = ratio;
      log_density_[v] = std::log(ratio);
    }
    locator_ = planar_triangle_locator<Scalar>(std::move(pts), std::move(tris));
    Eigen::Matrix<Scalar, Eigen::Dynamic, 2> P(nv, 2);
    for (index_t v = 0; v < nv; ++v) {
      // Unused vertices get a far-away position so that they are never the nearest.
      const complex z = used_[static_cast<std::size_t>(v)] ? vertex_z_[static_cast<std::size_t>(v)] : complex(Scalar(1e30), Scalar(1e30));
      P(v, 0) = z.real();
      P(v, 1) = z.imag();
    }
    vertex_index_ = std::make_shared<knn_index<Scalar, 2>>(P);
  }

  status info_ = status::ok;
  index_t cut_ = no_index;
  face_matrix faces_;
  Eigen::Matrix<index_t, Eigen::Dynamic, 3> face_edges_;
  Eigen::Matrix<index_t, Eigen::Dynamic, 2> edges_;
  std::vector<std::array<index_t, 2>> edge_faces_;
  std::vector<char> used_;
  vector_x<Scalar> u_;
  std::vector<complex> edge_z_;
  std::vector<complex> vertex_z_;
  vector_x<Scalar> density_, log_density_;
  std::vector<index_t> sub_face_;
  std::vector<Eigen::Matrix<Scalar, 3, 3>> sub_bary_;
  planar_triangle_locator<Scalar> locator_;
  std::shared_ptr<knn_index<Scalar, 2>> vertex_index_;  // shared: knn_index is move-only, flattenings are copied
};

/// Flattens any SurfaceMesh (gathered into triangle_mesh<double>). See the class for the algorithm.
/// \throws invalid_input as the kernel constructor.
template <SurfaceMesh Mesh>
[[nodiscard]] mid_edge_flattening<double> flatten_mid_edge(const Mesh& mesh, const mid_edge_flattening_options& options = {}) {
  const auto m = to_triangle_mesh<double>(mesh);
  return mid_edge_flattening<double>(m.V, m.F, options);
}

}  // namespace shapestruct
