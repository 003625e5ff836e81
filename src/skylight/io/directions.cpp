#include "skylight/io/directions.h"

#include <fmt/format.h>

#include <utility>

#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"

namespace skylight::io {
namespace {

// The text split into non-empty lines (CRLF accepted), each with its 1-based line number.
std::vector<std::pair<std::size_t, std::string_view>> lines_of(std::string_view text) {
  std::vector<std::pair<std::size_t, std::string_view>> out;
  std::size_t line_no = 0, start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++line_no;
    if (!line.empty()) out.emplace_back(line_no, line);
    start = end + 1;
  }
  return out;
}

}  // namespace

const ParameterSpec& direction_zenith_spec() {
  static const ParameterSpec spec{.name = "zenith_deg",
                                  .unit = "deg",
                                  .min = 0.0,
                                  .max = 180.0,
                                  .default_value = Required{},
                                  .description = "view zenith angle"};
  return spec;
}

const ParameterSpec& direction_azimuth_spec() {
  static const ParameterSpec spec{.name = "azimuth_deg",
                                  .unit = "deg",
                                  .min = -360.0,
                                  .max = 360.0,
                                  .default_value = Required{},
                                  .description = "view azimuth from north towards east"};
  return spec;
}

std::vector<DirectionRow> parse_directions_csv(std::string_view text, std::string_view source) {
  const auto lines = lines_of(text);
  if (lines.empty())
    throw InvalidArgument(
        fmt::format("{}: empty input, expected header '{}'", source, kDirectionsHeader));
  if (lines.front().second != kDirectionsHeader)
    throw InvalidArgument(fmt::format("{} line {}: header must be '{}', got '{}'", source,
                                      lines.front().first, kDirectionsHeader,
                                      excerpt(lines.front().second)));
  auto field = [&](std::size_t line_no, std::string_view s, const ParameterSpec& spec) {
    const auto v = parse_number(s);
    if (!v)
      throw InvalidArgument(fmt::format("{} line {}: {} '{}' {}", source, line_no, spec.name,
                                        excerpt(s), number_problem(s)));
    if (*v < spec.min || *v > spec.max)
      throw InvalidArgument(fmt::format("{} line {}: {} = {} is outside [{}, {}]", source, line_no,
                                        spec.name, excerpt(s), spec.min, spec.max));
    return *v;
  };
  std::vector<DirectionRow> rows;
  rows.reserve(lines.size() - 1);
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const auto [line_no, line] = lines[k];
    const auto comma = line.find(',');
    if (comma == std::string_view::npos || line.find(',', comma + 1) != std::string_view::npos)
      throw InvalidArgument(fmt::format("{} line {}: expected 2 fields '{}', got '{}'", source,
                                        line_no, kDirectionsHeader, excerpt(line)));
    const double zen = field(line_no, line.substr(0, comma), direction_zenith_spec());
    const double az = field(line_no, line.substr(comma + 1), direction_azimuth_spec());
    rows.push_back({line_no, line, deg_to_rad(zen), wrap_azimuth(deg_to_rad(az))});
  }
  return rows;
}

}  // namespace skylight::io
