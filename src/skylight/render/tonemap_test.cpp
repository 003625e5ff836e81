#include "skylight/render/tonemap.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "skylight/core/error.h"
#include "support/scratch_dir.h"

namespace skylight::render {
namespace {

namespace fs = std::filesystem;
using testing_support::ScratchDir;
using testing_support::slurp;

ImageF ramp_grey(int w, int h) {
  ImageF img(w, h, 1);
  for (int i = 0; i < w * h; ++i) img.data[i] = static_cast<float>(i) - 1.0f;
  return img;
}

// A .png target gets the tone-mapped preview (the PNG writer itself is tested in io/).
TEST(ToneMap, PngTargetGetsThePreview) {
  ScratchDir dir;
  const ImageF image = ramp_grey(6, 5);
  write_image_or_preview(dir / "p.png", image, {{"Software", "skylight"}});
  int w = 0, h = 0, n = 0;
  unsigned char* pixels = stbi_load((dir / "p.png").c_str(), &w, &h, &n, 3);
  ASSERT_NE(pixels, nullptr) << stbi_failure_reason();
  const Image8 want = tonemap_preview(image);
  ASSERT_EQ(w * h * 3, static_cast<int>(want.data.size()));
  EXPECT_TRUE(std::equal(want.data.begin(), want.data.end(), pixels));
  EXPECT_EQ(pixels[0], 0);  // the ramp starts negative: black
  stbi_image_free(pixels);
  EXPECT_NE(slurp(dir / "p.png").find("Software"), std::string::npos);
  // Float formats go to the float writers unchanged.
  write_image_or_preview(dir / "p.pfm", image);
  EXPECT_EQ(io::read_image(dir / "p.pfm").data, image.data);
}

TEST(ToneMap, UniformGreyMapsToUniformValue) {
  ImageF image(7, 5, 3);
  std::fill(image.data.begin(), image.data.end(), 123.0f);
  const Image8 out = tonemap_preview(image);
  // Auto exposure puts the grey at Lk = 1, Reinhard gives 0.5, sRGB-encoded 0.7354 -> 188.
  for (auto v : out.data) EXPECT_EQ(v, 188);
}

TEST(ToneMap, MonotonicAndZeroIsBlack) {
  ImageF image(64, 1, 1);
  for (int x = 0; x < image.width; ++x)
    image.data[x] = x == 0 ? 0.0f : std::pow(10.0f, (static_cast<float>(x) - 32.0f) / 8.0f);
  const Image8 out = tonemap_preview(image, {.percentile = 0.5, .exposure = 1.0});
  EXPECT_EQ(out.pixel(0, 0)[0], 0);
  for (int x = 1; x < image.width; ++x) {
    EXPECT_GE(out.pixel(x, 0)[0], out.pixel(x - 1, 0)[0]) << x;
    EXPECT_EQ(out.pixel(x, 0)[0], out.pixel(x, 0)[1]);  // grey stays grey
  }
  EXPECT_GT(out.pixel(63, 0)[0], 250);  // far above the percentile: nearly white
}

TEST(ToneMap, InvalidValuesAreBlackAndHueIsKept) {
  ImageF image(4, 1, 3);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float values[] = {-1.0f, -2.0f, -3.0f, nan, inf, nan, 4.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f};
  std::copy(std::begin(values), std::end(values), image.data.begin());
  const Image8 out = tonemap_preview(image);
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out.pixel(x, 0)[c], 0) << x;
  EXPECT_GT(out.pixel(2, 0)[0], 0);  // pure red stays pure red
  EXPECT_EQ(out.pixel(2, 0)[1], 0);
  EXPECT_EQ(out.pixel(2, 0)[2], 0);
  EXPECT_THROW(tonemap_preview(image, {.percentile = 0.0}), InvalidArgument);
  EXPECT_THROW(tonemap_preview(image, {.exposure = -1.0}), InvalidArgument);
}

}  // namespace
}  // namespace skylight::render
