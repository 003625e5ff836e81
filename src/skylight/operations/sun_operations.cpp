// `sun` (the NREL SPA for a time and place, docs/SUN.md) and `daylight` (the Perez sky from
// measured direct and diffuse light, or the annual sky matrix of a weather file,
// docs/DAYLIGHT.md).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "skylight/core/math.h"
#include "skylight/daylight/daylight.h"
#include "skylight/io/epw.h"
#include "skylight/io/file.h"
#include "skylight/models/perez.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/operations.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::operations::detail {
namespace {

// ---- sun ----------------------------------------------------------------------------------------

struct SunResult {
  sun::SpaInput in{};
  sun::SpaResult spa{};
  sun::SunEvents events{};

  double zenith_deg() const { return rad_to_deg(spa.zenith); }
};

// An event as ISO 8601 local time at the input's UTC offset, to the second; null if it does not
// occur on the local date.
std::optional<std::string> event_text(const std::optional<sun::SunEvent>& e) {
  if (!e) return std::nullopt;
  return sun::format_iso8601(e->local, 0);
}

const ResultSchema<SunResult>& sun_result() {
  using R = SunResult;
  static const ResultSchema<R> s = [] {
    ResultSchema<R> s;
    s.text("time", "the time, ISO 8601 with its UTC offset",
           [](const R& r) { return sun::format_iso8601(r.in.time, 3); })
        .number(
            "julian_day", "d", "the Julian Day (UT)", [](const R& r) { return r.spa.trace.JD; }, 6)
        .number("lat_deg", "deg", "the observer's geodetic latitude",
                [](const R& r) { return rad_to_deg(r.in.latitude); })
        .number("lon_deg", "deg", "the observer's longitude, east positive",
                [](const R& r) { return rad_to_deg(r.in.longitude); })
        .number("elevation_m", "m", "the observer's elevation",
                [](const R& r) { return r.in.elevation; })
        .number("pressure_mbar", "mbar", "the air pressure (refraction)",
                [](const R& r) { return r.in.pressure; })
        .number("temperature_degC", "degC", "the air temperature (refraction)",
                [](const R& r) { return r.in.temperature; })
        .number("delta_t_s", "s", "Delta T = TT - UT", [](const R& r) { return r.in.delta_t; })
        .number("delta_ut1_s", "s", "Delta UT1 = UT1 - UTC",
                [](const R& r) { return r.in.delta_ut1; })
        .number("atmos_refract_deg", "deg", "the refraction at sunrise and sunset",
                [](const R& r) { return rad_to_deg(r.in.atmos_refract); })
        .number(
            "zenith_deg", "deg", "topocentric zenith angle with refraction",
            [](const R& r) { return r.zenith_deg(); }, 6)
        .number(
            "azimuth_deg", "deg", "topocentric azimuth from north towards east",
            [](const R& r) { return rad_to_deg(r.spa.azimuth); }, 6)
        .number(
            "elevation_deg", "deg", "90 - zenith", [](const R& r) { return 90.0 - r.zenith_deg(); },
            6)
        .number(
            "declination_deg", "deg", "the geocentric declination",
            [](const R& r) { return r.spa.trace.delta; }, 6)
        .number("topocentric_declination_deg", "deg", "the topocentric declination",
                [](const R& r) { return r.spa.trace.delta_prime; })
        .number("right_ascension_deg", "deg", "the geocentric right ascension",
                [](const R& r) { return r.spa.trace.alpha; })
        .number("hour_angle_deg", "deg", "the topocentric local hour angle",
                [](const R& r) { return r.spa.trace.H_prime; })
        .number("incidence_deg", "deg", "the incidence angle on the surface (slope, rotation)",
                [](const R& r) { return rad_to_deg(r.spa.incidence); })
        .number(
            "equation_of_time_min", "min", "the equation of time",
            [](const R& r) { return r.spa.equation_of_time; }, 4)
        .text("sunrise", "local sunrise, null when none on this date",
              [](const R& r) { return event_text(r.events.sunrise); })
        .text("transit", "local transit, null when none on this date",
              [](const R& r) { return event_text(r.events.transit); })
        .text("sunset", "local sunset, null when none on this date",
              [](const R& r) { return event_text(r.events.sunset); })
        .text("polar", "polar_day or polar_night; null on a normal day",
              [](const R& r) -> std::optional<std::string> {
                if (r.events.kind == sun::DayKind::polar_day) return "polar_day";
                if (r.events.kind == sun::DayKind::polar_night) return "polar_night";
                return std::nullopt;
              });
    return s;
  }();
  return s;
}

OperationInfo sun_operation() {
  std::vector<ParameterSpec> spa{sun::time_spec("")};
  spa.front().default_value = Required{};
  for (const auto& spec : sun::spa_parameter_specs()) spa.push_back(spec);
  OperationInfo op{
      .name = "sun",
      .summary = "solar position (NREL SPA): zenith, azimuth, sunrise, transit, sunset",
      .description =
          "the solar position of the NREL SPA (Reda & Andreas 2004) for a time and place: "
          "topocentric zenith and azimuth, and the day's sunrise, transit, sunset (docs/SUN.md)",
      .parameters = spa,
      .result = sun_result().fields(),
      .result_type = "sun::SpaResult and sun::SunEvents"};
  op.run = [](const Request& r, const ProgressSink&) {
    SunResult s;
    s.in = *solar_position_input(r.values());
    s.spa = sun::solar_position(s.in);
    s.events = sun::sun_events(s.in);
    Result out;
    out.record = sun_result().record(s);
    return out;
  };
  return op;
}

// ---- daylight -----------------------------------------------------------------------------------

// One sky (PerezSky) or the matrix's summary: the other mode's fields are null.
struct DaylightResult {
  std::optional<PerezSky> sky{};
  std::optional<int> day_of_year{};
  std::string compat{};
  std::optional<daylight::SkyMatrix> matrix{};
};

const ResultSchema<DaylightResult>& daylight_result() {
  using R = DaylightResult;
  const auto sky = [](double PerezSky::*m) {
    return [m](const R& r) -> std::optional<double> {
      if (!r.sky) return std::nullopt;
      return (*r.sky).*m;
    };
  };
  const auto coefficient = [](std::size_t k) {
    return [k](const R& r) -> std::optional<double> {
      if (!r.sky) return std::nullopt;
      return r.sky->coefficients[k];
    };
  };
  const auto matrix = [](auto get) {
    return [get](const R& r) -> std::optional<long long> {
      if (!r.matrix) return std::nullopt;
      return static_cast<long long>(get(*r.matrix));
    };
  };
  static const ResultSchema<R> s = [&] {
    ResultSchema<R> s;
    s.number("epsilon", "1", "the sky's clearness (one sky)", sky(&PerezSky::epsilon), 6)
        .integer("bin", "1", "the clearness bin, 1-8 (one sky)",
                 [](const R& r) -> std::optional<long long> {
                   if (!r.sky) return std::nullopt;
                   return r.sky->bin;
                 })
        .number("delta", "1", "the sky's brightness (one sky)", sky(&PerezSky::delta), 6);
    for (std::size_t k = 0; k < 5; ++k)
      s.number(std::string(1, static_cast<char>('a' + k)), "1",
               "a..e of the Perez luminance distribution (one sky)", coefficient(k), 6);
    s.number("zenith_luminance_cd_m2", "cd/m^2", "the normalised sky's zenith luminance",
             sky(&PerezSky::zenith_luminance_cd_m2))
        .number("diffuse_horizontal_lux", "lx", "from the diffuse efficacy model",
                sky(&PerezSky::diffuse_horizontal_lux))
        .number("direct_normal_lux", "lx", "from the direct efficacy model",
                sky(&PerezSky::direct_normal_lux))
        .number("zenith_luminance_model_cd_m2", "cd/m^2",
                "the zenith luminance model (Perez 1990 eq. 10), for comparison",
                sky(&PerezSky::zenith_luminance_model_cd_m2))
        .number("dni_w_m2", "W/m^2", "the direct normal irradiance used", sky(&PerezSky::dni_w_m2))
        .number("dhi_w_m2", "W/m^2", "the diffuse horizontal irradiance used",
                sky(&PerezSky::dhi_w_m2))
        .number("diffuse_efficacy_lm_w", "lm/W", "the diffuse luminous efficacy",
                sky(&PerezSky::diffuse_efficacy))
        .number("direct_efficacy_lm_w", "lm/W", "the direct luminous efficacy",
                sky(&PerezSky::direct_efficacy))
        .number("air_mass", "1", "the relative optical air mass", sky(&PerezSky::air_mass))
        .number("extraterrestrial_w_m2", "W/m^2", "the extraterrestrial normal irradiance",
                sky(&PerezSky::extraterrestrial_w_m2))
        .number("precipitable_water_cm", "cm", "the precipitable water",
                sky(&PerezSky::precipitable_water_cm))
        .number("sky_integral_sr", "sr", "the quadrature of the distribution times cos(theta)",
                sky(&PerezSky::sky_integral))
        .number("sun_zenith_deg", "deg", "the sun the sky uses",
                [](const R& r) -> std::optional<double> {
                  if (!r.sky) return std::nullopt;
                  return rad_to_deg(r.sky->sun.zenith);
                })
        .number("sun_azimuth_deg", "deg", "from north towards east",
                [](const R& r) -> std::optional<double> {
                  if (!r.sky) return std::nullopt;
                  return rad_to_deg(r.sky->sun.azimuth);
                })
        .integer("day_of_year", "1", "the day whose extraterrestrial irradiance is used",
                 [](const R& r) -> std::optional<long long> { return r.day_of_year; })
        .text("compat", "papers or radiance (gendaylit's clamps)",
              [](const R& r) -> std::optional<std::string> {
                if (!r.sky) return std::nullopt;
                return r.compat;
              })
        .flag("dark", "no sky: the sun below the horizon or no diffuse light (one sky)",
              [](const R& r) -> std::optional<bool> {
                if (!r.sky) return std::nullopt;
                return r.sky->dark;
              })
        .texts("notes", "what was adjusted, or why the sky is dark (one sky)",
               [](const R& r) -> std::optional<std::vector<std::string>> {
                 if (!r.sky) return std::nullopt;
                 return r.sky->notes;
               })
        .integer("hours", "1", "the matrix's rows: hours with the sun up (--epw)",
                 matrix([](const daylight::SkyMatrix& m) { return m.hours.size(); }))
        .integer("patches", "1", "the matrix's columns: the ground and the sky patches (--epw)",
                 matrix([](const daylight::SkyMatrix& m) { return m.patches.size(); }))
        .integer("records_sun_down", "1", "records with the sun below the horizon (--epw)",
                 matrix([](const daylight::SkyMatrix& m) { return m.skipped_sun_down; }))
        .integer("hours_without_diffuse_light", "1", "rows of 0 with the sun up (--epw)",
                 matrix([](const daylight::SkyMatrix& m) { return m.dark_hours; }))
        .texts("columns", "the matrix's columns before the patches (--epw)",
               [](const R& r) -> std::optional<std::vector<std::string>> {
                 if (!r.matrix) return std::nullopt;
                 return daylight::matrix_hour_columns();
               });
    return s;
  }();
  return s;
}

DaylightResult daylight_matrix(const Request& r, daylight::DaylightRequest req, Result& out) {
  const io::EpwFile epw = io::read_epw(req.epw);
  req.matrix.compat = req.sky.compat;
  DaylightResult d;
  d.matrix = daylight::sky_matrix(
      epw, req.matrix, io::shown_path(req.epw), [&](std::size_t done, std::size_t total) {
        const std::size_t step = std::max<std::size_t>(1, total / 20);
        if (done % step == 0 || done == total)
          r.progress(static_cast<int>(done), static_cast<int>(total), "hours");
      });
  const std::string ext = std::filesystem::path(r.output_path("output")).extension().string();
  r.write_text(out, "output",
               ext == ".npy" ? daylight::matrix_npy(*d.matrix) : daylight::matrix_csv(*d.matrix));
  return d;
}

DaylightResult daylight_sky(const Request& r, daylight::DaylightRequest req) {
  // The sun (and the date of --time) as every sky gets it (operations::sky_request).
  const SkyParameters sky =
      sky_request(require_model(PerezModel::kName), r.values().only(model_specs())).parameters;
  req.sky.sun = sky.sun;
  if (!req.sky.day_of_year) req.sky.day_of_year = sky.day_of_year;
  const PerezModel model(req.sky);
  for (const auto& issue : model.domain().issues)
    r.warn(fmt::format("{} ({}): {}", model.name(), to_string(issue.validity), issue.message));
  DaylightResult d;
  d.sky = *model.irradiance_sky();
  d.day_of_year = *req.sky.day_of_year;
  d.compat = req.sky.compat == PerezCompat::radiance ? "radiance" : "papers";
  return d;
}

OperationInfo daylight_operation() {
  OperationInfo op{
      .name = "daylight",
      .summary = "Perez skies from measured light; sky matrices from EPW weather files",
      .description =
          "the Perez all-weather sky from measured direct and diffuse light (Perez et al. 1990, "
          "1993): epsilon, delta, the bin, a..e, the zenith luminance and the illuminances; with "
          "--epw, the annual sky matrix of a weather file (docs/DAYLIGHT.md)",
      .parameters = concat({sun_specs("from --time (one sky); from each record (--epw)"),
                            solar_position_specs("the sun from the angles"),
                            daylight::DaylightRequest::schema().specs(),
                            {output_file("output", "the matrix of --epw", {".csv", ".npy"},
                                         "one sky: its values are the result")}}),
      .relations = solar_position_relations({"sun-zenith", "sun-azimuth"}),
      .result = daylight_result().fields(),
      .result_type = "models::PerezSky, or daylight::SkyMatrix"};
  // The file the daylight schema declares as text is an input.
  for (ParameterSpec& s : op.parameters)
    if (s.name == "epw") s.file = FileRole::input;
  for (const std::string& name : daylight::DaylightRequest::one_sky_only())
    op.relations.push_back(unread_with(name, "epw", "each record gives it"));
  for (const char* name : {"sun-zenith", "sun-azimuth", "time"})
    op.relations.push_back(unread_with(name, "epw", "the sun of each record"));
  for (const std::string& name : daylight::DaylightRequest::matrix_only())
    op.relations.push_back(unread_without(name, "epw"));
  op.relations.push_back(needs("output", "epw", "one sky prints its values"));
  op.relations.push_back(excludes("channels", "quantity"));
  op.check = [](Request& r) {
    if (r.given("epw")) {
      daylight::matrix_channels(r.bind(daylight::MatrixSettings::schema()));
      if (!r.output_wanted("output"))
        throw InvalidArgument(
            fmt::format("{} needs {} FILE.csv or FILE.npy", spelled("epw"), spelled("output")));
      return;
    }
    const auto req = r.bind(daylight::DaylightRequest::schema());
    if (!req.sky.from_irradiance())
      throw InvalidArgument(fmt::format("daylight needs {} and {} (or {} and {}), or {} FILE",
                                        spelled("dni"), spelled("dhi"), spelled("dni-illuminance"),
                                        spelled("dhi-illuminance"), spelled("epw")));
    if (!r.given("sun-zenith") && !r.given("time"))
      throw InvalidArgument(fmt::format("daylight needs the sun: {} [{}], or {} {} {}",
                                        spelled("sun-zenith"), spelled("sun-azimuth"),
                                        spelled("time"), spelled("lat"), spelled("lon")));
  };
  op.run = [](const Request& r, const ProgressSink&) {
    const auto req = r.bind(daylight::DaylightRequest::schema());
    Result out;
    const DaylightResult d = req.epw.empty() ? daylight_sky(r, req) : daylight_matrix(r, req, out);
    out.record = daylight_result().record(d);
    return out;
  };
  return op;
}

}  // namespace

std::vector<OperationInfo> sun_operations() {
  return {sun_operation(), daylight_operation()};
}

}  // namespace skylight::operations::detail
