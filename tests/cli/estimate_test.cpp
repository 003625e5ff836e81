// End-to-end tests of `skylight estimate`: skies rendered by `skylight render` read back.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "skylight/estimate/photo.h"
#include "skylight/io/image.h"
#include "support/cli_run.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;

// render's float batch path is within 2e-5 relative of the model (batch_test.cpp) and the EXR
// stores float: the fitted T moves by well under 1e-3.
constexpr double kRoundTripTurbidityTol = 1e-3;
// The sun found in the image (centroid of the peak region, 0.9 deg pixels at 200 px): its error
// moves T by a few hundredths.
constexpr double kAutoSunTurbidityTol = 0.05;
constexpr double kAutoSunDegTol = 1.0;

const std::string kSun = "--sun-zenith 58.4 --sun-azimuth -179.4";

TEST_F(Cli, EstimateReadsBackARenderedFisheye) {
  for (const std::string lens : {"--lens equidistant", "--lens equisolid --north-angle 30"}) {
    const fs::path exr = dir_ / "sky.exr";
    auto r = run("render --model preetham --turbidity 4 " + kSun + " --projection fisheye " + lens +
                 " --width 200 --height 200 -o '" + exr.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    r = run("estimate --image '" + exr.string() + "' " + lens + " " + kSun + " --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["model"], "preetham");
    EXPECT_NEAR(j["turbidity"].get<double>(), 4.0, kRoundTripTurbidityTol) << lens;
    EXPECT_LT(j["turbidity_sigma"].get<double>(), kRoundTripTurbidityTol);
    EXPECT_DOUBLE_EQ(j["inlier_fraction"].get<double>(), 1.0);
    EXPECT_LT(j["residual"].get<double>(), 1e-4);
    EXPECT_DOUBLE_EQ(j["sun_zenith_deg"].get<double>(), 58.4);
    EXPECT_NEAR(j["sun_azimuth_deg"].get<double>(), 180.6, 1e-9);
    EXPECT_EQ(j["sun_source"], "given");
    EXPECT_EQ(j["samples"], estimate::kPhotoSamples);  // of 31 000 sky pixels
  }
  // A small photo has fewer sky pixels than the default samples: each is used once.
  const fs::path small = dir_ / "small.exr";
  auto r = run("render --model preetham --turbidity 4 " + kSun +
               " --projection fisheye --width 60 --height 60 -o '" + small.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("estimate --image '" + small.string() + "' " + kSun + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["sky_pixels"].get<int>(), estimate::kPhotoSamples);
  EXPECT_EQ(j["samples"], j["sky_pixels"]);
  EXPECT_NEAR(j["turbidity"].get<double>(), 4.0, kRoundTripTurbidityTol);
}

TEST_F(Cli, EstimateFindsTheSunOrTakesItFromTheTime) {
  const fs::path exr = dir_ / "sky.exr";
  // The SPA's worked example (Reda & Andreas 2004, Table A5.1 inputs).
  const std::string when =
      "--time 2003-10-17T12:30:30-07:00 --lat 39.742476 --lon -105.1786 --elevation 1830.14 "
      "--pressure 820 --temperature 11 --delta-t 67";
  auto r =
      run("render --model preetham --turbidity 3 " + when +
          " --projection fisheye --include-sun --width 200 --height 200 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("estimate --image '" + exr.string() + "' " + when + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["sun_source"], "time");
  EXPECT_NEAR(j["turbidity"].get<double>(), 3.0, kRoundTripTurbidityTol);
  const double zenith = j["sun_zenith_deg"], azimuth = j["sun_azimuth_deg"];
  // Its published topocentric zenith and azimuth: 50.111622 deg, 194.340241 deg.
  EXPECT_NEAR(zenith, 50.111622, 1e-5);
  EXPECT_NEAR(azimuth, 194.340241, 1e-5);
  r = run("estimate --image '" + exr.string() + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["sun_source"], "image");
  EXPECT_NEAR(j["sun_zenith_deg"].get<double>(), zenith, kAutoSunDegTol);
  EXPECT_NEAR(j["sun_azimuth_deg"].get<double>(), azimuth, kAutoSunDegTol);
  EXPECT_NEAR(j["turbidity"].get<double>(), 3.0, kAutoSunTurbidityTol);
  // Labelled lines without --json.
  r = run("estimate --image '" + exr.string() + "' " + when);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("turbidity        3.00"), std::string::npos) << r.out;
}

// A photo with its capture's EXIF (tests/data/exif/capture.jpg: 2024-06-21 15:00:00 +02:00 at
// 48 deg 8' N, 11 deg 34' 30" E, 520 m) and a calibration file instead of the layout flags: the
// sun is the SPA's for the EXIF time and GPS place, and the fit recovers the rendered sky.
TEST_F(Cli, EstimateTakesTheSunFromExifAndTheLayoutFromACalibration) {
  const std::string exif = std::string(SKYLIGHT_SOURCE_DIR) + "/tests/data/exif/capture.jpg";
  const std::string when =
      "--time 2024-06-21T15:00:00+02:00 --lat 48.133333333333333 --lon 11.575 --elevation 520";
  const fs::path exr = dir_ / "sky.exr", cal = dir_ / "camera.json";
  auto r = run("render --model preetham --turbidity 4 " + when +
               " --projection fisheye --lens equisolid --north-angle 30 --width 200 --height 200 "
               "-o '" +
               exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ofstream(cal) << R"({"projection": "fisheye", "lens": "equisolid", "north_angle_deg": 30,
                           "radius_px": 100, "image_size": [200, 200]})";
  r = run("estimate --image '" + exr.string() + "' " + when + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto by_time = nlohmann::json::parse(r.out);
  const std::string photo = "estimate --image '" + exr.string() + "' --calibration '" +
                            cal.string() + "' --exif '" + exif + "'";
  r = run(photo + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["sun_source"], "exif");
  EXPECT_DOUBLE_EQ(j["sun_zenith_deg"].get<double>(), by_time["sun_zenith_deg"].get<double>());
  EXPECT_DOUBLE_EQ(j["sun_azimuth_deg"].get<double>(), by_time["sun_azimuth_deg"].get<double>());
  EXPECT_NEAR(j["turbidity"].get<double>(), 4.0, kRoundTripTurbidityTol);
  EXPECT_EQ(j["exif"]["camera"], "SkylightTest Fisheye 8mm");
  EXPECT_EQ(j["exif"]["date_time"], "2024:06:21 15:00:00");
  EXPECT_EQ(j["exif"]["focal_length_mm"], 8.0);
  EXPECT_EQ(j["calibration"], cal.string());
  // The layout flags beside a calibration are not read: warned, the calibration wins.
  r = run(photo + " --lens equidistant --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --lens is not read (--calibration gives the layout); ignored"),
            std::string::npos)
      << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["turbidity"].get<double>(), 4.0, kRoundTripTurbidityTol);
  // --lat overrides the GPS place; the sun moves with it.
  r = run(photo + " --lat 40 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(std::abs(nlohmann::json::parse(r.out)["sun_zenith_deg"].get<double>() -
                     j["sun_zenith_deg"].get<double>()),
            1.0);
  // An EXIF time without an offset needs --utc-offset; --lat without a time is refused.
  const std::string tif = std::string(SKYLIGHT_SOURCE_DIR) + "/tests/data/exif/capture.tif";
  r = run("estimate --image '" + exr.string() + "' --exif '" + tif + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("has no UTC offset (OffsetTimeOriginal, EXIF 2.31); give it with "
                       "--utc-offset"),
            std::string::npos)
      << r.err;
  r = run("estimate --image '" + exr.string() + "' --lat 40 --lon 10");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--lat needs --time, or --exif with an EXIF time"), std::string::npos)
      << r.err;
  // A calibration for another image size.
  std::ofstream(cal) << R"({"projection": "fisheye", "image_size": [400, 300]})";
  r = run("estimate --image '" + exr.string() + "' --calibration '" + cal.string() + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("is for 400 x 300 photos, not 200 x 200"), std::string::npos) << r.err;
}

