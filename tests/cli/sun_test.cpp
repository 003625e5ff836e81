// End-to-end tests of `skylight sun` and of the --time/--lat/--lon flags of `render` and `eval`.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "skylight/io/image.h"
#include "support/cli_run.h"
#include "support/exr_metadata.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;
using testing_support::parse_csv_numbers;

// The worked example of Reda & Andreas 2004 (A.5): Golden, CO, 2003-10-17 12:30:30 at UTC-7.
const std::string kExampleFlags =
    "--time 2003-10-17T12:30:30-07:00 --lat 39.742476 --lon -105.1786 --elevation 1830.14 "
    "--pressure 820 --temperature 11 --delta-t 67";
// Required of the SPA port: the example's published zenith and azimuth to 1e-5 deg.
constexpr double kExampleAngleTolDeg = 1e-5;
// `sun --json` prints the angles in shortest round-trip form, and --time passes the SPA's angles
// through the same degree -> radian conversion as --sun-zenith/--sun-azimuth: the skies are built
// from identical doubles, so pixels and values agree exactly; this allows for nothing more than
// the last bit of a float pixel.
constexpr double kTimeVsAnglesRelTol = 1e-7;
// Table A5.1 prints delta to 1e-5 deg: half a unit of its last digit.
constexpr double kDeclinationTolDeg = 0.5e-5;
// Table A5.1's E = 14.641503 min is 8e-6 min from eq. A1 with the table's own inputs
// (data/test_vectors/PROVENANCE_reda_andreas_2008_tables.md).
constexpr double kEquationOfTimeTolMin = 1e-5;

// `sun --json`'s angles as the flags that give them to render and eval.
std::string sun_angle_flags(const nlohmann::json& sun) {
  return "--sun-zenith " + sun.at("zenith_deg").dump() + " --sun-azimuth " +
         sun.at("azimuth_deg").dump();
}

TEST_F(Cli, SunWorkedExampleAsJson) {
  const testing_support::CliResult r = run("sun " + kExampleFlags + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j.at("zenith_deg").get<double>(), 50.111622, kExampleAngleTolDeg);
  EXPECT_NEAR(j.at("azimuth_deg").get<double>(), 194.340241, kExampleAngleTolDeg);
  EXPECT_NEAR(j.at("elevation_deg").get<double>(), 90.0 - 50.111622, kExampleAngleTolDeg);
  // Table A5.1: delta = -9.31434 deg, E = 14.641503 min (to the table's last digits).
  EXPECT_NEAR(j.at("declination_deg").get<double>(), -9.31434, kDeclinationTolDeg);
  EXPECT_NEAR(j.at("equation_of_time_min").get<double>(), 14.641503, kEquationOfTimeTolMin);
  // The local day's events (docs/SUN.md: the published "sunset 17:20:19" is the 16th's).
  EXPECT_EQ(j.at("sunrise"), "2003-10-17T06:12:43-07:00");
  EXPECT_EQ(j.at("transit"), "2003-10-17T11:46:05-07:00");
  EXPECT_EQ(j.at("sunset"), "2003-10-17T17:18:52-07:00");
  EXPECT_TRUE(j.at("polar").is_null());
  // The inputs are echoed.
  EXPECT_EQ(j.at("time"), "2003-10-17T12:30:30.000-07:00");
  EXPECT_EQ(j.at("lat_deg").get<double>(), 39.742476);
  EXPECT_EQ(j.at("lon_deg").get<double>(), -105.1786);
  EXPECT_EQ(j.at("elevation_m").get<double>(), 1830.14);
  EXPECT_EQ(j.at("pressure_mbar").get<double>(), 820.0);
  EXPECT_EQ(j.at("temperature_degC").get<double>(), 11.0);
  EXPECT_EQ(j.at("delta_t_s").get<double>(), 67.0);

  // The same instant in UTC gives the same position.
  const testing_support::CliResult u =
      run("sun --time 2003-10-17T19:30:30Z --lat 39.742476 --lon -105.1786 --elevation 1830.14 "
          "--pressure 820 --temperature 11 --delta-t 67 --json");
  ASSERT_EQ(u.status, 0) << u.err;
  const auto ju = nlohmann::json::parse(u.out);
  EXPECT_EQ(ju.at("zenith_deg"), j.at("zenith_deg"));
  EXPECT_EQ(ju.at("azimuth_deg"), j.at("azimuth_deg"));
}

