#include "skylight/daylight/sky_matrix.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/io/table.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::daylight {
namespace {

// The record range of --hours ("FIRST-LAST", 1-based, inclusive) within `count` records.
std::pair<std::size_t, std::size_t> hour_range(const std::string& text, std::size_t count) {
  if (text.empty()) return {1, count};
  const auto dash = text.find('-');
  const auto first = dash == std::string::npos
                         ? std::nullopt
                         : parse_integer(std::string_view(text).substr(0, dash));
  const auto last = dash == std::string::npos
                        ? std::nullopt
                        : parse_integer(std::string_view(text).substr(dash + 1));
  if (!first || !last || *first < 1 || *last < *first)
    throw InvalidArgument(fmt::format("{} '{}' must be FIRST-LAST with 1 <= FIRST <= LAST",
                                      spelled("hours"), excerpt(text)));
  if (static_cast<std::size_t>(*last) > count)
    throw InvalidArgument(fmt::format("{} '{}' goes beyond the file's {} records", spelled("hours"),
                                      excerpt(text), count));
  return {static_cast<std::size_t>(*first), static_cast<std::size_t>(*last)};
}

// The midpoint of an hour-ending record in local standard time (the header's time zone).
sun::DateTime midpoint(const io::EpwRecord& r, double time_zone_h) {
  sun::DateTime t;
  t.year = r.year;
  t.month = r.month;
  t.day = r.day;
  t.hour = r.hour - 1;
  t.minute = 30;
  t.utc_offset_minutes = static_cast<int>(std::lround(time_zone_h * 60.0));
  return t;
}

// The SPA's input for a record: the midpoint of its hour at the file's location, with the
// record's pressure and temperature where it has them.
sun::SpaInput spa_input(const io::EpwRecord& r, const io::EpwLocation& loc) {
  sun::SpaInput spa;
  spa.time = midpoint(r, loc.time_zone_h);
  spa.latitude = deg_to_rad(loc.latitude_deg);
  spa.longitude = deg_to_rad(loc.longitude_deg);
  spa.elevation = loc.elevation_m;
  if (r.pressure_pa) spa.pressure = *r.pressure_pa / 100.0;
  if (r.dry_bulb_c) spa.temperature = *r.dry_bulb_c;
  return spa;
}

// The matrix's row header of record k: its date, sun and the sky's parameters.
MatrixHour matrix_hour(std::size_t k, const io::EpwRecord& r, int day_of_year,
                       const sun::SpaResult& sp, const PerezSky& sky) {
  MatrixHour h;
  h.record = k;
  h.line = r.line;
  h.month = r.month;
  h.day = r.day;
  h.hour = r.hour;
  h.day_of_year = day_of_year;
  h.dew_point_c = r.dew_point_c;
  h.sun_zenith_deg = rad_to_deg(sp.zenith);
  h.sun_azimuth_deg = rad_to_deg(sp.azimuth);
  h.dni_w_m2 = sky.dni_w_m2;
  h.dhi_w_m2 = sky.dhi_w_m2;
  h.direct_normal_lux = sky.direct_normal_lux;
  h.diffuse_horizontal_lux = sky.diffuse_horizontal_lux;
  h.epsilon = sky.epsilon;
  h.delta = sky.delta;
  h.bin = sky.bin;
  h.measured_diffuse_lux = r.diffuse_horizontal_lux;
  return h;
}

// The sky at the patch centres, normalised on the patches (gendaymtx's normalisation), into the
// row starting at `row` (lv: a buffer of one value per patch).
void add_sky(const std::vector<SkyPatch>& ps, const PerezSky& sky, std::vector<double>& lv,
             SkyMatrix& m, std::size_t row) {
  const std::size_t n = ps.size();
  const Vec3 sun_dir = sky.sun.direction();
  double sum = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const Vec3 c = ps[i].centre;
    lv[i] = std::max(0.0, allweather_relative_luminance(sky.coefficients, std::acos(c.z),
                                                        angle_between(c, sun_dir)));
    sum += lv[i] * ps[i].solid_angle * c.z;
  }
  if (sum > 0.0) {
    for (std::size_t i = 1; i < n; ++i) {
      m.radiance[row + i] = sky.dhi_w_m2 * lv[i] / sum;
      m.luminance[row + i] = sky.diffuse_horizontal_lux * lv[i] / sum;
    }
  }
}

