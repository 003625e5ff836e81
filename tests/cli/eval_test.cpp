// End-to-end tests of `skylight eval`: real processes, real files.
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

// hosek: its batch bound (1e-5, hosek_wilkie_test.cpp) plus the XYZ -> sRGB matrix and float
// storage; a channel that nearly cancels in the matrix gets relatively more.
constexpr double kHosekRenderVsEvalRelTol = 1e-4;

TEST_F(Cli, EvalQuantities) {
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n60,90\n";
  testing_support::CliResult r =
      run("eval --model cie --cie-type 16 --zenith-luminance 3000 --quantity luminance", in);
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  auto rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,luminance");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0][2], 3000.0);
  EXPECT_NEAR(rows[1][2], 2000.0, 1e-9);  // (1 + 2 cos 60) / 3 = 2/3
  r = run("eval --model preetham --quantity xyz", in);
  ASSERT_EQ(r.status, 0) << r.err;
  rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,x,y,z");
  r = run("eval --model preetham --quantity spectral --wavelengths 450,550,650", in);
  ASSERT_EQ(r.status, 0) << r.err;
  rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,L450,L550,L650");
  EXPECT_GT(rows[0][2], rows[0][4]) << "blue sky";
  // Round-trip precision: the printed numbers re-parse to the same double.
  r =
      run("eval --model perez --perez -1,-0.32,10,-3,0.45 --zenith-luminance 1234.5 --quantity "
          "luminance",
          in);
  ASSERT_EQ(r.status, 0) << r.err;
  rows = parse_csv_numbers(r.out, &header);
  EXPECT_DOUBLE_EQ(rows[0][2], 1234.5);
  // --input file works like stdin.
  std::ofstream(dir_ / "in.csv") << in;
  r = run("eval --model cie --input '" + (dir_ / "in.csv").string() + "' --quantity luminance");
  EXPECT_EQ(r.status, 0) << r.err;
}

// --reference: the model's reference integrator with a standard-error column per value; the
// options it reads warn without it; a model without one, rgb and the sun modes are errors.
TEST_F(Cli, EvalReferenceAddsStandardErrorColumns) {
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n70,180\n";
  auto r = run("eval --model hillaire --quantity luminance --reference --paths 2000", in);
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  const auto rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,luminance,luminance_se");
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) {
    EXPECT_GT(row[3], 0.0);
    EXPECT_LT(row[3], 0.05 * row[2]);
  }
  r = run("eval --model nishita --quantity xyz --reference", in);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "zenith_deg,azimuth_deg,x,y,z,x_se,y_se,z_se");
  r = run("eval --model hillaire --quantity luminance --paths 10", in);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --paths is not read without --reference; ignored"),
            std::string::npos)
      << r.err;
  for (const char* bad : {"eval --model preetham --reference", "eval --model hillaire --reference",
                          "eval --model hillaire --reference --quantity xyz --include-sun"}) {
    r = run(bad, in);
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_NE(r.err.find("reference"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << bad;
  }
}

TEST_F(Cli, EvalNishitaUnitIrradianceAndObserverAltitude) {
  // zenith, horizon (north), 30 deg below the horizon (south).
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n90,0\n120,180\n";
  testing_support::CliResult r =
      run("eval --model nishita --sun-elevation 30 --solar-irradiance 1 --quantity "
          "spectral --wavelengths 440,550,680",
          in);
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  auto rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,L440,L550,L680");
  ASSERT_EQ(rows.size(), 3u);
  // Per unit irradiance [sr^-1]: a clear zenith scatters ~1 % sr^-1 at 440 nm, bluer than red.
  EXPECT_GT(rows[0][2], 0.005);
  EXPECT_LT(rows[0][2], 0.03);
  EXPECT_GT(rows[0][2], 3 * rows[0][4]) << "blue zenith";
  EXPECT_EQ(rows[2][2], 0.0) << "observer on the ground looking down: no air in between";
  // From 400 km: the horizontal ray passes above the atmosphere (0), the zenith sees nothing, the
  // planet below is bright.
  r =
      run("eval --model nishita --sun-elevation 30 --solar-irradiance 1 --observer-altitude 4e5 "
          "--quantity spectral --wavelengths 440,550,680",
          in);
  ASSERT_EQ(r.status, 0) << r.err;
  rows = parse_csv_numbers(r.out, &header);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0][3], 0.0);
  EXPECT_EQ(rows[1][3], 0.0);
  EXPECT_GT(rows[2][2], 0.01);
}

