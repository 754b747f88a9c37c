// SPDX-License-Identifier: MIT
// zoomout_refiner: spectral upsampling of a functional map (ZoomOut, Melzi et al. 2019) as a MapRefiner.
#pragma once

#include <algorithm>
#include <cstdint>
#include <future>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/QR>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/maps/surface_map.hpp"
#include "shapestruct/spectral/laplace_beltrami_basis.hpp"

namespace shapestruct {

/// How point maps are searched in the spectral embedding.
enum class zoomout_dense_search {
  /// A point first finds the nearest target farthest-point sample, then the nearest target vertex within
  /// zoomout_options::local_radius of it (a source vertex: of the samples found by its local_seeds nearest source
  /// samples). Measured to agree with `exact` on nearly every vertex at a small fraction of its cost
  /// (docs/blended_maps.md).
  local,
  /// Every query against every target vertex: O(#queries #Vb k), the reference.
  exact,
};

/// Options of zoomout_refiner (ZoomOut, Melzi et al. 2019, with its sub-sampled iterations).
struct zoomout_options {
  index_t initial_size = 20;  ///< size of the functional map read from the input map (k0)
  index_t final_size = 100;   ///< size after upsampling: Laplace-Beltrami eigenfunctions per shape (k_max)
  index_t step = 5;           ///< eigenfunctions added per iteration
  /// The iterations alternate point maps and functional maps on this many farthest-point samples of the source
  /// (and as many target samples guide the local search); 0 = every vertex. Only the final point map is computed
  /// at every source vertex.
  index_t samples = 2000;
  zoomout_dense_search dense_search = zoomout_dense_search::local;
  /// zoomout_dense_search::local: the neighbourhood of a target sample is the target vertices within this many
  /// covering radii of the target samples; a source vertex searches those of the coarse images of its
  /// `local_seeds` nearest source samples.
  double local_radius = 3.0;
  index_t local_seeds = 3;
  /// The bases need no more than this: the Galerkin solver with one refinement step (within 0.2 % of Lanczos on
  /// SCAPE in less than half its time), and a looser tolerance than the solver's default.
  laplace_beltrami_options basis = loose_basis();

  static laplace_beltrami_options loose_basis() {
    laplace_beltrami_options o;
    o.tolerance = 1e-5;
    o.solver = laplace_beltrami_solver::galerkin;
    return o;
  }
};

/// What zoomout_refiner::refine_with_bases returns.
template <class Scalar = double>
struct zoomout_result {
  surface_map<Scalar> map;        ///< source vertex -> target vertex (as a surface point at that vertex)
  matrix_x<Scalar> functional_map;  ///< final C (k x k): Phi_a C ~ Pi Phi_b, target coefficients to source ones
  status info = status::ok;
};

/// ZoomOut: reads a small functional map C (k0 x k0) off the input map, then alternates "point map from C" and
/// "C from the point map" while the basis grows from k0 to k_max eigenfunctions. The final point map sends a
/// source vertex to the target vertex whose spectral embedding Phi_b C^T is nearest to its own Phi_a row.
/// Low frequencies keep the input map's global structure; the high ones sharpen it locally, so a map that is
/// right up to a few percent of the shape's size becomes precise, while a map that is globally wrong (a flip)
/// stays wrong. Models MapRefiner.
class zoomout_refiner {
 public:
  zoomout_refiner() = default;
  explicit zoomout_refiner(zoomout_options options) : options_(std::move(options)) {}
  [[nodiscard]] const zoomout_options& options() const noexcept { return options_; }

  /// Refines `map` (source vertices of a -> surface of b). Computes both Laplace-Beltrami bases (side by side
  /// when threads > 1), then refine_with_bases.
  /// \throws invalid_input (bad_parameter) for options out of range or a map whose size is not #Va; as
  ///         compute_laplace_beltrami_basis for bad meshes. A basis that fails to converge returns `map` as is.
  template <class Scalar>
  [[nodiscard]] surface_map<Scalar> refine(const triangle_mesh<Scalar>& a, const triangle_mesh<Scalar>& b,
                                           const surface_map<Scalar>& map, int threads) const {
    check(a, b, map);
    const index_t k = std::min<index_t>({options_.final_size, a.V.rows() - 1, b.V.rows() - 1});
    const unsigned workers = detail::resolve_threads(threads, "zoomout_refiner");
    auto basis_of = [&](const triangle_mesh<Scalar>& m) {
      return compute_laplace_beltrami_basis<Scalar>(m.V, m.F, k, options_.basis);
    };
    auto future_a = std::async(workers > 1 ? std::launch::async : std::launch::deferred, [&] { return basis_of(a); });
    const auto basis_b = basis_of(b);
    const auto basis_a = future_a.get();
    if (basis_a.info == status::numerical_issue || basis_b.info == status::numerical_issue) return map;
    return refine_with_bases(a, basis_a, b, basis_b, map, threads).map;
  }

