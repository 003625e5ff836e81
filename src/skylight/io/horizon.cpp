#include "skylight/io/horizon.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "skylight/core/detail/json_reader.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"

namespace skylight::io {
namespace {

// 0 and 360 deg given both: the same azimuth, whose elevations must agree to this [deg].
constexpr double kSameAzimuthTolerance = 1e-9;

double wrap_degrees(double a) {
  double w = std::fmod(a, 360.0);
  if (w < 0.0) w += 360.0;
  return w;
}

// The fields of a line split at commas or tabs, trimmed.
std::vector<std::string_view> fields_of(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',' || line[i] == '\t') {
      out.push_back(trim(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  return out;
}

struct Line {
  std::size_t number = 0;
  std::string_view text;
};

std::vector<Line> lines_of(std::string_view text) {
  std::vector<Line> out;
  std::size_t start = 0, n = 1;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    out.push_back({n++, text.substr(start, end - start)});
    start = end + 1;
  }
  return out;
}

struct ParsedPoint {
  HorizonProfile::Point point;
  std::size_t line = 0;  // 0 in JSON (the list index names it instead)
};

// The checked point of one row: `azimuth` already in skylight's convention.
ParsedPoint checked_point(double azimuth, double elevation, const std::string& where,
                          std::size_t line) {
  if (!(elevation >= 0.0 && elevation <= 90.0))
    throw InvalidArgument(
        fmt::format("{}: elevation {} deg is outside [0, 90] (the sky models end "
                    "at the geometric horizon)",
                    where, elevation));
  return {{azimuth, elevation}, line};
}

std::vector<ParsedPoint> parse_pvgis_json(std::string_view text, const std::string& source) {
  namespace js = skylight::detail::json;
  const auto j = js::parse_object(text, source);
  const auto& outputs = js::field(j, source, "outputs");
  const auto& profile = js::array(js::field(outputs, source, "horizon_profile", "outputs."), source,
                                  "outputs.horizon_profile");
  std::vector<ParsedPoint> out;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const std::string name = fmt::format("outputs.horizon_profile[{}]", i);
    const double a =
        js::number(js::field(profile[i], source, "A", name + "."), source, name + ".A");
    const double h =
        js::number(js::field(profile[i], source, "H_hor", name + "."), source, name + ".H_hor");
    if (!(a >= -180.0 && a <= 180.0))
      throw InvalidArgument(
          fmt::format("{}: field '{}.A' = {} is outside [-180, 180]", source, name, a));
    out.push_back(checked_point(wrap_degrees(a + 180.0), h, source + ": " + name, 0));
  }
  return out;
}

// PVGIS's CSV: the table after the header line `A <sep> H_hor ...`, until the first line that
// does not start with two numbers.
std::optional<std::vector<ParsedPoint>> parse_pvgis_csv(const std::vector<Line>& lines,
                                                        const std::string& source) {
  std::size_t k = 0;
  for (; k < lines.size(); ++k) {
    const auto f = fields_of(lines[k].text);
    if (f.size() >= 2 && f[0] == "A" && f[1] == "H_hor") break;
  }
  if (k == lines.size()) return std::nullopt;
  std::vector<ParsedPoint> out;
  for (++k; k < lines.size(); ++k) {
    const auto f = fields_of(lines[k].text);
    if (f.size() < 2 || !parse_number(f[0]) || !parse_number(f[1])) break;
    const std::string where = fmt::format("{} line {}", source, lines[k].number);
    const double a = *parse_number(f[0]);
    if (!(a >= -180.0 && a <= 180.0))
      throw InvalidArgument(fmt::format("{}: A = {} is outside [-180, 180]", where, a));
    out.push_back(
        checked_point(wrap_degrees(a + 180.0), *parse_number(f[1]), where, lines[k].number));
  }
  if (out.empty())
    throw InvalidArgument(fmt::format("{}: PVGIS's table (A, H_hor) has no rows", source));
  return out;
}

std::vector<ParsedPoint> parse_csv(const std::vector<Line>& lines, const std::string& source) {
  std::vector<ParsedPoint> out;
  bool first = true;
  for (const Line& line : lines) {
    if (trim(line.text).empty()) continue;
    const std::string where = fmt::format("{} line {}", source, line.number);
    const auto f = fields_of(line.text);
    if (first && f.size() == 2 && f[0] == "azimuth_deg" && f[1] == "elevation_deg") {
      first = false;
      continue;
    }
    first = false;
    if (f.size() != 2)
      throw InvalidArgument(fmt::format(
          "{}: expected 2 fields (azimuth_deg,elevation_deg), found {}", where, f.size()));
    const double a = parse_number(f[0], where + ": azimuth_deg");
    const double h = parse_number(f[1], where + ": elevation_deg");
    if (!(a >= 0.0 && a <= 360.0))
      throw InvalidArgument(fmt::format("{}: azimuth_deg {} is outside [0, 360]", where, a));
    out.push_back(checked_point(a, h, where, line.number));
  }
  if (out.empty())
    throw InvalidArgument(
        fmt::format("{}: no points (expected lines azimuth_deg,elevation_deg)", source));
  return out;
}

// Sorted, 360 folded onto 0, each azimuth once.
std::vector<HorizonProfile::Point> unique_points(std::vector<ParsedPoint> parsed,
                                                 const std::string& source) {
  for (auto& p : parsed)
    if (p.point.azimuth_deg >= 360.0) p.point.azimuth_deg -= 360.0;
  std::stable_sort(parsed.begin(), parsed.end(), [](const ParsedPoint& a, const ParsedPoint& b) {
    return a.point.azimuth_deg < b.point.azimuth_deg;
  });
  std::vector<HorizonProfile::Point> out;
  for (std::size_t i = 0; i < parsed.size(); ++i) {
    if (i > 0 && parsed[i].point.azimuth_deg == parsed[i - 1].point.azimuth_deg) {
      const double d = parsed[i].point.elevation_deg - parsed[i - 1].point.elevation_deg;
      if (std::abs(d) <= kSameAzimuthTolerance) continue;
      const auto where = [&](const ParsedPoint& p) {
        return p.line > 0 ? fmt::format("line {}", p.line) : std::string("the list");
      };
      throw InvalidArgument(fmt::format(
          "{}: azimuth {} deg is given twice with different elevations ({} and {}, {} and {})",
          source, parsed[i].point.azimuth_deg, parsed[i - 1].point.elevation_deg,
          parsed[i].point.elevation_deg, where(parsed[i - 1]), where(parsed[i])));
    }
    out.push_back(parsed[i].point);
  }
  return out;
}

}  // namespace

HorizonProfile::HorizonProfile(std::vector<Point> points) : points_(std::move(points)) {
  SKYLIGHT_CHECK(!points_.empty(), "a horizon profile needs at least one point");
  for (auto& p : points_) {
    SKYLIGHT_CHECK(p.elevation_deg >= 0.0 && p.elevation_deg <= 90.0,
                   "horizon elevation outside [0, 90]");
    p.azimuth_deg = wrap_degrees(p.azimuth_deg);
    max_elevation_deg_ = std::max(max_elevation_deg_, p.elevation_deg);
  }
  std::sort(points_.begin(), points_.end(),
            [](const Point& a, const Point& b) { return a.azimuth_deg < b.azimuth_deg; });
  format_ = "constant";
}

HorizonProfile HorizonProfile::constant(double elevation_deg) {
  return HorizonProfile({{0.0, elevation_deg}});
}

double HorizonProfile::elevation(double azimuth) const {
  if (points_.empty()) return 0.0;
  if (points_.size() == 1) return deg_to_rad(points_.front().elevation_deg);
  const double a = wrap_degrees(rad_to_deg(azimuth));
  // The first point beyond a; its predecessor (cyclically) is at or before a.
  const auto next = std::upper_bound(points_.begin(), points_.end(), a,
                                     [](double v, const Point& p) { return v < p.azimuth_deg; });
  const Point& p1 = next == points_.end() ? points_.front() : *next;
  const Point& p0 = next == points_.begin() ? points_.back() : *(next - 1);
  double span = p1.azimuth_deg - p0.azimuth_deg, offset = a - p0.azimuth_deg;
  if (span <= 0.0) span += 360.0;
  if (offset < 0.0) offset += 360.0;
  const double t = offset / span;
  return deg_to_rad(p0.elevation_deg + t * (p1.elevation_deg - p0.elevation_deg));
}

bool HorizonProfile::open(Vec3 d) const {
  if (d.z <= 0.0) return false;
  if (flat()) return true;
  const double elev = std::atan2(d.z, std::hypot(d.x, d.y));
  return elev > elevation(std::atan2(d.x, d.y));
}

HorizonProfile parse_horizon(std::string_view text, std::string_view source_view) {
  const std::string source(source_view);
  std::vector<ParsedPoint> parsed;
  std::string format = "csv";
  if (!trim(text).empty() && trim(text).front() == '{') {
    parsed = parse_pvgis_json(text, source);
    format = "pvgis";
    if (parsed.empty())
      throw InvalidArgument(fmt::format("{}: outputs.horizon_profile is empty", source));
  } else {
    const auto lines = lines_of(text);
    if (auto pvgis = parse_pvgis_csv(lines, source)) {
      parsed = std::move(*pvgis);
      format = "pvgis";
    } else {
      parsed = parse_csv(lines, source);
    }
  }
  HorizonProfile h(unique_points(std::move(parsed), source));
  h.format_ = format;
  return h;
}

HorizonProfile read_horizon(const std::filesystem::path& path) {
  return parse_horizon(read_text_file(path), shown_path(path));
}

}  // namespace skylight::io
