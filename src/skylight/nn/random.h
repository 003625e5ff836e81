// The one pseudo-random generator of skylight::nn: xoshiro256** (Blackman & Vigna 2018) seeded by
// SplitMix64 (Steele, Lea & Flood 2014; core/random.h). Everything that needs randomness (weight
// initialisation, stratified jitter, example shuffling, mini-batches) draws from it, so a seed
// fixes every result on every platform: no std::*_distribution (their output differs between
// standard libraries) and no transcendental functions (uniform draws only).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

#include "skylight/core/random.h"

namespace skylight::nn {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    SplitMix64 sm(seed);
    for (auto& w : s_) w = sm.next();
  }
  // An independent generator for sub-stream `stream` (e.g. one per restart or per thread slice):
  // seeded from this generator's seed material, not from its current position.
  static Rng stream(std::uint64_t seed, std::uint64_t stream) {
    return Rng(SplitMix64(seed ^ (0xd1b54a32d192ed03ULL * (stream + 1))).next());
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  // Uniform integer in [0, n), n > 0, unbiased (rejection of the short last interval).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t threshold = (0 - n) % n;  // 2^64 mod n
    for (;;) {
      const std::uint64_t r = next();
      if (r >= threshold) return r % n;
    }
  }
  // Fisher-Yates shuffle.
  template <class T>
  void shuffle(std::span<T> v) {
    for (std::size_t i = v.size(); i > 1; --i) {
      std::swap(v[i - 1], v[below(i)]);
    }
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

}  // namespace skylight::nn
