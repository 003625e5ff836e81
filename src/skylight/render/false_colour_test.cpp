#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/render/false_colour.h"

namespace skylight::render {
namespace {

using Rgb8 = std::array<std::uint8_t, 3>;

constexpr Rgb8 kInvalidGrey = {40, 40, 40};

Rgb8 at(const Image8& image, int x, int y) {
  const std::uint8_t* p = image.pixel(x, y);
  return {p[0], p[1], p[2]};
}

int distance(const Rgb8& a, const Rgb8& b) {
  int d = 0;
  for (int c = 0; c < 3; ++c) d += std::abs(int{a[c]} - int{b[c]});
  return d;
}

// A luminance image whose column x holds 10^(log10 values[x]).
ImageF columns_of(const std::vector<double>& log10_values, int height) {
  ImageF image(static_cast<int>(log10_values.size()), height, 1);
  for (int y = 0; y < height; ++y)
    for (size_t x = 0; x < log10_values.size(); ++x)
      image.pixel(static_cast<int>(x), y)[0] = static_cast<float>(std::pow(10.0, log10_values[x]));
  return image;
}

TEST(FalseColour, LegendMakesOutputWiderWithSameHeight) {
  const ImageF image = columns_of({0.5, 1.5, 2.5, 3.5}, 400);
  const Image8 with = false_colour(image);
  EXPECT_GT(with.width, image.width);
  EXPECT_EQ(with.height, image.height);
  const Image8 without = false_colour(image, {.legend = false});
  EXPECT_EQ(without.width, image.width);
  EXPECT_EQ(without.height, image.height);

  // The legend panel holds the colour bar (both ends of the scale) and light text.
  FalseColourOptions options;
  std::set<Rgb8> panel;
  for (int y = 0; y < with.height; ++y)
    for (int x = image.width; x < with.width; ++x) panel.insert(at(with, x, y));
  EXPECT_TRUE(panel.count(false_colour_of(options.log10_min, options)));
  EXPECT_TRUE(panel.count(false_colour_of(options.log10_max, options)));
  EXPECT_TRUE(panel.count(Rgb8{230, 230, 230}));
}

TEST(FalseColour, SmallImagesStillGetALegend) {
  for (int height : {1, 5, 20, 63}) {
    const ImageF image = columns_of({1.0, 2.0, 3.0}, height);
    const Image8 out = false_colour(image);
    EXPECT_GE(out.width, image.width + 60) << height;
    EXPECT_EQ(out.height, height);
  }
}

TEST(FalseColour, EachDecadeHasItsOwnColour) {
  const FalseColourOptions options;  // 10^0 ... 10^6
  std::set<Rgb8> colours;
  for (double v = 0.5; v < 6.0; v += 1.0) colours.insert(false_colour_of(v, options));
  EXPECT_EQ(colours.size(), 6u);
  const Image8 map = false_colour(columns_of({0.5, 1.5, 2.5, 3.5, 4.5, 5.5}, 2), {.legend = false});
  std::set<Rgb8> in_map;
  for (int x = 0; x < map.width; ++x) in_map.insert(at(map, x, 1));
  EXPECT_EQ(in_map.size(), 6u);
}

// Channels are rounded to 8 bits, so hue ratios hold to about one unit in the smaller channel.
constexpr int kRoundingUnits = 2;
// A decade boundary must be an obvious jump (sum of |dR|+|dG|+|dB|), far above rounding noise.
constexpr int kMinBoundaryJump = 60;

TEST(FalseColour, HueIsConstantWithinADecadeAndJumpsAtBoundaries) {
  const FalseColourOptions options;
  for (int decade = 0; decade < 6; ++decade) {
    const Rgb8 dark = false_colour_of(decade + 0.05, options);
    const Rgb8 light = false_colour_of(decade + 0.95, options);
    // Same hue family: light = s * dark channel by channel for one brightness factor s > 1.
    const int top = static_cast<int>(std::max_element(light.begin(), light.end()) - light.begin());
    ASSERT_GT(dark[top], 0);
    const double s = static_cast<double>(light[top]) / dark[top];
    EXPECT_GT(s, 1.5) << decade;  // brighter at the top of the decade
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(light[c], s * dark[c], kRoundingUnits * s) << decade << " channel " << c;

    if (decade > 0) {
      const Rgb8 below = false_colour_of(decade - 0.001, options);
      const Rgb8 above = false_colour_of(decade + 0.001, options);
      EXPECT_GE(distance(below, above), kMinBoundaryJump) << decade;
    }
  }
}

TEST(FalseColour, OutOfRangeValuesClampToTheEnds) {
  const FalseColourOptions options{.log10_min = -1.0, .log10_max = 3.0};
  EXPECT_EQ(false_colour_of(-7.0, options), false_colour_of(-1.0, options));
  EXPECT_EQ(false_colour_of(-std::numeric_limits<double>::infinity(), options),
            false_colour_of(-1.0, options));
  EXPECT_EQ(false_colour_of(9.0, options), false_colour_of(3.0, options));
  EXPECT_EQ(false_colour_of(std::numeric_limits<double>::quiet_NaN(), options), kInvalidGrey);
}

TEST(FalseColour, InvalidAndMaskedPixelsAreDarkGrey) {
  ImageF image(6, 1, 1);
  image.data = {0.0f,
                -1.0f,
                std::numeric_limits<float>::quiet_NaN(),
                std::numeric_limits<float>::infinity(),
                100.0f,
                100.0f};
  const std::vector<std::uint8_t> mask = {0, 0, 0, 0, 1, 0};
  const Image8 out = false_colour(image, {.legend = false}, &mask);
  for (int x = 0; x < 5; ++x) EXPECT_EQ(at(out, x, 0), kInvalidGrey) << x;
  EXPECT_NE(at(out, 5, 0), kInvalidGrey);
}

TEST(FalseColour, ScaleFunctionAgreesWithTheMap) {
  const FalseColourOptions options{.log10_min = -2.0, .log10_max = 4.5, .legend = true};
  std::vector<double> values;
  for (double v = -3.0; v <= 5.5; v += 0.173) values.push_back(v);
  const ImageF image = columns_of(values, 3);
  const Image8 map = false_colour(image, options);
  for (size_t x = 0; x < values.size(); ++x) {
    const double v = std::log10(double{image.pixel(static_cast<int>(x), 0)[0]});
    EXPECT_EQ(at(map, static_cast<int>(x), 2), false_colour_of(v, options)) << values[x];
  }
}

TEST(FalseColour, RejectsBadInput) {
  EXPECT_THROW(false_colour(ImageF(2, 2, 3)), InvalidArgument);  // not a luminance image
  EXPECT_THROW(false_colour(ImageF(2, 2, 1), {.log10_min = 3.0, .log10_max = 3.0}),
               InvalidArgument);
  const std::vector<std::uint8_t> short_mask(3, 0);
  EXPECT_THROW(false_colour(ImageF(2, 2, 1), {}, &short_mask), InvalidArgument);
  EXPECT_THROW(false_colour_of(1.0, {.log10_min = std::nan(""), .log10_max = 1.0}),
               InvalidArgument);
}

}  // namespace
}  // namespace skylight::render
