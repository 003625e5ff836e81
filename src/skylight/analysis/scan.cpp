// Sky-luminance scans: the CSV format and the Tregenza patches (core only; scan_models.cpp holds
// the parts that evaluate sky models).
#include "skylight/analysis/scan.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/io/file.h"

namespace skylight::analysis {
namespace {

constexpr std::string_view kAzimuthColumn = "azimuth_deg";
constexpr std::string_view kElevationColumn = "elevation_deg";
constexpr std::string_view kLuminanceColumn = "luminance_cd_m2";
constexpr std::string_view kSunAzimuthKey = "sun_azimuth_deg";
constexpr std::string_view kSunElevationKey = "sun_elevation_deg";

// `# key = value` comment: the sun position keys are read, anything else is free text.
void read_comment(std::string_view body, const std::string& source, std::size_t line,
                  SkyScan& scan) {
  const auto eq = body.find('=');
  if (eq == std::string_view::npos) return;
  const std::string_view key = trim(body.substr(0, eq));
  const std::string_view value = trim(body.substr(eq + 1));
  const bool azimuth = key == kSunAzimuthKey, elevation = key == kSunElevationKey;
  if (!azimuth && !elevation) return;
  const auto v = parse_number(value);
  if (!v)
    throw InvalidArgument(fmt::format("{} line {}: {} '{}' {}", source, line, key, excerpt(value),
                                      number_problem(value)));
  const double lo = azimuth ? -360.0 : 0.0, hi = azimuth ? 360.0 : 90.0;
  if (*v < lo || *v > hi)
    throw InvalidArgument(
        fmt::format("{} line {}: {} = {} is outside [{}, {}]", source, line, key, *v, lo, hi));
  if (azimuth)
    scan.sun_azimuth = wrap_azimuth(deg_to_rad(*v));
  else
    scan.sun_elevation = deg_to_rad(*v);
}

}  // namespace

SkyScan parse_sky_scan(std::string_view text, std::string source) {
  SkyScan scan;
  scan.source = source;
  // Comment lines become blank lines, so that the table's line numbers stay those of the file.
  std::string table;
  table.reserve(text.size());
  std::size_t line = 0, pos = 0;
  while (pos <= text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view raw = text.substr(pos, nl == text.npos ? text.npos : nl - pos);
    ++line;
    pos = nl == text.npos ? text.size() + 1 : nl + 1;
    const std::string_view t = trim(raw);
    if (!t.empty() && t.front() == '#') {
      read_comment(t.substr(1), source, line, scan);
    } else {
      table += raw;
    }
    table += '\n';
  }
  try {
    const data::CsvTable csv(table, source, /*has_header=*/true);
    const std::size_t ca = csv.column(kAzimuthColumn), ce = csv.column(kElevationColumn),
                      cl = csv.column(kLuminanceColumn);
    for (std::size_t r = 0; r < csv.rows(); ++r) {
      const double az = csv.number(r, ca), el = csv.number(r, ce), lum = csv.number(r, cl);
      auto out_of_range = [&](std::size_t col, std::string_view name, double v,
                              std::string_view range) {
        return InvalidArgument(fmt::format("{} line {} column {}: {} = {} is outside {}", source,
                                           csv.line(r), col + 1, name, v, range));
      };
      if (az < -360.0 || az > 360.0) throw out_of_range(ca, kAzimuthColumn, az, "[-360, 360]");
      if (el < 0.0 || el > 90.0) throw out_of_range(ce, kElevationColumn, el, "[0, 90]");
      if (!(lum > 0.0)) throw out_of_range(cl, kLuminanceColumn, lum, "(0, inf)");
      scan.samples.push_back({wrap_azimuth(deg_to_rad(az)), deg_to_rad(el), lum, csv.line(r)});
    }
  } catch (const IoError& e) {
    // The CSV loader reports malformed tables as IoError; here they are bad user input.
    throw InvalidArgument(e.what());
  }
  if (scan.samples.empty()) throw InvalidArgument(fmt::format("{}: no samples", source));
  return scan;
}

SkyScan read_sky_scan(const std::filesystem::path& path) {
  return parse_sky_scan(io::read_text_file(path), path.string());
}

std::string format_sky_scan(const SkyScan& scan, const std::vector<std::string>& comments) {
  std::string out;
  for (const auto& c : comments) out += "# " + c + "\n";
  if (scan.sun_azimuth)
    out += fmt::format("# {} = {:.6g}\n", kSunAzimuthKey, rad_to_deg(*scan.sun_azimuth));
  if (scan.sun_elevation)
    out += fmt::format("# {} = {:.6g}\n", kSunElevationKey, rad_to_deg(*scan.sun_elevation));
  out += fmt::format("{},{},{}\n", kAzimuthColumn, kElevationColumn, kLuminanceColumn);
  for (const auto& s : scan.samples)
    out += fmt::format("{:.6g},{:.6g},{:.6g}\n", rad_to_deg(s.azimuth), rad_to_deg(s.elevation),
                       s.luminance);
  return out;
}

std::vector<PatchCentre> tregenza_patch_centres() {
  // Tregenza 1987, Table 1: band centre elevation [deg] and number of patches.
  constexpr std::array<std::array<int, 2>, 8> kBands = {
      {{6, 30}, {18, 30}, {30, 24}, {42, 24}, {54, 18}, {66, 12}, {78, 6}, {90, 1}}};
  std::vector<PatchCentre> out;
  for (const auto& [elevation, count] : kBands)
    for (int k = 0; k < count; ++k)
      out.push_back({deg_to_rad(360.0 * k / count), deg_to_rad(static_cast<double>(elevation))});
  SKYLIGHT_CHECK(out.size() == kTregenzaPatchCount, "Tregenza bands must give 145 patches");
  return out;
}

}  // namespace skylight::analysis
