// Civil date-times for the solar position code: a strict ISO 8601 parser and formatter, and the
// calendar <-> Julian Day conversions of Reda & Andreas 2004 (eq. 4 and Appendix A.3).
//
// Calendar: as in the paper (and Meeus 1998, ch. 7), dates from 1582-10-15 on are Gregorian and
// earlier dates are Julian-calendar dates; 1582-10-05 .. 1582-10-14 do not exist. (ISO 8601 itself
// would use the proleptic Gregorian calendar before 1582; the two agree from 1582-10-15 on.)
// Leap seconds are not representable (second < 60).
#pragma once

#include <string>
#include <string_view>

namespace skylight::sun {

// A civil date and time of day with its offset from UTC, as written in ISO 8601. With
// utc_offset_minutes = 0 it is UTC.
struct DateTime {
  int year = 2000;             // astronomical year numbering (0 = 1 BC); [-4712, 9999]
  int month = 1;               // [1, 12]
  int day = 1;                 // [1, days_in_month(year, month)]
  int hour = 0;                // [0, 23]
  int minute = 0;              // [0, 59]
  double second = 0.0;         // [0, 60), with fraction
  int utc_offset_minutes = 0;  // local time minus UTC [min]; [-1080, 1080] (i.e. +-18:00)
};

// Leap year in the calendar in use (Julian rule before 1582, Gregorian from 1582 on).
bool is_leap_year(int year);
// Days in the month in the calendar in use; 31 for October 1582 (days 5..14 do not exist).
int days_in_month(int year, int month);

// The day of the year (1 .. 366) of the date as written (local civil date, not UTC's).
int day_of_year(const DateTime& t);

// Throws InvalidArgument naming the first field that is NaN or out of range (message:
// "<name>.<field> = <value> is out of range ...").
void validate(const DateTime& t, std::string_view name = "time");

// Strict ISO 8601 / RFC 3339 date-time: [+-]YYYY-MM-DDThh:mm:ss[.f](Z|+hh:mm|-hh:mm), with 1 to 9
// fraction digits; a signed year is ISO 8601's expanded form with 4 digits, astronomical
// numbering (0000 = 1 BC, -2000 = 2001 BC). Everything else (missing seconds or offset, lower-case
// 't'/'z', space instead of 'T', basic format, 24:00:00, leap second 60, nonexistent dates,
// trailing text) throws InvalidArgument with a one-line message naming the offending field.
DateTime parse_iso8601(std::string_view text);

// YYYY-MM-DDThh:mm:ss[.fff](Z|+hh:mm|-hh:mm), the seconds rounded to fraction_digits (0..9)
// decimals (a carry into the next minute, day, month or year is propagated). UTC is written as
// "Z"; a year before 0 with a '-' (expanded form). Throws InvalidArgument if the fields are
// invalid or the year is outside -9999..9999.
std::string format_iso8601(const DateTime& t, int fraction_digits = 0);

// Julian Day of the calendar date `year`-`month` at day-of-month `day` with the time of day as
// its fraction (D of eq. 4, e.g. 2.521180556 for the 2nd at 12:30:30), Reda & Andreas eq. (4).
// `day` may lie outside the month (local-time and Delta UT1 corrections are simply added to it,
// as in the paper, 3.1.1). Valid for JD >= 0 (from -4712-01-01T12:00).
double julian_day(int year, int month, double day);

// Julian Day (UT) of a civil date-time: eq. (4) with D = day + UT time of day, where
// UT = local time - utc_offset + delta_ut1 (eq. 3: UT = UTC + Delta UT1) [delta_ut1 in s].
double julian_day(const DateTime& t, double delta_ut1 = 0.0);

// Civil date-time at UTC offset `utc_offset_minutes` of the Julian Day `jd` (UT), Reda & Andreas
// App. A.3 (eqs. A15-A23), the seconds rounded to `fraction_digits` decimals (0..9) before the
// date is split off, so that the result never shows second = 60. Needs jd >= 0.
DateTime date_time_from_julian_day(double jd, int utc_offset_minutes, int fraction_digits = 0);

}  // namespace skylight::sun
