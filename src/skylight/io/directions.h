// The directions CSV that `skylight eval` reads (README, "eval"): the header
// `zenith_deg,azimuth_deg`, then one row per view direction: the zenith angle [deg] in [0, 180]
// and the azimuth [deg] from north towards east in [-360, 360]. Blank lines are skipped; CRLF is
// accepted.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "skylight/core/parameters.h"

namespace skylight::io {

inline constexpr std::string_view kDirectionsHeader = "zenith_deg,azimuth_deg";

// The two columns, declared like the sun's angles.
const ParameterSpec& direction_zenith_spec();
const ParameterSpec& direction_azimuth_spec();

struct DirectionRow {
  std::size_t line = 0;   // 1-based line of the source text
  std::string_view text;  // the row as written (without the line end), a view into the input
  double zenith = 0.0;    // [rad], [0, pi]
  double azimuth = 0.0;   // [rad] from north towards east, wrapped to [0, 2 pi)
};

// Parses the CSV text; `source` names it in messages. Throws InvalidArgument
// "<source>: empty input ...", "<source> line L: header must be ...", "<source> line L: expected
// 2 fields ...", "<source> line L: <column> '<text>' is not a number" (or "overflows", "underflows
// to 0": number_problem)" or "... is outside [min, max]". A header without rows gives no rows.
std::vector<DirectionRow> parse_directions_csv(std::string_view text, std::string_view source);

}  // namespace skylight::io