TEST_F(Cli, SunTextOutput) {
  const testing_support::CliResult r = run("sun " + kExampleFlags);
  ASSERT_EQ(r.status, 0) << r.err;
  // The record's labelled lines, each value with its unit (the declared fields' decimals).
  using testing_support::text_field;
  EXPECT_EQ(text_field(r.out, "zenith"), "50.111622 deg") << r.out;
  EXPECT_EQ(text_field(r.out, "azimuth"), "194.340241 deg") << r.out;
  EXPECT_EQ(text_field(r.out, "sunrise"), "2003-10-17T06:12:43-07:00") << r.out;
  EXPECT_EQ(text_field(r.out, "polar"), "") << "a normal day has no polar line";
}

// The SPA's range, -2000 .. 6000, is reachable: years before 0 in ISO 8601's expanded form.
TEST_F(Cli, SunAcceptsTheWholeSpaRangeOfYears) {
  auto r = run("sun --time -2000-01-01T12:00:00Z --lat 0 --lon 0 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"time\": \"-2000-01-01T12:00:00.000Z\""), std::string::npos) << r.out;
  r = run("sun --time 6000-12-31T12:00:00Z --lat 0 --lon 0");
  EXPECT_EQ(r.status, 0) << r.err;
  r = run("sun --time -2001-12-31T12:00:00Z --lat 0 --lon 0");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("is out of range [-2000, 6000]"), std::string::npos) << r.err;
}

