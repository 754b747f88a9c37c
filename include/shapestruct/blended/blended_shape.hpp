// SPDX-License-Identifier: MIT
// blended_shape: everything blended intrinsic maps need from one shape, computed once and reused for every pair.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/conformal/mid_edge_flattening.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/heap_bytes.hpp"
#include "shapestruct/core/triangle_mesh.hpp"
#include "shapestruct/core/types.hpp"
#include "shapestruct/core/validate.hpp"
#include "shapestruct/geometry/closest_point_query.hpp"
#include "shapestruct/geometry/dijkstra_geodesics.hpp"
#include "shapestruct/geometry/farthest_point_sampling.hpp"
#include "shapestruct/geometry/average_geodesic_distance.hpp"
#include "shapestruct/geometry/geodesic_ball_convexity.hpp"
#include "shapestruct/geometry/mesh_measures.hpp"
#include "shapestruct/geometry/sphere_repair.hpp"

namespace shapestruct {

/// Options of the per-shape precomputation (dissertation ch. 3.3 defaults).
struct blended_shape_options {
  /// |P_even|: evenly spread (geodesic farthest-point) samples where confidence and consistency are evaluated.
  index_t num_samples = 256;
  /// Cap on the AGD-maxima feature points, strongest (highest AGD) first. The chapter reports |P| <= 10 on
  /// most shapes; the number of candidate maps grows as |P|^6.
  index_t max_features = 10;
  /// Suppression radius of the AGD maxima in units of sqrt(area); bumps narrower than this are not features.
  /// 0.15 makes a hand one feature rather than one per spread finger tip: with 0.1, SHREC'07 human 3 had three
  /// features on each hand, their near-duplicate triplet maps outweighed the true ones in S~, and 3 of the 4
  /// humans-set pairs that failed outright (3->mesh007, michael14->mesh042, mesh028->4) were lost. 0.15 against
  /// 0.1 on all five benchmark lists: better on humans, SHREC'07 and TOSCA, a little worse on SCAPE and animals
  /// (the measurements: docs/blended_maps.md).
  double feature_radius = 0.15;
  /// Least AGD persistence of a feature, in units of sqrt(area) (maximum_persistence: how far the AGD falls from
  /// the maximum before it meets higher ground). An extremity's tip stands well clear of the body; a bump on an
  /// extremity does not, however far it lies from the tip. 0 = every maximum, as in the chapter: small
  /// extremities (a fish's fins) lie as low as bumps, and every threshold measured lost on SHREC'07
  /// (docs/blended_maps.md).
  double min_feature_persistence = 0;
  /// A second feature set: the same maxima without those whose AGD persistence is below this (units of
  /// sqrt(area)). blended_matcher matches with both sets and keeps the second set's map where it distorts
  /// geodesic distances clearly less (blended_matcher_options::alternative_distortion_margin). Bumps on an
  /// extremity (a dog's eyes and mouth) give near-duplicate triplet maps that outvote the true ones in S~;
  /// without them the true group forms. Where small extremities are the features that matter (a fish's fins,
  /// a horse's ears) the full set's map is the less distorted and is kept. Only shapes that have such bumps get
  /// the second set (blended_shape::alternative). 0 = one feature set, as in the chapter (the measurements:
  /// docs/blended_maps.md).
  double alternative_feature_persistence = 0.08;
  /// Fewest feature points. A shape whose AGD has fewer maxima (SHREC'07 glasses 43-45: only the two temple tips)
  /// is completed with its most central vertex (least AGD) and then with geodesic farthest points from the
  /// features so far. With fewer than three features on a side no triplet map exists, and three give a single
  /// triplet; four give four (measured: docs/blended_maps.md). 0 = the AGD maxima alone, as in the chapter.
  /// Never more than max_features.
  index_t min_features = 4;
  /// Samples used to interpolate a per-sample quantity to a vertex (Gaussian weights, eq. 3.2's "smooth
  /// interpolation"); the Gaussian width is the sampling's covering radius.
  index_t interpolation_samples = 6;
  /// Repairs, all off by default (the matcher refuses meshes that are not closed genus-0 manifolds otherwise);
  /// blended_shape::repairs() says what they changed.
  sphere_repair_options repairs{};
  /// Geodesic radii (unit-area units) of the per-sample convexity descriptor (geodesic_ball_convexity) that
  /// blended_matcher uses to tell a blended map from its intrinsic flip; about a nose, a knee and a foot on a
  /// unit-area human. Empty = no descriptor.
  std::vector<double> convexity_radii{0.04, 0.08, 0.16};
  /// Where the flattening is cut (flattening.cut_face == no_index, automatic): the largest face, unless one of its
  /// corners lies within this geodesic distance (unit-area units) of a feature point; then the largest face
  /// around the most central vertex (least AGD). The cut's neighbourhood goes to infinity, where the flattening is
  /// resolved worst, and the triplet maps are anchored at the features: a cut at a finger tip (SHREC'07 mesh 8)
  /// folds the flattening there and made every map with that mesh fail (a cut on the torso fixes them; the
  /// measurements: docs/blended_maps.md). 0 = always the largest face.
  double cut_clearance = 0.2;
  mid_edge_flattening_options flattening{};
  int threads = 0;  ///< std::threads for the geodesic tables, 0 = all cores; results do not depend on it
};

namespace detail {

/// The automatic cut face of blended_shape (see blended_shape_options::cut_clearance): `largest` if all its
/// corners are at least `clearance` from every feature (distance_to_features: #V x #features), else the largest
/// face incident to the vertex of least AGD (ties: lowest index).
template <class Scalar>
index_t cut_face_away_from_features(const matrix_x3<Scalar>& V, const face_matrix& F, index_t largest,
                                    const matrix_x<Scalar>& distance_to_features, const vector_x<Scalar>& agd,
                                    Scalar clearance) {
  if (distance_to_features.cols() == 0 || largest == no_index) return largest;
  bool clear = true;
  for (int k = 0; k < 3; ++k) clear = clear && distance_to_features.row(F(largest, k)).minCoeff() >= clearance;
  if (clear) return largest;
  index_t center = 0;
  agd.minCoeff(&center);
  const vector_x<Scalar> area = face_areas<Scalar>(V, F, validation_level::trust);
  index_t best = largest;
  Scalar best_area = -1;
  for (index_t f = 0; f < F.rows(); ++f)
    if ((F(f, 0) == center || F(f, 1) == center || F(f, 2) == center) && area[f] > best_area) {
      best_area = area[f];
      best = f;
    }
  return best;
}

}  // namespace detail

/// Per-shape precomputation of blended intrinsic maps: the mesh scaled to unit area, its mid-edge flattening,
/// even samples with their geodesic distance table, AGD feature points, interpolation weights and a
/// closest-point structure. Build once per shape; matching one shape against many reuses it.
/// All members are read-only after construction and may be shared by concurrent matches.
template <class Scalar = double>
class blended_shape {
 public:
  blended_shape() = default;

