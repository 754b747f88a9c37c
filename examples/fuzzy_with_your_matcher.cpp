// SPDX-License-Identifier: MIT
// Fuzzy correspondences with your own pairwise matcher: any PairwiseMatcher (a functional-map or learned
// matcher, say) and its AlignmentScore plug into compute_fuzzy_correspondences through matcher_aligner.
//
//   example_fuzzy_with_your_matcher [N]     (N generated chairs, default 24)
//
// The matcher here is deliberately simple (each vertex goes to the nearest vertex of the other shape after both
// are centred and scaled to unit RMS radius; its score is the mean distance of that match), so that the example
// shows the plumbing, not a matcher: the collection makes its per-pair guesses consistent.
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/collection/make_shape_record.hpp"
#include "shapestruct/collection/spherical_harmonic_descriptor.hpp"
#include "shapestruct/fuzzy/fuzzy_collection.hpp"
#include "shapestruct/fuzzy/matcher_aligner.hpp"
#include "shapestruct/generate/assembly_generator.hpp"
#include "shapestruct/knn/knn_index.hpp"
#include "shapestruct/maps/vertex_map.hpp"

namespace ss = shapestruct;

/// Your matcher: match(a, b) returns something with .map (a CorrespondenceMap of a's vertices) and .info.
struct normalised_nearest_matcher {
  struct result {
    ss::vertex_map<double> map;
    ss::status info = ss::status::ok;
  };
  static Eigen::Matrix<double, Eigen::Dynamic, 3> normalised(const ss::triangle_mesh<double>& m) {
    Eigen::Matrix<double, Eigen::Dynamic, 3> V = m.V.rowwise() - m.V.colwise().mean();
    return V / std::sqrt(V.rowwise().squaredNorm().mean());
  }
  [[nodiscard]] result match(const ss::triangle_mesh<double>& a, const ss::triangle_mesh<double>& b) const {
    const auto A = normalised(a), B = normalised(b);
    const ss::knn_index<double, 3> index(B);
    result r;
    r.map.targets.resize(static_cast<std::size_t>(A.rows()));
    for (ss::index_t v = 0; v < A.rows(); ++v) r.map.targets[std::size_t(v)] = index.nearest(A.row(v).transpose()).index;
    return r;
  }
};

/// Your score: lower is better; an empty optional would reject the map (and drop that edge of the graph).
struct mean_match_distance {
  using scalar_type = double;
  [[nodiscard]] std::optional<double> operator()(const ss::vertex_map<double>& m, const ss::triangle_mesh<double>& a,
                                                 const ss::triangle_mesh<double>& b) const {
    const auto A = normalised_nearest_matcher::normalised(a), B = normalised_nearest_matcher::normalised(b);
    double sum = 0;
    for (ss::index_t v = 0; v < m.source_size(); ++v) sum += (A.row(v) - B.row(m.target_vertex(v))).norm();
    return sum / double(m.source_size());
  }
};

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::max(3, std::atoi(argv[1])) : 24;
  const ss::assembly_generator<double> generator(ss::assembly_kind::chair, 11);
  std::vector<ss::triangle_mesh<double>> meshes;
  std::vector<ss::shape_record> records;
  const ss::spherical_harmonic_descriptor describe;
  for (int i = 0; i < n; ++i) {
    meshes.push_back(generator.generate(std::uint64_t(i)).mesh);
    records.push_back(ss::make_shape_record(meshes.back(), "chair" + std::to_string(i), describe,
                                            {.samples = 64, .metric = ss::sample_metric::euclidean}));
  }
  const ss::matcher_aligner aligner(records, [&](ss::index_t k) { return meshes[std::size_t(k)]; },
                                    normalised_nearest_matcher{}, mean_match_distance{});
  ss::fuzzy_collection_options options;
  options.embedding.dimensions = 64;
  const auto result = ss::compute_fuzzy_correspondences(records, aligner, options);
  std::printf("%d chairs: %zu of %d pairs matched, %zu rounds of graph optimisation%s\n", n, result.pairs_aligned,
              n * (n - 1) / 2, result.log.size() - 1, result.converged ? " (converged)" : "");
  // Where does the first sample of chair 0 go on every other chair?
  for (ss::index_t l = 1; l < std::min<ss::index_t>(n, 6); ++l) {
    const ss::index_t q = result.fuzzy.best_match(result.fuzzy.point(0, 0), l);
    std::printf("  chair0 sample 0 (%.2f %.2f %.2f) -> chair%ld sample %ld (%.2f %.2f %.2f)\n", records[0].samples(0, 0),
                records[0].samples(0, 1), records[0].samples(0, 2), long(l), long(q), records[std::size_t(l)].samples(q, 0),
                records[std::size_t(l)].samples(q, 1), records[std::size_t(l)].samples(q, 2));
  }
  return 0;
}
