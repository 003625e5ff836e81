#include "skylight/sun/time.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "support/test_vectors.h"

namespace skylight::sun {
namespace {

using testing_support::cell_integer;
using testing_support::cell_number;

// Table A4.1 prints JD to 0.1 day, but every entry is an exact multiple of 0.1; the double JD
// near 2.4e6 has a resolution of 4.7e-10 day.
constexpr double kJdTol = 1e-8;
// A round trip JD -> civil time (rounded to 1 ms) -> JD: half a millisecond plus JD resolution.
constexpr double kRoundTripTolDay = 0.6e-3 / 86400.0;

TEST(Iso8601, ParsesOffsetsAndFractions) {
  const DateTime t = parse_iso8601("2003-10-17T12:30:30-07:00");
  EXPECT_EQ(t.year, 2003);
  EXPECT_EQ(t.month, 10);
  EXPECT_EQ(t.day, 17);
  EXPECT_EQ(t.hour, 12);
  EXPECT_EQ(t.minute, 30);
  EXPECT_EQ(t.second, 30.0);
  EXPECT_EQ(t.utc_offset_minutes, -420);
  EXPECT_EQ(parse_iso8601("2003-10-17T19:30:30Z").utc_offset_minutes, 0);
  EXPECT_EQ(parse_iso8601("2003-10-17T19:30:30+05:30").utc_offset_minutes, 330);
  EXPECT_EQ(parse_iso8601("2003-10-17T19:30:30-00:00").utc_offset_minutes, 0);
  EXPECT_EQ(parse_iso8601("2003-10-17T19:30:30.25Z").second, 30.25);
  EXPECT_NEAR(parse_iso8601("2003-10-17T19:30:59.123456789+14:00").second, 59.123456789, 1e-12);
  // The worked example of Reda & Andreas (A.5) is JD 2452930.312847 (UT 19:30:30).
  EXPECT_NEAR(julian_day(t), 2452930.312847222, kJdTol);
  EXPECT_EQ(julian_day(t), julian_day(parse_iso8601("2003-10-17T19:30:30Z")));
}

TEST(Iso8601, RejectsMalformedTextNamingTheField) {
  struct Bad {
    const char* text;
    const char* field;  // must appear in the message
  };
  const Bad bad[] = {
      {"", "year"},
      {"03-10-17T12:30:30Z", "year"},
      {"+203-10-17T12:30:30Z", "year"},
      {"--2003-10-17T12:30:30Z", "year"},
      {"2003/10/17T12:30:30Z", "date separator after year"},
      {"2003-1-17T12:30:30Z", "month"},
      {"2003-13-17T12:30:30Z", "month: 13 is out of range"},
      {"2003-00-17T12:30:30Z", "month"},
      {"2003-02-29T12:30:30Z", "day: 29 is out of range [01, 28]"},
      {"2003-04-31T12:30:30Z", "day: 31"},
      {"1582-10-10T12:00:00Z", "day: 1582-10-05 .. 1582-10-14 do not exist"},
      {"2003-10-17 12:30:30Z", "date/time separator"},
      {"2003-10-17t12:30:30Z", "date/time separator"},
      {"2003-10-17", "date/time separator"},
      {"2003-10-17T24:00:00Z", "hour: 24"},
      {"2003-10-17T12:60:00Z", "minute: 60"},
      {"2003-10-17T12:30Z", "seconds are required"},
      {"2003-10-17T12:30:60Z", "second: 60"},
      {"2003-10-17T12:30:3Z", "second"},
      {"2003-10-17T12:30:30.Z", "fraction of second"},
      {"2003-10-17T12:30:30,5Z", "fraction of second"},
      {"2003-10-17T12:30:30.1234567890Z", "fraction of second: more than 9 digits"},
      {"2003-10-17T12:30:30", "UTC offset: missing"},
      {"2003-10-17T12:30:30z", "UTC offset"},
      {"2003-10-17T12:30:30+0530", "UTC offset separator"},
      {"2003-10-17T12:30:30+05", "UTC offset separator"},
      {"2003-10-17T12:30:30+5:30", "UTC offset hours"},
      {"2003-10-17T12:30:30+05:60", "UTC offset minutes: 60"},
      {"2003-10-17T12:30:30+19:00", "UTC offset: +19:00 is beyond +-18:00"},
      {"2003-10-17T12:30:30-18:01", "UTC offset: -18:01 is beyond +-18:00"},
      {"2003-10-17T12:30:30Z ", "end"},
      {"2003-10-17T12:30:30-07:00x", "end"},
      {" 2003-10-17T12:30:30Z", "year"},
      {"2003-10-17T12:30:30\n", "UTC offset"},
  };
  for (const auto& b : bad) {
    try {
      parse_iso8601(b.text);
      ADD_FAILURE() << "accepted: " << b.text;
    } catch (const InvalidArgument& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(b.field), std::string::npos) << b.text << " -> " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
      EXPECT_EQ(msg.rfind("invalid ISO 8601 date-time", 0), 0u) << msg;
    }
  }
}

TEST(Iso8601, CalendarOfThePaper) {
  // Julian leap rule before 1582 (eq. 4, Table A4.1 has -1000-02-29), Gregorian from 1582 on.
  EXPECT_NO_THROW(parse_iso8601("1000-02-29T00:00:00Z"));
  EXPECT_NO_THROW(parse_iso8601("2000-02-29T00:00:00Z"));
  EXPECT_THROW(parse_iso8601("1900-02-29T00:00:00Z"), InvalidArgument);
  // 1582-10-04 (Julian) is followed by 1582-10-15 (Gregorian).
  EXPECT_EQ(julian_day(parse_iso8601("1582-10-15T00:00:00Z")) -
                julian_day(parse_iso8601("1582-10-04T00:00:00Z")),
            1.0);
}

TEST(Iso8601, FormatsRoundTripAndCarries) {
  for (const char* s :
       {"2003-10-17T06:12:43-07:00", "2003-10-17T19:30:30Z", "1999-12-31T23:59:59+05:30",
        "0001-01-01T00:00:00-12:00", "9999-12-31T23:59:59+14:00"}) {
    EXPECT_EQ(format_iso8601(parse_iso8601(s)), s);
  }
  EXPECT_EQ(format_iso8601(parse_iso8601("2003-10-17T12:30:30.125Z"), 3),
            "2003-10-17T12:30:30.125Z");
  EXPECT_EQ(format_iso8601(parse_iso8601("2003-10-17T12:30:30.4Z")), "2003-10-17T12:30:30Z");
  EXPECT_EQ(format_iso8601(parse_iso8601("2003-10-17T12:30:30.6Z")), "2003-10-17T12:30:31Z");
  // Rounding up to 60 s carries into the minute, hour, day, month and year ...
  EXPECT_EQ(format_iso8601(parse_iso8601("2003-12-31T23:59:59.9996-03:00"), 3),
            "2004-01-01T00:00:00.000-03:00");
  EXPECT_EQ(format_iso8601(parse_iso8601("2004-02-28T23:59:59.5Z")), "2004-02-29T00:00:00Z");
  // ... and across the calendar reform.
  EXPECT_EQ(format_iso8601(parse_iso8601("1582-10-04T23:59:59.5Z")), "1582-10-15T00:00:00Z");
  // Expanded years (astronomical numbering): the SPA's range reaches -2000.
  EXPECT_EQ(parse_iso8601("-2000-01-01T12:00:00Z").year, -2000);
  EXPECT_EQ(parse_iso8601("+2003-10-17T12:30:30Z").year, 2003);
  EXPECT_EQ(format_iso8601(parse_iso8601("-2000-02-29T12:00:00Z")), "-2000-02-29T12:00:00Z");
  EXPECT_EQ(format_iso8601(parse_iso8601("0000-12-31T23:59:59.5Z")), "0001-01-01T00:00:00Z");
  // Found by the fuzz target iso8601: an expanded year before -4712 (Julian Day 0) was accepted
  // and then failed validate(); the parser refuses it, naming the field.
  EXPECT_EQ(parse_iso8601("-4712-01-01T12:00:00Z").year, -4712);
  try {
    parse_iso8601("-6025-02-21T12:00:00Z");
    ADD_FAILURE() << "accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("year"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("[-4712, 9999]"), std::string::npos) << e.what();
  }
  DateTime t;
  t.year = -10000;
  EXPECT_THROW(format_iso8601(t), InvalidArgument);
  t.year = 2000;
  t.second = std::nan("");
  EXPECT_THROW(format_iso8601(t), InvalidArgument);
  EXPECT_THROW(format_iso8601(DateTime{}, 10), InvalidArgument);
}

TEST(JulianDay, PaperTableA41) {
  const auto rows =
      testing_support::read_test_vector_csv("reda_andreas_2008_table_a4_1_julian_day.csv");
  ASSERT_EQ(rows.size(), 16u);
  for (const auto& r : rows) {
    const int year = cell_integer(r.at(0)), month = cell_integer(r.at(1)),
              day = cell_integer(r.at(2));
    const int h = cell_integer(r.at(3).substr(0, 2)), m = cell_integer(r.at(3).substr(3, 2));
    const double jd = cell_number(r.at(4));
    EXPECT_NEAR(julian_day(year, month, day + (h + m / 60.0) / 24.0), jd, kJdTol)
        << year << "-" << month << "-" << day;
    // Calendar date from JD (A.3) inverts it.
    const DateTime t = date_time_from_julian_day(jd, 0);
    EXPECT_EQ(t.year, year);
    EXPECT_EQ(t.month, month);
    EXPECT_EQ(t.day, day);
    EXPECT_EQ(t.hour, h);
    EXPECT_EQ(t.minute, m);
    EXPECT_EQ(t.second, 0.0);
    DateTime with_fields = t;
    EXPECT_NEAR(julian_day(with_fields), jd, kJdTol);
  }
}

TEST(JulianDay, LocalTimeAndRoundTrip) {
  // 12:30:30 at UTC-7 is 19:30:30 UT; at UTC+05:30 the local date can be the next day.
  const double jd = julian_day(parse_iso8601("2003-10-17T19:30:30Z"));
  EXPECT_EQ(format_iso8601(date_time_from_julian_day(jd, -420)), "2003-10-17T12:30:30-07:00");
  EXPECT_EQ(format_iso8601(date_time_from_julian_day(jd, 330)), "2003-10-18T01:00:30+05:30");
  // Rounding never shows 60 s: 23:59:59.9996 at 3 decimals is the next day.
  const double late = julian_day(parse_iso8601("2003-12-31T23:59:59.9996Z"));
  EXPECT_EQ(format_iso8601(date_time_from_julian_day(late, 0, 3), 3), "2004-01-01T00:00:00.000Z");
  // Delta UT1 is added to UTC (eq. 3).
  EXPECT_NEAR((julian_day(parse_iso8601("2003-10-17T19:30:30Z"), 0.5) - jd) * 86400.0, 0.5, 1e-4);

  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    const double j = 1.0 + 5e6 * u(rng);  // years -4710 .. 8977
    const int offset = static_cast<int>(std::lround((u(rng) - 0.5) * 2 * 840));
    const DateTime t = date_time_from_julian_day(j, offset, 3);
    EXPECT_NO_THROW(validate(t)) << j;
    EXPECT_NEAR(julian_day(t), j, kRoundTripTolDay) << j;
  }
  EXPECT_THROW(date_time_from_julian_day(-1.0, 0), InvalidArgument);
  EXPECT_THROW(date_time_from_julian_day(std::nan(""), 0), InvalidArgument);
  EXPECT_THROW(date_time_from_julian_day(jd, 2000), InvalidArgument);
}

