// SPDX-License-Identifier: MIT
// heat_geodesic_solver: approximate geodesic distances by the heat method (Crane, Weischedel, Wardetzky 2013).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/detail/disjoint_sets.hpp"
#include "shapestruct/geometry/cotan_laplacian.hpp"
#include "shapestruct/geometry/detail/geometry_common.hpp"
#include "shapestruct/geometry/mass_matrix.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"

namespace shapestruct {

/// Options of heat_geodesic_solver.
///
/// | field | default | meaning |
/// |---|---|---|
/// | time_factor | 1.0 | heat time t = time_factor * h^2, h = mean edge length (Crane et al.'s choice m = 1); larger values smooth more |
/// | mass | barycentric | lumped mass matrix used in the heat step |
/// | regularisation | 1e-10 | the Poisson matrix is L + r * (tr L / tr M) * M: makes the singular L factorisable; relative, so scale-free |
struct heat_geodesic_options {
  double time_factor = 1.0;
  mass_type mass = mass_type::barycentric;
  double regularisation = 1e-10;
};

/// Distances from one set of sources.
template <class Scalar>
struct heat_geodesic_result {
  vector_x<Scalar> distance;  ///< (#V) >= 0, 0 at the sources; +inf on components without a source
  status info = status::ok;   ///< numerical_issue if a factorisation failed: then every distance is +inf
};

/// Distances from several sources, one column each.
template <class Scalar>
struct heat_distance_table {
  matrix_x<Scalar> distances;  ///< (#V x #sources), column-major
  status info = status::ok;    ///< numerical_issue if a factorisation failed: then every entry is +inf
};

/// The heat method for geodesic distance: (1) diffuse heat from the sources for a short time t by one
/// backward-Euler step (M + t L) u = delta; (2) X = -grad u / |grad u| per face; (3) solve the Poisson
/// problem L phi = div X; (4) shift so the sources are at 0. L is the PSD cotan Laplacian (clamped
/// cotangents), M the lumped mass matrix; both systems are factorised once (SimplicialLDLT, always in double
/// whatever Scalar is) in the constructor, so each query costs two triangular solves and one pass over F.
///
/// Accuracy: on well-shaped meshes the heat method is CLOSER to the true geodesic distance than Dijkstra on
/// edges, which overestimates by a zig-zag factor. Measured on the unit icosphere of level 5 (10,242 vertices)
/// against exact great-circle distances: mean relative error 0.74% (heat) vs 7.1% (Dijkstra); on a flat
/// 40 x 40 grid 1.7% against Euclidean distance (tests/geometry/test_heat_geodesics.cpp). Its error is a smoothing
/// near the sources (t ~ h^2) and grows on badly shaped triangles.
///
/// Robustness: degenerate faces (zero cross product) carry no gradient and contribute nothing to the
/// divergence; the gradient is never divided by the face area (only its direction is used), so slivers cannot
/// produce Inf/NaN. Vertices on a connected component without a source get +inf; each component is shifted
/// by its own sources. Backward Euler makes u decay about e^-1 per edge ring at time_factor 1, so in double
/// precision the direction of grad u is reliable up to ~700 rings from the source.
///
/// Queries are const and may run concurrently. Cost: construction O(factorisation) (~30 ms for 12.5K vertices
/// here), each source ~2 sparse solves + O(F).
template <class Scalar = double>
class heat_geodesic_solver {
 public:
  using scalar_type = Scalar;