TEST_F(Cli, SunPolarNightHasNoSunriseOrSunset) {
  const testing_support::CliResult r =
      run("sun --time 2003-12-21T12:00:00+01:00 --lat 69.6492 --lon 18.9553 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j.at("sunrise").is_null());
  EXPECT_TRUE(j.at("sunset").is_null());
  EXPECT_EQ(j.at("polar"), "polar_night");
  EXPECT_FALSE(j.at("transit").is_null());
  EXPECT_GT(j.at("zenith_deg").get<double>(), 90.0);
}

TEST_F(Cli, SunBadInputsExitTwoWithOneLine) {
  struct Bad {
    std::string args;
    std::string says;  // must appear in the message
  };
  const std::string place = " --lat 39.7 --lon -105.2";
  const Bad bad[] = {
      {"--time 2003-10-17T12:30:30" + place, "UTC offset: missing"},
      {"--time 2003-10-17T12:30" + place, "seconds are required"},
      {"--time 2003-02-29T12:30:30Z" + place, "day: 29 is out of range"},
      {"--time 2003-10-17T25:30:30Z" + place, "hour: 25"},
      {"--time 'Oct 17 2003'" + place, "invalid ISO 8601 date-time"},
      {"--time 2003-10-17T12:30:30Z --lat 91 --lon 0", "--lat"},
      {"--time 2003-10-17T12:30:30Z --lat abc --lon 0", "--lat"},
      {"--time 2003-10-17T12:30:30Z --lat 40 --lon 181", "--lon"},
      {"--time 2003-10-17T12:30:30Z --lat 40 --lon 0 --pressure -5", "--pressure"},
      {"--time 2003-10-17T12:30:30Z --lon 0", "--lat"},
      {"--time 7000-01-01T00:00:00Z" + place, "[-2000, 6000]"},
  };
  for (const auto& b : bad) {
    const testing_support::CliResult r = run("sun " + b.args);
    EXPECT_EQ(r.status, 2) << b.args << ": " << r.err;
    EXPECT_NE(r.err.find(b.says), std::string::npos) << b.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << b.args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << b.args;
  }
}

TEST_F(Cli, RenderWithTimeEqualsRenderWithTheSameAngles) {
  const testing_support::CliResult s = run("sun " + kExampleFlags + " --json");
  ASSERT_EQ(s.status, 0) << s.err;
  const auto j = nlohmann::json::parse(s.out);
  const std::string angles = sun_angle_flags(j);
  const fs::path a = dir_ / "time.exr", b = dir_ / "angles.exr";
  const std::string common = "render --model preetham --turbidity 3 --width 48 --height 24 ";
  const testing_support::CliResult ra = run(common + kExampleFlags + " -o '" + a.string() + "'");
  ASSERT_EQ(ra.status, 0) << ra.err;
  const testing_support::CliResult rb = run(common + angles + " -o '" + b.string() + "'");
  ASSERT_EQ(rb.status, 0) << rb.err;
  const io::ImageF ia = io::read_image(a), ib = io::read_image(b);
  ASSERT_EQ(ia.data.size(), ib.data.size());
  double max_rel = 0.0;
  for (std::size_t i = 0; i < ia.data.size(); ++i) {
    const double d = std::abs(static_cast<double>(ia.data[i]) - ib.data[i]);
    max_rel = std::max(max_rel, d / std::max(1e-30, std::abs(static_cast<double>(ib.data[i]))));
  }
  EXPECT_LE(max_rel, kTimeVsAnglesRelTol);
  // The time and place are recorded.
  const auto md = io::read_exr_metadata(a);
  using testing_support::metadata_value;
  EXPECT_EQ(metadata_value(md, "skylight:time"), "2003-10-17T12:30:30.000-07:00");
  EXPECT_EQ(metadata_value(md, "skylight:latitude_deg"), "39.742476");
  EXPECT_EQ(metadata_value(md, "skylight:longitude_deg"), "-105.1786");
  EXPECT_EQ(metadata_value(md, "skylight:sun_zenith_deg"), j.at("zenith_deg").dump());
}

TEST_F(Cli, EvalWithTimeEqualsEvalWithTheSameAngles) {
  const testing_support::CliResult s = run("sun " + kExampleFlags + " --json");
  ASSERT_EQ(s.status, 0) << s.err;
  const auto j = nlohmann::json::parse(s.out);
  const std::string angles = sun_angle_flags(j);
  const std::string input = "zenith_deg,azimuth_deg\n0,0\n30,200\n60,90\n85,300\n";
  const std::string common = "eval --model hosek --turbidity 4 --quantity xyz ";
  const testing_support::CliResult ea = run(common + kExampleFlags, input);
  ASSERT_EQ(ea.status, 0) << ea.err;
  const testing_support::CliResult eb = run(common + angles, input);
  ASSERT_EQ(eb.status, 0) << eb.err;
  std::string ha, hb;
  const auto va = parse_csv_numbers(ea.out, &ha), vb = parse_csv_numbers(eb.out, &hb);
  ASSERT_EQ(va.size(), 4u);
  ASSERT_EQ(va.size(), vb.size());
  for (std::size_t r = 0; r < va.size(); ++r)
    for (std::size_t c = 0; c < va[r].size(); ++c)
      EXPECT_NEAR(va[r][c], vb[r][c], kTimeVsAnglesRelTol * std::abs(vb[r][c])) << r << "," << c;
}

TEST_F(Cli, TimeExcludesSunAnglesAndNeedsAPlace) {
  const std::string model = "eval --model preetham ";
  const std::string input = "zenith_deg,azimuth_deg\n0,0\n";
  for (const std::string& args :
       {model + "--time 2003-10-17T12:30:30Z --lat 40 --lon 0 --sun-zenith 30",
        model + "--time 2003-10-17T12:30:30Z --lat 40 --lon 0 --sun-elevation 30",
        model + "--time 2003-10-17T12:30:30Z --lat 40 --lon 0 --sun-azimuth 30",
        model + "--lat 40 --lon 0", model + "--time 2003-10-17T12:30:30Z --lat 40",
        model + "--time 2003-10-17T12:30:30 --lat 40 --lon 0"}) {
    const testing_support::CliResult r = run(args, input);
    EXPECT_EQ(r.status, 2) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
  }
}

}  // namespace
}  // namespace skylight
