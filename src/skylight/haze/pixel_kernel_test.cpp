#include "skylight/haze/detail/pixel_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

namespace skylight::haze::detail {
namespace {

// The SIMD path does the scalar loop's operations in its order; a compiler may still fuse a
// multiply and an add (one rounding less) in either: a few float ulps of values <= ~2, times the
// 1 / min_t = 20 amplification of remove and retarget.
constexpr double kSimdVsScalarTol = 20.0 * 8.0 * 1.2e-7;

// A Gamma-like table: decreasing from 1, per channel, `entries` long.
std::vector<float> table(std::size_t entries, float rate) {
  std::vector<float> t(3 * entries);
  for (std::size_t i = 0; i < entries; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      t[3 * i + c] = std::exp(-rate * (1.0f + 0.3f * static_cast<float>(c)) *
                              static_cast<float>(i) / static_cast<float>(entries));
  return t;
}

TEST(PixelKernel, SimdMatchesTheScalarReference) {
  const std::size_t entries = 300;
  const std::vector<float> gs = table(entries, 4.0f), gt = table(entries, 1.5f);
  // 1237 pixels: not a multiple of any vector width (the padded tail).
  const std::size_t n = 1237;
  std::vector<float> image(3 * n), depth(n), a_t(3 * n), a_s(3 * n);
  for (std::size_t i = 0; i < 3 * n; ++i) {
    image[i] = 0.05f + 0.9f * static_cast<float>((i * 53) % 97) / 96.0f;
    a_t[i] = 0.5f + 0.5f * static_cast<float>((i * 29) % 31) / 30.0f;
    a_s[i] = 0.6f + 0.4f * static_cast<float>((i * 17) % 23) / 22.0f;
  }
  const float step = 10.0f;
  for (std::size_t i = 0; i < n; ++i)  // [0, the table's end], the end itself included
    depth[i] = step * static_cast<float>(entries - 1) * static_cast<float>((i * 71) % 211) / 210.0f;
  double worst = 0.0;
  std::size_t cases = 0;
  for (int op = 0; op < 3; ++op)         // add, remove, retarget
    for (int map = 0; map < 3; ++map) {  // constants, a_t map, both maps
      PixelUniforms u;
      u.gs = op == 0 ? nullptr : gs.data();
      u.gt = op == 1 ? nullptr : gt.data();
      u.inv_step = 1.0f / step;
      u.last = static_cast<int>(entries) - 2;
      u.min_t = 0.05f;
      u.a_t = {0.7f, 0.8f, 0.9f};
      u.scale = {1.1f, 0.95f, 1.0f};
      const float* at = map > 0 ? a_t.data() : nullptr;
      const float* as = map > 1 ? a_s.data() : nullptr;
      std::vector<float> simd = image, scalar = image;
      const std::size_t low_simd = haze_pixels(u, simd.data(), depth.data(), at, as, n);
      const std::size_t low_scalar = haze_pixels_scalar(u, scalar.data(), depth.data(), at, as, n);
      EXPECT_EQ(low_simd, low_scalar) << op << " " << map;
      if (op > 0) {
        EXPECT_GT(low_scalar, 0u);  // the floor is exercised
      }
      for (std::size_t i = 0; i < 3 * n; ++i) {
        ASSERT_TRUE(std::isfinite(simd[i]));
        worst = std::max(worst, std::abs(static_cast<double>(simd[i]) - scalar[i]));
      }
      ++cases;
    }
  std::cout << "[ haze simd ] worst |simd - scalar| over " << cases << " cases: " << worst << "\n";
  EXPECT_LE(worst, kSimdVsScalarTol);
}

}  // namespace
}  // namespace skylight::haze::detail
