// SPDX-License-Identifier: MIT
// shape_rng: the platform-independent random stream behind every synthetic shape (one stream per shape).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <string_view>

namespace shapestruct {

/// A seeded std::mt19937_64 with its own uniform / integer / bernoulli draws.
///
/// Why not std::uniform_real_distribution: the standard fixes the engine's output sequence but not the
/// distributions' algorithms, so libstdc++ and libc++ may give different shapes for the same seed. The draws
/// here are written out so that shape i of a collection is the same on every platform.
///
/// The stream of shape i is derived from (kind, seed, i) only, so any subset of a collection can be
/// regenerated without generating the shapes before it.
class shape_rng {
 public:
  /// Stream for shape `index` of the collection (`kind`, `seed`); `stream` separates independent aspects of
  /// one shape (e.g. body parameters vs triangulation), so changing one does not shift the other.
  shape_rng(std::string_view kind, std::uint64_t seed, std::uint64_t index, std::uint64_t stream = 0)
      : engine_(mix(mix(mix(hash(kind) ^ seed) ^ index) + 0x632be59bd9b4e019ULL * (stream + 1))) {}

  /// Uniform in [0, 1): the top 53 bits of one engine draw.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [lo, hi] (inclusive); the modulo bias is below 2^-40 for the small ranges used here.
  int integer(int lo, int hi) {
    const auto span = static_cast<std::uint64_t>(hi - lo + 1);
    return lo + static_cast<int>(engine_() % span);
  }
  /// True with probability p.
  bool chance(double p) { return uniform() < p; }
  /// Raw 64-bit draw.
  std::uint64_t bits() { return engine_(); }

  /// SplitMix64 finaliser: spreads nearby seeds (0, 1, 2, ...) over the whole state space.
  static constexpr std::uint64_t mix(std::uint64_t z) noexcept {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// FNV-1a of a kind name, so "chairs" and "tables" with the same seed give unrelated streams.
  static constexpr std::uint64_t hash(std::string_view s) noexcept {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (const char c : s) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
    return h;
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace shapestruct
