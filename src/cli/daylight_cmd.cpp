// `skylight daylight`: the Perez all-weather sky from measured direct and diffuse light (one set
// of inputs: epsilon, delta, the bin, a..e, the zenith luminance and the illuminances; labelled
// lines or JSON), or with --epw the annual sky matrix of a weather file (docs/DAYLIGHT.md).
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/daylight/daylight.h"
#include "skylight/io/epw.h"
#include "skylight/io/file.h"
#include "skylight/models/perez.h"
#include "skylight/operations/operations.h"
#include "skylight/sun/time.h"

namespace skylight::cli {
namespace {

struct DaylightCommand {
  SchemaFlags flags;
  std::string output;
  bool json = false;
};

int run_matrix(const DaylightCommand& f, daylight::DaylightRequest req,
               const ParameterValues& given) {
  for (const std::string& name : daylight::DaylightRequest::one_sky_only())
    if (given.has(name))
      warn(fmt::format("--{} is not read with --epw (each record gives it); ignored", name));
  for (const auto& spec :
       operations::select(operations::find("daylight"), {"sun-zenith", "sun-azimuth", "time"}))
    if (given.has(spec.name))
      warn(fmt::format("--{} is not read with --epw (the sun of each record); ignored", spec.name));
  if (f.output.empty())
    throw InvalidArgument("daylight --epw needs -o/--output FILE.csv or FILE.npy");
  const std::string ext = std::filesystem::path(f.output).extension().string();
  if (ext != ".csv" && ext != ".npy")
    throw InvalidArgument(fmt::format("-o/--output '{}': the matrix is written as .csv or .npy",
                                      io::shown_path(f.output)));
  const io::EpwFile epw = io::read_epw(req.epw);
  req.matrix.compat = req.sky.compat;
  Progress progress("daylight");
  const daylight::SkyMatrix m = daylight::sky_matrix(
      epw, req.matrix, io::shown_path(req.epw), [&](std::size_t done, std::size_t total) {
        const std::size_t step = std::max<std::size_t>(1, total / 20);
        if (done % step == 0 || done == total)
          progress(static_cast<int>(done), static_cast<int>(total), "hours");
      });
  io::write_text_file(f.output, ext == ".npy" ? daylight::matrix_npy(m) : daylight::matrix_csv(m));
  announce_after_commit(
      fmt::format("skylight daylight: wrote {} hours x {} patches ({}) to {}", m.hours.size(),
                  m.patches.size(), req.matrix.quantity, io::shown_path(f.output)),
      true);
  if (f.json) {
    nlohmann::ordered_json j;
    j["hours"] = m.hours.size();
    j["patches"] = m.patches.size();
    j["records_sun_down"] = m.skipped_sun_down;
    j["hours_without_diffuse_light"] = m.dark_hours;
    j["columns"] = daylight::matrix_hour_columns();
    write_stdout(j.dump(2) + "\n");
  }
  return kExitOk;
}

int run_daylight(const DaylightCommand& f) {
  const ParameterValues given = f.flags.values();
  daylight::DaylightRequest req =
      f.flags.bind(daylight::DaylightRequest::schema(), daylight::DaylightRequest{}, "daylight");
  if (!req.epw.empty()) return run_matrix(f, req, given);
  for (const std::string& name : daylight::DaylightRequest::matrix_only())
    if (given.has(name)) warn(fmt::format("--{} is read with --epw only; ignored", name));
  if (!f.output.empty())
    throw InvalidArgument("-o/--output is the matrix of --epw; one sky prints to standard output");
  if (!req.sky.from_irradiance())
    throw InvalidArgument(
        "daylight needs --dni and --dhi (or --dni-illuminance and --dhi-illuminance), or --epw "
        "FILE");
  if (!given.has("sun-zenith") && !given.has("time"))
    throw InvalidArgument(
        "daylight needs the sun: --sun-zenith [--sun-azimuth], or --time --lat "
        "--lon");
  // The sun (and the date of --time) as every sky gets it (operations::sky_request).
  const SkyParameters sky = operations::sky_request(require_model(PerezModel::kName),
                                                    given.only(operations::model_specs()))
                                .parameters;
  req.sky.sun = sky.sun;
  if (!req.sky.day_of_year) req.sky.day_of_year = sky.day_of_year;
  const PerezModel model(req.sky);
  warn_domain(model);
  const PerezSky& s = *model.irradiance_sky();
  const auto& k = s.coefficients;
  if (f.json) {
    nlohmann::ordered_json j;
    j["epsilon"] = s.epsilon;
    j["delta"] = s.delta;
    j["bin"] = s.bin;
    j["a"] = k[0];
    j["b"] = k[1];
    j["c"] = k[2];
    j["d"] = k[3];
    j["e"] = k[4];
    j["zenith_luminance_cd_m2"] = s.zenith_luminance_cd_m2;
    j["diffuse_horizontal_lux"] = s.diffuse_horizontal_lux;
    j["direct_normal_lux"] = s.direct_normal_lux;
    j["zenith_luminance_model_cd_m2"] = s.zenith_luminance_model_cd_m2;
    j["dni_w_m2"] = s.dni_w_m2;
    j["dhi_w_m2"] = s.dhi_w_m2;
    j["diffuse_efficacy_lm_w"] = s.diffuse_efficacy;
    j["direct_efficacy_lm_w"] = s.direct_efficacy;
    j["air_mass"] = s.air_mass;
    j["extraterrestrial_w_m2"] = s.extraterrestrial_w_m2;
    j["precipitable_water_cm"] = s.precipitable_water_cm;
    j["sky_integral_sr"] = s.sky_integral;
    j["sun_zenith_deg"] = rad_to_deg(s.sun.zenith);
    j["sun_azimuth_deg"] = rad_to_deg(s.sun.azimuth);
    j["day_of_year"] = *req.sky.day_of_year;
    j["compat"] = req.sky.compat == PerezCompat::radiance ? "radiance" : "papers";
    j["dark"] = s.dark;
    j["notes"] = s.notes;
    write_stdout(j.dump(2) + "\n");
    return kExitOk;
  }
  std::string out;
  out += fmt::format("epsilon                 {:.6f} (bin {})\n", s.epsilon, s.bin);
  out += fmt::format("delta                   {:.6f}\n", s.delta);
  out += fmt::format("a b c d e               {:.6f} {:.6f} {:.6f} {:.6f} {:.6f}\n", k[0], k[1],
                     k[2], k[3], k[4]);
  out += fmt::format("zenith luminance        {:.6g} cd/m^2 (efficacy model: {:.6g})\n",
                     s.zenith_luminance_cd_m2, s.zenith_luminance_model_cd_m2);
  out += fmt::format("diffuse horizontal      {:.6g} lx ({:.6g} W/m^2, {:.5g} lm/W)\n",
                     s.diffuse_horizontal_lux, s.dhi_w_m2, s.diffuse_efficacy);
  out += fmt::format("direct normal           {:.6g} lx ({:.6g} W/m^2, {:.5g} lm/W)\n",
                     s.direct_normal_lux, s.dni_w_m2, s.direct_efficacy);
  out += fmt::format("sun zenith              {:.4f} deg, air mass {:.5f}\n",
                     rad_to_deg(s.sun.zenith), s.air_mass);
  out += fmt::format("precipitable water      {:.4f} cm\n", s.precipitable_water_cm);
  for (const std::string& n : s.notes) out += fmt::format("note                    {}\n", n);
  write_stdout(out);
  return kExitOk;
}

}  // namespace

void add_daylight_command(CLI::App& app, Commands& commands) {
  auto f = std::make_shared<DaylightCommand>();
  auto* cmd = app.add_subcommand(
      "daylight",
      "Perez skies from measured light; sky matrices from EPW weather files\n"
      "The Perez all-weather sky from measured direct and diffuse light (Perez et al. 1990, "
      "1993): epsilon, delta, the bin, a..e, the zenith luminance and the illuminances; with "
      "--epw FILE -o OUT.csv|OUT.npy the annual sky matrix (docs/DAYLIGHT.md).");
  f->flags.add(*cmd, operations::find("daylight").parameters);
  wire_solar_position(f->flags, {"sun-zenith", "sun-azimuth"});
  cmd->add_option("-o,--output", f->output, "the matrix of --epw: FILE.csv or FILE.npy");
  cmd->add_flag("--json", f->json, "write JSON instead of labelled lines");
  commands.push_back({cmd, [f] { return run_daylight(*f); }});
}

}  // namespace skylight::cli
