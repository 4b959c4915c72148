#pragma once
#include <cmath>
#include <cstdint>

namespace semantic_edge_vo {
namespace synthetic {

/// SplitMix64 finaliser: the hash behind every random choice of the generator. Unlike the standard
/// library's distributions it gives the same numbers on every platform, so a seed names one world.
inline std::uint64_t mix64(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// Hash of a seed and a key (a chunk index, a frame number, a salt naming the purpose).
inline std::uint64_t hashCombine(std::uint64_t seed, std::uint64_t key) {
  return mix64(seed * 0x9e3779b97f4a7c15ULL + mix64(key + 0x632be59bd9b4e019ULL));
}

/// A small portable random number generator (SplitMix64).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() { return mix64(state_ += 0x9e3779b97f4a7c15ULL); }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [low, high).
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  /// Uniform integer in [0, n), n > 0.
  int index(int n) { return static_cast<int>(uniform() * n); }
  /// True with probability p.
  bool chance(double p) { return uniform() < p; }
  /// Standard normal (Box-Muller).
  double normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  std::uint64_t state_;
};

}  // namespace synthetic
}  // namespace semantic_edge_vo
