#include "skylight/io/directions.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "support/error_message.h"

namespace skylight::io {
namespace {

// deg_to_rad of the same literal: exact up to the last bit of the conversion.
constexpr double kAngleTol = 1e-15;

std::string error_of(std::string_view text) {
  return testing_support::error_message([&] { parse_directions_csv(text, "dirs.csv"); });
}

TEST(Directions, ParsesRowsWithLineNumbersAndWrapsTheAzimuth) {
  const std::string text = "zenith_deg,azimuth_deg\r\n0,0\n\n90,-90\r\n180,360\n";
  const auto rows = parse_directions_csv(text, "dirs.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].line, 2u);
  EXPECT_EQ(rows[1].line, 4u);        // the blank line 3 is skipped but counted
  EXPECT_EQ(rows[1].text, "90,-90");  // CR removed
  EXPECT_NEAR(rows[1].zenith, kPi / 2, kAngleTol);
  EXPECT_NEAR(rows[1].azimuth, 1.5 * kPi, kAngleTol);  // -90 deg wrapped
  EXPECT_NEAR(rows[2].zenith, kPi, kAngleTol);
  EXPECT_EQ(rows[2].azimuth, 0.0);  // 360 deg wraps to 0
  EXPECT_TRUE(parse_directions_csv("zenith_deg,azimuth_deg\n", "dirs.csv").empty());
}

TEST(Directions, BadInputNamesSourceLineAndField) {
  const std::string head = "zenith_deg,azimuth_deg\n";
  EXPECT_EQ(error_of(""), "dirs.csv: empty input, expected header 'zenith_deg,azimuth_deg'");
  EXPECT_EQ(error_of("zen,az\n0,0\n"),
            "dirs.csv line 1: header must be 'zenith_deg,azimuth_deg', got 'zen,az'");
  EXPECT_EQ(error_of(head + "1,2,3\n"),
            "dirs.csv line 2: expected 2 fields 'zenith_deg,azimuth_deg', got '1,2,3'");
  EXPECT_EQ(error_of(head + "nan,0\n"), "dirs.csv line 2: zenith_deg 'nan' is not a number");
  EXPECT_EQ(error_of(head + "0,1e999\n"),
            "dirs.csv line 2: azimuth_deg '1e999' overflows (the largest number is 1.8e+308)");
  // A literal that underflows is named as such, not "not a number" (it is one, too small).
  EXPECT_EQ(error_of(head + "1e-400,0\n"),
            "dirs.csv line 2: zenith_deg '1e-400' underflows to 0 (the smallest non-zero number "
            "is 4.94e-324)");
  EXPECT_EQ(error_of(head + "180.5,0\n"),
            "dirs.csv line 2: zenith_deg = 180.5 is outside [0, 180]");
  EXPECT_EQ(error_of(head + "0,-360.1\n"),
            "dirs.csv line 2: azimuth_deg = -360.1 is outside [-360, 360]");
  // Untrusted text is quoted as a bounded, escaped excerpt.
  const std::string message = error_of(head + "1\x01" + std::string(10000, '9') + ",0\n");
  EXPECT_LT(message.size(), 200u);
  EXPECT_NE(message.find("\\x01"), std::string::npos);
}

}  // namespace
}  // namespace skylight::io
