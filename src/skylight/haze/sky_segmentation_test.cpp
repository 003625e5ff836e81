#include "skylight/haze/sky_segmentation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "support/skyline_scene.h"

namespace skylight::haze {
namespace {

using testing_support::kSceneTurbidity;
using testing_support::render_skyline_scene;
using testing_support::ScenePhoto;

// The watershed mask against the scene's sky (measured: IoU 0.9978 equirect 360 x 180, 0.9973
// fisheye 256 x 256; the misses are mixed pixels on the skyline, a third to a half sky).
constexpr double kMaskIoUFloor = 0.99;
// The scene's sky follows eq. 13's gradation exactly, so eq. 12 from any sky pixel recovers the
// horizon's airlight; the brightest 1 % of pixels with 1 % noise are biased up by up to the noise
// (measured 0.85 %).
constexpr double kWatershedAirlightRelTol = 0.02;
// The fixed band's brightest pixels are the snow field (measured 134 % off): the watershed region
// must do at least this many times better.
constexpr double kBandOverWatershed = 10.0;
constexpr double kSegmentationClosedFormRelTol = 1e-12;

double iou(const estimate::SkyMask& a, const estimate::SkyMask& b) {
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i < a.sky.size(); ++i) {
    both += a.sky[i] && b.sky[i] ? 1 : 0;
    either += a.sky[i] || b.sky[i] ? 1 : 0;
  }
  return static_cast<double>(both) / static_cast<double>(either);
}

// The horizon's airlight of the scene: eq. 12 at theta = pi/2 is the clear sky there.
Rgb3 true_airlight() {
  const auto a = testing_support::skyline_scene_horizon();
  return {a[0], a[1], a[2]};
}

double relative_error(const Rgb3& a, const Rgb3& truth) {
  double worst = 0.0;
  for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[c] - truth[c]) / truth[c]);
  return worst;
}

HorizonSettings band_region() {
  HorizonSettings h;
  h.region = HorizonRegion::band;
  return h;
}

const Camera kEquirect{Projection::equirect, 360, 180, {}};
const Camera kFisheye{Projection::fisheye, 256, 256,
                      FisheyeLayout{FisheyeLens::equidistant, kPi, 0.0}};

TEST(SkySegmentation, WatershedMaskMatchesTheSceneSky) {
  for (const auto& entry : {std::pair{"equirect", kEquirect}, {"fisheye", kFisheye}}) {
    // Named references, not structured bindings: the lambda below captures the camera, which
    // clang 14 (the sanitizer and fuzz builds' compiler) does not allow for a binding.
    const char* const name = entry.first;
    const Camera& cam = entry.second;
    const ScenePhoto p = render_skyline_scene(cam);
    const estimate::SkyMask mask = segment_sky(p.image, cam);
    const double score = iou(mask, p.truth);
    std::cout << "[ sky mask ] " << name << " " << cam.width << "x" << cam.height
              << ": IoU = " << score << " (" << mask.count << " sky pixels, truth " << p.truth.count
              << ")\n";
    EXPECT_GE(score, kMaskIoUFloor) << name;
    // The sun, the clouds and the snow field are where the scene says.
    const auto at = [&](Vec3 d) {
      const auto px = cam.pixel(d);
      return mask.at(static_cast<int>((*px)[0]), static_cast<int>((*px)[1]));
    };
    EXPECT_TRUE(at(direction_from_angles(kPi / 2 - 35 * kDegree, 1.5))) << name << ": the sun";
    EXPECT_TRUE(at(direction_from_angles(kPi / 2 - 60 * kDegree, -2.0))) << name << ": a cloud";
    EXPECT_FALSE(at(direction_from_angles(kPi / 2 - 3 * kDegree, 2.2))) << name << ": the snow";
    EXPECT_FALSE(at(direction_from_angles(kPi / 2 - 20 * kDegree, 0.7))) << name << ": building";
  }
}

