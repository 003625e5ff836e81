#include "skylight/io/epw.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "support/error_message.h"

namespace skylight::io {
namespace {

// The 8 header lines of a small EPW (a location at 48.1 N, 11.6 E, UTC+1, 520 m).
constexpr std::string_view kEpwHeader =
    "LOCATION,Munich,BY,DEU,Synthetic,108660,48.10,11.60,1.0,520.0\n"
    "DESIGN CONDITIONS,0\n"
    "TYPICAL/EXTREME PERIODS,0\n"
    "GROUND TEMPERATURES,0\n"
    "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\n"
    "COMMENTS 1,a test file\n"
    "COMMENTS 2,\n"
    "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";

// One record with the given hour, dew point and radiation (Wh/m^2); the other fields as typical
// files write them, the present-weather codes with their leading apostrophe.
std::string record(int month, int day, int hour, std::string_view dew, std::string_view ghi,
                   std::string_view dni, std::string_view dhi,
                   std::string_view dhi_lux = "999999") {
  return fmt::format(
      "2005,{},{},{},60,?9?9?9?9E0?9?9?9*9*9?9?9?9?9?9?9?9?9*_*9*9*9*9*9,12.5,{},60,95500,1200,"
      "1415,"
      "330,{},{},{},50000,60000,{},2000,180,2.1,5,3,20.0,1500,9,'999999999,15,0.1000,0,88,0.20,0.0,"
      "1.0\n",
      month, day, hour, dew, ghi, dni, dhi, dhi_lux);
}

std::string epw_error_of(std::string_view text) {
  return testing_support::error_message([&] { parse_epw(text, "w.epw"); });
}

TEST(Epw, ReadsLocationAndTheFieldsSkylightUses) {
  const std::string text = std::string(kEpwHeader) + record(6, 21, 13, "8.5", "850", "700", "150") +
                           record(6, 21, 14, "99.9", "", "9999", "120", "15500") + "\r\n";
  const EpwFile f = parse_epw(text, "w.epw");
  EXPECT_EQ(f.location.city, "Munich");
  EXPECT_EQ(f.location.wmo, "108660");
  EXPECT_DOUBLE_EQ(f.location.latitude_deg, 48.1);
  EXPECT_DOUBLE_EQ(f.location.longitude_deg, 11.6);
  EXPECT_DOUBLE_EQ(f.location.time_zone_h, 1.0);
  EXPECT_DOUBLE_EQ(f.location.elevation_m, 520.0);
  ASSERT_EQ(f.records.size(), 2u);
  const EpwRecord& a = f.records[0];
  EXPECT_EQ(a.line, 9u);
  EXPECT_EQ(a.year, 2005);
  EXPECT_EQ(a.month, 6);
  EXPECT_EQ(a.day, 21);
  EXPECT_EQ(a.hour, 13);
  EXPECT_EQ(a.minute, 60);
  EXPECT_EQ(a.dry_bulb_c, 12.5);
  EXPECT_EQ(a.dew_point_c, 8.5);
  EXPECT_EQ(a.pressure_pa, 95500.0);
  EXPECT_EQ(a.global_horizontal_wh_m2, 850.0);
  EXPECT_EQ(a.direct_normal_wh_m2, 700.0);
  EXPECT_EQ(a.diffuse_horizontal_wh_m2, 150.0);
  EXPECT_EQ(a.global_horizontal_lux, 50000.0);
  EXPECT_EQ(a.direct_normal_lux, 60000.0);
  EXPECT_FALSE(a.diffuse_horizontal_lux.has_value());  // 999999: missing
  EXPECT_EQ(a.zenith_luminance_cd_m2, 2000.0);
  EXPECT_EQ(a.precipitable_water_mm, 15.0);
  EXPECT_EQ(a.albedo, 0.2);
  // Missing markers and an empty field.
  const EpwRecord& b = f.records[1];
  EXPECT_FALSE(b.dew_point_c.has_value());              // 99.9
  EXPECT_FALSE(b.global_horizontal_wh_m2.has_value());  // empty
  EXPECT_FALSE(b.direct_normal_wh_m2.has_value());      // 9999
  EXPECT_EQ(b.diffuse_horizontal_lux, 15500.0);
}

TEST(Epw, BadInputNamesLineAndField) {
  const std::string head(kEpwHeader);
  EXPECT_EQ(epw_error_of(""),
            "w.epw: ends after 0 lines, before the 8 header lines and the records");
  EXPECT_EQ(epw_error_of(head), "w.epw: no records after the 8 header lines");
  EXPECT_EQ(epw_error_of("LOCATION,a,b,c,d,e,1,2,3\n"),
            "w.epw line 1: LOCATION needs 10 fields (LOCATION, city, state, country, source, "
            "WMO, latitude, longitude, time zone, elevation), got 9");
  EXPECT_EQ(epw_error_of("LOCATION,a,b,c,d,e,91,2,3,4\n"),
            "w.epw line 1: field 7 (latitude) = 91 is outside [-90, 90]");
  EXPECT_EQ(epw_error_of("LOCATION,a,b,c,d,e,45,2,3,4\nDESIGN CONDITIONS\nGROUND TEMPERATURES\n"),
            "w.epw line 3: header line 3 must start with 'TYPICAL/EXTREME PERIODS', got 'GROUND "
            "TEMPERATURES'");
  EXPECT_EQ(epw_error_of(head + "2005,1,1\n"), "w.epw line 9: a record needs 35 fields, got 3");
  EXPECT_EQ(epw_error_of(head + record(13, 1, 1, "1", "0", "0", "0")),
            "w.epw line 9: field 2 (month) = 13 is outside [1, 12]");
  EXPECT_EQ(epw_error_of(head + record(1, 1, 0, "1", "0", "0", "0")),
            "w.epw line 9: field 4 (hour) = 0 is outside [1, 24]");
  EXPECT_EQ(epw_error_of(head + record(1, 1, 1, "1", "0", "abc", "0")),
            "w.epw line 9: field 15 (direct normal radiation) 'abc' is not a number");
  EXPECT_EQ(epw_error_of(head + record(1, 1, 1, "1", "0", "0", "-5")),
            "w.epw line 9: field 16 (diffuse horizontal radiation) = -5 is below 0");
  EXPECT_EQ(epw_error_of(head + record(1, 1, 1, "-80", "0", "0", "0")),
            "w.epw line 9: field 8 (dew point temperature) = -80 is outside [-70, 70]");
}

}  // namespace
}  // namespace skylight::io
