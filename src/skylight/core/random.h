// SplitMix64 (Steele, Lea & Flood 2014): the project's one small seeded generator. Its sequence is
// fixed by the seed on every platform (std::*_distribution is not), so a seed fixes every sampled
// result: estimation's view samples, RANSAC and bootstrap (core/robust.h), the synthetic scans
// (analysis/scan_models.cpp), and the seeding of the network trainers' xoshiro256** (nn/random.h).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace skylight {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1): the top 53 bits as a double.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform in [-1, 1).
  double symmetric() { return 2.0 * uniform() - 1.0; }
  // Uniform integer in [0, n), n >= 1: uniform() scaled by n (bias below 2^-53 n, negligible for
  // the index ranges drawn here).
  std::size_t below(std::size_t n) {
    return std::min(n - 1, static_cast<std::size_t>(uniform() * static_cast<double>(n)));
  }

 private:
  std::uint64_t state_;
};

}  // namespace skylight