  /// Builds and factorises both systems.
  /// \param V (#V x 3) vertex positions  \param F (#F x 3) triangles  \param options see heat_geodesic_options
  /// \throws invalid_input (empty, non_finite, bad_face) from validate_mesh; (bad_parameter) for a time_factor
  /// that is not finite and > 0 or a regularisation that is not finite and >= 0. A failed factorisation is not
  /// thrown: info() and every result report status::numerical_issue.
  heat_geodesic_solver(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                       const heat_geodesic_options& options = {}, validation_level level = validation_level::full) {
    validate_mesh(V, F, "heat_geodesic_solver", level);
    if (!(options.time_factor > 0) || !std::isfinite(options.time_factor))
      throw invalid_input(input_error::bad_parameter, no_index,
                          "heat_geodesic_solver: options.time_factor must be finite and > 0, got " +
                              std::to_string(options.time_factor));
    if (!(options.regularisation >= 0) || !std::isfinite(options.regularisation))
      throw invalid_input(input_error::bad_parameter, no_index,
                          "heat_geodesic_solver: options.regularisation must be finite and >= 0, got " +
                              std::to_string(options.regularisation));
    const matrix_x3<double> Vd = V.template cast<double>();
    F_ = F;
    n_ = V.rows();
    h_ = mean_edge_length<double>(Vd, F, validation_level::trust);
    t_ = options.time_factor * h_ * h_;
    const Eigen::SparseMatrix<double> L = cotan_laplacian<double>(Vd, F, {}, validation_level::trust);
    const Eigen::SparseMatrix<double> M = mass_matrix<double>(Vd, F, options.mass, validation_level::trust);
    const Eigen::SparseMatrix<double> A = M + t_ * L;
    heat_.compute(A);
    const double trL = L.diagonal().sum(), trM = M.diagonal().sum();
    const double scale = trM > 0 ? trL / trM : 1.0;
    const Eigen::SparseMatrix<double> B = L + (options.regularisation * scale) * M;
    poisson_.compute(B);
    info_ = (heat_.info() == Eigen::Success && poisson_.info() == Eigen::Success && h_ > 0) ? status::ok
                                                                                              : status::numerical_issue;
    // Per-face rotated edges R_k = N x e_k (e_k opposite corner k, counter-clockwise): grad u = sum u_k R_k /
    // (2 area) and the weak divergence of a per-face X at corner k is R_k . X / 2. Keeping R_k un-divided by
    // the area is what makes slivers harmless.
    R_.resize(F.rows(), 9);
    valid_.assign(static_cast<std::size_t>(F.rows()), 0);
    for (index_t f = 0; f < F.rows(); ++f) {
      vec3<double> p[3];
      for (int k = 0; k < 3; ++k) p[k] = Vd.row(F(f, k)).transpose();
      const vec3<double> c = (p[1] - p[0]).cross(p[2] - p[0]);
      const double len = c.norm();
      if (!(len > 0) || !std::isfinite(len)) {
        R_.row(f).setZero();
        continue;
      }
      valid_[static_cast<std::size_t>(f)] = 1;
      const vec3<double> N = c / len;
      for (int k = 0; k < 3; ++k) {
        const vec3<double> r = N.cross(p[(k + 2) % 3] - p[(k + 1) % 3]);
        R_.block<1, 3>(f, 3 * k) = r.transpose();
      }
    }
    // Connected components (through faces): distances never cross between them.
    detail::disjoint_sets ds(n_);
    for (index_t f = 0; f < F.rows(); ++f) {
      ds.unite(F(f, 0), F(f, 1));
      ds.unite(F(f, 0), F(f, 2));
    }
    component_.resize(static_cast<std::size_t>(n_));
    for (index_t v = 0; v < n_; ++v) component_[static_cast<std::size_t>(v)] = ds.find(v);
  }

  /// Gathers any SurfaceMesh (coordinates converted to Scalar).
  template <SurfaceMesh Mesh>
  explicit heat_geodesic_solver(const Mesh& mesh, const heat_geodesic_options& options = {})
      : heat_geodesic_solver(to_triangle_mesh<Scalar>(mesh), options, 0) {}

  /// ok, or numerical_issue if a factorisation failed (then every query returns +inf distances).
  [[nodiscard]] status info() const noexcept { return info_; }
  /// Number of vertices (#V).
  [[nodiscard]] index_t num_vertices() const noexcept { return n_; }
  /// The heat time t actually used (time_factor * h^2).
  [[nodiscard]] double time() const noexcept { return t_; }
  /// Mean edge length h.
  [[nodiscard]] double mean_edge() const noexcept { return h_; }

  /// Approximate geodesic distance from the nearest of `sources` to every vertex.
  /// \throws invalid_input (empty) for no sources, (bad_parameter, element = the source) for a bad index.
  /// Complexity two sparse solves + O(F).
  [[nodiscard]] heat_geodesic_result<Scalar> distances(std::span<const index_t> sources) const {
    check_sources(sources, "heat_geodesic_solver::distances");
    heat_geodesic_result<Scalar> out;
    out.distance.resize(n_);
    out.info = info_;
    scratch s;
    solve_into(sources, s, out.distance.data());
    return out;
  }
  /// Single-source version of distances(sources).
  [[nodiscard]] heat_geodesic_result<Scalar> distances(index_t source) const {
    const index_t s[1] = {source};
    return distances(std::span<const index_t>(s, 1));
  }

