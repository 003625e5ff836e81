// EnergyPlus weather files (EPW; EnergyPlus "Auxiliary Programs", chapter "Weather Converter
// Program", section "EnergyPlus Weather File (EPW) Data Dictionary"): a strict reader.
//
// Layout: 8 header lines, each starting with its keyword in this order: LOCATION, DESIGN
// CONDITIONS, TYPICAL/EXTREME PERIODS, GROUND TEMPERATURES, HOLIDAYS/DAYLIGHT SAVINGS,
// COMMENTS 1, COMMENTS 2, DATA PERIODS; then one record per line of exactly 35 comma-separated
// fields (year, month, day, hour 1..24, minute, data flags, then 29 values). Only the LOCATION
// line is read from the header (city .. elevation); the others are checked for their keyword.
//
// Hour convention: EPW hours are hour-ending in local standard time (the header's time zone, no
// daylight saving): hour h is the interval (h-1, h], and its radiation values are the energy of
// that interval [Wh/m^2] (= the interval's mean irradiance [W/m^2]).
//
// Missing values: each field's documented marker (9999 for radiation, 999999 for illuminance,
// 99.9 for temperatures, ...) or an empty field reads as absent (std::nullopt); a value at or
// above the marker is missing, as EnergyPlus reads it. Present values outside the dictionary's
// range are errors.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skylight::io {

struct EpwLocation {
  std::string city, state, country, source, wmo;
  double latitude_deg = 0.0;   // [-90, 90], north positive
  double longitude_deg = 0.0;  // [-180, 180], east positive
  double time_zone_h = 0.0;    // local standard time minus UTC [h], [-12, 14]
  double elevation_m = 0.0;    // [-1000, 9999.9]
};

// One record: the values skylight reads (the other fields are checked for their number format
// only where skylight reads them; text fields are not interpreted).
struct EpwRecord {
  std::size_t line = 0;  // 1-based line in the file
  int year = 0, month = 1, day = 1;
  int hour = 1;  // 1..24, hour-ending
  int minute = 0;
  std::optional<double> dry_bulb_c, dew_point_c, pressure_pa;
  // Radiation of the hour [Wh/m^2] (the hour's mean irradiance [W/m^2]).
  std::optional<double> global_horizontal_wh_m2, direct_normal_wh_m2, diffuse_horizontal_wh_m2;
  // Illuminance [lx] and zenith luminance [cd/m^2], the hour's means.
  std::optional<double> global_horizontal_lux, direct_normal_lux, diffuse_horizontal_lux;
  std::optional<double> zenith_luminance_cd_m2;
  std::optional<double> precipitable_water_mm;
  std::optional<double> albedo;
};

struct EpwFile {
  EpwLocation location;
  std::vector<EpwRecord> records;
};

// The number of fields of a record.
inline constexpr std::size_t kEpwFields = 35;

// Parses an EPW text; `source` names it in messages. Throws InvalidArgument "<source> line L:
// <what>" naming the line and the field (e.g. "<source> line 12: field 15 (direct normal
// radiation) 'abc' is not a number"), for: a header line with the wrong keyword, a LOCATION line
// without 10 fields or with a value out of range, a record without 35 fields, a malformed or
// out-of-range value, no records.
EpwFile parse_epw(std::string_view text, std::string_view source);
// Reads and parses a file (IoError naming it when it cannot be read).
EpwFile read_epw(const std::filesystem::path& path);

}  // namespace skylight::io
