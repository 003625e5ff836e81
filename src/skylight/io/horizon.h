// Horizon profiles: the elevation of the skyline [deg] around a site, as a function of azimuth
// (skylight's convention: from north towards east, docs/CONVENTIONS.md), interpolated linearly in
// azimuth and periodic over 360 deg. A far horizon (mountains, buildings across a street): it
// blocks the sky and the sun alike for the whole site (`skylight irradiance --horizon`,
// docs/IRRADIANCE.md).
//
// Files read (the format is recognised from the text):
//  * CSV `azimuth_deg,elevation_deg`: one point per line, the header line optional; azimuths in
//    [0, 360], any order, each at most once (0 and 360 are the same azimuth and must agree);
//  * PVGIS's horizon tool (`printhorizon`), its CSV (a table whose header line is `A`, `H_hor`,
//    ... separated by tabs or commas, with text lines before and after) or its JSON
//    (`outputs.horizon_profile`, a list of {"A", "H_hor"}). PVGIS's azimuth A is counted from
//    south towards west (-180 = north, -90 = east, 90 = west): skylight's azimuth is A + 180.
// Elevations are in [0, 90]: the sky models end at the geometric horizon, so a skyline below it
// (a site on a summit) cannot uncover more sky and is refused rather than ignored.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/frame.h"

namespace skylight::io {

class HorizonProfile {
 public:
  struct Point {
    double azimuth_deg = 0.0;    // [0, 360)
    double elevation_deg = 0.0;  // [0, 90]
  };
  // The flat horizon (elevation 0 everywhere): nothing blocked.
  HorizonProfile() = default;
  // Points in any order (sorted here); a programming error for none or values out of range
  // (parse_horizon checks a user's file and names the line).
  explicit HorizonProfile(std::vector<Point> points);
  // A constant elevation [deg] at every azimuth.
  static HorizonProfile constant(double elevation_deg);

  // The skyline's elevation [rad] at azimuth `azimuth` [rad] (any value; periodic), linear
  // between the neighbouring points.
  double elevation(double azimuth) const;
  // The direction (unit vector, ENU) is above the skyline: its elevation is above the profile's
  // at its azimuth (and above the geometric horizon).
  bool open(Vec3 direction) const;
  // No point above 0: the geometric horizon.
  bool flat() const { return max_elevation_deg_ <= 0.0; }
  double max_elevation_deg() const { return max_elevation_deg_; }
  const std::vector<Point>& points() const { return points_; }
  // "csv" or "pvgis" (what the file was read as), "flat" or "constant" for those built here.
  const std::string& format() const { return format_; }

 private:
  std::vector<Point> points_;
  double max_elevation_deg_ = 0.0;
  std::string format_ = "flat";
  friend HorizonProfile parse_horizon(std::string_view text, std::string_view source);
};

// Parses a horizon file (any of the formats above); `source` names it in messages, which say the
// line and the field: "<source> line 4: elevation_deg '95' is outside [0, 90]".
HorizonProfile parse_horizon(std::string_view text, std::string_view source);
// Reads and parses a file (IoError naming it when it cannot be read).
HorizonProfile read_horizon(const std::filesystem::path& path);

}  // namespace skylight::io