TEST(DateTimeFields, ValidateNamesTheField) {
  DateTime t;
  t.minute = 61;
  try {
    validate(t, "start");
    ADD_FAILURE();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "start.minute = 61 is out of range [0, 59]");
  }
  t = DateTime{};
  t.utc_offset_minutes = -1200;
  EXPECT_THROW(validate(t), InvalidArgument);
  t = DateTime{};
  t.second = 60.0;
  EXPECT_THROW(validate(t), InvalidArgument);
  EXPECT_EQ(days_in_month(1582, 10), 31);
  EXPECT_EQ(days_in_month(-1000, 2), 29);
  EXPECT_EQ(days_in_month(2100, 2), 28);
}

}  // namespace
}  // namespace skylight::sun

namespace skylight::sun {
namespace {

TEST(DayOfYear, CountsTheLocalDateInTheCalendarInUse) {
  EXPECT_EQ(day_of_year(parse_iso8601("2023-01-01T00:00:00Z")), 1);
  EXPECT_EQ(day_of_year(parse_iso8601("2023-12-31T23:59:59Z")), 365);
  EXPECT_EQ(day_of_year(parse_iso8601("2024-12-31T12:00:00Z")), 366);      // leap year
  EXPECT_EQ(day_of_year(parse_iso8601("2024-03-01T00:30:00+02:00")), 61);  // the local date
  EXPECT_EQ(day_of_year(parse_iso8601("1900-03-01T00:00:00Z")), 60);       // not a leap year
  // 1582: October 5-14 do not exist, so October 15 is day 278, not 288.
  EXPECT_EQ(day_of_year(parse_iso8601("1582-10-04T00:00:00Z")), 277);
  EXPECT_EQ(day_of_year(parse_iso8601("1582-10-15T00:00:00Z")), 278);
  EXPECT_EQ(day_of_year(parse_iso8601("1582-12-31T00:00:00Z")), 355);
}

}  // namespace
}  // namespace skylight::sun