  /// \param V (#V x 3) \param F (#F x 3) a closed, connected, genus-0 manifold (or one the enabled repairs make so)
  /// \throws invalid_input: empty / non_finite / bad_face (validate_mesh); mesh_defect_error for a surface that
  ///         is not (or that the enabled repairs do not make) a closed genus-0 manifold, for coordinates that
  ///         overflow and for zero area (repair_to_sphere); bad_parameter (options out of range).
  /// Complexity: O(S (V + E) log V / threads) for the S-sample distance table, plus one sparse factorisation.
  blended_shape(const Eigen::Ref<const matrix_x3<Scalar>>& V, const Eigen::Ref<const face_matrix>& F,
                const blended_shape_options& options = {}) {
    if (options.num_samples < 3 || options.max_features < 3 || !(options.feature_radius > 0) ||
        options.min_features < 0 || !(options.min_feature_persistence >= 0) ||
        !std::isfinite(options.min_feature_persistence) || !(options.alternative_feature_persistence >= 0) ||
        !std::isfinite(options.alternative_feature_persistence) ||
        options.interpolation_samples < 1 || !(options.cut_clearance >= 0) || !std::isfinite(options.cut_clearance))
      throw invalid_input(input_error::bad_parameter, no_index,
                          "blended_shape: need num_samples >= 3, max_features >= 3, feature_radius > 0, "
                          "min_features >= 0, finite min_feature_persistence and alternative_feature_persistence >= 0, "
                          "interpolation_samples >= 1 "
                          "and a finite cut_clearance >= 0");
    repaired_sphere<Scalar> r = repair_to_sphere<Scalar>(V, F, options.repairs, "blended_shape",
                                                               options.flattening.accept_pinched_vertices);
    triangle_mesh<Scalar> m = std::move(r.mesh);
    repairs_ = std::move(r.report);
    original_vertices_ = V.rows();
    original_of_ = std::move(r.original_vertex);
    // internal_of_[v]: the internal vertex of input vertex v, the first one standing for it (a split vertex's
    // first fan keeps the original index, so copies come later); no_index if a repair dropped it.
    internal_of_.assign(static_cast<std::size_t>(V.rows()), no_index);
    for (index_t i = static_cast<index_t>(original_of_.size()) - 1; i >= 0; --i)
      if (original_of_[static_cast<std::size_t>(i)] != no_index)
        internal_of_[static_cast<std::size_t>(original_of_[static_cast<std::size_t>(i)])] = i;
    const Scalar area = total_area<Scalar>(m.V, m.F, validation_level::trust);  // > 0: repair_to_sphere checked
    // Unit area: the chapter's sigma = 0.5 and the benchmark's error normalisation are in units of sqrt(area).
    scale_ = std::sqrt(area);
    mesh_.V = m.V / scale_;
    mesh_.F = m.F;
    geo_ = std::make_shared<dijkstra_geodesics<Scalar>>(mesh_.V, mesh_.F);
    const index_t nv = mesh_.V.rows();
    const index_t S = std::min(options.num_samples, nv);
    // FPS from the vertex farthest from vertex 0: a deterministic start that does not depend on the file's
    // first vertex being anywhere in particular.
    const vector_x<Scalar> d0 = geo_->distances_from(0);
    index_t start = 0;
    d0.maxCoeff(&start);
    const auto fps = geodesic_farthest_point_sampling(*geo_, S, start);
    samples_ = fps.indices;
    spacing_ = fps.radii.empty() ? Scalar(1) : std::max(fps.radii.back(), Scalar(1e-6));
    matrix_x<Scalar> table = geo_->distance_table(std::span<const index_t>(samples_), options.threads);
    // AGD from the same table (samples are even, so equal weights approximate the area integral).
    agd_ = table.rowwise().mean();
    auto maxima = agd_local_maxima<Scalar>(mesh_.V, mesh_.F, agd_, options.feature_radius);
    if (options.min_feature_persistence > 0) {
      const auto persistence = maximum_persistence<Scalar>(geo_->graph(), agd_, maxima);
      std::vector<index_t> kept;
      for (std::size_t i = 0; i < maxima.size(); ++i)
        if (persistence[i] >= Scalar(options.min_feature_persistence)) kept.push_back(maxima[i]);
      maxima = std::move(kept);
    }
    place_features(maxima, options);
    // Interpolation weights: the K nearest samples of every vertex, Gaussian in geodesic distance.
    const index_t K = std::min(options.interpolation_samples, S);
    interp_index_.resize(nv, K);
    interp_weight_.resize(nv, K);
    detail::parallel_for(nv, detail::resolve_threads(options.threads, "blended intrinsic maps"), [&](index_t v) {
      std::vector<index_t> order(static_cast<std::size_t>(S));
      std::iota(order.begin(), order.end(), index_t(0));
      std::partial_sort(order.begin(), order.begin() + K, order.end(),
                        [&](index_t a, index_t b) {
                          return table(v, a) < table(v, b) || (table(v, a) == table(v, b) && a < b);
                        });
      Scalar sum = 0;
      for (index_t k = 0; k < K; ++k) {
        const Scalar d = table(v, order[static_cast<std::size_t>(k)]) / spacing_;
        const Scalar w = std::exp(-Scalar(0.5) * d * d) + Scalar(1e-300);
        interp_index_(v, k) = order[static_cast<std::size_t>(k)];
        interp_weight_(v, k) = w;
        sum += w;
      }
      interp_weight_.row(v) /= sum;
    });
    cpq_ = std::make_shared<closest_point_query<Scalar>>(mesh_.V, mesh_.F);
    std::vector<Scalar> radii(options.convexity_radii.begin(), options.convexity_radii.end());
    convexity_ = geodesic_ball_convexity<Scalar>(mesh_.V, mesh_.F, table, std::span<const index_t>(samples_),
                                                 std::span<const Scalar>(radii), options.threads);
    table_ = std::make_shared<const matrix_x<Scalar>>(std::move(table));
    if (options.alternative_feature_persistence > options.min_feature_persistence && !maxima.empty()) {
      const auto persistence = maximum_persistence<Scalar>(geo_->graph(), agd_, maxima);
      std::vector<index_t> kept;
      for (std::size_t i = 0; i < maxima.size(); ++i)
        if (persistence[i] >= Scalar(options.alternative_feature_persistence)) kept.push_back(maxima[i]);
      if (kept.size() < maxima.size()) {
        // A copy shares the geodesics, the distance table and (when the cut stays) the flattening.
        auto other = std::make_shared<blended_shape>(*this);
        other->place_features(std::move(kept), options, flat_);
        if (other->features_ != features_) alternative_ = std::move(other);
      }
    }
  }

