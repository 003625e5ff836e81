#include "skylight/core/robust.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "skylight/core/random.h"

namespace skylight {
namespace {

// The estimate: the mean of the drawn values.
std::vector<double> mean_of(const std::vector<double>& x, std::span<const std::size_t> idx) {
  double s = 0.0;
  for (std::size_t i : idx) s += x[i];
  return {s / static_cast<double>(idx.size())};
}

// 40 blocks of 25 values: each block a common offset +-1 (alternating) plus a small spread of
// +-0.01 within the block. Closed forms of the mean's standard deviation: drawing single values,
// sd(all values) / sqrt(1000) ~ 1 / sqrt(1000) = 0.0316; drawing whole blocks, sd(block means) /
// sqrt(40) ~ 1 / sqrt(40) = 0.158. The bootstrap's own scatter with 400 draws: ~4 % (1/sqrt(2 x
// 400)); kBootstrapTolerance is 4 of those.
constexpr double kBootstrapTolerance = 0.15;

TEST(Robust, BlockBootstrapSeesErrorsSharedWithinABlock) {
  std::vector<double> x;
  std::vector<int> block;
  for (int b = 0; b < 40; ++b)
    for (int k = 0; k < 25; ++k) {
      x.push_back((b % 2 == 0 ? 1.0 : -1.0) + 0.01 * (k % 2 == 0 ? 1.0 : -1.0));
      block.push_back(b);
    }
  std::vector<std::size_t> all(x.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  const auto fit = [&](std::span<const std::size_t> idx) { return mean_of(x, idx); };
  SplitMix64 rng(7);
  const double pixel = bootstrap_sigma(all, 400, rng, fit)[0];
  const double blocks = block_bootstrap_sigma(all, block, 400, rng, fit)[0];
  EXPECT_NEAR(pixel, 1.0 / std::sqrt(1000.0), kBootstrapTolerance / std::sqrt(1000.0));
  EXPECT_NEAR(blocks, 1.0 / std::sqrt(40.0), kBootstrapTolerance / std::sqrt(40.0));
  // One value per block: the block bootstrap is the plain one.
  std::vector<int> own(x.size());
  std::iota(own.begin(), own.end(), 0);
  EXPECT_NEAR(block_bootstrap_sigma(all, own, 400, rng, fit)[0], 1.0 / std::sqrt(1000.0),
              kBootstrapTolerance / std::sqrt(1000.0));
}

}  // namespace
}  // namespace skylight