TEST(SkySegmentation, WatershedHorizonRegionBeatsTheFixedBand) {
  const ScenePhoto p = render_skyline_scene(kEquirect);
  const Rgb3 truth = true_airlight();
  const PhotoAirlight band =
      photo_airlight(p.image, kEquirect, kSceneTurbidity, kPi / 2, band_region());
  const PhotoAirlight shed =
      photo_airlight(p.image, kEquirect, kSceneTurbidity, kPi / 2, HorizonSettings());
  const double band_error = relative_error(band.airlight, truth);
  const double shed_error = relative_error(shed.airlight, truth);
  std::cout << "[ airlight ] relative error: fixed band " << band_error << " (theta' "
            << rad_to_deg(band.theta_prime) << " deg), watershed " << shed_error << " (theta' "
            << rad_to_deg(shed.theta_prime) << " deg)\n";
  EXPECT_LE(shed_error, kWatershedAirlightRelTol);
  EXPECT_GT(band_error, kBandOverWatershed * shed_error);
  // The true mask gives the same region.
  HorizonSettings given;
  given.mask = &p.truth;
  EXPECT_LE(
      relative_error(photo_airlight(p.image, kEquirect, kSceneTurbidity, kPi / 2, given).airlight,
                     truth),
      kWatershedAirlightRelTol);
}

TEST(SkySegmentation, HorizonRegionIsTheBandOverTheLowestSkyPixel) {
  // An equirect mask whose sky starts at row 20 in columns < 180 and at row 60 elsewhere: the
  // region holds, per azimuth, the rows within 9.5 deg (1 deg a row) above the lowest sky row.
  estimate::SkyMask m;
  m.width = 360;
  m.height = 180;
  m.sky.assign(360 * 180, 0);
  for (int y = 0; y < 90; ++y)
    for (int x = 0; x < 360; ++x)
      if (y <= (x < 180 ? 20 : 60)) m.sky[static_cast<std::size_t>(y * 360 + x)] = 1;
  const std::vector<std::uint8_t> r = horizon_region(m, kEquirect, 9.5 * kDegree);
  for (int x = 0; x < 360; x += 7)
    for (int y = 0; y < 90; ++y) {
      const int low = x < 180 ? 20 : 60;
      EXPECT_EQ(r[static_cast<std::size_t>(y * 360 + x)] != 0, y <= low && y > low - 10)
          << x << "," << y;
    }
}

TEST(SkySegmentation, MaskImageRoundTripAndErrors) {
  const ScenePhoto p = render_skyline_scene(kFisheye);
  const io::Image8 png = mask_image(p.truth);
  io::ImageF back(png.width, png.height, 1);
  for (std::size_t i = 0; i < back.data.size(); ++i) back.data[i] = png.data[3 * i];
  const estimate::SkyMask m = mask_from_image(back, kFisheye);
  EXPECT_EQ(m.sky, p.truth.sky);
  EXPECT_EQ(m.count, p.truth.count);
  EXPECT_THROW(mask_from_image(io::ImageF(8, 8, 1), kFisheye), InvalidArgument);
  // A photo with nothing smooth near the zenith seeds no sky (random pixels of 1 and 0.1; a
  // checkerboard would not do: Sobel cancels on a period of 2).
  io::ImageF rough(64, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c)
        rough.pixel(x, y)[c] = testing_support::scene_noise(x, y) > 0.0 ? 1.0f : 0.1f;
  const Camera eq{Projection::equirect, 64, 32, {}};
  EXPECT_THROW(segment_sky(rough, eq), InvalidArgument);
  SegmentationSettings bad;
  bad.ground_texture = bad.sky_seed_texture / 2;
  EXPECT_THROW(validate(bad), InvalidArgument);
  // The band option is photo_airlight's own band.
  const PhotoAirlight a =
      photo_airlight(p.image, kFisheye, kSceneTurbidity, kPi / 2, band_region());
  const PhotoAirlight b = photo_airlight(p.image, kFisheye, kSceneTurbidity, kPi / 2);
  EXPECT_NEAR(a.airlight[1], b.airlight[1], kSegmentationClosedFormRelTol * b.airlight[1]);
}

}  // namespace
}  // namespace skylight::haze
