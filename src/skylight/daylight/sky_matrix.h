// Annual sky matrices from an EPW weather file (docs/DAYLIGHT.md): for each hour with the sun up,
// the Perez all-weather sky of that hour's direct normal and diffuse horizontal radiation
// (models/perez_allweather.h) sampled at the centre of every sky patch (daylight/sky_patches.h),
// normalised on the patches so that sum_i L_i Omega_i cos(theta_i) is the hour's diffuse
// horizontal illuminance (irradiance, for radiance), as Radiance's gendaymtx normalises; the
// ground patch reflects the global horizontal light; the sun either spread over the patches
// around it or left to the hour's own columns (direct normal values and the sun's angles).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "skylight/core/parameters.h"
#include "skylight/daylight/sky_patches.h"
#include "skylight/io/epw.h"
#include "skylight/models/perez_allweather.h"

namespace skylight::daylight {

// Ground reflectance without --ground-albedo and without the record's albedo (gendaymtx's).
inline constexpr double kDefaultGroundAlbedo = 0.2;
// gendaymtx's weight of a patch receiving the sun: 1 / (1.002 - cos(angle to its centre)).
inline constexpr double kSunWeightOffset = 1.002;

struct MatrixSettings {
  std::string patches = "tregenza";  // tregenza | reinhart2 | reinhart4
  // The sun's direct light in the patch that holds it and the next nearest (weights
  // 1 / (1.002 - cos)); 0: not in the patches (the hour's direct normal columns carry it).
  int sun_patches = 4;
  // FIRST-LAST, 1-based records of the file (e.g. 1-24 = the first day); empty: every record.
  std::string hours;
  std::optional<double> ground_albedo;  // absent: the record's albedo, else 0.2
  std::string quantity = "radiance";    // radiance [W m^-2 sr^-1] | luminance [cd/m^2]
  // --channels radiance,luminance[,melanopic]: several quantities side by side (each channel's
  // patches, named <channel>_p<i>); empty: `quantity` alone (columns p<i>).
  std::string channels;
  PerezCompat compat = PerezCompat::papers;

  static const ParameterSchema<MatrixSettings>& schema();
};

// One row of the matrix: an hour with the sun up at its midpoint.
struct MatrixHour {
  std::size_t record = 0;  // 1-based record of the file
  std::size_t line = 0;    // its line in the file
  int month = 1, day = 1, hour = 1;
  int day_of_year = 1;
  std::optional<double> dew_point_c;                   // the record's, when present
  double sun_zenith_deg = 0.0, sun_azimuth_deg = 0.0;  // at the hour's midpoint (SPA)
  double dni_w_m2 = 0.0, dhi_w_m2 = 0.0;
  double direct_normal_lux = 0.0, diffuse_horizontal_lux = 0.0;  // Perez 1990 efficacies
  double epsilon = 0.0, delta = 0.0;
  int bin = 0;
  std::optional<double> measured_diffuse_lux;  // the file's own, when present
};

struct SkyMatrix {
  PatchSet patches{1};
  MatrixSettings settings;
  std::vector<MatrixHour> hours;
  // hours x patches, row-major, patch 0 = ground.
  std::vector<double> radiance;      // [W m^-2 sr^-1]
  std::vector<double> luminance;     // [cd/m^2]
  std::size_t skipped_sun_down = 0;  // records with the sun below the horizon at the midpoint
  std::size_t dark_hours = 0;        // sun up, no diffuse light: rows of 0

  double value(std::size_t hour, std::size_t patch, bool luminance_values) const {
    return (luminance_values ? luminance : radiance)[hour * patches.size() + patch];
  }
};

// The records of an EPW file that have a sky: those of `hours` ("FIRST-LAST", 1-based; empty:
// every record) with the sun up at their midpoint, in file order, each with its row header, its
// sun (SPA, the hour's midpoint), its albedo and its Perez sky (coefficients, efficacies and
// illuminances; not normalised: callers normalise on their own samples). Errors as sky_matrix's.
struct WeatherHour {
  MatrixHour header;
  SunPosition sun;
  std::optional<double> albedo;  // the record's
  PerezSky sky;
};
struct WeatherYear {
  std::vector<WeatherHour> hours;
  std::size_t sun_down = 0;  // records of the range with the sun below the horizon
};
WeatherYear weather_hours(const io::EpwFile& epw, const std::string& hours, PerezCompat compat,
                          const std::string& source,
                          const std::function<void(std::size_t, std::size_t)>& progress = {});

// The matrix of an EPW file; `source` names it in messages (InvalidArgument "<source> line L:
// ..." for a record the sky cannot use: missing radiation with the sun up, a date the calendar
// does not have, radiation beyond the extraterrestrial). `progress(done, total)` after each record.
SkyMatrix sky_matrix(const io::EpwFile& epw, const MatrixSettings& settings,
                     const std::string& source,
                     const std::function<void(std::size_t, std::size_t)>& progress = {});

// The leading columns of every row, then the patches p0 (ground) .. pN.
const std::vector<std::string>& matrix_hour_columns();
// The matrix's channels in order: each true for luminance, false for radiance (the settings'
// --channels, else its quantity). InvalidArgument for an unknown channel, and for melanopic: the
// weather file's Perez sky has no spectrum.
std::vector<bool> matrix_channels(const MatrixSettings& settings);
// CSV: a header and one row per hour (the settings' channels).
std::string matrix_csv(const SkyMatrix& m);
// NumPy .npy (format 1.0): float64, C order, shape (hours, columns) with the CSV's columns.
std::string matrix_npy(const SkyMatrix& m);

}  // namespace skylight::daylight