  /// The (possibly repaired) mesh scaled to unit area.
  [[nodiscard]] const triangle_mesh<Scalar>& mesh() const noexcept { return mesh_; }
  /// sqrt of the original area: multiply unit-area lengths by it to get the input's units.
  [[nodiscard]] Scalar scale() const noexcept { return scale_; }
  [[nodiscard]] const mid_edge_flattening<Scalar>& flattening() const noexcept { return *flat_; }
  [[nodiscard]] const dijkstra_geodesics<Scalar>& geodesics() const noexcept { return *geo_; }
  [[nodiscard]] const closest_point_query<Scalar>& closest_points() const noexcept { return *cpq_; }
  /// Even samples P_even (vertex ids) and the (#V x #samples) unit-area geodesic distance table.
  [[nodiscard]] const std::vector<index_t>& samples() const noexcept { return samples_; }
  [[nodiscard]] const matrix_x<Scalar>& sample_distances() const noexcept { return *table_; }
  /// Covering radius of the samples (unit-area units).
  [[nodiscard]] Scalar sample_spacing() const noexcept { return spacing_; }
  /// (#samples x #convexity radii) signed convexity of the surface around each sample (geodesic_ball_convexity).
  [[nodiscard]] const matrix_x<Scalar>& sample_convexity() const noexcept { return convexity_; }
  /// How many of features() are AGD maxima (they come first); the rest completed them to min_features.
  [[nodiscard]] index_t num_agd_maxima() const noexcept { return agd_maxima_; }
  /// AGD (#V, unit-area units, estimated from the samples) and its maxima (feature points), strongest first.
  [[nodiscard]] const vector_x<Scalar>& agd() const noexcept { return agd_; }
  [[nodiscard]] const std::vector<index_t>& features() const noexcept { return features_; }
  /// (#V x #features) distances to the feature points.
  [[nodiscard]] const matrix_x<Scalar>& feature_distances() const noexcept { return feature_table_; }
  /// The same shape with the second feature set (blended_shape_options::alternative_feature_persistence: the
  /// features without the low bumps), sharing everything else; nullptr when the shape has no such bump.
  [[nodiscard]] const blended_shape* alternative() const noexcept { return alternative_.get(); }
  /// Interpolation of per-sample values to vertex v: sum_k weight(v, k) * value[index(v, k)].
  [[nodiscard]] const Eigen::Matrix<index_t, Eigen::Dynamic, Eigen::Dynamic>& interpolation_index() const noexcept {
    return interp_index_;
  }
  [[nodiscard]] const matrix_x<Scalar>& interpolation_weight() const noexcept { return interp_weight_; }
  /// Geodesic (unit-area) distance from sample s to a surface point (barycentric blend of the corner distances).
  [[nodiscard]] Scalar sample_distance(index_t s, const surface_point<Scalar>& p) const {
    const matrix_x<Scalar>& table = *table_;
    return p.bary[0] * table(mesh_.F(p.face, 0), s) + p.bary[1] * table(mesh_.F(p.face, 1), s) +
           p.bary[2] * table(mesh_.F(p.face, 2), s);
  }
  /// Vertex numbering: the input's vertex v is internal vertex internal_vertex(v) (no_index if a repair dropped
  /// it); internal vertex i is the input's original_vertex(i) (no_index if a repair added it).
  [[nodiscard]] index_t internal_vertex(index_t v) const { return internal_of_[static_cast<std::size_t>(v)]; }
  [[nodiscard]] index_t original_vertex(index_t i) const { return original_of_[static_cast<std::size_t>(i)]; }
  [[nodiscard]] index_t original_size() const noexcept { return original_vertices_; }
  /// What the repairs enabled in blended_shape_options::repairs changed (nothing when none was enabled or needed).
  [[nodiscard]] const sphere_repair_report& repairs() const noexcept { return repairs_; }
  /// Bytes held on the heap (core/heap_bytes.hpp): what a cache of prepared shapes keeps per shape. Most of it
  /// is the sample distance table (#V x num_samples) and the flattening's split triangulation and trees.
  [[nodiscard]] std::size_t heap_bytes() const noexcept {
    return own_heap_bytes(nullptr) + (alternative_ ? sizeof(blended_shape) + alternative_->own_heap_bytes(this) : 0);
  }