  /// Distances from each source separately, one column per source, computed in parallel over sources.
  /// \param threads std::threads to use (0 = all cores); the result is identical for any value.
  /// \throws invalid_input (empty, bad_parameter).
  [[nodiscard]] heat_distance_table<Scalar> distance_table(std::span<const index_t> sources, int threads = 0) const {
    check_sources(sources, "heat_geodesic_solver::distance_table");
    const unsigned workers = detail::resolve_threads(threads, "heat_geodesic_solver::distance_table");
    heat_distance_table<Scalar> out;
    out.distances.resize(n_, static_cast<index_t>(sources.size()));
    out.info = info_;
    std::vector<scratch> ws(workers);
    detail::parallel_for(static_cast<index_t>(sources.size()), workers, [&](unsigned w, index_t k) {
      const index_t s[1] = {sources[static_cast<std::size_t>(k)]};
      solve_into(std::span<const index_t>(s, 1), ws[w], out.distances.col(k).data());
    });
    return out;
  }

 private:
  // Delegation target of the SurfaceMesh constructor (the int tag keeps it from competing with the public one).
  heat_geodesic_solver(const triangle_mesh<Scalar>& m, const heat_geodesic_options& options, int)
      : heat_geodesic_solver(m.V, m.F, options) {}

  struct scratch {
    Eigen::VectorXd rhs, u, b, phi;
  };

  void check_sources(std::span<const index_t> sources, const char* who) const {
    if (sources.empty()) throw invalid_input(input_error::empty, no_index, std::string(who) + ": no source vertices");
    for (const index_t s : sources) detail::geometry_check_vertex(s, n_, who, "source");
  }

  void solve_into(std::span<const index_t> sources, scratch& s, Scalar* out) const {
    constexpr Scalar inf = std::numeric_limits<Scalar>::infinity();
    if (info_ != status::ok) {
      std::fill(out, out + n_, inf);
      return;
    }
    s.rhs = Eigen::VectorXd::Zero(n_);
    for (const index_t v : sources) s.rhs[v] = 1.0;
    s.u = heat_.solve(s.rhs);
    s.b = Eigen::VectorXd::Zero(n_);
    for (index_t f = 0; f < F_.rows(); ++f) {
      if (!valid_[static_cast<std::size_t>(f)]) continue;
      const index_t a = F_(f, 0), b = F_(f, 1), c = F_(f, 2);
      const Eigen::Vector3d G = s.u[a] * R_.block<1, 3>(f, 0).transpose() + s.u[b] * R_.block<1, 3>(f, 3).transpose() +
                                s.u[c] * R_.block<1, 3>(f, 6).transpose();
      const double g = G.norm();
      if (!(g > 0) || !std::isfinite(g)) continue;  // flat heat (or underflow): no direction
      const Eigen::Vector3d X = -G / g;
      s.b[a] += 0.5 * R_.block<1, 3>(f, 0).dot(X.transpose());
      s.b[b] += 0.5 * R_.block<1, 3>(f, 3).dot(X.transpose());
      s.b[c] += 0.5 * R_.block<1, 3>(f, 6).dot(X.transpose());
    }
    s.phi = poisson_.solve(s.b);
    // Shift each component by the smallest value at its sources; components without a source are unreachable.
    std::vector<double> shift(static_cast<std::size_t>(n_), std::numeric_limits<double>::infinity());
    for (const index_t v : sources) {
      double& sh = shift[static_cast<std::size_t>(component_[static_cast<std::size_t>(v)])];
      sh = std::min(sh, s.phi[v]);
    }
    for (index_t v = 0; v < n_; ++v) {
      const double sh = shift[static_cast<std::size_t>(component_[static_cast<std::size_t>(v)])];
      if (sh == std::numeric_limits<double>::infinity()) {
        out[v] = inf;
        continue;
      }
      const double d = s.phi[v] - sh;
      // Near the sources phi can dip a little below the source value (the heat is smoothed over ~sqrt(t));
      // distances are non-negative, so clamp; a non-finite value can only come from a failed solve.
      out[v] = std::isfinite(d) ? static_cast<Scalar>(std::max(0.0, d)) : inf;
    }
    for (const index_t v : sources) out[v] = 0;
  }

  index_t n_ = 0;
  double h_ = 0, t_ = 0;
  face_matrix F_;
  Eigen::Matrix<double, Eigen::Dynamic, 9, Eigen::RowMajor> R_;  // row-major: one face = 9 contiguous doubles
  std::vector<unsigned char> valid_;
  std::vector<index_t> component_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> heat_, poisson_;
  status info_ = status::ok;
};

}  // namespace shapestruct