// The sun in the patch that holds it and the next nearest (weights 1 / (1.002 - cos)), added to
// the row starting at `row`.
void add_sun(const SunPosition& sun, const PerezSky& sky, int sun_patches, SkyMatrix& m,
             std::size_t row) {
  const std::vector<SkyPatch>& ps = m.patches.patches();
  const std::size_t n = ps.size();
  const Vec3 s = sun.direction();
  const std::size_t holder = m.patches.find(s);
  std::vector<std::size_t> order(n - 1);
  std::iota(order.begin(), order.end(), std::size_t{1});
  const auto k_sun = std::min<std::size_t>(static_cast<std::size_t>(sun_patches), n - 1);
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(k_sun), order.end(),
                    [&](std::size_t a, std::size_t b) {
                      if ((a == holder) != (b == holder)) return a == holder;
                      return dot(ps[a].centre, s) > dot(ps[b].centre, s);
                    });
  double wsum = 0.0;
  std::vector<double> w(k_sun);
  for (std::size_t j = 0; j < k_sun; ++j)
    wsum += w[j] = 1.0 / (kSunWeightOffset - dot(ps[order[j]].centre, s));
  for (std::size_t j = 0; j < k_sun; ++j) {
    const std::size_t i = order[j];
    m.radiance[row + i] += sky.dni_w_m2 * w[j] / wsum / ps[i].solid_angle;
    m.luminance[row + i] += sky.direct_normal_lux * w[j] / wsum / ps[i].solid_angle;
  }
}

}  // namespace

const ParameterSchema<MatrixSettings>& MatrixSettings::schema() {
  static const auto s = [] {
    ParameterSchema<MatrixSettings> s;
    s.text(&MatrixSettings::patches,
           {.name = "patches",
            .default_value = ParameterValue(std::string("tregenza")),
            .description = "sky subdivision: Tregenza's 145 patches or Reinhart's 577 / 2305 "
                           "(plus the ground)",
            .choices = {"tregenza", "reinhart2", "reinhart4"}});
    s.integer(&MatrixSettings::sun_patches,
              {.name = "sun-patches",
               .min = 0,
               .max = 16,
               .default_value = ParameterValue(4.0),
               .description = "patches that receive the sun's direct light (the one holding the "
                              "sun and the next nearest); 0: the sun stays in its own columns"});
    s.text(&MatrixSettings::hours, {.name = "hours",
                                    .default_value = Absent{"every record"},
                                    .description = "records FIRST-LAST of the file (1-based)"});
    s.optional_number(&MatrixSettings::ground_albedo,
                      {.name = "ground-albedo",
                       .unit = "1",
                       .min = 0.0,
                       .max = 1.0,
                       .default_value = Absent{"the record's albedo, else 0.2"},
                       .description = "reflectance of the ground patch"});
    s.text(&MatrixSettings::channels,
           {.name = "channels",
            .default_value = Absent{"--quantity's one"},
            .description = "radiance,luminance: both, side by side (<channel>_p<i> columns); "
                           "melanopic needs spectra the weather sky has not"});
    s.text(&MatrixSettings::quantity,
           {.name = "quantity",
            .default_value = ParameterValue(std::string("radiance")),
            .description = "patch values: radiance [W m^-2 sr^-1] or luminance [cd/m^2]",
            .choices = {"radiance", "luminance"}});
    return s;
  }();
  return s;
}

