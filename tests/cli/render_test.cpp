// End-to-end tests of `skylight render`: real processes, real files.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/io/image.h"
#include "support/cli_run.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;
using testing_support::parse_csv_numbers;

// The render path is the float SIMD batch; eval is the double scalar path: they agree to the
// batch tolerance (2e-5 relative, see batch_test.cpp) plus float storage (6e-8).
constexpr double kRenderVsEvalRelTol = 3e-5;
TEST_F(Cli, RenderedExrPixelMatchesEval) {
  const std::string model = "--model preetham --turbidity 3.5 --sun-zenith 50 --sun-azimuth 120";
  const fs::path exr = dir_ / "sky.exr";
  const testing_support::CliResult r =
      run("render " + model + " --width 64 --height 32 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF img = io::read_image(exr);
  ASSERT_EQ(img.width, 64);
  ASSERT_EQ(img.height, 32);
  ASSERT_EQ(img.channels, 3);
  // Pixel (col 20, row 9) of a 64x32 equirect: theta = 180 * 9.5/32, phi = 360 * 20.5/64.
  const double zen = 180.0 * 9.5 / 32.0, az = 360.0 * 20.5 / 64.0;
  const testing_support::CliResult e =
      run("eval " + model + " --quantity rgb",
          "zenith_deg,azimuth_deg\n" + std::to_string(zen) + "," + std::to_string(az) + "\n");
  ASSERT_EQ(e.status, 0) << e.err;
  std::string header;
  const auto rows = parse_csv_numbers(e.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,r,g,b");
  ASSERT_EQ(rows.size(), 1u);
  const float* px = img.pixel(20, 9);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(px[c], rows[0][2 + c], std::abs(rows[0][2 + c]) * kRenderVsEvalRelTol)
        << "channel " << c;
  // Lower half (below the horizon) is 0 for the analytic skies.
  EXPECT_EQ(img.pixel(20, 25)[1], 0.0f);
  // Every parameter and the version are recorded.
  const auto md = io::read_exr_metadata(exr);
  auto find = [&](const std::string& k) {
    for (const auto& [key, value] : md)
      if (key == k) return value;
    return std::string("<missing>");
  };
  EXPECT_EQ(find("skylight:model"), "preetham");
  EXPECT_EQ(find("skylight:turbidity"), "3.5");
  EXPECT_EQ(find("skylight:sun_zenith_deg"), "50");
  EXPECT_NE(find("skylight:version"), "<missing>");
}

TEST_F(Cli, RenderAllFormatsAndProjections) {
  for (const char* ext : {"exr", "hdr", "pfm", "png"}) {
    const fs::path p = dir_ / (std::string("a.") + ext);
    const testing_support::CliResult r =
        run("render --model cie --cie-type 7 --width 24 --height 12 -o '" + p.string() + "'");
    EXPECT_EQ(r.status, 0) << ext << ": " << r.err;
    EXPECT_GT(fs::file_size(p), 0u) << ext;
  }
  const fs::path fc = dir_ / "fc.png", fe = dir_ / "fe.exr";
  testing_support::CliResult r =
      run("render --model preetham --projection fisheye --lens equisolid --fov 180 --width 40 "
          "--height 40 -o '" +
          fe.string() + "' --false-colour '" + fc.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF img = io::read_image(fe);
  EXPECT_EQ(img.pixel(0, 0)[1], 0.0f) << "corner outside the image circle";
  EXPECT_GT(img.pixel(20, 20)[1], 0.0f) << "zenith";
  EXPECT_TRUE(fs::exists(fc));
  r = run("render --model cie --projection cubemap --width 60 --height 10 -o '" +
          (dir_ / "c.exr").string() + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  r = run("render --model cie --projection hemisphere --width 20 --height 10 -o '" +
          (dir_ / "h.pfm").string() + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  // The sun disc adds a pixel far brighter than the sky.
  r = run("render --model preetham --sun-zenith 45 --include-sun --width 2048 --height 1024 -o '" +
          (dir_ / "s.pfm").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF sun = io::read_image(dir_ / "s.pfm");
  float peak = 0;
  for (int x = 0; x < sun.width; ++x)
    for (int y = 0; y < sun.height; ++y) peak = std::max(peak, sun.pixel(x, y)[1]);
  EXPECT_GT(peak, 1e8f);
}

TEST_F(Cli, RenderNishitaFromOrbitWithCamera) {
  const fs::path exr = dir_ / "orbit.exr";
  const testing_support::CliResult r =
      run("render --model nishita --observer-altitude 1e6 --sun-elevation 20 --projection camera "
          "--look-elevation -30 --fov 70 --width 32 --height 16 -o '" +
          exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF img = io::read_image(exr);
  ASSERT_EQ(img.width, 32);
  EXPECT_EQ(img.pixel(16, 0)[1], 0.0f) << "top centre: space above the limb";
  EXPECT_GT(img.pixel(16, 15)[1], 0.0f) << "bottom centre: the lit atmosphere over the planet";
}

}  // namespace
}  // namespace skylight
