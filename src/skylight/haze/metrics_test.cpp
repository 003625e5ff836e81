#include "skylight/haze/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "skylight/core/error.h"

namespace skylight::haze {
namespace {

constexpr double kClosedFormTol = 1e-12;  // sums of a few hundred doubles

io::ImageF constant(int w, int h, float r, float g, float b) {
  io::ImageF im(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      im.pixel(x, y)[0] = r;
      im.pixel(x, y)[1] = g;
      im.pixel(x, y)[2] = b;
    }
  return im;
}

io::ImageF noise(int w, int h) {
  io::ImageF im(w, h, 3);
  std::uint32_t state = 12345;
  for (float& v : im.data) {
    state = state * 1664525u + 1013904223u;
    v = static_cast<float>(state >> 8) / static_cast<float>(1u << 24);
  }
  return im;
}

TEST(HazeMetrics, SsimOfIdenticalImagesIsOne) {
  const io::ImageF a = noise(24, 20);
  EXPECT_NEAR(ssim(a, a), 1.0, kClosedFormTol);
}

TEST(HazeMetrics, SsimOfConstantImagesIsTheLuminanceTerm) {
  // sigma = 0 everywhere: SSIM = (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1) (Wang et al. eq. 13),
  // C1 = (0.01 x 1)^2.
  const io::ImageF a = constant(16, 16, 0.2f, 0.5f, 0.8f), b = constant(16, 16, 0.4f, 0.5f, 0.2f);
  const double c1 = 1e-4;
  double expected = 0.0;
  const float ma[3] = {0.2f, 0.5f, 0.8f}, mb[3] = {0.4f, 0.5f, 0.2f};
  for (int c = 0; c < 3; ++c)
    expected +=
        (2.0 * ma[c] * mb[c] + c1) / (double(ma[c]) * ma[c] + double(mb[c]) * mb[c] + c1) / 3;
  EXPECT_NEAR(ssim(a, b), expected, 1e-9);  // float pixels through a filter summing to 1
}

TEST(HazeMetrics, SsimOfANegatedPatternIsNegative) {
  // y = 1 - x: equal variances, covariance -sigma^2, so the structure term is ~ -1.
  const io::ImageF a = noise(32, 32);
  io::ImageF b = a;
  for (float& v : b.data) v = 1.0f - v;
  EXPECT_LT(ssim(a, b), -0.5);
  EXPECT_THROW(ssim(a, noise(8, 8)), InvalidArgument);
  EXPECT_THROW(ssim(noise(8, 8), noise(8, 8)), InvalidArgument);  // smaller than the window
}

TEST(HazeMetrics, HsvCorrelationOfIdenticalImagesIsOne) {
  const io::ImageF a = noise(20, 10);
  EXPECT_NEAR(hsv_histogram_correlation(a, a), 1.0, kClosedFormTol);
}

TEST(HazeMetrics, HsvCorrelationHandComputed) {
  // Two bins per channel. Image 1: 4 red pixels (H 0, S 1, V 1). Image 2: 2 red + 2 black (H 0,
  // S 0, V 0). H: [4, 0] vs [4, 0] -> 1. S: [0, 4] vs [2, 2] -> constant second histogram -> 0.
  // V: [0, 4] vs [2, 2] -> 0. Mean 1/3.
  const HsvHistogramSettings two{2, 2, 2};
  io::ImageF a = constant(2, 2, 1.0f, 0.0f, 0.0f), b = a;
  b.pixel(0, 1)[0] = b.pixel(1, 1)[0] = 0.0f;
  EXPECT_NEAR(hsv_histogram_correlation(a, b, two), 1.0 / 3.0, kClosedFormTol);
  // Three pixels red, one black vs all red: S [1, 3] vs [0, 4]: deviations (-1, 1) and (-2, 2):
  // 4 / sqrt(2 x 8) = 1; same for V; H [4, 0] both -> 1. Mean 1.
  io::ImageF c = a;
  c.pixel(0, 1)[0] = 0.0f;
  EXPECT_NEAR(hsv_histogram_correlation(c, a, two), 1.0, kClosedFormTol);
  // Anti-correlated value histograms: [3, 1] vs [1, 3] -> -1 (S likewise), H 1: mean -1/3.
  io::ImageF d = constant(2, 2, 0.0f, 0.0f, 0.0f);
  d.pixel(0, 0)[0] = 1.0f;
  EXPECT_NEAR(hsv_histogram_correlation(d, c, two), -1.0 / 3.0, kClosedFormTol);
}

}  // namespace
}  // namespace skylight::haze