TEST_F(Cli, EvalNishitaOzoneAbsorbsInTheChappuisBand) {
  // Sun at 2 deg: the zenith's light crosses the ozone layer obliquely. Ozone only absorbs, most
  // near 600 nm (cross-section 5.2e-25 m^2 vs 6.6e-27 at 440 nm).
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n";
  const std::string q =
      "eval --model nishita --sun-elevation 2 --solar-irradiance 1 --quantity "
      "spectral --wavelengths 440,600";
  const testing_support::CliResult a = run(q, in), b = run(q + " --ozone 300", in);
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(b.status, 0) << b.err;
  std::string header;
  const auto ra = parse_csv_numbers(a.out, &header), rb = parse_csv_numbers(b.out, &header);
  ASSERT_EQ(ra.size(), 1u);
  ASSERT_EQ(rb.size(), 1u);
  const double loss440 = rb[0][2] / ra[0][2], loss600 = rb[0][3] / ra[0][3];
  EXPECT_LT(loss440, 1.0);
  EXPECT_LT(loss600, loss440);
  EXPECT_GT(loss440, 0.95);  // 440 nm: ozone optical depth ~0.001 per column crossed
  EXPECT_EQ(run("eval --model nishita --ozone -1", in).status, 2);
}

TEST_F(Cli, HosekEvalAllQuantitiesAndRender) {
  const std::string model =
      "--model hosek --turbidity 4.5 --albedo 0.2 --sun-zenith 50 --sun-azimuth 120";
  // Zenith, the sun centre, and a direction far from the sun.
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n50,120\n60,300\n";
  std::string header;
  auto eval = [&](const std::string& args) {
    const testing_support::CliResult r = run("eval " + model + " " + args, in);
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
    return parse_csv_numbers(r.out, &header);
  };
  const auto sky = eval("--quantity luminance");
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,luminance");
  const auto both = eval("--quantity luminance --include-sun");
  const auto sun = eval("--quantity luminance --sun-only");
  ASSERT_EQ(sky.size(), 3u);
  ASSERT_EQ(both.size(), 3u);
  ASSERT_EQ(sun.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(sky[i][2], 0.0);
    EXPECT_NEAR(both[i][2], sky[i][2] + sun[i][2], 1e-9 * both[i][2]);
  }
  EXPECT_EQ(sun[0][2], 0.0);
  EXPECT_EQ(sun[2][2], 0.0);
  EXPECT_GT(sun[1][2], 1e4 * sky[1][2]) << "the solar disc";
  const auto xyz = eval("--quantity xyz");
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,x,y,z");
  EXPECT_DOUBLE_EQ(xyz[0][3], sky[0][2]);
  const auto rgb = eval("--quantity rgb");
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,r,g,b");
  EXPECT_GT(rgb[0][4], rgb[0][2]) << "blue zenith (native RGB)";
  eval("--quantity rgb --include-sun");
  eval("--quantity xyz --sun-only");
  const auto L = eval("--quantity spectral --wavelengths 320,450,550,720");
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,L320,L450,L550,L720");
  const auto Ls = eval("--quantity spectral --wavelengths 320,450,550,720 --sun-only");
  const auto Lb = eval("--quantity spectral --wavelengths 320,450,550,720 --include-sun");
  for (int c = 2; c < 6; ++c) {
    EXPECT_GT(L[0][c], 0.0);
    EXPECT_NEAR(Lb[1][c], L[1][c] + Ls[1][c], 1e-9 * Lb[1][c]);
    EXPECT_EQ(Ls[0][c], 0.0);
  }
  // Outside the spectral range 320-720 nm, or outside turbidity 1-10: a clear error.
  testing_support::CliResult r =
      run("eval " + model + " --quantity spectral --wavelengths 800", in);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("800"), std::string::npos) << r.err;
  r = run("eval --model hosek --turbidity 12", in);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("turbidity"), std::string::npos) << r.err;

  // render: the float batch path; pixel = linear sRGB of the XYZ dataset.
  const fs::path exr = dir_ / "hosek.exr";
  r = run("render " + model + " --width 64 --height 32 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF img = io::read_image(exr);
  r = run("eval " + model + " --quantity xyz",
          testing_support::equirect_pixel_input(20, 9, 64, 32));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto px_xyz = parse_csv_numbers(r.out, &header);
  const Rgb want = xyz_to_linear_srgb({px_xyz[0][2], px_xyz[0][3], px_xyz[0][4]});
  const float* px = img.pixel(20, 9);
  EXPECT_NEAR(px[0], want.r, std::abs(want.r) * kHosekRenderVsEvalRelTol);
  EXPECT_NEAR(px[1], want.g, std::abs(want.g) * kHosekRenderVsEvalRelTol);
  EXPECT_NEAR(px[2], want.b, std::abs(want.b) * kHosekRenderVsEvalRelTol);
  r = run("render " + model + " --include-sun --width 256 --height 128 -o '" +
          (dir_ / "hs.pfm").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("render " + model + " --sun-only --width 256 --height 128 -o '" +
          (dir_ / "so.pfm").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF so = io::read_image(dir_ / "so.pfm");
  float peak = 0;
  for (int x = 0; x < so.width; ++x)
    for (int y = 0; y < so.height; ++y) peak = std::max(peak, so.pixel(x, y)[1]);
  EXPECT_GT(peak, 0.0f);
  EXPECT_EQ(so.pixel(0, 0)[1], 0.0f);
}

}  // namespace
}  // namespace skylight
