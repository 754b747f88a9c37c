// SPDX-License-Identifier: MIT
// Static tests of the policy concepts: CorrespondenceMap, MatchResult, PairwiseMatcher, AlignmentScore,
// LinearOperator (Spectra's operators are models unchanged), EmbeddingSolver and EnergyTerm.
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Spectra/MatOp/DenseSymMatProd.h>
#include <Spectra/MatOp/SparseSymMatProd.h>

#include "shapestruct/core/concepts.hpp"
#include "shapestruct/core/triangle_mesh.hpp"

namespace ss = shapestruct;

namespace mocks {
struct vertex_map {
  using scalar_type = double;
  std::vector<ss::index_t> target;
  ss::index_t source_size() const { return ss::index_t(target.size()); }
  ss::index_t target_vertex(ss::index_t i) const { return target[std::size_t(i)]; }
};
struct map_without_scalar {
  ss::index_t source_size() const { return 0; }
  ss::index_t target_vertex(ss::index_t) const { return 0; }
};
struct map_without_size {
  using scalar_type = double;
  ss::index_t target_vertex(ss::index_t) const { return 0; }
};
struct map_without_lookup {
  using scalar_type = double;
  ss::index_t source_size() const { return 0; }
};
struct match_result {
  vertex_map map;
  ss::status info = ss::status::ok;
};
struct result_without_status {
  vertex_map map;
};
struct matcher {
  template <class A, class B>
  match_result match(const A&, const B&) { return {}; }
};
struct matcher_returning_map {
  template <class A, class B>
  vertex_map match(const A&, const B&) { return {}; }
};
struct score {
  using scalar_type = double;
  template <class Map, class A, class B>
  std::optional<double> operator()(const Map&, const A&, const B&) const { return 0.0; }
};
struct score_without_scalar {
  template <class Map, class A, class B>
  std::optional<double> operator()(const Map&, const A&, const B&) const { return 0.0; }
};
struct op {
  using Scalar = double;
  ss::index_t rows() const { return 1; }
  ss::index_t cols() const { return 1; }
  void perform_op(const double* x, double* y) const { *y = *x; }
};
struct op_without_product {
  using Scalar = double;
  ss::index_t rows() const { return 1; }
  ss::index_t cols() const { return 1; }
};
struct eigen_result {
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  ss::status info = ss::status::ok;
};
struct solver {
  template <class Op>
  eigen_result solve(const Op&, ss::index_t) { return {}; }
};
struct state {
  Eigen::VectorXd x;
};
struct energy {
  using scalar_type = double;
  double value(const state& s) const { return s.x.squaredNorm(); }
  void accumulate_gradient(const state& s, Eigen::VectorXd& g) const { g += 2 * s.x; }
};
struct energy_without_gradient {
  using scalar_type = double;
  double value(const state&) const { return 0; }
};
struct energy_without_value {
  using scalar_type = double;
};
}  // namespace mocks

using mesh = ss::triangle_mesh<double>;

static_assert(ss::CorrespondenceMap<mocks::vertex_map>);
static_assert(!ss::CorrespondenceMap<mocks::map_without_scalar>);
static_assert(!ss::CorrespondenceMap<mocks::map_without_size>);
static_assert(!ss::CorrespondenceMap<mocks::map_without_lookup>);

static_assert(ss::MatchResult<mocks::match_result>);
static_assert(!ss::MatchResult<mocks::result_without_status>);

static_assert(ss::PairwiseMatcher<mocks::matcher, mesh, mesh>);
static_assert(!ss::PairwiseMatcher<mocks::matcher_returning_map, mesh, mesh>);
static_assert(!ss::PairwiseMatcher<mocks::matcher, mesh, int>);

static_assert(ss::AlignmentScore<mocks::score, mocks::vertex_map, mesh, mesh>);
static_assert(!ss::AlignmentScore<mocks::score_without_scalar, mocks::vertex_map, mesh, mesh>);
static_assert(!ss::AlignmentScore<mocks::score, mocks::map_without_lookup, mesh, mesh>);

static_assert(ss::LinearOperator<mocks::op>);
static_assert(ss::LinearOperator<Spectra::DenseSymMatProd<double>>);
static_assert(ss::LinearOperator<Spectra::SparseSymMatProd<double>>);
static_assert(!ss::LinearOperator<mocks::op_without_product>);

static_assert(ss::EmbeddingSolver<mocks::solver, mocks::op>);
static_assert(!ss::EmbeddingSolver<mocks::solver, mocks::op_without_product>);

static_assert(ss::EnergyTerm<mocks::energy, mocks::state>);
static_assert(ss::DifferentiableEnergyTerm<mocks::energy, mocks::state>);
static_assert(ss::EnergyTerm<mocks::energy_without_gradient, mocks::state>);
static_assert(!ss::DifferentiableEnergyTerm<mocks::energy_without_gradient, mocks::state>);
static_assert(!ss::EnergyTerm<mocks::energy_without_value, mocks::state>);
