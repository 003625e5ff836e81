// End-to-end tests of `skylight haze`: coefficients, attenuation, cameras, the image operations
// and the sky mask.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "skylight/core/math.h"
#include "skylight/haze/request.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"
#include "support/cli_run.h"
#include "support/skyline_scene.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;

// Morales 2017 prints 4 decimals; eq. 3 gives 0.013563 (printed 0.0135, truncated).
constexpr double kPrintedDigitTol = 1e-4;
// Float images through EXR (bit-exact) and float arithmetic of values <= 1.
constexpr double kFloatTol = 1e-5;
// Gamma at distance 0 is a ratio of two equal 81-term trapezoid sums, computed in different orders:
// rounding only (a few units of 1e-16; the JSON prints 17 digits).
constexpr double kRatioRounding = 1e-14;
// The watershed mask of the 360 x 180 skyline scene (measured IoU 0.9978, as in
// haze/sky_segmentation_test.cpp).
constexpr double kCliMaskIoUFloor = 0.99;
// The airlight recovered from one hazed pixel against the scene's horizon sky: the brightest 1 %
// of the horizon region with 1 % noise is biased up by up to the noise (measured 0.85 %).
constexpr double kCliAirlightRelTol = 0.02;
// The fixed band's brightest pixels are the snow field: far off (measured 134 %).
constexpr double kCliBandAirlightError = 0.5;

bool one_line(const std::string& err) {
  return !err.empty() && err.find('\n') == err.size() - 1 && err.rfind("skylight: error: ", 0) == 0;
}