 private:
  triangle_mesh<Scalar> mesh_;
  Scalar scale_ = 1;
  std::shared_ptr<const mid_edge_flattening<Scalar>> flat_ = std::make_shared<const mid_edge_flattening<Scalar>>();
  std::shared_ptr<dijkstra_geodesics<Scalar>> geo_;
  std::shared_ptr<closest_point_query<Scalar>> cpq_;
  std::vector<index_t> samples_;
  Scalar spacing_ = 1;
  std::shared_ptr<const matrix_x<Scalar>> table_ = std::make_shared<const matrix_x<Scalar>>();
  matrix_x<Scalar> convexity_;
  vector_x<Scalar> agd_;
  /// Adds the most central vertex, then geodesic farthest points, until there are `wanted` features (fewer only
  /// on a mesh with fewer vertices).
  void complete_features(std::vector<index_t>& features, index_t wanted) const {
    index_t centre = 0;
    agd_.minCoeff(&centre);
    if (std::find(features.begin(), features.end(), centre) == features.end()) features.push_back(centre);
    vector_x<Scalar> nearest = vector_x<Scalar>::Constant(mesh_.V.rows(), std::numeric_limits<Scalar>::infinity());
    typename dijkstra_geodesics<Scalar>::workspace ws;
    for (const index_t f : features) geo_->update_distances(f, nearest, ws);
    while (static_cast<index_t>(features.size()) < wanted) {
      index_t farthest = 0;
      if (!(nearest.maxCoeff(&farthest) > Scalar(0))) break;
      features.push_back(farthest);
      geo_->update_distances(farthest, nearest, ws);
    }
  }