  /// The refinement with precomputed bases (reuse them when one shape is matched against many).
  /// \throws invalid_input (bad_parameter) as refine, or (size_mismatch) for bases of the wrong size.
  template <class Scalar>
  [[nodiscard]] zoomout_result<Scalar> refine_with_bases(const triangle_mesh<Scalar>& a,
                                                         const laplace_beltrami_basis<Scalar>& basis_a,
                                                         const triangle_mesh<Scalar>& b,
                                                         const laplace_beltrami_basis<Scalar>& basis_b,
                                                         const surface_map<Scalar>& map, int threads) const {
    check(a, b, map);
    if (basis_a.vectors.rows() != a.V.rows() || basis_b.vectors.rows() != b.V.rows())
      throw invalid_input(input_error::size_mismatch, no_index,
                          "zoomout_refiner: a basis does not have one row per vertex of its mesh");
    const unsigned workers = detail::resolve_threads(threads, "zoomout_refiner");
    const index_t K = std::min<index_t>({options_.final_size, basis_a.vectors.cols(), basis_b.vectors.cols()});
    const index_t k0 = std::min(options_.initial_size, K);
    const matrix_x<Scalar>& Pa = basis_a.vectors;
    const matrix_x<Scalar>& Pb = basis_b.vectors;
    zoomout_result<Scalar> out;
    out.info = basis_a.info != status::ok ? basis_a.info : basis_b.info;

    // C0 = Phi_a^T M_a (Pi Phi_b): the target basis read at each source vertex's image (barycentric).
    matrix_x<Scalar> pulled = matrix_x<Scalar>::Zero(a.V.rows(), k0);
    vector_x<Scalar> weight = basis_a.mass;
    for (index_t v = 0; v < a.V.rows(); ++v) {
      const auto& p = map.points[static_cast<std::size_t>(v)];
      if (!p.valid()) {
        weight[v] = 0;
        continue;
      }
      for (int c = 0; c < 3; ++c) pulled.row(v) += p.bary[c] * Pb.row(b.F(p.face, c)).head(k0);
    }
    matrix_x<Scalar> C = Pa.leftCols(k0).transpose() * weight.asDiagonal() * pulled;

    // Iterations on farthest-point samples of the source. A sample's image is searched in two steps: the nearest
    // target sample in the embedding (global, so a wrong region can still move anywhere), then the nearest target
    // vertex around it (local, so the images, and the functional map fitted to them, are not quantised to the
    // target samples' spacing).
    const auto sample = [&](const triangle_mesh<Scalar>& m) {
      const index_t n = options_.samples > 0 ? std::min(options_.samples, m.V.rows()) : m.V.rows();
      if (n < m.V.rows()) return farthest_point_sampling<Scalar>(m.V, n, 0);
      farthest_point_result<Scalar> every;  // every vertex, in order: no O(#V^2) sampling for nothing
      every.indices.resize(static_cast<std::size_t>(n));
      for (index_t i = 0; i < n; ++i) every.indices[static_cast<std::size_t>(i)] = i;
      return every;
    };
    auto sampled_a = std::async(workers > 1 ? std::launch::async : std::launch::deferred, [&] { return sample(a); });
    const auto fb = sample(b);
    const auto fa = sampled_a.get();
    const bool exhaustive = options_.dense_search == zoomout_dense_search::exact || options_.samples <= 0 ||
                            fb.indices.size() >= static_cast<std::size_t>(b.V.rows());
    const auto near = exhaustive ? std::vector<std::vector<std::uint32_t>>{} : neighbourhoods(b, fb, workers);
    const row_major Sa = rows_of(Pa, fa.indices, K), Sb = rows_of(Pb, fb.indices, K);
    const row_major Pbf = Pb.leftCols(K).template cast<float>();
    const auto images = [&](const row_major& queries, index_t k, const std::vector<std::vector<index_t>>& seeds) {
      const row_major Eb = embed(Pbf, C, k, workers);
      if (exhaustive) return nearest_rows(queries.leftCols(k), Eb, workers);
      return nearest_among(queries.leftCols(k), Eb, near, seeds, workers);
    };
    const auto own_images = [&](const std::vector<index_t>& coarse) {
      std::vector<std::vector<index_t>> seeds(coarse.size());
      for (std::size_t i = 0; i < coarse.size(); ++i) seeds[i] = {coarse[i]};
      return seeds;
    };
    for (index_t k = k0; k < K;) {
      const auto coarse =
          exhaustive ? std::vector<index_t>{} : nearest_rows(Sa.leftCols(k), embed(Sb, C, k, workers), workers);
      const auto image = images(Sa, k, own_images(coarse));
      const index_t next = std::min(K, k + std::max<index_t>(options_.step, 1));
      matrix_x<Scalar> target(Sa.rows(), next);
      for (index_t i = 0; i < Sa.rows(); ++i)
        target.row(i) = Pbf.row(image[static_cast<std::size_t>(i)]).head(next).template cast<Scalar>();
      const matrix_x<Scalar> source = Sa.leftCols(next).template cast<Scalar>();
      C = source.colPivHouseholderQr().solve(target);
      k = next;
    }
    out.functional_map = C;

    // The final point map at every source vertex; locally, around the coarse images of its nearest samples.
    const row_major Qa = Pa.leftCols(K).template cast<float>();
    std::vector<std::vector<index_t>> seeds;
    if (!exhaustive) {
      const auto coarse = nearest_rows(Sa, embed(Sb, C, K, workers), workers);
      matrix_x3<Scalar> sample_points(static_cast<index_t>(fa.indices.size()), 3);
      for (std::size_t i = 0; i < fa.indices.size(); ++i) sample_points.row(static_cast<index_t>(i)) = a.V.row(fa.indices[i]);
      const knn_index<Scalar, 3> source_samples(sample_points);
      const index_t count = std::min<index_t>(options_.local_seeds, static_cast<index_t>(fa.indices.size()));
      seeds.resize(static_cast<std::size_t>(a.V.rows()));
      detail::parallel_for(a.V.rows(), workers, [&](index_t v) {
        for (index_t s : source_samples.knn(a.V.row(v).transpose(), count).indices)
          seeds[static_cast<std::size_t>(v)].push_back(coarse[static_cast<std::size_t>(s)]);
      }, index_t(256));
    }
    out.map = surface_map_at_vertices(b, images(Qa, K, seeds));
    return out;
  }