class HazeCli : public Cli {
 protected:
  // A 24 x 16 RGB pattern and a depth ramp (metres), written as EXR.
  void write_scene() {
    io::ImageF im(24, 16, 3), d(24, 16, 1);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 24; ++x) {
        im.pixel(x, y)[0] = 0.1f + 0.03f * x;
        im.pixel(x, y)[1] = (x + y) % 2 ? 0.7f : 0.2f;
        im.pixel(x, y)[2] = 0.1f + 0.05f * y;
        d.pixel(x, y)[0] = 100.0f + 400.0f * static_cast<float>(16 - y);
      }
    io::write_image(dir_ / "scene.exr", im);
    io::write_image(dir_ / "depth.exr", d);
    scene_ = im;
  }
  // sky.exr: a Preetham sky of turbidity `turbidity` rendered as a fisheye photo.
  void write_sky_photo(const std::string& turbidity) {
    const testing_support::CliResult r =
        run("render --model preetham --turbidity " + turbidity +
            " --projection fisheye --width 96 --height 96 -o " + p("sky.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  // The path of a scratch file, quoted for the shell (built in steps: GCC 12 reports a false
  // -Wrestrict on "'" + string + "'").
  std::string p(const std::string& name) {
    std::string quoted(1, '\'');
    quoted += (dir_ / name).string();
    quoted += '\'';
    return quoted;
  }
  // Runs `flags` with `--gpu` and without, writing <stem>_gpu.exr and <stem>_cpu.exr: with the
  // GPU module both succeed and agree to float rounding; without it the `--gpu` run exits 1 and
  // says so.
  void expect_gpu_matches_cpu(const std::string& flags, const std::string& stem) {
    auto r = run(flags + "--gpu -o " + p(stem + "_gpu.exr"));
#ifdef SKYLIGHT_HAVE_GPU
    ASSERT_EQ(r.status, 0) << r.err;
    r = run(flags + "-o " + p(stem + "_cpu.exr"));
    ASSERT_EQ(r.status, 0) << r.err;
    const io::ImageF a = io::read_image(dir_ / (stem + "_gpu.exr"));
    const io::ImageF b = io::read_image(dir_ / (stem + "_cpu.exr"));
    ASSERT_EQ(a.data.size(), b.data.size());
    for (std::size_t i = 0; i < a.data.size(); ++i)
      EXPECT_NEAR(a.data[i], b.data[i], kFloatTol * (1.0 + std::abs(b.data[i])))
          << stem << " " << i;
#else
    testing_support::expect_built_without_gpu(r);
#endif
  }
  io::ImageF scene_;
};

TEST_F(HazeCli, CoefficientsJsonHasThePapersNumbers) {
  auto r =
      run("haze coefficients --turbidity 2 --wavelength 550 --altitude 0 --variant preetham "
          "--json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["beta_rayleigh_per_km"].get<double>(), 0.0135, kPrintedDigitTol);
  r = run("haze coefficients --turbidity 2 --json");  // improved, 550 nm, 0 m by default
  ASSERT_EQ(r.status, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["beta_rayleigh_per_km"].get<double>(), 0.0141, kPrintedDigitTol / 2);
  // eq. 18 at T = 2: 0.4340 x 0.65e-16 x pi x (2 pi / 550 nm)^2 x 0.0092 = 0.1064 /km.
  EXPECT_NEAR(j["beta_mie_per_km"].get<double>(), 0.1064, kPrintedDigitTol);
  EXPECT_EQ(j["weather_class"], "very clear");
  r = run("haze coefficients --turbidity 1.6");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("exceptionally clear"), std::string::npos) << r.out;
  r = run("haze coefficients --turbidity 0.5");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(one_line(r.err)) << r.err;
}

TEST_F(HazeCli, AttenuationJsonGivesGammaPerChannel) {
  auto r = run("haze attenuation --turbidity 3 --distance 5000 --camera canon-eos-5d --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto g = nlohmann::json::parse(r.out)["gamma"];
  ASSERT_EQ(g.size(), 3u);
  EXPECT_LT(g[2].get<double>(), g[1].get<double>());
  EXPECT_LT(g[1].get<double>(), g[0].get<double>());
  EXPECT_GT(g[2].get<double>(), 0.0);
  r = run("haze attenuation --turbidity 3 --distance 0 --camera sony-ilce-7m3 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto unit = nlohmann::json::parse(r.out)["gamma"];  // a copy: the parsed object dies here
  for (const auto& v : unit) EXPECT_NEAR(v.get<double>(), 1.0, kRatioRounding);
  // A user CSV: flat channels.
  std::ofstream(dir_ / "cam.csv") << "nm,r,g,b\n380,1,1,1\n780,1,1,1\n";
  r = run("haze attenuation --turbidity 3 --distance 5000 --camera-csv " + p("cam.csv") +
          " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto flat = nlohmann::json::parse(r.out)["gamma"];
  EXPECT_DOUBLE_EQ(flat[0].get<double>(), flat[2].get<double>());
  std::ofstream(dir_ / "bad.csv") << "nm,r,g,b\n380,1,1,1\n780,1,oops,1\n";
  r = run("haze attenuation --turbidity 3 --distance 5000 --camera-csv " + p("bad.csv"));
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("line 3 column 3: 'oops'"), std::string::npos) << r.err;
  r = run("haze attenuation --turbidity 3 --distance 5000 --camera canon-eos-6d");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(one_line(r.err)) << r.err;
}

TEST_F(HazeCli, CamerasListsTheEmbeddedNames) {
  const auto r = run("haze cameras");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("canon-eos-5d "), std::string::npos);
  EXPECT_NE(r.out.find("sony-ilce-7m3 "), std::string::npos);
  // A table: its title, header and one row per camera.
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 2 + 40);
  const auto j = nlohmann::json::parse(run("haze cameras --json").out);
  EXPECT_EQ(j["cameras"].size(), 40u);
  EXPECT_EQ(j["cameras"][0]["name"].get<std::string>().empty(), false);
}

TEST_F(HazeCli, AddThenRemoveRestoresTheImage) {
  write_scene();
  const std::string common = " --depth " + p("depth.exr") +
                             " --turbidity 2.5 --camera canon-eos-5d --airlight 0.8,0.85,0.9 ";
  auto r = run("haze add --image " + p("scene.exr") + common + "-o " + p("hazy.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF hazy = io::read_image(dir_ / "hazy.exr");
  // Far pixels (top) moved towards the airlight more than near ones (bottom).
  EXPECT_LT(std::abs(hazy.pixel(3, 0)[1] - 0.85f), std::abs(scene_.pixel(3, 0)[1] - 0.85f));
  r = run("haze remove --image " + p("hazy.exr") + common + "-o " + p("clear.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF clear = io::read_image(dir_ / "clear.exr");
  for (std::size_t i = 0; i < clear.data.size(); ++i)
    EXPECT_NEAR(clear.data[i], scene_.data[i], 20 * kFloatTol) << i;
  // Re-target 2.5 -> 2.5 with the same airlight: unchanged.
  r = run("haze retarget --image " + p("hazy.exr") + common + "--target-turbidity 2.5 -o " +
          p("same.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF same = io::read_image(dir_ / "same.exr");
  for (std::size_t i = 0; i < same.data.size(); ++i)
    EXPECT_NEAR(same.data[i], hazy.data[i], kFloatTol) << i;
}

// The README's quick start on the shipped valley (data/haze_scene/, scripts/make_haze_scene.py):
// the scene is what its provenance says (depth 0.2-31 km on the ground, 100 km on the sky), haze
// of T = 3 greys the far ridges more than the near ones, and `haze remove` restores every pixel
// whose own light is above the transmission floor (Gamma > 0.05: up to the 6 km ridge) to float
// rounding of the eq. 10 round trip, and says how many hit it (the sky, the 14 and 30 km ridges).
TEST_F(HazeCli, ShippedValleyRoundTripsLikeTheQuickStart) {
  const std::string dir = std::string(SKYLIGHT_TEST_DATA_DIR) + "/haze_scene/";
  const io::ImageF valley = io::read_image(dir + "valley.hdr");
  const io::ImageF depth = io::read_scalar_image(dir + "valley_depth.pfm");
  ASSERT_EQ(valley.width, 320);
  ASSERT_EQ(valley.height, 160);
  ASSERT_EQ(depth.width, valley.width);
  auto r =
      run("render --model hosek --turbidity 3 --sun-zenith 40 --sun-azimuth 150 --width 256 "
          "--height 128 -o " +
          p("sky.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string common =
      " --depth '" + dir + "valley_depth.pfm' --turbidity 3 --camera canon-eos-5d --sky " +
      p("sky.exr") + " --sky-projection equirect --vfov 30 --heading 200 --pitch 2 ";
  r = run("haze add --image '" + dir + "valley.hdr'" + common + "-o " + p("hazy.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("haze remove --image " + p("hazy.exr") + common + "-o " + p("dehazed.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF hazy = io::read_image(dir_ / "hazy.exr");
  const io::ImageF dehazed = io::read_image(dir_ / "dehazed.exr");
  constexpr float kSkyDepthM = 100000.0f;  // make_haze_scene.py's SKY_DEPTH_M
  // Gamma(T = 3) > 0.05 on every channel up to here (0.15 in blue at 6 km, 0.013 at 14 km:
  // `haze attenuation --turbidity 3 --camera canon-eos-5d --distance 14000`).
  constexpr float kRecoverableM = 10000.0f;
  // eq. 10 forward then inverted in float, the airlight and Gamma recomputed the same way: a few
  // float roundings of the hazy value, amplified by 1 / Gamma (at most 1 / 0.05 here) in the
  // inversion (measured: median 8e-7 of the value, worst 2.1e-5 where Gamma is smallest).
  constexpr double kRoundings = 8.0;
  constexpr double kMinGamma = 0.05;  // haze remove's default --min-transmission
  std::size_t sky = 0, restored = 0, floored = 0, near = 0, far = 0;
  double near_shift = 0, far_shift = 0;  // sums of |hazy - valley| / valley (green)
  for (int y = 0; y < valley.height; ++y)
    for (int x = 0; x < valley.width; ++x) {
      const float s = depth.pixel(x, y)[0];
      ASSERT_TRUE(s == kSkyDepthM || (s > 200.0f && s < 31000.0f)) << x << "," << y << ": " << s;
      if (s == kSkyDepthM) ++sky;
      const float* v = valley.pixel(x, y);
      const float* h = hazy.pixel(x, y);
      const double shift = std::abs(h[1] - v[1]) / v[1];
      if (s < 1000.0f) {
        near_shift += shift;
        ++near;
      } else if (s > 3000.0f && s < kRecoverableM) {
        far_shift += shift;
        ++far;
      }
      if (s >= kRecoverableM) {
        ++floored;
        continue;
      }
      ++restored;
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(dehazed.pixel(x, y)[c], v[c],
                    kRoundings * std::numeric_limits<float>::epsilon() * h[c] / kMinGamma)
            << x << "," << y << " at " << s << " m";
    }
  EXPECT_GT(sky, 15000u);
  EXPECT_GT(restored, 25000u);
  EXPECT_EQ(testing_support::text_field(r.out, "pixels below min transmission"),
            std::to_string(floored))
      << r.out;
  ASSERT_GT(near, 0u);
  ASSERT_GT(far, 0u);
  EXPECT_GT(far_shift / far, 3 * near_shift / near) << "far ridges hazier than the meadow";
}

// Every model --help lists for --sky-model works (hosek's spectrum ends at 720 nm, the camera's at
// 780: flat tails), its airlight is positive and finite and makes distant pixels brighter; any
// other model is refused with the list. The physical atmospheres take --turbidity as Preetham's
// aerosols; those with a costly set-up (bruneton's tables: minutes under the sanitizers) are
// listed but run by their own tests only.
TEST_F(HazeCli, EverySkyModelTheHelpListsWorks) {
  write_scene();
  const std::string common = " --depth " + p("depth.exr") +
                             " --turbidity 3 --camera canon-eos-5d --sun-zenith 40 "
                             "--sun-azimuth 150 --image " +
                             p("scene.exr") + " ";
  const std::string help = run("haze add --help").out;
  for (const std::string& m : haze::airlight_models()) {
    EXPECT_NE(help.find(m), std::string::npos) << m;
    if (find_model(m)->costly_setup) continue;
    const auto r = run("haze add --sky-model " + m + common + "-o " + p(m + ".exr"));
    ASSERT_EQ(r.status, 0) << m << ": " << r.err;
    const io::ImageF out = io::read_image(dir_ / (m + ".exr"));
    for (const float v : out.data) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << m;
    EXPECT_GT(out.pixel(3, 0)[1], scene_.pixel(3, 0)[1]) << m << ": far pixel not brightened";
  }
  EXPECT_EQ(haze::airlight_models(),
            (std::vector<std::string>{"preetham", "hosek", "nishita", "hillaire", "bruneton"}));
  const auto r = run("haze add --sky-model cie" + common + "-o " + p("n.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("is not one of preetham|hosek|nishita|hillaire|bruneton"), std::string::npos)
      << r.err;
}

// `haze retarget --gpu` against the CPU path end to end: the shader reproduces the CPU kernel's
// float arithmetic (gpu/haze_test.cpp), so the files agree to float rounding.
TEST_F(HazeCli, RetargetOnTheGpuMatchesTheCpuPath) {
  write_scene();
  const std::string common = "haze retarget --image " + p("scene.exr") + " --depth " +
                             p("depth.exr") +
                             " --turbidity 5 --target-turbidity 2 --camera canon-eos-5d "
                             "--airlight 0.8,0.85,0.9 ";
  expect_gpu_matches_cpu(common, "retarget");
}

TEST_F(HazeCli, NormalisedDepthWithNearAndFar) {
  write_scene();
  io::ImageF bar(24, 16, 1);
  for (float& v : bar.data) v = 1.0f;  // s_bar = 1: the far plane
  io::write_image(dir_ / "bar.pfm", bar);
  io::ImageF far(24, 16, 1);
  for (float& v : far.data) v = 3000.0f;
  io::write_image(dir_ / "far.pfm", far);
  const std::string rest = " --turbidity 3 --camera canon-eos-5d --airlight 1,1,1 ";
  auto r = run("haze add --image " + p("scene.exr") + " --depth " + p("bar.pfm") + rest +
               "--near 10 --far 3000 -o " + p("a.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("haze add --image " + p("scene.exr") + " --depth " + p("far.pfm") + rest + "-o " +
          p("b.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF a = io::read_image(dir_ / "a.exr"), b = io::read_image(dir_ / "b.exr");
  for (std::size_t i = 0; i < a.data.size(); ++i) EXPECT_NEAR(a.data[i], b.data[i], kFloatTol);
}

TEST_F(HazeCli, ErrorsAreOneLineAndNothingIsWritten) {
  write_scene();
  io::write_image(dir_ / "small.exr", io::ImageF(8, 8, 1));
  const std::string rest = " --turbidity 3 --camera canon-eos-5d --airlight 1,1,1 ";
  auto r = run("haze add --image " + p("scene.exr") + " --depth " + p("small.exr") + rest + "-o " +
               p("out.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("is 8x8 but the image is 24x16"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
  // Never overwrite an input.
  r = run("haze add --image " + p("scene.exr") + " --depth " + p("depth.exr") + rest + "-o " +
          p("scene.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(one_line(r.err)) << r.err;
  // No airlight source.
  r = run("haze add --image " + p("scene.exr") + " --depth " + p("depth.exr") +
          " --turbidity 3 --camera canon-eos-5d -o " + p("out.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(one_line(r.err)) << r.err;
  // retarget needs its target.
  r = run("haze retarget --image " + p("scene.exr") + " --depth " + p("depth.exr") + rest + "-o " +
          p("out.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(fs::exists(dir_ / "out.exr"));
}

TEST_F(HazeCli, AirlightFromARenderedSkyPhoto) {
  write_scene();
  ASSERT_NO_FATAL_FAILURE(write_sky_photo("2.5"));
  auto r =
      run("haze add --image " + p("scene.exr") + " --depth " + p("depth.exr") +
          " --turbidity 2.5 --camera canon-eos-5d --sky " + p("sky.exr") + " -o " + p("out.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF out = io::read_image(dir_ / "out.exr");
  for (float v : out.data) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
  // The far pixels moved towards a bright sky.
  EXPECT_GT(out.pixel(3, 0)[2], scene_.pixel(3, 0)[2]);
  r = run("haze add --image " + p("scene.exr") + " --depth " + p("depth.exr") +
          " --turbidity 2.5 --camera canon-eos-5d --sky " + p("sky.exr") + " --airlight 1,1,1 -o " +
          p("out2.exr"));
  EXPECT_EQ(r.status, 2);  // one airlight source only
}

TEST_F(HazeCli, CompositeWithASkyModelAirlight) {
  write_scene();
  io::ImageF obj(24, 16, 3), od(24, 16, 1);
  for (int x = 4; x < 12; ++x)
    for (int y = 4; y < 12; ++y) {
      for (int c = 0; c < 3; ++c) obj.pixel(x, y)[c] = 0.5f;
      od.pixel(x, y)[0] = 3500.0f;
    }
  io::write_image(dir_ / "obj.exr", obj);
  io::write_image(dir_ / "od.exr", od);
  auto r = run("haze composite --background " + p("scene.exr") + " --object " + p("obj.exr") +
               " --object-depth " + p("od.exr") +
               " --turbidity 2.94 --altitude 40 --camera canon-eos-5d --sky-model preetham -o " +
               p("mr.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF mr = io::read_image(dir_ / "mr.exr");
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(mr.pixel(0, 0)[c], scene_.pixel(0, 0)[c]);  // outside the object: the background
    EXPECT_GT(mr.pixel(6, 6)[c], 0.5f);  // the object took on the (bright) sky's airlight
  }
}

// An image camera gives every pixel its own airlight (Morales 2017 §6.2): a black scene at one
// far depth shows A (1 - Gamma) with one Gamma, so rows differ by the airlight alone; with --sky
// by eq. 13's ratio zeta(T, theta_a, theta') / zeta(T, theta_b, theta') = term(theta_a) /
// term(theta_b), theta of each row from the pinhole (level camera: tan(elevation) = (1 - 2 l_y)
// tan(fov / 2) at the centre column).
class HazeCameraCli : public HazeCli {
 protected:
  static constexpr int kW = 25, kH = 15;  // odd: the centre pixel is on the optical axis
  void write_black_far(float depth_m) {
    io::ImageF im(kW, kH, 3), d(kW, kH, 1);
    for (float& v : d.data) v = depth_m;
    io::write_image(dir_ / "black.exr", im);
    io::write_image(dir_ / "far.exr", d);
  }
  static double term(double turbidity, double theta) {  // Morales 2017 eq. 13's numerator
    const double c = std::max(std::cos(theta), 0.01);
    return 1.0 + (0.178 * turbidity - 1.463) * std::exp((-0.355 * turbidity + 0.427) / c);
  }
  static double row_zenith(int row, double vfov_deg) {
    const double ly = 1.0 - (row + 0.5) / kH;
    return kPi / 2 - std::atan((2.0 * ly - 1.0) * std::tan(vfov_deg * kDegree / 2));
  }
};

// Float images of values <= 1 through EXR and float arithmetic.
constexpr double kRatioTol = 1e-5;
// The sky-model airlight table (1 deg grid, bilinear) against direct evaluation: the library's
// measured worst away from the sun (haze/airlight_field_test.cpp).
constexpr double kAirlightTableRelTol = 2e-3;

TEST_F(HazeCameraCli, SkyPhotoAirlightFollowsEquation13PerRow) {
  write_black_far(20000.0f);
  ASSERT_NO_FATAL_FAILURE(write_sky_photo("3"));
  const double vfov = 30.0;
  auto r = run("haze add --image " + p("black.exr") + " --depth " + p("far.exr") +
               " --turbidity 3 --camera canon-eos-5d --sky " + p("sky.exr") +
               " --vfov 30 --heading 200 --pitch 0 -o " + p("out.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(testing_support::text_field(r.out, "airlight"), "per-pixel") << r.out;
  const io::ImageF out = io::read_image(dir_ / "out.exr");
  const int mid = kW / 2;
  for (int row = 0; row < kH; ++row)
    for (int c = 0; c < 3; ++c) {
      const double expected =
          term(3.0, row_zenith(row, vfov)) / term(3.0, row_zenith(kH - 1, vfov));
      EXPECT_NEAR(out.pixel(mid, row)[c] / out.pixel(mid, kH - 1)[c], expected, kRatioTol)
          << row << " " << c;
    }
  // The horizon row is brighter than the top row (a clear sky darkens towards the zenith).
  EXPECT_GT(out.pixel(mid, kH / 2)[0], out.pixel(mid, 0)[0]);
}

TEST_F(HazeCameraCli, SkyModelAirlightAtTheCentreIsTheOpticalAxis) {
  write_black_far(20000.0f);
  const std::string common = "haze add --image " + p("black.exr") + " --depth " + p("far.exr") +
                             " --turbidity 3 --camera canon-eos-5d --sky-model preetham "
                             "--sun-zenith 40 --sun-azimuth 90 ";
  auto r = run(common + "--vfov 40 --heading 250 --pitch 12 --roll 7 -o " + p("cam.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  r = run(common + "--view-elevation 12 --view-azimuth 250 -o " + p("one.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF cam = io::read_image(dir_ / "cam.exr"), one = io::read_image(dir_ / "one.exr");
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(cam.pixel(kW / 2, kH / 2)[c], one.pixel(kW / 2, kH / 2)[c],
                kAirlightTableRelTol * one.pixel(kW / 2, kH / 2)[c]);
  // Off the axis the airlight differs; the constant one does not.
  EXPECT_NE(cam.pixel(0, 0)[0], cam.pixel(kW - 1, kH - 1)[0]);
  EXPECT_EQ(one.pixel(0, 0)[0], one.pixel(kW - 1, kH - 1)[0]);
}

// The raw matrices of the same pinhole give the same image; retarget and composite take the camera.
TEST_F(HazeCameraCli, RawMatricesEqualThePinholeFlags) {
  write_black_far(8000.0f);
  ASSERT_NO_FATAL_FAILURE(write_sky_photo("3"));
  const std::string common = "haze retarget --image " + p("black.exr") + " --depth " +
                             p("far.exr") +
                             " --turbidity 3 --target-turbidity 5 --camera "
                             "canon-eos-5d --sky " +
                             p("sky.exr") + " ";
  auto r = run(common + "--hfov 60 --heading 90 --pitch 5 -o " + p("pinhole.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  // heading 90 (east), pitch 5: right = (0, -1, 0) (south), forward = (cos 5, 0, sin 5).
  const double c5 = std::cos(5.0 * kDegree), s5 = std::sin(5.0 * kDegree);
  const std::string view = fmt::format("0,-1,0,0,{},0,{},0,{},0,{},0,0,0,0,1", -s5, c5, -c5, -s5);
  const double aspect = static_cast<double>(kW) / kH, fx = 1.0 / std::tan(30.0 * kDegree);
  const double n = 1.0, f = 1e4;
  const std::string proj = fmt::format("{},0,0,0,0,{},0,0,0,0,{},{},0,0,-1,0", fx, fx * aspect,
                                       (f + n) / (n - f), 2 * f * n / (n - f));
  r = run(common + "--view-matrix " + view + " --projection-matrix " + proj + " -o " +
          p("raw.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF a = io::read_image(dir_ / "pinhole.exr"), b = io::read_image(dir_ / "raw.exr");
  for (std::size_t i = 0; i < a.data.size(); ++i) EXPECT_NEAR(a.data[i], b.data[i], kFloatTol) << i;
  // Composite: the object's pixels (black, one depth) take the per-pixel airlight too.
  r = run("haze composite --background " + p("black.exr") + " --object " + p("black.exr") +
          " --object-depth " + p("far.exr") + " --turbidity 3 --camera canon-eos-5d --sky " +
          p("sky.exr") + " --vfov 30 --pitch 0 -o " + p("comp.exr"));
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF comp = io::read_image(dir_ / "comp.exr");
  EXPECT_NEAR(comp.pixel(kW / 2, 0)[1] / comp.pixel(kW / 2, kH - 1)[1],
              term(3.0, row_zenith(0, 30.0)) / term(3.0, row_zenith(kH - 1, 30.0)), kRatioTol);
}

// `--gpu` with an image camera: the per-pixel airlights as textures (gpu/haze.h).
TEST_F(HazeCameraCli, PerPixelAirlightOnTheGpuMatchesTheCpuPath) {
  write_scene();
  const std::string common = "haze retarget --image " + p("scene.exr") + " --depth " +
                             p("depth.exr") +
                             " --turbidity 5 --target-turbidity 2 --camera canon-eos-5d "
                             "--sky-model preetham --vfov 30 --heading 120 --pitch 5 ";
  expect_gpu_matches_cpu(common, "retarget");
  // The composite too (the scene as background and as object, hazed at its own depth).
  const std::string comp = "haze composite --background " + p("scene.exr") + " --object " +
                           p("scene.exr") + " --object-depth " + p("depth.exr") +
                           " --turbidity 3 --camera canon-eos-5d --sky-model preetham --vfov 30 "
                           "--heading 120 --pitch 5 ";
  expect_gpu_matches_cpu(comp, "composite");
}

TEST_F(HazeCameraCli, IncompleteOrConflictingCamerasAreErrors) {
  write_black_far(1000.0f);
  const std::string common = "haze add --image " + p("black.exr") + " --depth " + p("far.exr") +
                             " --turbidity 3 --camera canon-eos-5d --sky-model preetham ";
  const std::string bad[] = {
      "--heading 10",                   // no field of view
      "--vfov 30 --hfov 40",            // two fields of view
      "--vfov 30 --view-elevation 10",  // one airlight and a camera
      "--vfov 30 --view-matrix 1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1 --pitch 3",  // M and angles
      "--projection-matrix 0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0",                // singular
      "--projection-matrix 1,0,0,0,0,1,0,0,0,0,1,0,0,0,1,1",  // far plane at infinity: w = 0
      "--vfov 200",                                           // out of range
  };
  for (const std::string& flags : bad) {
    auto r = run(common + flags + " -o " + p("bad.exr"));
    EXPECT_EQ(r.status, 2) << flags << ": " << r.err;
    EXPECT_TRUE(one_line(r.err)) << flags << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.exr")) << flags;
  }
}

// The watershed mask of the skyline scene (tests/support/skyline_scene.h) and the airlight from
// its horizon region, given as a file or segmented again, against the fixed band.
TEST_F(HazeCli, SkyMaskAndTheWatershedHorizonRegion) {
  write_scene();
  const Camera cam{Projection::equirect, 360, 180, {}};
  const testing_support::ScenePhoto photo = testing_support::render_skyline_scene(cam);
  io::write_image(dir_ / "sky.exr", photo.image);
  auto r =
      run("haze sky-mask --sky " + p("sky.exr") + " --sky-projection equirect -o " + p("mask.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("sky pixels"), std::string::npos) << r.out;
  const io::Image8 mask = io::read_png(dir_ / "mask.png");
  ASSERT_EQ(mask.width, 360);
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i < photo.truth.sky.size(); ++i) {
    const bool sky = mask.data[3 * i] == 255;
    EXPECT_TRUE(mask.data[3 * i] == 0 || sky);
    both += sky && photo.truth.sky[i] ? 1 : 0;
    either += sky || photo.truth.sky[i] ? 1 : 0;
  }
  EXPECT_GE(static_cast<double>(both) / static_cast<double>(either), kCliMaskIoUFloor);

  const std::string add = "haze add --image " + p("scene.exr") + " --depth " + p("depth.exr") +
                          " --turbidity 2.5 --camera canon-eos-5d --sky " + p("sky.exr") +
                          " --sky-projection equirect ";
  for (const std::string& region :
       {std::string("--sky-mask ") + p("mask.png"), std::string("--horizon-region watershed"),
        std::string(""), std::string("--horizon-region band")}) {
    r = run(add + region + " -o " + p("out.exr"));
    ASSERT_EQ(r.status, 0) << region << ": " << r.err;
    // The far pixel (depth 6500 m) with its Gamma: recover the airlight the command used.
    r = run("haze attenuation --turbidity 2.5 --distance 6500 --camera canon-eos-5d --json");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto gamma = nlohmann::json::parse(r.out)["gamma"];
    const io::ImageF out = io::read_image(dir_ / "out.exr");
    const auto truth = testing_support::skyline_scene_horizon();
    double worst = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double g = gamma[c].get<double>();
      const double airlight = (out.pixel(3, 0)[c] - scene_.pixel(3, 0)[c] * g) / (1.0 - g);
      worst = std::max(worst, std::abs(airlight - truth[c]) / truth[c]);
    }
    if (region == "--horizon-region band")
      EXPECT_GT(worst, kCliBandAirlightError);
    else
      EXPECT_LE(worst, kCliAirlightRelTol) << region;
  }
  // Errors: a mask of another size, a mask with the band, a mask that is not a PNG.
  io::write_image(dir_ / "small.pfm", io::ImageF(8, 8, 1));
  r = run(add + "--sky-mask " + p("small.pfm") + " -o " + p("x.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_NE(r.err.find("the sky mask is 8x8 but the sky photo 360x180"), std::string::npos)
      << r.err;
  r = run(add + "--sky-mask " + p("mask.png") + " --horizon-region band -o " + p("x.exr"));
  EXPECT_EQ(r.status, 2);
  r = run("haze sky-mask --sky " + p("sky.exr") + " --sky-projection equirect -o " + p("m.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(one_line(r.err)) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "m.exr"));
}

// `haze composite --gpu` against the CPU path; without the GPU module the error comes before any
// input is read (the inputs here do not exist).
TEST_F(HazeCli, CompositeOnTheGpuMatchesTheCpuPath) {
  write_scene();
  io::ImageF obj(24, 16, 3), od(24, 16, 1), alpha(24, 16, 1);
  for (int x = 4; x < 20; ++x)
    for (int y = 2; y < 14; ++y) {
      for (int c = 0; c < 3; ++c) obj.pixel(x, y)[c] = 0.2f + 0.1f * static_cast<float>(c);
      od.pixel(x, y)[0] = 300.0f * static_cast<float>(x);
      alpha.pixel(x, y)[0] = static_cast<float>(y) / 16.0f;
    }
  io::write_image(dir_ / "obj.exr", obj);
  io::write_image(dir_ / "od.exr", od);
  io::write_image(dir_ / "alpha.pfm", alpha);
  const std::string common = "haze composite --background " + p("scene.exr") + " --object " +
                             p("obj.exr") + " --object-depth " + p("od.exr") + " --object-alpha " +
                             p("alpha.pfm") +
                             " --turbidity 4 --camera canon-eos-5d --airlight 0.8,0.85,0.9 ";
  expect_gpu_matches_cpu(common, "composite");
#ifndef SKYLIGHT_HAVE_GPU
  for (const char* op : {"add", "remove"}) {
    const auto r =
        run(std::string("haze ") + op + " --image " + p("missing.exr") + " --depth " +
            p("missing.pfm") + " --turbidity 3 --camera canon-eos-5d --airlight 1,1,1 --gpu -o " +
            p("out.exr"));
    testing_support::expect_built_without_gpu(r);
  }
#endif
}

}  // namespace
}  // namespace skylight