TEST_F(Cli, EstimateUsesAUserMaskAndRefusesBadInputs) {
  const fs::path exr = dir_ / "sky.exr", png = dir_ / "mask.png", bad = dir_ / "bad.png";
  auto r = run("render --model preetham --turbidity 5 " + kSun +
               " --projection equirect --width 120 --height 60 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  io::Image8 mask(120, 60), wrong(100, 60);
  for (int row = 0; row < 30; ++row)
    for (int col = 0; col < 60; ++col) mask.pixel(col, row)[0] = 255;
  io::write_png(png, mask);
  io::write_png(bad, wrong);
  r = run("estimate --image '" + exr.string() + "' --projection equirect --mask '" + png.string() +
          "' " + kSun + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["turbidity"].get<double>(), 5.0, kRoundTripTurbidityTol);
  EXPECT_LE(j["sky_pixels"].get<int>(), 60 * 30);

  r = run("estimate --image '" + exr.string() + "' --projection equirect --mask '" + bad.string() +
          "' " + kSun);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("100 x 60"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("120 x 60"), std::string::npos) << r.err;

  // Missing inputs: usage errors found before any work.
  r = run("estimate --image '" + (dir_ / "missing.exr").string() + "' " + kSun);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("missing.exr"), std::string::npos) << r.err;
  r = run("estimate --image '" + exr.string() + "' --mask '" + (dir_ / "nomask.png").string() +
          "' " + kSun);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("nomask.png"), std::string::npos) << r.err;
  r = run("estimate --image '" + exr.string() + "' --sun-zenith 40");
  EXPECT_EQ(r.status, 2) << "zenith without azimuth";
  r = run("estimate --image '" + exr.string() + "' --sun-zenith 95 --sun-azimuth 10");
  EXPECT_EQ(r.status, 2) << "sun below the horizon";
  EXPECT_NE(r.err.find("above the horizon"), std::string::npos) << r.err;
  r = run("estimate --image '" + exr.string() + "' --projection cubemap " + kSun);
  EXPECT_EQ(r.status, 2);
  r = run("estimate --image '" + exr.string() + "' --samples 1000000 " + kSun);
  EXPECT_EQ(r.status, 2) << "more samples than sky pixels";
  r = run("estimate --image '" + png.string() + "' " + kSun);
  EXPECT_EQ(r.status, 2) << "an 8-bit PNG is not an HDR photo";
  r = run("estimate --image '" + exr.string() + "' --compare '" + (dir_ / "c.jpg").string() + "' " +
          kSun);
  EXPECT_EQ(r.status, 2) << "--compare writes PNG only";
}