 private:
  template <class Scalar>
  void check(const triangle_mesh<Scalar>& a, const triangle_mesh<Scalar>& b, const surface_map<Scalar>& map) const {
    if (options_.initial_size < 1 || options_.final_size < options_.initial_size || options_.step < 1 ||
        options_.samples < 0 || !(options_.local_radius > 0) || options_.local_seeds < 1)
      throw invalid_input(input_error::bad_parameter, no_index,
                          "zoomout_refiner: need 1 <= initial_size <= final_size, step >= 1, samples >= 0, "
                          "local_radius > 0 and local_seeds >= 1");
    if (map.source_size() != a.V.rows())
      throw invalid_input(input_error::size_mismatch, no_index,
                          "zoomout_refiner: the map has " + std::to_string(map.source_size()) +
                              " points but the source mesh has " + std::to_string(a.V.rows()) + " vertices");
    if (a.V.rows() < 3 || b.V.rows() < 3 || b.F.rows() == 0)
      throw invalid_input(input_error::empty, no_index, "zoomout_refiner: both meshes need faces");
  }

  using row_major = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  template <class Scalar>
  static row_major rows_of(const matrix_x<Scalar>& P, const std::vector<index_t>& rows, index_t k) {
    row_major out(static_cast<Eigen::Index>(rows.size()), k);
    for (std::size_t i = 0; i < rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = P.row(rows[i]).head(k).template cast<float>();
    return out;
  }

  /// Target embedding Phi_b C^T restricted to the first k eigenfunctions, by blocks of rows on `workers` threads.
  /// Written in place (noalias), each block's product is the whole product's to the last bit, so the result does
  /// not depend on the worker count.
  template <class Scalar>
  static row_major embed(const row_major& Pb, const matrix_x<Scalar>& C, index_t k, unsigned workers) {
    const Eigen::MatrixXf Ct = C.topLeftCorner(k, k).transpose().template cast<float>();
    row_major out(Pb.rows(), k);
    constexpr index_t block = 1024;
    detail::parallel_for((Pb.rows() + block - 1) / block, workers, [&](index_t bi) {
      const index_t begin = bi * block, count = std::min(block, static_cast<index_t>(Pb.rows()) - begin);
      out.middleRows(begin, count).noalias() = Pb.middleRows(begin, count).leftCols(k) * Ct;
    });
    return out;
  }

  /// For every row of Q, the index of the nearest row of D (ties: lower index), by blocks of Q on `workers`
  /// threads: |q - d|^2 = |d|^2 - 2 q.d + const, the products as one matrix multiplication per block.
  template <class DQ>
  static std::vector<index_t> nearest_rows(const Eigen::MatrixBase<DQ>& Q, const row_major& D, unsigned workers) {
    const Eigen::VectorXf norms = D.rowwise().squaredNorm();
    std::vector<index_t> out(static_cast<std::size_t>(Q.rows()), 0);
    constexpr index_t block = 256;
    const index_t blocks = (Q.rows() + block - 1) / block;
    detail::parallel_for(blocks, workers, [&](index_t bi) {
      const index_t begin = bi * block, count = std::min(block, static_cast<index_t>(Q.rows()) - begin);
      const Eigen::MatrixXf G = D * Q.middleRows(begin, count).transpose();  // #D x count
      for (index_t j = 0; j < count; ++j) {
        index_t best = 0;
        float best_d = std::numeric_limits<float>::infinity();
        for (index_t i = 0; i < D.rows(); ++i) {
          const float d = norms[i] - 2.0f * G(i, j);
          if (d < best_d) {
            best_d = d;
            best = i;
          }
        }
        out[static_cast<std::size_t>(begin + j)] = best;
      }
    });
    return out;
  }

  /// The target vertices within options_.local_radius covering radii of each target sample (the sample first).
  template <class Scalar>
  std::vector<std::vector<std::uint32_t>> neighbourhoods(const triangle_mesh<Scalar>& b, const farthest_point_result<Scalar>& fb,
                                                         unsigned workers) const {
    const knn_index<Scalar, 3> target_vertices(b.V);
    const Scalar radius = static_cast<Scalar>(options_.local_radius) * (fb.radii.empty() ? Scalar(0) : fb.radii.back());
    std::vector<std::vector<std::uint32_t>> near(fb.indices.size());
    detail::parallel_for(static_cast<index_t>(fb.indices.size()), workers, [&](index_t j) {
      const index_t t = fb.indices[static_cast<std::size_t>(j)];
      std::vector<std::pair<std::uint32_t, Scalar>> hits;
      target_vertices.radius_into(b.V.row(t).transpose(), radius, hits);
      auto& c = near[static_cast<std::size_t>(j)];
      c.reserve(hits.size() + 1);
      c.push_back(static_cast<std::uint32_t>(t));
      for (const auto& h : hits) c.push_back(h.first);
    });
    return near;
  }

  /// For every row q of Q, the nearest row of E among the neighbourhoods of the target samples seeds[q]
  /// (ties: lower index).
  template <class DQ>
  static std::vector<index_t> nearest_among(const Eigen::MatrixBase<DQ>& Q, const row_major& E,
                                            const std::vector<std::vector<std::uint32_t>>& near,
                                            const std::vector<std::vector<index_t>>& seeds, unsigned workers) {
    const Eigen::VectorXf norms = E.rowwise().squaredNorm();
    const row_major Qr = Q;
    std::vector<index_t> out(static_cast<std::size_t>(Q.rows()), 0);
    // Neighbourhoods of nearby seeds overlap: a per-worker stamp scores each target vertex once per query.
    std::vector<std::vector<index_t>> seen(workers, std::vector<index_t>(static_cast<std::size_t>(E.rows()), no_index));
    detail::parallel_for(static_cast<index_t>(Q.rows()), workers, [&](unsigned worker, index_t q) {
      auto& stamp = seen[worker];
      index_t best = no_index;
      float best_d = std::numeric_limits<float>::infinity();
      for (index_t s : seeds[static_cast<std::size_t>(q)])
        for (std::uint32_t t : near[static_cast<std::size_t>(s)]) {
          if (stamp[t] == q) continue;
          stamp[t] = q;
          const float d = norms[t] - 2.0f * E.row(t).dot(Qr.row(q));
          if (d < best_d || (d == best_d && static_cast<index_t>(t) < best)) {
            best_d = d;
            best = static_cast<index_t>(t);
          }
        }
      out[static_cast<std::size_t>(q)] = best;
    }, index_t(256));
    return out;
  }

  zoomout_options options_{};
};

}  // namespace shapestruct
