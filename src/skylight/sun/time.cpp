#include "skylight/sun/time.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"

namespace skylight::sun {
namespace {

// The Julian calendar ends on 1582-10-04 (JD 2299160, at noon) and the Gregorian calendar starts
// on 1582-10-15 (Reda & Andreas 2004, 3.1).
constexpr int kReformYear = 1582;
constexpr int kReformMonth = 10;
constexpr int kFirstMissingDay = 5;
constexpr int kFirstGregorianDay = 15;
constexpr double kGregorianJd = 2299160.0;  // eq. (4): B = 0 below, Gregorian B above
constexpr double kGregorianZ = 2299161.0;   // App. A.3.2

constexpr int kMinYear = -4712;  // JD 0 is -4712-01-01T12:00 UT
constexpr int kMaxYear = 9999;
constexpr int kMaxOffsetMinutes = 18 * 60;
constexpr int kMaxFractionDigits = 9;

bool in_reform_gap(int year, int month, int day) {
  return year == kReformYear && month == kReformMonth && day >= kFirstMissingDay &&
         day < kFirstGregorianDay;
}

long long pow10(int n) {
  long long p = 1;
  for (int i = 0; i < n; ++i) p *= 10;
  return p;
}

[[noreturn]] void out_of_range(std::string_view name, const char* field, const std::string& value,
                               const std::string& range) {
  throw InvalidArgument(std::string(name) + "." + field + " = " + value + " is out of range " +
                        range);
}

// One character as it may appear inside a one-line message.
std::string shown(char c) {
  return (c >= 0x20 && c < 0x7f) ? std::string("'") + c + "'"
                                 : std::string("a control or non-ASCII byte");
}

// Strict left-to-right reader of one ISO 8601 date-time; every failure names the field.
class Iso8601Reader {
 public:
  explicit Iso8601Reader(std::string_view text) : text_(text) {}

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InvalidArgument("invalid ISO 8601 date-time '" + excerpt(text_) + "': " + field + ": " +
                          problem);
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return at_end() ? '\0' : text_[pos_]; }
  std::size_t pos() const { return pos_; }

  // Exactly `n` ASCII digits (no sign, no spaces), read with the strict integer parser.
  int digits(int n, const std::string& field) {
    for (int i = 0; i < n; ++i) {
      const std::size_t at = pos_ + static_cast<std::size_t>(i);
      const char c = at < text_.size() ? text_[at] : '\0';
      if (c < '0' || c > '9') {
        fail(field, "expected " + std::to_string(n) + " digits at position " +
                        std::to_string(at + 1) +
                        (at >= text_.size() ? " (end of text)" : ", found " + shown(c)));
      }
    }
    const int value =
        static_cast<int>(parse_integer(text_.substr(pos_, static_cast<std::size_t>(n)), field));
    pos_ += static_cast<std::size_t>(n);
    return value;
  }

  void expect(char separator, const std::string& field) {
    if (peek() != separator) {
      fail(field, std::string("expected '") + separator + "' at position " +
                      std::to_string(pos_ + 1) +
                      (at_end() ? " (end of text)" : ", found " + shown(peek())));
    }
    ++pos_;
  }