// render's float batch path (1e-5 relative for hosek) and the EXR's float: T and albedo move by
// well under these.
constexpr double kHosekRoundTripTurbidityTol = 1e-2;
constexpr double kHosekRoundTripAlbedoTol = 0.05;

TEST_F(Cli, EstimateFitsHosekTurbidityAndAlbedo) {
  const fs::path exr = dir_ / "hosek.exr", png = dir_ / "compare.png";
  auto r = run("render --model hosek --turbidity 5 --albedo 0.4 " + kSun +
               " --projection fisheye --width 200 --height 200 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("estimate --model hosek --image '" + exr.string() + "' " + kSun + " --compare '" +
          png.string() + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"], "hosek");
  EXPECT_NEAR(j["turbidity"].get<double>(), 5.0, kHosekRoundTripTurbidityTol);
  EXPECT_NEAR(j["albedo"].get<double>(), 0.4, kHosekRoundTripAlbedoTol);
  EXPECT_DOUBLE_EQ(j["inlier_fraction"].get<double>(), 1.0);
  EXPECT_TRUE(fs::exists(png));
}

TEST_F(Cli, EstimateRecognisesTheCieTypeOfARenderedSky) {
  const fs::path exr = dir_ / "cie.exr";
  const std::string sun = "--sun-zenith 40 --sun-azimuth 100";
  for (const int type : {3, 7, 13}) {
    auto r = run("render --model cie --cie-type " + std::to_string(type) + " " + sun +
                 " --projection fisheye --width 160 --height 160 -o '" + exr.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    r = run("estimate --model cie --image '" + exr.string() + "' " + sun + " --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["cie_type"], type);
    EXPECT_TRUE(j["turbidity"].is_null());
    EXPECT_DOUBLE_EQ(j["inlier_fraction"].get<double>(), 1.0);
    EXPECT_EQ(j["cie_ranking"].size(), 15u);
  }
}

// A real photograph (data/hdr_sky/sunrise.exr, CC0): equirect, scenery, a clipped sun just above
// the horizon. Plausibility only: the sun is found low in the sky (a sunrise), T lies in the fit
// range, RANSAC rejects part of the samples (trees, power lines, the photo's departure from the
// model), and --compare writes the false-colour comparison.
TEST_F(Cli, EstimateRunsOnARealPanorama) {
  const fs::path png = dir_ / "compare.png";
  const auto r =
      run(std::string("estimate --image '") + SKYLIGHT_TEST_DATA_DIR +
          "/hdr_sky/sunrise.exr' --projection equirect --compare '" + png.string() + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["sun_source"], "image");
  EXPECT_GT(j["sun_zenith_deg"].get<double>(), 75.0);
  EXPECT_LT(j["sun_zenith_deg"].get<double>(), 90.0);
  EXPECT_GE(j["turbidity"].get<double>(), 1.7);
  EXPECT_LE(j["turbidity"].get<double>(), 20.0);
  EXPECT_LT(j["inlier_fraction"].get<double>(), 1.0);
  EXPECT_LT(j["residual"].get<double>(), 0.1) << "inliers are within the 0.1 threshold";
  const io::Image8 img = io::read_png(png);
  EXPECT_GT(img.width, 2 * 1024);
  EXPECT_EQ(img.height, 512);
}

}  // namespace
}  // namespace skylight
