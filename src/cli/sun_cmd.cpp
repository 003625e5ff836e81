// `skylight sun`: the solar position of the NREL SPA (sun/spa.h, docs/SUN.md) for a time and place:
// topocentric zenith and azimuth with refraction, declination, equation of time, and the local
// day's sunrise, transit and sunset; labelled lines or JSON on standard output.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/operations/operations.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::cli {
namespace {

struct SunCommand {
  SchemaFlags flags;
  bool json = false;
};

// An event as ISO 8601 local time at the input's UTC offset, to the second; null if it does not
// occur on the local date.
nlohmann::ordered_json event_json(const std::optional<sun::SunEvent>& e) {
  if (!e) return nullptr;
  return sun::format_iso8601(e->local, 0);
}

std::string event_text(const std::optional<sun::SunEvent>& e) {
  return e ? sun::format_iso8601(e->local, 0) : "none on this date";
}

int run_sun(const SunCommand& f) {
  const sun::SpaInput in = *solar_position_input(f.flags.values());
  const sun::SpaResult r = sun::solar_position(in);
  const sun::SunEvents ev = sun::sun_events(in);
  const double zenith_deg = rad_to_deg(r.zenith), azimuth_deg = rad_to_deg(r.azimuth);
  const double elevation_deg = 90.0 - zenith_deg;
  const char* polar = ev.kind == sun::DayKind::polar_day     ? "polar_day"
                      : ev.kind == sun::DayKind::polar_night ? "polar_night"
                                                             : nullptr;
  if (f.json) {
    nlohmann::ordered_json j;
    j["time"] = sun::format_iso8601(in.time, 3);
    j["julian_day"] = r.trace.JD;
    j["lat_deg"] = rad_to_deg(in.latitude);
    j["lon_deg"] = rad_to_deg(in.longitude);
    j["elevation_m"] = in.elevation;
    j["pressure_mbar"] = in.pressure;
    j["temperature_degC"] = in.temperature;
    j["delta_t_s"] = in.delta_t;
    j["delta_ut1_s"] = in.delta_ut1;
    j["atmos_refract_deg"] = rad_to_deg(in.atmos_refract);
    j["zenith_deg"] = zenith_deg;
    j["azimuth_deg"] = azimuth_deg;
    j["elevation_deg"] = elevation_deg;
    j["declination_deg"] = r.trace.delta;
    j["topocentric_declination_deg"] = r.trace.delta_prime;
    j["right_ascension_deg"] = r.trace.alpha;
    j["hour_angle_deg"] = r.trace.H_prime;
    j["incidence_deg"] = rad_to_deg(r.incidence);
    j["equation_of_time_min"] = r.equation_of_time;
    j["sunrise"] = event_json(ev.sunrise);
    j["transit"] = event_json(ev.transit);
    j["sunset"] = event_json(ev.sunset);
    j["polar"] = polar ? nlohmann::ordered_json(polar) : nlohmann::ordered_json(nullptr);
    write_stdout(j.dump(2) + "\n");
    return kExitOk;
  }
  std::string out;
  out += fmt::format("time              {}\n", sun::format_iso8601(in.time, 3));
  out += fmt::format("place             lat {} deg, lon {} deg, {} m\n", rad_to_deg(in.latitude),
                     rad_to_deg(in.longitude), in.elevation);
  out += fmt::format("zenith            {:.6f} deg (topocentric, with refraction)\n", zenith_deg);
  out += fmt::format("azimuth           {:.6f} deg (from north towards east)\n", azimuth_deg);
  out += fmt::format("elevation         {:.6f} deg\n", elevation_deg);
  out += fmt::format("declination       {:.6f} deg (geocentric)\n", r.trace.delta);
  out += fmt::format("equation of time  {:.4f} min\n", r.equation_of_time);
  out += fmt::format("sunrise           {}\n", event_text(ev.sunrise));
  out += fmt::format("transit           {}\n", event_text(ev.transit));
  out += fmt::format("sunset            {}\n", event_text(ev.sunset));
  if (polar) out += fmt::format("polar             {}\n", polar);
  write_stdout(out);
  return kExitOk;
}

}  // namespace

void add_sun_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<SunCommand>();
  auto* cmd = app.add_subcommand(
      "sun", "solar position (NREL SPA): zenith, azimuth, sunrise, transit, sunset");
  f->flags.add(*cmd, operations::find("sun").parameters);
  for (const char* name : {"time", "lat", "lon"}) f->flags.option(name)->required();
  cmd->add_flag("--json", f->json, "write JSON instead of labelled lines");
  commands.push_back({cmd, [f] { return run_sun(*f); }});
}

}  // namespace skylight::cli
