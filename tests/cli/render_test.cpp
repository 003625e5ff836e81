// End-to-end tests of `skylight render`: real processes, real files.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"
#include "support/cli_run.h"
#include "support/exr_metadata.h"
#include "support/scratch_dir.h"

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
  const testing_support::CliResult e = run("eval " + model + " --quantity rgb",
                                           testing_support::equirect_pixel_input(20, 9, 64, 32));
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
  using testing_support::metadata_value;
  EXPECT_EQ(metadata_value(md, "skylight:model"), "preetham");
  EXPECT_EQ(metadata_value(md, "skylight:turbidity"), "3.5");
  EXPECT_EQ(metadata_value(md, "skylight:sun_zenith_deg"), "50");
  EXPECT_NE(metadata_value(md, "skylight:version"), testing_support::kMissingMetadata);
}

// A luminance-only model's images are grey by design and say so (skylight:colour, in the EXR and in
// the PNG preview's text chunks); every other model's sky has colour. Checked on the pixels, for
// every registered model.
TEST_F(Cli, GreyByDesignIsSaidAndTrue) {
  for (const ModelInfo& m : model_registry()) {
    const std::string args = "render --model " + m.name + testing_support::example_flags(m);
    const fs::path exr = dir_ / (m.name + ".exr"), png = dir_ / (m.name + ".png");
    const auto r = run(args + " --width 32 --height 16 -o '" + exr.string() + "' --preview '" +
                       png.string() + "'");
    ASSERT_EQ(r.status, 0) << args << ": " << r.err;
    EXPECT_EQ(testing_support::metadata_value(io::read_exr_metadata(exr), "skylight:colour"),
              m.colour_note())
        << m.name;
    std::ifstream in(png, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string chunk = "skylight:colour";  // a tEXt chunk: key, NUL, text
    chunk.push_back('\0');
    chunk.append(m.colour_note());
    EXPECT_NE(bytes.find(chunk), std::string::npos) << m.name << ": no tEXt chunk";
    // Largest chroma difference over the upper half (the sky).
    const io::ImageF img = io::read_image(exr);
    float spread = 0.0f;
    for (int y = 0; y < img.height / 2; ++y)
      for (int x = 0; x < img.width; ++x) {
        const float* p = img.pixel(x, y);
        const float mx = std::max({p[0], p[1], p[2]}), mn = std::min({p[0], p[1], p[2]});
        if (mx > 0.0f) spread = std::max(spread, (mx - mn) / mx);
      }
    if (m.luminance_only)
      EXPECT_LT(spread, 1e-6f) << m.name << " is declared luminance-only";
    else
      EXPECT_GT(spread, 0.05f) << m.name << " is declared chromatic";
    EXPECT_EQ(m.colour_note().starts_with("grey by design"), m.luminance_only);
  }
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

TEST_F(Cli, CubemapWidthDefaultsToSixTimesTheHeight) {
  // Without --width the cube map is 6 x height (the --help text); with only --height too.
  testing_support::CliResult r = run("render --model cie --projection cubemap --height 16 -o '" +
                                     (dir_ / "a.pfm").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  io::ImageF img = io::read_image(dir_ / "a.pfm");
  EXPECT_EQ(img.width, 96);
  EXPECT_EQ(img.height, 16);
  r = run("render --model cie --projection cubemap --threads 2 -o '" + (dir_ / "b.pfm").string() +
          "'");
  ASSERT_EQ(r.status, 0) << r.err;
  img = io::read_image(dir_ / "b.pfm");
  EXPECT_EQ(img.width, 6 * 512);
  EXPECT_EQ(img.height, 512);
  // A given width must still be 6 x height.
  r = run("render --model cie --projection cubemap --width 100 --height 16 -o '" +
          (dir_ / "c.pfm").string() + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("got 100 x 16"), std::string::npos) << r.err;
}

TEST_F(Cli, FlagsOfAnotherProjectionAreIgnoredWithOneWarning) {
  const std::string out = " --width 8 --height 4 -o '" + (dir_ / "a.pfm").string() + "'";
  const std::string wrote = "skylight: wrote " + (dir_ / "a.pfm").string() + "\n";
  testing_support::CliResult r =
      run("render --model cie --lens equisolid --fov 100 --look-azimuth 3" + out);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err,
            "skylight: warning: --lens, --fov, --look-azimuth not used by --projection equirect; "
            "ignored\n" +
                wrote);
  r = run("render --model cie --projection camera --north-angle 10 --look-elevation 5 --fov 50" +
          out);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err,
            "skylight: warning: --north-angle not used by --projection camera; ignored\n" + wrote);
  r = run("render --model cie --projection fisheye --lens equisolid --fov 100 --north-angle 5" +
          out);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, wrote);
}

