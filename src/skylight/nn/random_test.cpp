#include "skylight/nn/random.h"

#include <gtest/gtest.h>

#include <vector>

namespace skylight::nn {
namespace {

TEST(Random, SplitMix64ReferenceValue) {
  // First output of the reference splitmix64.c for state 0.
  EXPECT_EQ(SplitMix64(0).next(), 0xe220a8397b1dcdafULL);
}

TEST(Random, UniformAndBelowStayInRange) {
  Rng rng(9);
  for (int i = 0; i < 10000; ++i) {
    const double u = rng.uniform();
    EXPECT_GE(u, 0.0);
    EXPECT_LT(u, 1.0);
    EXPECT_LT(rng.below(7), 7u);
  }
}

TEST(Random, StreamsAndShufflesAreReproducible) {
  std::vector<int> a = {0, 1, 2, 3, 4, 5, 6, 7}, b = a;
  Rng::stream(5, 1).shuffle(std::span<int>(a));
  Rng::stream(5, 1).shuffle(std::span<int>(b));
  EXPECT_EQ(a, b);
  EXPECT_NE(Rng::stream(5, 1).next(), Rng::stream(5, 2).next());
}

}  // namespace
}  // namespace skylight::nn
