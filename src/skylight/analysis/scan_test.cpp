#include "skylight/analysis/scan.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <string_view>

#include "skylight/core/error.h"

#include "skylight/core/data.h"
#include "skylight/models/sky_model.h"
#include "support/error_message.h"

namespace skylight::analysis {
namespace {

// The same sky compared with itself: exactly 0 (same numbers); allow last-bit noise of log10.
constexpr double kScanSelfRmsTol = 1e-12;
// log10(1 +- 0.05): the largest |d| the synthetic scan's noise can produce against its own sky.
const double kNoiseLog10Bound = std::log10(1.0 / 0.95);

std::string error_of(std::string_view text) {
  return testing_support::error_message([&] { parse_sky_scan(text, "scan.csv"); });
}

TEST(Scan, ParsesSunCommentsAndRows) {
  const auto s = parse_sky_scan(
      "# a free comment\n# sun_azimuth_deg = -90\n# sun_elevation_deg = 35\r\n"
      "elevation_deg,azimuth_deg,luminance_cd_m2,extra\n\n6,0,1000,x\n90, 370e-1 ,2.5e4,y\n",
      "scan.csv");
  ASSERT_EQ(s.samples.size(), 2u);
  ASSERT_TRUE(s.sun_azimuth && s.sun_elevation);
  EXPECT_NEAR(*s.sun_azimuth, deg_to_rad(270.0), 1e-12);  // wrapped into [0, 2 pi)
  EXPECT_NEAR(*s.sun_elevation, deg_to_rad(35.0), 1e-12);
  EXPECT_NEAR(s.samples[1].azimuth, deg_to_rad(37.0), 1e-12);
  EXPECT_NEAR(s.samples[1].elevation, kPi / 2, 1e-12);
  EXPECT_EQ(s.samples[1].luminance, 2.5e4);
  EXPECT_EQ(s.samples[0].line, 6u);
}

TEST(Scan, BadInputNamesFileLineAndColumn) {
  const std::string head = "azimuth_deg,elevation_deg,luminance_cd_m2\n";
  EXPECT_NE(error_of(head + "0,6,100\n12,abc,100\n")
                .find("scan.csv line 3 column 2: 'abc' is not a number"),
            std::string::npos);
  // An elevation of 1e-400 is in range once rounded, but the literal underflows: said so.
  EXPECT_NE(error_of(head + "0,1e-400,100\n")
                .find("scan.csv line 2 column 2: '1e-400' underflows to 0 (the smallest non-zero "
                      "number is 4.94e-324)"),
            std::string::npos);
  EXPECT_NE(error_of(head + "0,6,nan\n").find("scan.csv line 2 column 3: 'nan'"),
            std::string::npos);
  EXPECT_NE(error_of(head + "0,6,inf\n").find("scan.csv line 2 column 3"), std::string::npos);
  EXPECT_NE(error_of(head + "0,6\n")
                .find("scan.csv line 2: expected 3 comma-separated fields, "
                      "found 2"),
            std::string::npos);
  EXPECT_NE(error_of("azimuth_deg,luminance_cd_m2\n0,100\n").find("no column 'elevation_deg'"),
            std::string::npos);
  EXPECT_NE(error_of(head + "0,95,100\n").find("scan.csv line 2 column 2: elevation_deg = 95"),
            std::string::npos);
  EXPECT_NE(error_of(head + "0,6,0\n").find("scan.csv line 2 column 3: luminance_cd_m2 = 0"),
            std::string::npos);
  EXPECT_NE(error_of("# sun_elevation_deg = high\n" + head + "0,6,1\n")
                .find("scan.csv line 1: sun_elevation_deg 'high' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of(head).find("scan.csv: no samples"), std::string::npos);
  EXPECT_NE(error_of("").find("scan.csv"), std::string::npos);
  EXPECT_THROW(read_sky_scan("/nonexistent/scan.csv"), IoError);
}

// Found by the fuzz target sky_scan (docs/TESTING.md): a bad sun comment was quoted whole, with
// its control characters, into the message.
TEST(Scan, BadSunCommentIsQuotedAsABoundedEscapedExcerpt) {
  const std::string message = error_of("# sun_azimuth_deg = \x01" + std::string(100000, '7') +
                                       "\nazimuth_deg,elevation_deg,luminance_cd_m2\n0,6,1\n");
  EXPECT_NE(message.find("scan.csv line 1: sun_azimuth_deg '\\x01777"), std::string::npos)
      << message;
  EXPECT_LT(message.size(), 200u);
}

TEST(Scan, TregenzaPatches) {
  const auto p = tregenza_patch_centres();
  ASSERT_EQ(p.size(), 145u);
  int band6 = 0, zenith = 0;
  for (const auto& c : p) {
    if (std::abs(c.elevation - deg_to_rad(6.0)) < 1e-12) ++band6;
    if (std::abs(c.elevation - kPi / 2) < 1e-12) ++zenith;
  }
  EXPECT_EQ(band6, 30);
  EXPECT_EQ(zenith, 1);
}

TEST(Scan, ShippedSyntheticScanIsReproducible) {
  const SyntheticScanSettings settings;
  const std::string text =
      format_sky_scan(synthetic_tregenza_scan(settings), synthetic_scan_comments(settings));
  // The embedded copy and the file in data/ are exactly what the generator writes.
  EXPECT_EQ(std::string(data::embedded_file(kSyntheticScanDataPath)), text);
  std::ifstream f(std::string(SKYLIGHT_TEST_DATA_DIR) + "/" + std::string(kSyntheticScanDataPath),
                  std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  EXPECT_EQ(ss.str(), text);
}

TEST(Scan, ErrorsAgainstTheGeneratingSky) {
  SyntheticScanSettings quiet;
  quiet.noise = 0.0;
  const SkyScan exact = synthetic_tregenza_scan(quiet);
  const SkyScan noisy = synthetic_tregenza_scan();
  SkyParameters p;
  p.values.set("cie-type", 7);
  p.sun = {kPi / 2 - quiet.sun_elevation, quiet.sun_azimuth};
  const auto sky = make_sky_model("cie", p);
  const ScanErrors e0 = compare_to_scan(*sky, exact, deg_to_rad(5.0));
  // The same sky, unrounded in memory: round-off only.
  EXPECT_NEAR(e0.rms_log10_absolute, 0.0, kScanSelfRmsTol);
  EXPECT_NEAR(e0.rms_log10_relative, 0.0, kScanSelfRmsTol);
  const ScanErrors e = compare_to_scan(*sky, noisy, deg_to_rad(5.0));
  EXPECT_EQ(e.samples_used, 145u);
  EXPECT_GT(e.rms_log10_absolute, 0.0);
  EXPECT_LT(e.rms_log10_absolute, kNoiseLog10Bound);
  EXPECT_LT(std::abs(e.bias_log10_absolute), kNoiseLog10Bound);
  // Another type is clearly worse.
  p.values.set("cie-type", 12);
  const auto clear = make_sky_model("cie", p);
  EXPECT_GT(compare_to_scan(*clear, noisy, deg_to_rad(5.0)).rms_log10_relative,
            5 * e.rms_log10_relative);
}
}  // namespace
}  // namespace skylight::analysis