// A flag the chosen model does not read is a warning and is not recorded: a parameter of another
// model (pietras has no turbidity, nn no observer altitude) and a parameter of the model's schema
// that these values leave unread (a network trained on a source without turbidity).
TEST_F(Cli, AFlagTheModelDoesNotReadIsNotRecorded) {
  const auto keys = [](const fs::path& exr) {
    std::string all;
    for (const auto& [key, value] : io::read_exr_metadata(exr)) all += key + "=" + value + "\n";
    return all;
  };
  const fs::path exr = dir_ / "p.exr";
  // The run warned `warning` and did not record the turbidity.
  const auto expect_turbidity_ignored = [&](const testing_support::CliResult& r,
                                            const std::string& warning) {
    EXPECT_NE(r.err.find("skylight: warning: " + warning), std::string::npos) << r.err;
    EXPECT_EQ(keys(exr).find("skylight:turbidity"), std::string::npos) << keys(exr);
  };
  testing_support::CliResult r =
      run("render --model pietras --turbidity 5 --observer-altitude 800 --width 8 --height 4 -o '" +
          exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  expect_turbidity_ignored(r, "--turbidity is not a parameter of model 'pietras'; ignored");
  EXPECT_NE(keys(exr).find("skylight:observer_altitude_m=800\n"), std::string::npos) << keys(exr);
  r = run("render --model nn --width 8 --height 4 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(keys(exr).find("observer_altitude"), std::string::npos) << keys(exr);
  EXPECT_NE(keys(exr).find("skylight:turbidity=3\n"), std::string::npos) << keys(exr);
  // A network trained on cie (no turbidity input): --turbidity is not read.
  const fs::path w = dir_ / "cie.json";
  r =
      run("nn train --source cie --hidden 3 --suns 2 --view-zeniths 2 --view-azimuths 3 "
          "--iterations 2 --max-error 1e6 -o '" +
          w.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("render --model nn --weights '" + w.string() +
          "' --turbidity 4 --width 8 --height 4 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  expect_turbidity_ignored(r,
                           "--turbidity is not read by model 'nn' with these parameters; ignored");
}

TEST_F(Cli, PixelUnitSaysWhatEachOutputHolds) {
  const fs::path exr = dir_ / "a.exr", png = dir_ / "a.png", preview = dir_ / "p.png",
                 fc = dir_ / "fc.png";
  testing_support::CliResult r =
      run("render --model cie --width 8 --height 4 -o '" + exr.string() + "' --preview '" +
          preview.string() + "' --false-colour '" + fc.string() + "' --false-colour-range 1,5");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("render --model cie --width 8 --height 4 -o '" + png.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(testing_support::metadata_value(io::read_exr_metadata(exr), "skylight:pixel_unit"),
            "linear sRGB (D65), Y = luminance [cd/m^2]");
  const std::string tone = std::string("tEXtskylight:pixel_unit\0tone-mapped display values", 50);
  EXPECT_NE(slurp(preview).find(tone), std::string::npos);
  EXPECT_NE(slurp(png).find(tone), std::string::npos);
  EXPECT_EQ(slurp(preview).find("Y = luminance"), std::string::npos);
  EXPECT_NE(slurp(fc).find(std::string("skylight:pixel_unit\0false colour of log10 luminance, 1 "
                                       "to 5 log10 cd/m^2",
                                       72)),
            std::string::npos);
}

TEST_F(Cli, EveryMetadataKeyIsDocumentedInTheReadme) {
  // Renders that write every kind of key (each model's parameters, fisheye, camera, --time): each
  // key must appear in README.md in backticks, with or without its `skylight:` prefix.
  const std::string readme = testing_support::source_file("README.md");
  const std::string renders[] = {
      "--model nishita --albedo 0.3 --ozone 300 --solar-irradiance 1 --projection camera",
      "--model preetham --projection fisheye --time 2003-10-17T12:30:30-07:00 --lat 39 --lon -105",
      "--model hosek --include-sun", "--model cie --zenith-luminance 5000",
      "--model perez --perez -1,-0.32,10,-3,0.45 --zenith-luminance 5000"};
  // (Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "`" + std::string.)
  const auto in_backticks = [&](const std::string& name) {
    std::string quoted(1, '`');
    quoted.append(name).push_back('`');
    return readme.find(quoted) != std::string::npos;
  };
  int keys = 0;
  for (const auto& flags : renders) {
    const fs::path exr = dir_ / "a.exr";
    const testing_support::CliResult r =
        run("render " + flags + " --width 8 --height 8 -o '" + exr.string() + "'");
    ASSERT_EQ(r.status, 0) << flags << ": " << r.err;
    for (const auto& [key, value] : io::read_exr_metadata(exr)) {
      if (key.rfind("skylight:", 0) != 0) continue;
      ++keys;
      const bool documented = in_backticks(key.substr(9)) || in_backticks(key);
      EXPECT_TRUE(documented) << key << " (" << flags << ") is not documented in README.md";
    }
  }
  EXPECT_GT(keys, 50);
}

// `render --gpu` against the CPU render of the same network (gpu/sky_render_test.cpp holds the
// per-projection bounds; here the CLI path end to end): 1e-4 relative above 1e-3 of the peak.
constexpr double kGpuCliRelativeTolerance = 1e-4;
constexpr double kGpuCliFloor = 1e-3;

TEST_F(Cli, RenderGpuMatchesTheCpuRender) {
  // The embedded sky network and a Pietras network (per-pixel shadow test and rgb_at in GLSL).
  const std::string log3 = std::string(SKYLIGHT_TEST_DATA_DIR) + "/nn/log3.json";
  const std::string models[] = {"--model nn --turbidity 3 --sun-zenith 50 --sun-azimuth 120",
                                "--model pietras --weights '" + log3 +
                                    "' --observer-altitude 2000 --sun-zenith 50 --sun-azimuth 120"};
  testing_support::CliResult r;
  for (const std::string& model : models) {
    const fs::path gpu = dir_ / "gpu.exr", cpu = dir_ / "cpu.exr", png = dir_ / "gpu.png";
    fs::remove(png);
    r = run("render " + model + " --gpu --width 64 --height 32 -o '" + gpu.string() +
            "' --preview '" + png.string() + "'");
#ifdef SKYLIGHT_HAVE_GPU
    ASSERT_EQ(r.status, 0) << r.err;
    r = run("render " + model + " --width 64 --height 32 -o '" + cpu.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    const io::ImageF a = io::read_image(gpu), b = io::read_image(cpu);
    ASSERT_EQ(a.data.size(), b.data.size());
    const float peak = *std::max_element(b.data.begin(), b.data.end());
    double worst = 0.0;
    for (std::size_t i = 0; i < a.data.size(); ++i)
      if (b.data[i] > kGpuCliFloor * peak)
        worst = std::max(worst, std::abs(a.data[i] - b.data[i]) / static_cast<double>(b.data[i]));
    EXPECT_LE(worst, kGpuCliRelativeTolerance) << model;
    EXPECT_TRUE(fs::exists(png)) << model;
#else
    break;  // the first run's error is checked below
#endif
  }
#ifdef SKYLIGHT_HAVE_GPU
  // A model without a GPU form says why (ModelInfo::no_gpu).
  r = run("render --model sh --gpu --width 8 --height 4 -o '" + (dir_ / "p.exr").string() + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("model 'sh' has no GPU form: its reconstruction sums"), std::string::npos)
      << r.err;
#else
  testing_support::expect_built_without_gpu(r);
#endif
}

}  // namespace
}  // namespace skylight