  /// Features from the chosen AGD maxima (strongest first; completed to min_features), their distance table and
  /// the flattening, whose cut avoids them. `shared` is the flattening to keep when the automatic cut stays
  /// where it is (the alternative feature set's case).
  void place_features(std::vector<index_t> maxima, const blended_shape_options& options,
                      const std::shared_ptr<const mid_edge_flattening<Scalar>>& shared = nullptr) {
    if (static_cast<index_t>(maxima.size()) > options.max_features)
      maxima.resize(static_cast<std::size_t>(options.max_features));
    agd_maxima_ = static_cast<index_t>(maxima.size());
    const index_t wanted = std::min(options.min_features, options.max_features);
    if (agd_maxima_ < wanted) complete_features(maxima, wanted);
    features_ = std::move(maxima);
    feature_table_ = geo_->distance_table(std::span<const index_t>(features_), options.threads);
    // The flattening is built once, after the features, with its cut already chosen: the automatic cut is the
    // largest face (the flattening's own rule), moved away from the features when it is too close to one.
    mid_edge_flattening_options fo = options.flattening;
    if (fo.cut_face == no_index && options.cut_clearance > 0) {
      index_t largest = 0;
      face_areas<Scalar>(mesh_.V, mesh_.F, validation_level::trust).maxCoeff(&largest);
      fo.cut_face = detail::cut_face_away_from_features<Scalar>(mesh_.V, mesh_.F, largest, feature_table_, agd_,
                                                                Scalar(options.cut_clearance));
    }
    if (shared && fo.cut_face == cut_face_) return;
    cut_face_ = fo.cut_face;
    flat_ = std::make_shared<const mid_edge_flattening<Scalar>>(mesh_.V, mesh_.F, fo, validation_level::trust);
  }