WeatherYear weather_hours(const io::EpwFile& epw, const std::string& hours, PerezCompat compat,
                          const std::string& source,
                          const std::function<void(std::size_t, std::size_t)>& progress) {
  WeatherYear year;
  const auto [first, last] = hour_range(hours, epw.records.size());
  const io::EpwLocation& loc = epw.location;
  for (std::size_t k = first; k <= last; ++k) {
    const io::EpwRecord& r = epw.records[k - 1];
    auto fail = [&](const std::string& what) -> InvalidArgument {
      return InvalidArgument(fmt::format("{} line {}: {}", source, r.line, what));
    };
    const sun::SpaInput spa = spa_input(r, loc);
    sun::SpaResult sp;
    try {
      sun::validate(spa.time, "date");
      sp = sun::solar_position(spa);
    } catch (const InvalidArgument& e) {
      throw fail(e.what());
    }
    if (progress) progress(k - first + 1, last - first + 1);
    if (sp.zenith >= 0.5 * kPi) {
      ++year.sun_down;
      continue;
    }
    if (!r.direct_normal_wh_m2 || !r.diffuse_horizontal_wh_m2)
      throw fail(fmt::format("the sun is up ({:.2f} deg) and the {} radiation is missing",
                             90.0 - rad_to_deg(sp.zenith),
                             !r.direct_normal_wh_m2 ? "direct normal" : "diffuse horizontal"));
    PerezIrradianceInput in;
    in.sun = {sp.zenith, sp.azimuth};
    in.dni_w_m2 = *r.direct_normal_wh_m2;
    in.dhi_w_m2 = *r.diffuse_horizontal_wh_m2;
    in.day_of_year = sun::day_of_year(spa.time);
    in.dew_point_c = r.dew_point_c;
    in.compat = compat;
    in.normalise = false;
    WeatherHour h;
    try {
      h.sky = perez_sky_from_irradiance(in);
    } catch (const InvalidArgument& e) {
      throw fail(e.what());
    }
    h.header = matrix_hour(k, r, in.day_of_year, sp, h.sky);
    h.sun = {sp.zenith, sp.azimuth};
    h.albedo = r.albedo;
    year.hours.push_back(std::move(h));
  }
  return year;
}

SkyMatrix sky_matrix(const io::EpwFile& epw, const MatrixSettings& settings,
                     const std::string& source,
                     const std::function<void(std::size_t, std::size_t)>& progress) {
  MatrixSettings::schema().validate(settings, "daylight");
  auto patches = PatchSet::named(settings.patches);
  if (!patches)
    throw InvalidArgument(fmt::format("{} '{}' is not tregenza, reinhart2 or reinhart4",
                                      spelled("patches"), excerpt(settings.patches)));
  SkyMatrix m;
  m.patches = std::move(*patches);
  m.settings = settings;
  const std::vector<SkyPatch>& ps = m.patches.patches();
  const std::size_t n = ps.size();
  const WeatherYear year = weather_hours(epw, settings.hours, settings.compat, source, progress);
  m.skipped_sun_down = year.sun_down;
  std::vector<double> lv(n, 0.0);
  for (const WeatherHour& h : year.hours) {
    const PerezSky& sky = h.sky;
    m.hours.push_back(h.header);
    const std::size_t row = m.radiance.size();
    m.radiance.resize(row + n, 0.0);
    m.luminance.resize(row + n, 0.0);
    if (sky.dark) {
      ++m.dark_hours;
      continue;
    }
    // The sky at the patch centres, normalised on the patches (gendaymtx's normalisation).
    add_sky(ps, sky, lv, m, row);
    // The ground: a Lambertian reflector of the global horizontal light.
    const double albedo = settings.ground_albedo.value_or(h.albedo.value_or(kDefaultGroundAlbedo));
    const double cos_z = std::cos(h.sun.zenith);
    m.radiance[row] = albedo * (sky.dhi_w_m2 + sky.dni_w_m2 * cos_z) / kPi;
    m.luminance[row] = albedo * (sky.diffuse_horizontal_lux + sky.direct_normal_lux * cos_z) / kPi;
    // The sun in the patch that holds it and the next nearest (weights 1 / (1.002 - cos)).
    if (settings.sun_patches > 0 && sky.dni_w_m2 > 0.0)
      add_sun(h.sun, sky, settings.sun_patches, m, row);
  }
  return m;
}