  void skip() { ++pos_; }
  // The text from `from` up to the current position.
  std::string_view since(std::size_t from) const { return text_.substr(from, pos_ - from); }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

// The fraction of a second after the '.' at the reader's position: 1 to 9 digits.
double fraction_of_second(Iso8601Reader& in) {
  in.skip();
  const std::size_t first = in.pos();
  int n = 0;
  while (in.peek() >= '0' && in.peek() <= '9') {
    if (++n > kMaxFractionDigits) in.fail("fraction of second", "more than 9 digits");
    in.skip();
  }
  if (n == 0) in.fail("fraction of second", "expected digits after '.'");
  const long long fraction = parse_integer(in.since(first), "fraction of second");
  return static_cast<double>(fraction) / static_cast<double>(pow10(n));
}

// The UTC offset [min] at the reader's position: 'Z', '+hh:mm' or '-hh:mm', at most 18:00.
int utc_offset_minutes(Iso8601Reader& in) {
  const char sign = in.peek();
  if (sign == 'Z') {
    in.skip();
    return 0;
  }
  if (sign == '+' || sign == '-') {
    in.skip();
    const int hh = in.digits(2, "UTC offset hours");
    in.expect(':', "UTC offset separator");
    const int mm = in.digits(2, "UTC offset minutes");
    if (mm > 59) in.fail("UTC offset minutes", std::to_string(mm) + " is out of range [00, 59]");
    const int minutes = 60 * hh + mm;
    if (minutes > kMaxOffsetMinutes) {
      in.fail("UTC offset", fmt::format("{}{:02}:{:02} is beyond +-18:00", sign, hh, mm));
    }
    return sign == '-' ? -minutes : minutes;
  }
  if (in.at_end()) in.fail("UTC offset", "missing (expected 'Z', '+hh:mm' or '-hh:mm')");
  in.fail("UTC offset", std::string("expected 'Z', '+hh:mm' or '-hh:mm' at position ") +
                            std::to_string(in.pos() + 1) + ", found " + shown(sign));
}

void add_one_minute(DateTime& t) {
  if (++t.minute < 60) return;
  t.minute = 0;
  if (++t.hour < 24) return;
  t.hour = 0;
  ++t.day;
  if (in_reform_gap(t.year, t.month, t.day)) t.day = kFirstGregorianDay;
  if (t.day <= days_in_month(t.year, t.month)) return;
  t.day = 1;
  if (++t.month <= 12) return;
  t.month = 1;
  ++t.year;
}

}  // namespace

bool is_leap_year(int year) {
  if (year < kReformYear) return year % 4 == 0;  // Julian rule (also for year <= 0)
  return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

int days_in_month(int year, int month) {
  static constexpr std::array<int, 12> kDays{31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month < 1 || month > 12) return 0;
  if (month == 2 && is_leap_year(year)) return 29;
  return kDays[month - 1];
}

int day_of_year(const DateTime& t) {
  int n = t.day;
  for (int m = 1; m < t.month; ++m) n += days_in_month(t.year, m);
  // October 1582 lost 10 days in the switch to the Gregorian calendar (days_in_month counts 31).
  if (t.year == 1582 && (t.month > 10 || (t.month == 10 && t.day >= 15))) n -= 10;
  return n;
}

void validate(const DateTime& t, std::string_view name) {
  if (t.year < kMinYear || t.year > kMaxYear) {
    out_of_range(name, "year", std::to_string(t.year), "[-4712, 9999]");
  }
  if (t.month < 1 || t.month > 12) out_of_range(name, "month", std::to_string(t.month), "[1, 12]");
  const int dim = days_in_month(t.year, t.month);
  if (t.day < 1 || t.day > dim) {
    out_of_range(name, "day", std::to_string(t.day), "[1, " + std::to_string(dim) + "]");
  }
  if (in_reform_gap(t.year, t.month, t.day)) {
    throw InvalidArgument(std::string(name) + ".day = " + std::to_string(t.day) +
                          ": 1582-10-05 .. 1582-10-14 do not exist (Julian to Gregorian calendar)");
  }
  if (t.hour < 0 || t.hour > 23) out_of_range(name, "hour", std::to_string(t.hour), "[0, 23]");
  if (t.minute < 0 || t.minute > 59) {
    out_of_range(name, "minute", std::to_string(t.minute), "[0, 59]");
  }
  if (!(t.second >= 0.0 && t.second < 60.0))
    out_of_range(name, "second", fmt::format("{}", t.second), "[0, 60)");
  if (t.utc_offset_minutes < -kMaxOffsetMinutes || t.utc_offset_minutes > kMaxOffsetMinutes) {
    out_of_range(name, "utc_offset_minutes", std::to_string(t.utc_offset_minutes), "[-1080, 1080]");
  }
}

DateTime parse_iso8601(std::string_view text) {
  Iso8601Reader in(text);
  if (text.empty()) in.fail("year", "empty text");
  DateTime t;
  // ISO 8601 expanded years: a sign and 4 digits, astronomical numbering (0000 = 1 BC,
  // -2000 = 2001 BC), for the SPA's years before 0.
  const char year_sign = in.peek();
  if (year_sign == '+' || year_sign == '-') in.skip();
  t.year = in.digits(4, "year");
  if (year_sign == '-') t.year = -t.year;
  // The range of DateTime (Julian Day 0 on): -4712 .. 9999 (found by the fuzz target iso8601:
  // -6025 was accepted, then refused by validate()).
  if (t.year < kMinYear) {
    in.fail("year", std::to_string(t.year) + " is out of range [-4712, 9999]");
  }
  in.expect('-', "date separator after year");
  t.month = in.digits(2, "month");
  if (t.month < 1 || t.month > 12) {
    in.fail("month", std::to_string(t.month) + " is out of range [01, 12]");
  }
  in.expect('-', "date separator after month");
  t.day = in.digits(2, "day");
  const int dim = days_in_month(t.year, t.month);
  if (t.day < 1 || t.day > dim) {
    in.fail("day", std::to_string(t.day) + " is out of range [01, " + std::to_string(dim) +
                       "] for " + std::to_string(t.year) + "-" + (t.month < 10 ? "0" : "") +
                       std::to_string(t.month));
  }
  if (in_reform_gap(t.year, t.month, t.day)) {
    in.fail("day", "1582-10-05 .. 1582-10-14 do not exist (Julian to Gregorian calendar)");
  }
  in.expect('T', "date/time separator");
  t.hour = in.digits(2, "hour");
  if (t.hour > 23) in.fail("hour", std::to_string(t.hour) + " is out of range [00, 23]");
  in.expect(':', "time separator after hour");
  t.minute = in.digits(2, "minute");
  if (t.minute > 59) in.fail("minute", std::to_string(t.minute) + " is out of range [00, 59]");
  in.expect(':', "time separator after minute (seconds are required)");
  const int whole_seconds = in.digits(2, "second");
  if (whole_seconds > 59) {
    in.fail("second", std::to_string(whole_seconds) +
                          " is out of range [00, 59] (leap seconds are not supported)");
  }
  t.second = whole_seconds;
  if (in.peek() == ',') in.fail("fraction of second", "use '.' as the decimal separator");
  if (in.peek() == '.') t.second += fraction_of_second(in);
  t.utc_offset_minutes = utc_offset_minutes(in);
  if (!in.at_end()) {
    in.fail("end",
            "unexpected text after the UTC offset at position " + std::to_string(in.pos() + 1));
  }
  return t;
}

std::string format_iso8601(const DateTime& t_in, int fraction_digits) {
  validate(t_in, "time");
  if (fraction_digits < 0 || fraction_digits > kMaxFractionDigits) {
    throw InvalidArgument("fraction_digits = " + std::to_string(fraction_digits) +
                          " is out of range [0, 9]");
  }
  DateTime t = t_in;
  const long long scale = pow10(fraction_digits);
  long long ticks = std::llround(t.second * static_cast<double>(scale));
  if (ticks >= 60 * scale) {  // e.g. 59.9996 s written with 3 decimals
    ticks -= 60 * scale;
    add_one_minute(t);
  }
  if (t.year < -9999 || t.year > 9999) {
    throw InvalidArgument("time.year = " + std::to_string(t.year) +
                          " cannot be written as 4 ISO 8601 digits (-9999..9999)");
  }
  char buf[64];
  int n = std::snprintf(buf, sizeof buf, "%s%04d-%02d-%02dT%02d:%02d:%02lld", t.year < 0 ? "-" : "",
                        std::abs(t.year), t.month, t.day, t.hour, t.minute, ticks / scale);
  std::string s(buf, static_cast<std::size_t>(n));
  if (fraction_digits > 0) {
    n = std::snprintf(buf, sizeof buf, ".%0*lld", fraction_digits, ticks % scale);
    s.append(buf, static_cast<std::size_t>(n));
  }
  if (t.utc_offset_minutes == 0) return s + "Z";
  const int a = std::abs(t.utc_offset_minutes);
  n = std::snprintf(buf, sizeof buf, "%c%02d:%02d", t.utc_offset_minutes < 0 ? '-' : '+', a / 60,
                    a % 60);
  return s.append(buf, static_cast<std::size_t>(n));
}

double julian_day(int year, int month, double day) {
  // 3.1.1: January and February count as months 13 and 14 of the previous year.
  double Y = year, M = month;
  if (M < 3) {
    Y -= 1;
    M += 12;
  }
  // Eq. (4) with B = 0 (Julian calendar); INT truncates, and both arguments are positive here.
  double jd = std::trunc(365.25 * (Y + 4716)) + std::trunc(30.6001 * (M + 1)) + day - 1524.5;
  if (jd > kGregorianJd) {
    const double A = std::trunc(Y / 100);
    jd += 2 - A + std::trunc(A / 4);  // B of the Gregorian calendar
  }
  return jd;
}

double julian_day(const DateTime& t, double delta_ut1) {
  // D of eq. (4): day of the month with decimal time, in UT = local - offset + Delta UT1 (eq. 3).
  const double D = t.day + (t.hour + (t.minute + (t.second + delta_ut1) / 60.0) / 60.0) / 24.0 -
                   t.utc_offset_minutes / 1440.0;
  return julian_day(t.year, t.month, D);
}

DateTime date_time_from_julian_day(double jd, int utc_offset_minutes, int fraction_digits) {
  if (utc_offset_minutes < -kMaxOffsetMinutes || utc_offset_minutes > kMaxOffsetMinutes) {
    throw InvalidArgument("utc_offset_minutes = " + std::to_string(utc_offset_minutes) +
                          " is out of range [-1080, 1080]");
  }
  if (fraction_digits < 0 || fraction_digits > kMaxFractionDigits) {
    throw InvalidArgument("fraction_digits = " + std::to_string(fraction_digits) +
                          " is out of range [0, 9]");
  }
  // A.3.1, with the local time zone added (note below eq. A23).
  const double local = jd + 0.5 + utc_offset_minutes / 1440.0;
  if (!(local >= 0.0 && local < 1e8)) {
    throw InvalidArgument(fmt::format("jd = {}", jd) +
                          " is out of range (needs 0 <= JD + 0.5 < 1e8)");
  }
  double z = std::floor(local);
  // Round the time of day first, so that a carry moves the date and not the seconds to 60.
  const long long scale = pow10(fraction_digits);
  const long long ticks_per_day = 86400LL * scale;
  long long ticks = std::llround((local - z) * static_cast<double>(ticks_per_day));
  if (ticks >= ticks_per_day) {
    ticks -= ticks_per_day;
    z += 1.0;
  }
  // A.3.2-A.3.9 with F = 0 (the time of day is in `ticks`). All terms are integers below 1e9,
  // exact in double; INT is floor as every argument is positive.
  const double Z = z;
  double A = Z;  // A.3.2
  if (Z >= kGregorianZ) {
    const double B = std::floor((Z - 1867216.25) / 36524.25);  // (A15)
    A = Z + 1 + B - std::floor(B / 4);                         // (A16)
  }
  const double C = A + 1524;                          // (A17)
  const double D = std::floor((C - 122.1) / 365.25);  // (A18)
  const double G = std::floor(365.25 * D);            // (A19)
  const double I = std::floor((C - G) / 30.6001);     // (A20)
  DateTime t;
  t.day = static_cast<int>(C - G - std::floor(30.6001 * I));     // (A21)
  t.month = static_cast<int>(I < 14 ? I - 1 : I - 13);           // (A22)
  t.year = static_cast<int>(t.month > 2 ? D - 4716 : D - 4715);  // (A23)
  t.hour = static_cast<int>(ticks / (3600 * scale));
  t.minute = static_cast<int>(ticks / (60 * scale) % 60);
  t.second = static_cast<double>(ticks % (60 * scale)) / static_cast<double>(scale);
  t.utc_offset_minutes = utc_offset_minutes;
  return t;
}

}  // namespace skylight::sun
