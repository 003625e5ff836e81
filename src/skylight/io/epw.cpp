#include "skylight/io/epw.h"

#include <fmt/format.h>

#include <array>
#include <limits>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"

namespace skylight::io {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The header lines' keywords, in order (the data dictionary's header records).
constexpr std::array<std::string_view, 8> kHeaderKeywords = {"LOCATION",
                                                             "DESIGN CONDITIONS",
                                                             "TYPICAL/EXTREME PERIODS",
                                                             "GROUND TEMPERATURES",
                                                             "HOLIDAYS/DAYLIGHT SAVINGS",
                                                             "COMMENTS 1",
                                                             "COMMENTS 2",
                                                             "DATA PERIODS"};

// A value field skylight reads: its 1-based position, name, missing-value marker (values at or
// above it are missing) and the data dictionary's range of present values.
struct ValueField {
  std::size_t index;
  std::string_view name;
  double missing;
  double min, max;
  std::optional<double> EpwRecord::*field;
};

constexpr std::array<ValueField, 12> kValueFields = {{
    {7, "dry bulb temperature", 99.9, -70.0, 70.0, &EpwRecord::dry_bulb_c},
    {8, "dew point temperature", 99.9, -70.0, 70.0, &EpwRecord::dew_point_c},
    {10, "atmospheric station pressure", 999999.0, 31000.0, 120000.0, &EpwRecord::pressure_pa},
    {14, "global horizontal radiation", 9999.0, 0.0, kInf, &EpwRecord::global_horizontal_wh_m2},
    {15, "direct normal radiation", 9999.0, 0.0, kInf, &EpwRecord::direct_normal_wh_m2},
    {16, "diffuse horizontal radiation", 9999.0, 0.0, kInf, &EpwRecord::diffuse_horizontal_wh_m2},
    {17, "global horizontal illuminance", 999900.0, 0.0, kInf, &EpwRecord::global_horizontal_lux},
    {18, "direct normal illuminance", 999900.0, 0.0, kInf, &EpwRecord::direct_normal_lux},
    {19, "diffuse horizontal illuminance", 999900.0, 0.0, kInf, &EpwRecord::diffuse_horizontal_lux},
    {20, "zenith luminance", 9999.0, 0.0, kInf, &EpwRecord::zenith_luminance_cd_m2},
    {29, "precipitable water", 999.0, 0.0, kInf, &EpwRecord::precipitable_water_mm},
    {33, "albedo", 999.0, 0.0, kInf, &EpwRecord::albedo},
}};

// The fields of a line split at commas (no quoting in EPW records).
std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    if (comma == std::string_view::npos) {
      out.push_back(line.substr(start));
      return out;
    }
    out.push_back(line.substr(start, comma - start));
    start = comma + 1;
  }
}

class Reader {
 public:
  Reader(std::string_view text, std::string_view source) : text_(text), source_(source) {}

  // The next line (CR removed), or nullopt at the end.
  std::optional<std::string_view> next() {
    if (pos_ >= text_.size()) return std::nullopt;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end + 1;
    ++line_;
    return line;
  }
  std::size_t line() const { return line_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw InvalidArgument(fmt::format("{} line {}: {}", source_, line_, what));
  }

  double number(std::string_view text, std::size_t index, std::string_view name, double min,
                double max) const {
    const auto v = parse_number(trim(text));
    if (!v)
      fail(fmt::format("field {} ({}) '{}' {}", index, name, excerpt(text),
                       number_problem(trim(text))));
    if (max == kInf && *v < min)
      fail(fmt::format("field {} ({}) = {} is below {:g}", index, name, excerpt(text), min));
    if (*v < min || *v > max)
      fail(fmt::format("field {} ({}) = {} is outside [{:g}, {:g}]", index, name, excerpt(text),
                       min, max));
    return *v;
  }
  int integer(std::string_view text, std::size_t index, std::string_view name, int min,
              int max) const {
    const auto v = parse_integer(trim(text));
    if (!v) fail(fmt::format("field {} ({}) '{}' is not an integer", index, name, excerpt(text)));
    if (*v < min || *v > max)
      fail(fmt::format("field {} ({}) = {} is outside [{}, {}]", index, name, excerpt(text), min,
                       max));
    return static_cast<int>(*v);
  }

 private:
  std::string_view text_, source_;
  std::size_t pos_ = 0, line_ = 0;
};

EpwLocation parse_location(const Reader& r, const std::vector<std::string_view>& f) {
  if (f.size() != 10)
    r.fail(
        fmt::format("LOCATION needs 10 fields (LOCATION, city, state, country, source, WMO, "
                    "latitude, longitude, time zone, elevation), got {}",
                    f.size()));
  EpwLocation loc;
  loc.city = std::string(trim(f[1]));
  loc.state = std::string(trim(f[2]));
  loc.country = std::string(trim(f[3]));
  loc.source = std::string(trim(f[4]));
  loc.wmo = std::string(trim(f[5]));
  loc.latitude_deg = r.number(f[6], 7, "latitude", -90.0, 90.0);
  loc.longitude_deg = r.number(f[7], 8, "longitude", -180.0, 180.0);
  loc.time_zone_h = r.number(f[8], 9, "time zone", -12.0, 14.0);
  loc.elevation_m = r.number(f[9], 10, "elevation", -1000.0, 9999.9);
  return loc;
}

}  // namespace

EpwFile parse_epw(std::string_view text, std::string_view source) {
  Reader r(text, source);
  EpwFile out;
  for (std::size_t h = 0; h < kHeaderKeywords.size(); ++h) {
    const auto line = r.next();
    if (!line)
      throw InvalidArgument(
          fmt::format("{}: ends after {} lines, before the 8 header lines and "
                      "the records",
                      source, r.line()));
    const std::vector<std::string_view> f = split_fields(*line);
    if (trim(f[0]) != kHeaderKeywords[h])
      r.fail(fmt::format("header line {} must start with '{}', got '{}'", h + 1, kHeaderKeywords[h],
                         excerpt(f[0])));
    if (h == 0) out.location = parse_location(r, f);
  }
  while (const auto line = r.next()) {
    if (trim(*line).empty()) continue;
    const std::vector<std::string_view> f = split_fields(*line);
    if (f.size() != kEpwFields)
      r.fail(fmt::format("a record needs {} fields, got {}", kEpwFields, f.size()));
    EpwRecord rec;
    rec.line = r.line();
    rec.year = r.integer(f[0], 1, "year", 1, 9999);
    rec.month = r.integer(f[1], 2, "month", 1, 12);
    rec.day = r.integer(f[2], 3, "day", 1, 31);
    rec.hour = r.integer(f[3], 4, "hour", 1, 24);
    rec.minute = r.integer(f[4], 5, "minute", 0, 60);
    for (const ValueField& v : kValueFields) {
      const std::string_view s = trim(f[v.index - 1]);
      if (s.empty()) continue;  // an empty field is missing
      const auto x = parse_number(s);
      if (x && *x >= v.missing) continue;
      rec.*v.field = r.number(s, v.index, v.name, v.min, v.max);
    }
    out.records.push_back(std::move(rec));
  }
  if (out.records.empty())
    throw InvalidArgument(fmt::format("{}: no records after the 8 header lines", source));
  return out;
}

EpwFile read_epw(const std::filesystem::path& path) {
  return parse_epw(read_text_file(path), shown_path(path));
}

}  // namespace skylight::io
