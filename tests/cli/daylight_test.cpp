// End-to-end tests of `skylight daylight`: one sky from measured light, and the annual matrix of
// an EPW file.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "skylight/core/math.h"
#include "skylight/models/perez_allweather.h"
#include "support/cli_run.h"

namespace skylight {
namespace {

using Cli = testing_support::CliTest;

const std::string kSampleEpw =
    std::string(SKYLIGHT_TEST_DATA_DIR) + "/weather/synthetic_munich.epw";

TEST_F(Cli, DaylightJsonHasTheIssuesKeysAndTheLibrarysNumbers) {
  const auto r = run("daylight --dni 700 --dhi 120 --sun-zenith 30 --day-of-year 172 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"epsilon", "delta", "bin", "a", "b", "c", "d", "e",
                          "zenith_luminance_cd_m2", "diffuse_horizontal_lux", "direct_normal_lux"})
    EXPECT_TRUE(j.contains(key)) << key;
  PerezIrradianceInput in;
  in.sun = {deg_to_rad(30.0), kPi};
  in.dni_w_m2 = 700.0;
  in.dhi_w_m2 = 120.0;
  in.day_of_year = 172;
  const PerezSky s = perez_sky_from_irradiance(in);
  EXPECT_EQ(j["epsilon"].get<double>(), s.epsilon);
  EXPECT_EQ(j["bin"].get<int>(), s.bin);
  EXPECT_EQ(j["e"].get<double>(), s.coefficients[4]);
  EXPECT_EQ(j["diffuse_horizontal_lux"].get<double>(), s.diffuse_horizontal_lux);
  EXPECT_EQ(j["zenith_luminance_cd_m2"].get<double>(), s.zenith_luminance_cd_m2);
  // The date of --time gives the day of the year (2024 is a leap year: June 21 is day 173).
  const auto t = run(
      "daylight --dni 700 --dhi 120 --time 2024-06-21T12:00:00+02:00 --lat 48.1 --lon 11.6 --json");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_EQ(nlohmann::json::parse(t.out)["day_of_year"].get<int>(), 173);
}

TEST_F(Cli, DaylightRefusesMissingAndContradictoryInputs) {
  auto err = [&](const std::string& args) {
    const auto r = run("daylight " + args);
    EXPECT_EQ(r.status, 2) << args;
    return r.err;
  };
  EXPECT_EQ(err("--dni 700 --dhi 120"),
            "skylight: error: daylight needs the sun: --sun-zenith [--sun-azimuth], or --time "
            "--lat --lon\n");
  EXPECT_EQ(err("--sun-zenith 30 --day-of-year 5"),
            "skylight: error: daylight needs --dni and --dhi (or --dni-illuminance and "
            "--dhi-illuminance), or --epw FILE\n");
  EXPECT_EQ(err("--dni 700 --dhi 120 --sun-zenith 30"),
            "skylight: error: a Perez sky from irradiance needs the date: --day-of-year or "
            "--time\n");
  EXPECT_EQ(err("--dni 700 --dhi 120 --dhi-illuminance 5000 --sun-zenith 30 --day-of-year 5"),
            "skylight: error: the Perez sky needs either --dni and --dhi or --dni-illuminance "
            "and --dhi-illuminance, not both\n");
  EXPECT_EQ(err("--dni 50 --dhi 20 --sun-zenith 95 --day-of-year 5"),
            "skylight: error: --dni = 50 with the sun 5 deg below the horizon: no direct light "
            "can reach the ground\n");
  EXPECT_EQ(err("--epw " + kSampleEpw + " -o " + (dir_ / "m.txt").string()),
            "skylight: error: -o '" + (dir_ / "m.txt").string() + "': write .csv or .npy\n");
  EXPECT_EQ(
      err("--dni 700 --dhi 120 --sun-zenith 30 --day-of-year 5 -o " + (dir_ / "m.csv").string()),
      "skylight: error: -o needs --epw (one sky prints its values)\n");
}

TEST_F(Cli, DaylightMatrixOfTheSampleYear) {
  const auto out = dir_ / "m.csv";
  const auto r = run("daylight --epw " + kSampleEpw + " --hours 4000-4100 --patches reinhart2 " +
                     "--dni 5 --json -o " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --dni is not read with --epw"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["patches"].get<int>(), 578);
  std::ifstream f(out);
  std::string header;
  std::getline(f, header);
  EXPECT_EQ(header.rfind("record,month,day,hour,sun_zenith_deg,sun_azimuth_deg,", 0), 0u);
  EXPECT_NE(header.find(",p577"), std::string::npos);
  int rows = 0;
  for (std::string line; std::getline(f, line);) ++rows;
  EXPECT_EQ(rows, j["hours"].get<int>());
  EXPECT_GT(rows, 40);
}

}  // namespace
}  // namespace skylight
