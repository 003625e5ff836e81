#include "skylight/estimate/photo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "skylight/core/error.h"
#include "skylight/models/preetham.h"
#include "support/sky_photo.h"

namespace skylight::estimate {
namespace {

// float pixels -> double luminance: float round-off of the three channels.
constexpr double kFloatRelTol = 1e-6;

TEST(Photo, LuminanceIsTheModelsYThroughLinearSrgb) {
  const PreethamModel model({{50 * kDegree, 2.0}, 4.0});
  const Camera cam{Projection::fisheye, 64, 64, {}};
  const io::ImageF img = testing_support::render_photo(model, cam);
  for (int row = 0; row < 64; row += 5)
    for (int col = 0; col < 64; col += 5) {
      const auto d = cam.pixel_direction(col, row);
      if (!d) continue;
      const double y = model.tristimulus(*d).Y;
      EXPECT_NEAR(pixel_luminance(img, col, row), y, kFloatRelTol * y);
    }
  // IEC 61966-2-1: Y = 0.2126 R + 0.7152 G + 0.0722 B (4 digits as printed).
  io::ImageF g(3, 1, 3);
  g.pixel(0, 0)[0] = 1.0f;
  g.pixel(1, 0)[1] = 1.0f;
  g.pixel(2, 0)[2] = 1.0f;
  EXPECT_NEAR(pixel_luminance(g, 0, 0), 0.2126, 5e-5);
  EXPECT_NEAR(pixel_luminance(g, 1, 0), 0.7152, 5e-5);
  EXPECT_NEAR(pixel_luminance(g, 2, 0), 0.0722, 5e-5);
}

// Slow reference: the mask rule by rule, with a direction computed for every pixel.
TEST(Photo, AutomaticMaskMatchesItsRulesPixelByPixel) {
  for (const double fov_deg : {180.0, 200.0}) {
    const SunPosition sun{40 * kDegree, 300 * kDegree};
    const PreethamModel model({sun, 3.0});
    const Camera cam{
        Projection::fisheye, 120, 100, {FisheyeLens::equisolid, fov_deg * kDegree, 0.4}};
    io::ImageF img = testing_support::render_photo(model, cam);
    img.pixel(60, 50)[1] = std::numeric_limits<float>::quiet_NaN();
    img.pixel(61, 50)[0] = -1.0f;
    img.pixel(62, 50)[2] = std::numeric_limits<float>::infinity();
    const MaskSettings ms{5 * kDegree, 0.999, 8 * kDegree};
    const SkyMask m = sky_mask(img, cam, ms, sun);
    float peak = 0.0f;
    for (int row = 0; row < 100; ++row)
      for (int col = 0; col < 120; ++col) {
        const auto d = cam.pixel_direction(col, row);
        const float* p = img.pixel(col, row);
        bool finite = true;
        for (int c = 0; c < 3; ++c) finite = finite && std::isfinite(p[c]) && p[c] >= 0.0f;
        if (d && d->z > std::sin(ms.min_elevation) && finite)
          peak = std::max({peak, p[0], p[1], p[2]});
      }
    std::size_t count = 0;
    for (int row = 0; row < 100; ++row)
      for (int col = 0; col < 120; ++col) {
        const auto d = cam.pixel_direction(col, row);
        const float* p = img.pixel(col, row);
        bool ok = d && d->z > std::sin(ms.min_elevation) &&
                  angle_between(*d, sun.direction()) > ms.sun_exclusion;
        for (int c = 0; c < 3; ++c)
          ok = ok && std::isfinite(p[c]) && p[c] >= 0.0f && p[c] < 0.999f * peak;
        ok = ok && pixel_luminance(img, col, row) > 0.0;
        EXPECT_EQ(m.at(col, row), ok) << "fov " << fov_deg << " pixel " << col << "," << row;
        count += ok;
      }
    EXPECT_EQ(m.count, count);
    EXPECT_GT(count, 3000u);
  }
}

TEST(Photo, UserMaskRestrictsAndMustMatchTheImageSize) {
  const PreethamModel model({{30 * kDegree, 1.0}, 3.0});
  const Camera cam{Projection::equirect, 80, 40, {}};
  const io::ImageF img = testing_support::render_photo(model, cam);
  io::ImageF user(80, 40, 1);
  for (int row = 0; row < 40; ++row)
    for (int col = 0; col < 40; ++col) user.pixel(col, row)[0] = 1.0f;
  const SkyMask m = sky_mask(img, cam, MaskSettings{}, std::nullopt, &user);
  for (int row = 0; row < 40; ++row)
    for (int col = 0; col < 80; ++col) {
      if (col >= 40 || row >= 20) {
        EXPECT_FALSE(m.at(col, row)) << col << "," << row;
      }
    }
  EXPECT_GT(m.count, 700u);
  const io::ImageF wrong(81, 40, 1);
  try {
    sky_mask(img, cam, MaskSettings{}, std::nullopt, &wrong);
    FAIL() << "a wrong-size mask was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("81 x 40"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("80 x 40"), std::string::npos) << e.what();
  }
}

// A clipped solar disc (all channels at the exposure's maximum within kClippedDiscRadius of the
// sun, as in a photo): the centroid of the pixels it covers is within a fraction of a pixel of its
// centre, 180 deg / 200 px = 0.9 deg per fisheye pixel, 1 deg per equirect pixel.
constexpr double kClippedDiscRadius = 2.0 * kDegree;
constexpr double kSunFoundWithinRad = 0.5 * kDegree;
// Without a disc the region is the circumsolar peak of the sky, which the gradation term pulls
// towards the horizon (measured: ~2 deg at T = 2.5, theta_s = 60 deg).
constexpr double kPeakFoundWithinRad = 3.0 * kDegree;

TEST(Photo, DetectsTheSunOfARenderedSky) {
  struct Case {
    Projection projection;
    int w, h;
    SunPosition sun;
  };
  for (const Case& c : {Case{Projection::fisheye, 200, 200, {58.4 * kDegree, 180.6 * kDegree}},
                        Case{Projection::fisheye, 200, 200, {20 * kDegree, 70 * kDegree}},
                        Case{Projection::equirect, 360, 180, {45 * kDegree, 0.1 * kDegree}},
                        Case{Projection::equirect, 360, 180, {60 * kDegree, 250 * kDegree}}}) {
    const PreethamModel model({c.sun, 2.5});
    const Camera cam{c.projection, c.w, c.h, {}};
    io::ImageF img = testing_support::render_photo(model, cam);
    const SunDetection peak = detect_sun(img, cam);
    EXPECT_LT(angle_between(peak.sun.direction(), c.sun.direction()), kPeakFoundWithinRad);
    for (int row = 0; row < c.h; ++row)
      for (int col = 0; col < c.w; ++col) {
        const auto d = cam.pixel_direction(col, row);
        if (d && angle_between(*d, c.sun.direction()) < kClippedDiscRadius)
          for (int k = 0; k < 3; ++k) img.pixel(col, row)[k] = 65504.0f;
      }
    const SunDetection d = detect_sun(img, cam);
    EXPECT_LT(angle_between(d.sun.direction(), c.sun.direction()), kSunFoundWithinRad)
        << to_string(c.projection) << " sun " << rad_to_deg(c.sun.zenith) << ", "
        << rad_to_deg(c.sun.azimuth) << " found " << rad_to_deg(d.sun.zenith) << ", "
        << rad_to_deg(d.sun.azimuth);
    EXPECT_GE(d.region_pixels, 4u);
    EXPECT_EQ(d.peak_luminance,
              pixel_luminance(img, static_cast<int>(d.col), static_cast<int>(d.row)));
  }
  const Camera cam{Projection::fisheye, 8, 8, {}};
  EXPECT_THROW(detect_sun(io::ImageF(8, 8, 3), cam), InvalidArgument);
}

}  // namespace
}  // namespace skylight::estimate
