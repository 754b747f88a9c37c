// SPDX-License-Identifier: MIT
// learn_templates: the template refinement loop of dissertation 5.3.3 (fitting set, learning set, Gaussian
// re-estimation, agglomerative clustering and spawning, outlier rejection, termination), plus parallel fitting
// of a template set to a collection.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "shapestruct/core/errors.hpp"
#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/templates/part_template.hpp"
#include "shapestruct/templates/shape_samples.hpp"
#include "shapestruct/templates/template_fitter.hpp"

namespace shapestruct {

/// Options of learn_templates and fit_template_set. K_L, tau, N_iter and the 5% spawning fraction are the
/// chapter's; e_min / e_max are the chapter's thresholds re-expressed on this implementation's energy scale
/// (per-point means, distances in units of template_fit_options::distance_unit; see docs/part_templates.md).
struct template_learner_options {
  template_fit_options fit;
  int threads = 0;             ///< 0 = all cores; results do not depend on it
  index_t K_L = 50;            ///< fitting-set size: K_L best + K_L random shapes per iteration
  double e_min = 0.6;          ///< almost-certainly-good fit (learning set, and template re-estimation)
  double e_max = 1.2;          ///< learning-set threshold: energy below max(tau * best energy, e_max)
  double tau = 4;              ///< learning-set threshold factor over a template's best fit
  int N_iter = 10;             ///< maximal learning iterations
  double spawn_fraction = 0.05;  ///< clusters with more than this fraction of the learning set spawn templates
  double cluster_distance = 3;   ///< complete-linkage merge threshold, in template standard deviations (RMS z)
  double prior_weight = 2;     ///< pseudo-observations of the previous Gaussian when re-estimating
  double min_sigma = 0.01;     ///< floor of learned position / size standard deviations (canonical units)
  double min_feature_sigma = 0.1;  ///< floor of learned feature standard deviations
  std::uint64_t seed = 1;      ///< random half of the fitting set
  /// Called after each learning iteration with (iteration, #templates, learning-set size); may be empty.
  std::function<void(int, std::size_t, std::size_t)> progress;
};

/// The best template for one shape and that fit.
struct template_assignment {
  index_t template_index = no_index;
  template_fit fit;
};

/// Result of learn_templates.
struct template_learning_result {
  std::vector<part_template> templates;
  int iterations = 0;
  std::size_t learned_shapes = 0;  ///< shapes that entered a learning set
  std::size_t outliers = 0;        ///< learning-set shapes neither used for re-estimation nor for spawning
};

namespace detail {

/// Per-template running sums of the learned deformations (every learning-set shape contributes once).
struct gaussian_sums {
  double n = 0;
  std::vector<Eigen::Vector3d> sc, sc2, ss, ss2;  // per part, in box-axis coordinates
  std::vector<Eigen::VectorXd> sf, sf2;
  std::vector<double> nf;
};

inline void add_observation(gaussian_sums& g, const part_template& t, const shape_samples& s,
                            const template_fit& fit) {
  const std::size_t K = t.parts.size();
  if (g.sc.empty()) {
    g.sc.assign(K, Eigen::Vector3d::Zero());
    g.sc2 = g.ss = g.ss2 = g.sc;
    const index_t D = s.features.cols();
    g.sf.assign(K, Eigen::VectorXd::Zero(D));
    g.sf2 = g.sf;
    g.nf.assign(K, 0);
  }
  g.n += 1;
  for (std::size_t b = 0; b < K; ++b) {
    const Eigen::Vector3d c = t.parts[b].axes * fit.centers[b];
    g.sc[b] += c;
    g.sc2[b] += c.cwiseProduct(c);
    g.ss[b] += fit.sizes[b];
    g.ss2[b] += fit.sizes[b].cwiseProduct(fit.sizes[b]);
  }
  if (s.features.cols() > 0)
    for (std::size_t i = 0; i < fit.parts.size(); ++i) {
      const index_t b = fit.parts[i];
      if (b < 0 || g.sf[static_cast<std::size_t>(b)].size() != s.features.cols()) continue;
      const Eigen::VectorXd f = s.features.row(static_cast<index_t>(i)).transpose();
      g.sf[static_cast<std::size_t>(b)] += f;
      g.sf2[static_cast<std::size_t>(b)] += f.cwiseProduct(f);
      g.nf[static_cast<std::size_t>(b)] += 1;
    }
}

/// Gaussian re-estimation with `prior` pseudo-observations of the template's previous mean and variance.
inline part_template reestimate(const part_template& base, const gaussian_sums& g,
                                const template_learner_options& opt) {
  part_template t = base;
  if (g.n <= 0) return t;
  const double n = g.n, n0 = opt.prior_weight;
  for (std::size_t b = 0; b < t.parts.size(); ++b) {
    part_box& p = t.parts[b];
    const Eigen::Vector3d mc0 = p.axes * p.center;
    const Eigen::Vector3d mc = (g.sc[b] + n0 * mc0) / (n + n0);
    const Eigen::Vector3d vc =
        ((g.sc2[b] - 2 * mc.cwiseProduct(g.sc[b]) + n * mc.cwiseProduct(mc)) +
         n0 * (p.sigma_center.cwiseProduct(p.sigma_center) + (mc0 - mc).cwiseProduct(mc0 - mc))) /
        (n + n0);
    p.center = p.axes.transpose() * mc;
    p.sigma_center = vc.cwiseMax(0.0).cwiseSqrt().cwiseMax(opt.min_sigma);
    const Eigen::Vector3d ms = (g.ss[b] + n0 * p.size) / (n + n0);
    const Eigen::Vector3d vs =
        ((g.ss2[b] - 2 * ms.cwiseProduct(g.ss[b]) + n * ms.cwiseProduct(ms)) +
         n0 * (p.sigma_size.cwiseProduct(p.sigma_size) + (p.size - ms).cwiseProduct(p.size - ms))) /
        (n + n0);
    p.size = ms.cwiseMax(1e-3);
    p.sigma_size = vs.cwiseMax(0.0).cwiseSqrt().cwiseMax(opt.min_sigma);
    if (!g.sf.empty() && g.nf[b] >= 2) {
      const Eigen::VectorXd mf = g.sf[b] / g.nf[b];
      const Eigen::VectorXd vf = (g.sf2[b] / g.nf[b] - mf.cwiseProduct(mf)).cwiseMax(0.0);
      p.feature_mean = mf;
      p.feature_sigma = vf.cwiseSqrt().cwiseMax(opt.min_feature_sigma);
    }
  }
  // Parts that never received points keep no features while others have them: give them neutral ones so the
  // template stays dimensionally consistent (validate_template).
  index_t D = 0;
  for (const auto& p : t.parts) D = std::max<index_t>(D, p.feature_mean.size());
  for (auto& p : t.parts)
    if (p.feature_mean.size() != D) {
      p.feature_mean = Eigen::VectorXd::Constant(D, 0.25);
      p.feature_sigma = Eigen::VectorXd::Constant(D, 1.0);
    }
  return t;
}

/// Deformation vector of a fit in template-sigma units (for clustering shapes by how they deform t).
inline Eigen::VectorXd deformation_z(const part_template& t, const template_fit& f) {
  Eigen::VectorXd z(static_cast<index_t>(6 * t.parts.size()));
  for (std::size_t b = 0; b < t.parts.size(); ++b) {
    const auto& p = t.parts[b];
    z.segment<3>(static_cast<index_t>(6 * b)) = (p.axes * (f.centers[b] - p.center)).cwiseQuotient(p.sigma_center);
    z.segment<3>(static_cast<index_t>(6 * b + 3)) = (f.sizes[b] - p.size).cwiseQuotient(p.sigma_size);
  }
  return z;
}

}  // namespace detail

/// Fits every template to every shape (in parallel over shapes) and keeps, per shape, the template with the
/// lowest energy (ties: lower template index). Deterministic for any thread count.
/// \throws invalid_input from fit_template (bad template or samples; the message names the offending one).
/// Complexity: O(#shapes x #templates x fit).
inline std::vector<template_assignment> fit_template_set(const std::vector<part_template>& templates,
                                                         const std::vector<shape_samples>& shapes,
                                                         const template_learner_options& opt = {}) {
  if (templates.empty())
    throw invalid_input(input_error::empty, no_index, "fit_template_set: no templates");
  std::vector<template_assignment> out(shapes.size());
  detail::parallel_for(shapes.size(), detail::resolve_threads(opt.threads, "learn_templates"), [&](std::size_t i) {
    for (std::size_t t = 0; t < templates.size(); ++t) {
      auto f = fit_template(templates[t], shapes[i], opt.fit);
      if (out[i].template_index == no_index || f.energy < out[i].fit.energy) {
        out[i].template_index = static_cast<index_t>(t);
        out[i].fit = std::move(f);
      }
    }
  });
  return out;
}

/// Template refinement (5.3.3). Iteration 1 fits all shapes; later iterations re-fit a Fitting Set of the K_L
/// shapes with the lowest recent energy plus K_L random ones. Shapes of the fitting set not yet learned from,
/// with energy below e_min or below max(tau x their template's best energy, e_max), form the Learning Set.
/// Learning-set shapes with energy <= e_min re-estimate their template's Gaussians (centres, sizes, features);
/// the others are clustered per template by complete linkage on their deformations (RMS z-score distance below
/// cluster_distance); clusters larger than spawn_fraction of the learning set (and at least 2 shapes) spawn a
/// new template estimated from their fits; the remaining shapes are outliers and never learned from again.
/// Stops when the learning set is empty or after N_iter iterations. Memory: O(#shapes) small records besides
/// the samples the caller holds.
/// \throws invalid_input empty (no templates or shapes), bad_parameter (options), and fit_template's.
inline template_learning_result learn_templates(std::vector<part_template> templates,
                                                const std::vector<shape_samples>& shapes,
                                                const template_learner_options& opt = {}) {
  if (templates.empty() || shapes.empty())
    throw invalid_input(input_error::empty, no_index, "learn_templates: needs at least one template and one shape");
  if (opt.K_L < 1 || opt.N_iter < 0 || !(opt.tau > 0) || !(opt.cluster_distance > 0) || opt.prior_weight < 0)
    throw invalid_input(input_error::bad_parameter, no_index,
                        "learn_templates: K_L >= 1, N_iter >= 0, tau > 0, cluster_distance > 0, prior_weight >= 0");
  for (const auto& t : templates) validate_template(t, "learn_templates");
  const unsigned threads = detail::resolve_threads(opt.threads, "learn_templates");
  const std::size_t N = shapes.size();
  std::vector<double> energy(N, std::numeric_limits<double>::infinity());
  std::vector<index_t> best_t(N, no_index);
  std::vector<char> learned(N, 0);
  std::vector<detail::gaussian_sums> sums(templates.size());
  std::mt19937_64 rng(opt.seed);
  template_learning_result res;
  for (int iter = 0; iter < opt.N_iter; ++iter) {
    std::vector<std::size_t> fitting;
    if (iter == 0) {
      fitting.resize(N);
      std::iota(fitting.begin(), fitting.end(), std::size_t{0});
    } else {
      std::vector<std::size_t> cand;
      for (std::size_t i = 0; i < N; ++i)
        if (!learned[i]) cand.push_back(i);
      std::stable_sort(cand.begin(), cand.end(), [&](std::size_t a, std::size_t b) { return energy[a] < energy[b]; });
      const std::size_t k = std::min<std::size_t>(cand.size(), static_cast<std::size_t>(opt.K_L));
      fitting.assign(cand.begin(), cand.begin() + static_cast<std::ptrdiff_t>(k));
      std::vector<std::size_t> rest(cand.begin() + static_cast<std::ptrdiff_t>(k), cand.end());
      std::shuffle(rest.begin(), rest.end(), rng);
      rest.resize(std::min<std::size_t>(rest.size(), static_cast<std::size_t>(opt.K_L)));
      fitting.insert(fitting.end(), rest.begin(), rest.end());
      std::sort(fitting.begin(), fitting.end());
    }
    if (fitting.empty()) break;
    std::vector<template_assignment> fits(fitting.size());
    detail::parallel_for(fitting.size(), threads, [&](std::size_t k) {
      const std::size_t i = fitting[k];
      for (std::size_t t = 0; t < templates.size(); ++t) {
        auto f = fit_template(templates[t], shapes[i], opt.fit);
        if (fits[k].template_index == no_index || f.energy < fits[k].fit.energy) {
          fits[k].template_index = static_cast<index_t>(t);
          fits[k].fit = std::move(f);
        }
      }
    });
    std::vector<double> best_of(templates.size(), std::numeric_limits<double>::infinity());
    for (std::size_t k = 0; k < fitting.size(); ++k) {
      energy[fitting[k]] = fits[k].fit.energy;
      best_t[fitting[k]] = fits[k].template_index;
    }
    for (std::size_t i = 0; i < N; ++i)
      if (best_t[i] != no_index) best_of[static_cast<std::size_t>(best_t[i])] = std::min(best_of[static_cast<std::size_t>(best_t[i])], energy[i]);
    // Learning set.
    std::vector<std::size_t> learning;  // indices into fitting / fits
    for (std::size_t k = 0; k < fitting.size(); ++k) {
      const std::size_t i = fitting[k];
      const double e = energy[i];
      if (learned[i] || !std::isfinite(e)) continue;
      // 5.3.3: "less than e_min ... or less than max(e_t, e_max)". (An earlier version used min(e_t, e_max):
      // with tau x best below e_min that window is empty, so no shape could ever be a spawning candidate.)
      const double et = opt.tau * best_of[static_cast<std::size_t>(best_t[i])];
      if (e < opt.e_min || e < std::max(et, opt.e_max)) learning.push_back(k);
    }
    if (learning.empty()) break;
    res.iterations = iter + 1;
    // Re-estimation and spawning candidates per template.
    std::vector<std::vector<std::size_t>> spawn(templates.size());
    for (const std::size_t k : learning) {
      const std::size_t i = fitting[k];
      learned[i] = 1;
      ++res.learned_shapes;
      const auto t = static_cast<std::size_t>(fits[k].template_index);
      if (fits[k].fit.energy <= opt.e_min) detail::add_observation(sums[t], templates[t], shapes[i], fits[k].fit);
      else spawn[t].push_back(k);
    }
    const std::size_t n_old = templates.size();
    std::vector<part_template> updated(templates);
    for (std::size_t t = 0; t < n_old; ++t) updated[t] = detail::reestimate(templates[t], sums[t], opt);
    // Agglomerative (complete-linkage) clustering of the remaining learning-set shapes of each template.
    const double min_size = std::max(2.0, opt.spawn_fraction * static_cast<double>(learning.size()));
    for (std::size_t t = 0; t < n_old; ++t) {
      const auto& cand = spawn[t];
      if (cand.size() < 2) {
        res.outliers += cand.size();
        continue;
      }
      std::vector<Eigen::VectorXd> z;
      for (const std::size_t k : cand) z.push_back(detail::deformation_z(templates[t], fits[k].fit));
      const std::size_t m = cand.size();
      Eigen::MatrixXd D(static_cast<index_t>(m), static_cast<index_t>(m));
      for (std::size_t a = 0; a < m; ++a)
        for (std::size_t b = 0; b < m; ++b)
          D(static_cast<index_t>(a), static_cast<index_t>(b)) =
              std::sqrt((z[a] - z[b]).squaredNorm() / static_cast<double>(z[a].size()));
      std::vector<std::vector<std::size_t>> clusters;
      for (std::size_t a = 0; a < m; ++a) clusters.push_back({a});
      for (;;) {
        double best = std::numeric_limits<double>::infinity();
        std::size_t ba = 0, bb = 0;
        for (std::size_t a = 0; a < clusters.size(); ++a)
          for (std::size_t b = a + 1; b < clusters.size(); ++b) {
            double mx = 0;
            for (const auto x : clusters[a])
              for (const auto y : clusters[b]) mx = std::max(mx, D(static_cast<index_t>(x), static_cast<index_t>(y)));
            if (mx < best) {
              best = mx;
              ba = a;
              bb = b;
            }
          }
        if (!(best < opt.cluster_distance)) break;
        clusters[ba].insert(clusters[ba].end(), clusters[bb].begin(), clusters[bb].end());
        clusters.erase(clusters.begin() + static_cast<std::ptrdiff_t>(bb));
      }
      for (const auto& c : clusters) {
        if (static_cast<double>(c.size()) < min_size) {
          res.outliers += c.size();
          continue;
        }
        detail::gaussian_sums g;
        for (const auto x : c) detail::add_observation(g, templates[t], shapes[fitting[cand[x]]], fits[cand[x]].fit);
        template_learner_options spawn_opt = opt;
        spawn_opt.prior_weight = 0.5;  // a new template is mostly its cluster's statistics
        part_template nt = detail::reestimate(templates[t], g, spawn_opt);
        nt.id = templates[t].id + "+" + std::to_string(updated.size());
        updated.push_back(std::move(nt));
        sums.emplace_back(std::move(g));
      }
    }
    templates = std::move(updated);
    if (opt.progress) opt.progress(iter + 1, templates.size(), learning.size());
  }
  res.templates = std::move(templates);
  return res;
}

}  // namespace shapestruct
