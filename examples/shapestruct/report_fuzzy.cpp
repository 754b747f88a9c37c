// SPDX-License-Identifier: MIT
// read_fuzzy_colours: see report_fuzzy.hpp.
#include "report_fuzzy.hpp"

#include "shapestruct/detail/parallel_for.hpp"
#include "shapestruct/explore/sample_variance.hpp"
#include "shapestruct/fuzzy/fuzzy_output.hpp"

namespace shapestruct::cli {

fuzzy_colours read_fuzzy_colours(const std::filesystem::path& fuzzy_dir, int threads) {
  const fuzzy_output f = read_fuzzy_output(fuzzy_dir);
  fuzzy_colours out;
  const index_t N = f.shapes();
  sample_variance_options vo;
  vo.threads = threads;
  const Eigen::VectorXf var = sample_variance(f.fuzzy.embedding(), vo);
  out.names.resize(std::size_t(N));
  out.samples.resize(std::size_t(N));
  out.variance.resize(std::size_t(N));
  out.to_reference.resize(std::size_t(N));
  detail::parallel_for(N, detail::resolve_threads(threads, "analyze report"), [&](index_t k) {
    const auto& rec = f.records[std::size_t(k)];
    out.names[std::size_t(k)] = rec.name;
    out.samples[std::size_t(k)] = rec.samples.cast<double>();
    const index_t K = f.fuzzy.embedding().samples_of(k), o = f.fuzzy.embedding().offset(k);
    out.variance[std::size_t(k)].resize(std::size_t(K));
    for (index_t i = 0; i < K; ++i) out.variance[std::size_t(k)][std::size_t(i)] = var[o + i];
    const auto m = f.fuzzy.best_matches(k, 0);
    out.to_reference[std::size_t(k)].assign(m.begin(), m.end());
  });
  return out;
}

}  // namespace shapestruct::cli