const std::vector<std::string>& matrix_hour_columns() {
  static const std::vector<std::string> c = {"record",
                                             "month",
                                             "day",
                                             "hour",
                                             "sun_zenith_deg",
                                             "sun_azimuth_deg",
                                             "dni_w_m2",
                                             "dhi_w_m2",
                                             "direct_normal_lux",
                                             "diffuse_horizontal_lux",
                                             "epsilon",
                                             "delta",
                                             "bin"};
  return c;
}

namespace {

std::vector<double> hour_values(const MatrixHour& h) {
  return {static_cast<double>(h.record),
          static_cast<double>(h.month),
          static_cast<double>(h.day),
          static_cast<double>(h.hour),
          h.sun_zenith_deg,
          h.sun_azimuth_deg,
          h.dni_w_m2,
          h.dhi_w_m2,
          h.direct_normal_lux,
          h.diffuse_horizontal_lux,
          h.epsilon,
          h.delta,
          static_cast<double>(h.bin)};
}

}  // namespace

std::vector<bool> matrix_channels(const MatrixSettings& settings) {
  if (settings.channels.empty()) return {settings.quantity == "luminance"};
  std::vector<bool> out;
  std::string_view rest = settings.channels;
  while (true) {
    const std::size_t comma = rest.find(',');
    const std::string_view c = trim(rest.substr(0, comma));
    if (c == "radiance" || c == "luminance") {
      out.push_back(c == "luminance");
    } else if (c == "melanopic") {
      throw InvalidArgument(fmt::format(
          "{} melanopic: the weather file's Perez all-weather sky has no spectrum (melanopic light "
          "needs a spectral model's sky: `skylight irradiance` gives melanopic_edi_lx for hosek, "
          "preetham, hillaire and bruneton)",
          spelled("channels")));
    } else {
      throw InvalidArgument(fmt::format("{} '{}': '{}' is not radiance, luminance or melanopic",
                                        spelled("channels"), excerpt(settings.channels),
                                        excerpt(c)));
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return out;
}

namespace {

// The patch columns of every channel: p<i>, or <channel>_p<i> with several channels.
std::vector<std::string> patch_columns(const SkyMatrix& m) {
  const std::vector<bool> channels = matrix_channels(m.settings);
  std::vector<std::string> out;
  for (const bool lum : channels)
    for (std::size_t i = 0; i < m.patches.size(); ++i)
      out.push_back(channels.size() > 1 ? fmt::format("{}_p{}", lum ? "luminance" : "radiance", i)
                                        : fmt::format("p{}", i));
  return out;
}

}  // namespace

std::string matrix_csv(const SkyMatrix& m) {
  const std::vector<bool> channels = matrix_channels(m.settings);
  std::string out;
  for (const auto& c : matrix_hour_columns()) out += c + ",";
  const auto columns = patch_columns(m);
  for (std::size_t i = 0; i < columns.size(); ++i)
    out += columns[i] + (i + 1 < columns.size() ? "," : "\n");
  for (std::size_t h = 0; h < m.hours.size(); ++h) {
    for (double v : hour_values(m.hours[h])) out += fmt::format("{},", v);
    for (std::size_t c = 0; c < channels.size(); ++c)
      for (std::size_t i = 0; i < m.patches.size(); ++i)
        out += fmt::format("{:.7g}{}", m.value(h, i, channels[c]),
                           c + 1 == channels.size() && i + 1 == m.patches.size() ? '\n' : ',');
  }
  return out;
}

std::string matrix_npy(const SkyMatrix& m) {
  const std::vector<bool> channels = matrix_channels(m.settings);
  const std::size_t cols = matrix_hour_columns().size() + channels.size() * m.patches.size();
  std::string out = io::npy_header(m.hours.size(), cols);
  for (std::size_t h = 0; h < m.hours.size(); ++h) {
    for (double v : hour_values(m.hours[h])) io::append_npy_value(out, v);
    for (const bool lum : channels)
      for (std::size_t i = 0; i < m.patches.size(); ++i)
        io::append_npy_value(out, m.value(h, i, lum));
  }
  return out;
}

}  // namespace skylight::daylight
