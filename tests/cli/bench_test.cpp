// End-to-end tests of `skylight bench`: real processes, real files.
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

namespace skylight {
namespace {

using Cli = testing_support::CliTest;

TEST_F(Cli, BenchRunsAndPrintsRatios) {
  const testing_support::CliResult r =
      run("bench --width 64 --height 32 --repeats 1 --models preetham,cie,perez");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("SIMD x"), std::string::npos);
  EXPECT_NE(r.out.find("preetham"), std::string::npos);
}

// bench times every model at its defaults: a model's flag is not one of its parameters.
TEST_F(Cli, BenchRefusesModelFlagsSayingSo) {
  testing_support::CliResult r = run("bench --turbidity 3 --repeats 1 --width 4 --height 2");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "skylight: error: --turbidity is not a parameter of bench\n");
  EXPECT_EQ(r.out, "");
  r = run("bench --model cie --repeats 1 --width 4 --height 2");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "skylight: error: --model is not a parameter of bench; did you mean '--models'?\n");
  r = run("bench --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.find("--turbidity"), std::string::npos) << r.out;
}

// An empty list would time the defaults (minutes) instead of nothing: refused, as an empty name
// in a list.
TEST_F(Cli, BenchRefusesAnEmptyModelList) {
  testing_support::CliResult r = run("bench --models ''");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "skylight: error: --models = '' names no model\n");
  EXPECT_EQ(r.out, "");
  r = run("bench --models preetham,,cie");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "skylight: error: --models = 'preetham,,cie': name 2 is empty\n");
}

TEST_F(Cli, BenchTimesOneEstimateOnAMegapixelFisheye) {
  const testing_support::CliResult r =
      run("bench --width 8 --height 4 --repeats 1 --models preetham --estimate");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("estimate: 1024x1024 fisheye"), std::string::npos) << r.out;
  // The sky was rendered with T = 4; the auto-detected sun (centroid of the disc's pixel) moves the
  // fitted T by a few hundredths at most.
  constexpr double kAutoSunTurbidityTol = 0.05;
  const auto at = r.out.find("(T = ");
  ASSERT_NE(at, std::string::npos) << r.out;
  EXPECT_NEAR(std::stod(r.out.substr(at + 5)), 4.0, kAutoSunTurbidityTol) << r.out;
}

TEST_F(Cli, BenchTimesTheGlFrameOfTheNetwork) {
  const testing_support::CliResult r = run("bench --width 16 --height 8 --repeats 1 --models gpu");
#ifdef SKYLIGHT_HAVE_GPU
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("gpu: nn (6-12-3 satilmis/satilmis) 16x8 equirect on '"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("with the readback"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("gpu: Pietras log3 network (untrained weights, the same cost) per pixel "
                       "from 1 km 16x8 equirect on '"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("gpu: Pietras planet from orbit, icosphere level 6 (81924 vertices, "
                       "163840 triangles) 16x8 on '"),
            std::string::npos)
      << r.out;
#else
  testing_support::expect_built_without_gpu(r);
#endif
}

}  // namespace
}  // namespace skylight
