// The hourly light on a plane over a weather file (`skylight irradiance --epw`,
// docs/IRRADIANCE.md): one row per record with the sun up (daylight/sky_matrix.h, weather_hours),
// each the plane's light of that hour by part, in W/m^2 and, where the method gives it, lx.
//
// The hour's sky:
//  * perez1990 and isotropic transpose the record's light (its direct normal and diffuse
//    horizontal irradiance; the illuminances of the Perez 1990 efficacy models): no sky model;
//  * `sky` with a weather model (ModelInfo::weather_sky: perez): the hour's Perez all-weather sky
//    of the record's light, its relative luminance at the grid's cells;
//  * `sky` with any other model: the model's sky at its own parameters and the hour's sun, from a
//    table over the sun's zenith angle (kSeriesZenithStep, linear between rows) turned to the
//    sun's azimuth (linear between the grid's sectors): the skies of the registry turn with the
//    sun's azimuth over a uniform ground. Either sky is scaled to the hour's measured diffuse light
//    (measured_sky_light): the model gives the distribution, the weather file the level.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "skylight/daylight/irradiance.h"
#include "skylight/daylight/sky_matrix.h"
#include "skylight/io/epw.h"

namespace skylight::daylight {

// The table's step in the sun's zenith angle (its interpolation error is measured in
// plane_series_test.cpp).
inline constexpr double kSeriesZenithStep = 1.0 * kDegree;

// A model's sky for a sun (its own parameters otherwise); absent in the series of a transposition
// or of a weather sky.
using SkyForSun = std::function<std::unique_ptr<SkyModel>(const SunPosition&)>;

// Model `name`'s sky for each sun at its own parameter values `values` (make_sky_model).
SkyForSun sky_for_sun(std::string name, ParameterValues values);

struct SeriesSettings {
  std::string hours;  // FIRST-LAST records (1-based); empty: every record
  PerezCompat compat = PerezCompat::papers;
  std::optional<double> albedo;  // absent: the record's, else kDefaultGroundAlbedo
  bool weather_sky = false;      // `sky`: the hour's Perez all-weather sky
  SkyForSun model;               // `sky` without weather_sky: the model's sky
};

struct PlaneSeries {
  WeatherYear year;                  // the hours with a sky, and the records without
  std::vector<PlaneChannels> light;  // one per hour
  std::vector<double> albedo;        // the ground's reflectance of each hour
  std::size_t sky_models_built = 0;  // the table's skies (`sky` without weather_sky)
};

// `progress(done, total, step)` after each record read and each table row. Several planes share
// the hours' skies (one series per plane, in order).
std::vector<PlaneSeries> plane_series(
    const io::EpwFile& epw, const std::vector<const PlaneContext*>& planes,
    const SeriesSettings& settings, const std::string& source,
    const std::function<void(std::size_t, std::size_t, std::string_view)>& progress = {});
PlaneSeries plane_series(
    const io::EpwFile& epw, const PlaneContext& plane, const SeriesSettings& settings,
    const std::string& source,
    const std::function<void(std::size_t, std::size_t, std::string_view)>& progress = {});

// The series' columns: the hour's (record, month, day, hour, sun_zenith_deg, sun_azimuth_deg,
// dni_w_m2, dhi_w_m2, albedo, angle_of_incidence_deg), then the plane's keys of each channel the
// method gives (series_keys), and the values in that order, row-major.
std::vector<std::string> series_columns(const PlaneContext& plane);
std::vector<double> series_values(const PlaneSeries& series, const PlaneContext& plane);

// The plane's keys of one channel, in order: poa_global, poa_direct, poa_sky_diffuse,
// poa_ground_diffuse, poa_isotropic, poa_circumsolar, poa_horizon, each with `suffix` (_w_m2, _lx).
std::vector<std::string> plane_keys(const std::string& suffix);
// The value of key k (plane_keys' order) of a channel's light (nullopt where it has none).
std::optional<double> plane_value(const PlaneLight& light, std::size_t k);

}  // namespace skylight::daylight