  /// Heap bytes of the members, without those shared with `base` (the shape this one is the alternative of).
  [[nodiscard]] std::size_t own_heap_bytes(const blended_shape* base) const noexcept {
    using shapestruct::heap_bytes;
    std::size_t bytes = heap_bytes(mesh_) + heap_bytes(samples_) + heap_bytes(convexity_) + heap_bytes(agd_) +
                        heap_bytes(features_) + heap_bytes(feature_table_) + heap_bytes(interp_index_) +
                        heap_bytes(interp_weight_) + heap_bytes(internal_of_) + heap_bytes(original_of_) +
                        heap_bytes(repairs_.holes_filled);
    if (!base || flat_ != base->flat_) bytes += sizeof(*flat_) + flat_->heap_bytes();
    if (!base || table_ != base->table_) bytes += sizeof(*table_) + heap_bytes(*table_);
    if (geo_ && (!base || geo_ != base->geo_)) bytes += sizeof(*geo_) + geo_->heap_bytes();
    if (cpq_ && (!base || cpq_ != base->cpq_)) bytes += sizeof(*cpq_) + cpq_->heap_bytes();
    return bytes;
  }

  std::vector<index_t> features_;
  index_t agd_maxima_ = 0;
  index_t cut_face_ = no_index;
  std::shared_ptr<const blended_shape> alternative_;
  matrix_x<Scalar> feature_table_;
  Eigen::Matrix<index_t, Eigen::Dynamic, Eigen::Dynamic> interp_index_;
  matrix_x<Scalar> interp_weight_;
  std::vector<index_t> internal_of_, original_of_;
  index_t original_vertices_ = 0;
  sphere_repair_report repairs_;
};

/// Precomputes any SurfaceMesh (gathered into triangle_mesh<double>). \throws invalid_input as the constructor.
template <SurfaceMesh Mesh>
[[nodiscard]] blended_shape<double> make_blended_shape(const Mesh& mesh, const blended_shape_options& options = {}) {
  const auto m = to_triangle_mesh<double>(mesh);
  return blended_shape<double>(m.V, m.F, options);
}

}  // namespace shapestruct
