// `irradiance`: the light of a sky on a plane (docs/IRRADIANCE.md) — tilt, azimuth, the ground's
// albedo, a horizon profile; by the model's own sky, Perez 1990's transposition or the isotropic
// sky; in W/m^2, lx and melanopic EDI; for one sky or every hour of a weather file.
#include <fmt/format.h>

#include <filesystem>

#include "skylight/core/math.h"
#include "skylight/daylight/irradiance.h"
#include "skylight/daylight/plane_series.h"
#include "skylight/io/epw.h"
#include "skylight/io/file.h"
#include "skylight/io/horizon.h"
#include "skylight/io/table.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/operations.h"

namespace skylight::operations::detail {
namespace {

using daylight::PlaneChannels;
using daylight::PlaneLight;
using daylight::Transposition;

// The annual sums of a series: per key of each channel, Wh/m^2 and lx h (an hour's value is its
// mean, so the sum over hours is the energy or exposure).
struct SeriesSummary {
  std::size_t hours = 0, sun_down = 0, skies = 0;
  std::vector<double> irradiation_wh_m2, exposure_lxh;  // plane_keys' order
  std::vector<std::string> columns;
};

struct IrradianceResult {
  std::string model, transposition;
  daylight::PlaneSettings settings{};
  double albedo = 0.0;
  std::string horizon{};  // "flat", or "<format> <file>"
  std::optional<PlaneChannels> one{};
  SunPosition sun{};
  daylight::HorizonViews views{};
  std::optional<SeriesSummary> series{};
};

// A key of one channel of one sky: the value, or null where the channel or the part is absent.
std::function<std::optional<double>(const IrradianceResult&)> one_value(bool illuminance,
                                                                        std::size_t k) {
  return [illuminance, k](const IrradianceResult& r) -> std::optional<double> {
    if (!r.one) return std::nullopt;
    const auto& light = illuminance ? r.one->illuminance : r.one->irradiance;
    if (!light) return std::nullopt;
    return daylight::plane_value(*light, k);
  };
}

std::function<std::optional<double>(const IrradianceResult&)> series_sum(bool illuminance,
                                                                         std::size_t k) {
  return [illuminance, k](const IrradianceResult& r) -> std::optional<double> {
    if (!r.series) return std::nullopt;
    const auto& v = illuminance ? r.series->exposure_lxh : r.series->irradiation_wh_m2;
    if (v.empty()) return std::nullopt;
    return v[k] / 1000.0;  // kWh/m^2, klx h
  };
}

const std::vector<std::string>& part_meanings() {
  static const std::vector<std::string> m = {
      "global: direct + sky diffuse + ground diffuse",
      "direct: the sun's light, through the horizon",
      "sky diffuse: the sky's light (all its parts)",
      "ground diffuse: the ground's reflected light",
      "the sky's rest: neither circumsolar nor horizon band (perez1990: isotropic term)",
      "the sky within 25 deg of the sun (perez1990: F1 term)",
      "the sky's horizon band below 6.5 deg (perez1990: F2 term)"};
  return m;
}

void add_plane_fields(ResultSchema<IrradianceResult>& s) {
  using R = IrradianceResult;
  for (const bool lx : {false, true}) {
    const auto keys = daylight::plane_keys(lx ? "lx" : "w_m2");
    for (std::size_t k = 0; k < keys.size(); ++k)
      s.number(
          keys[k], lx ? "lx" : "W/m^2",
          fmt::format("{} ({}; one sky)", part_meanings()[k], lx ? "illuminance" : "irradiance"),
          one_value(lx, k));
  }
  s.number("melanopic_edi_lx", "lx",
           "melanopic equivalent daylight (D65) illuminance on the plane (CIE S 026; spectral "
           "models; one sky)",
           [](const R& r) -> std::optional<double> {
             if (!r.one) return std::nullopt;
             return r.one->melanopic_edi_lx;
           });
  for (const bool lx : {false, true}) {
    const auto keys = daylight::plane_keys(lx ? "klxh" : "kwh_m2");
    for (std::size_t k = 0; k < keys.size(); ++k)
      s.number(keys[k], lx ? "klx h" : "kWh/m^2",
               fmt::format("{}, summed over the hours (--epw)", part_meanings()[k]),
               series_sum(lx, k));
  }
}

// Perez 1990's state of one sky (perez1990).
void add_perez_fields(ResultSchema<IrradianceResult>& s) {
  using R = IrradianceResult;
  s.number("epsilon", "1", "perez1990: the sky's clearness (one sky)",
           [](const R& r) -> std::optional<double> {
             if (!r.one || !r.one->perez) return std::nullopt;
             return r.one->perez->epsilon;
           })
      .number("delta", "1", "perez1990: the sky's brightness (one sky)",
              [](const R& r) -> std::optional<double> {
                if (!r.one || !r.one->perez) return std::nullopt;
                return r.one->perez->delta;
              })
      .integer("bin", "1", "perez1990: the clearness bin 1-8 (one sky)",
               [](const R& r) -> std::optional<long long> {
                 if (!r.one || !r.one->perez) return std::nullopt;
                 return r.one->perez->bin;
               })
      .number("f1", "1", "perez1990: the circumsolar coefficient F1 (one sky)",
              [](const R& r) -> std::optional<double> {
                if (!r.one || !r.one->perez) return std::nullopt;
                return r.one->perez->f1;
              })
      .number("f2", "1", "perez1990: the horizon coefficient F2 (one sky)",
              [](const R& r) -> std::optional<double> {
                if (!r.one || !r.one->perez) return std::nullopt;
                return r.one->perez->f2;
              });
}

const ResultSchema<IrradianceResult>& irradiance_result() {
  using R = IrradianceResult;
  const auto one = [](auto get) {
    return [get](const R& r) -> std::optional<double> {
      if (!r.one) return std::nullopt;
      return get(*r.one);
    };
  };
  static const ResultSchema<R> s = [&] {
    ResultSchema<R> s;
    s.text("model", "the sky model", [](const R& r) { return r.model; })
        .text("transposition", "sky, perez1990 or isotropic",
              [](const R& r) { return r.transposition; })
        .number("tilt_deg", "deg", "the plane's tilt",
                [](const R& r) { return r.settings.tilt_deg; })
        .number("surface_azimuth_deg", "deg", "the way the plane faces, from north towards east",
                [](const R& r) { return r.settings.surface_azimuth_deg; })
        .number("albedo", "1", "the ground's reflectance (one sky; --epw: the hours' may differ)",
                [](const R& r) { return r.albedo; })
        .text("horizon", "flat, or the horizon file's format and name",
              [](const R& r) { return r.horizon; })
        .number("sky_view", "1",
                "(1/pi) of the open sky's view integral ((1 + cos tilt)/2 when flat)",
                [](const R& r) { return r.views.sky_view; })
        .number("horizontal_view", "1", "the same for the horizontal plane (1 when flat)",
                [](const R& r) { return r.views.horizontal_view; })
        .number("horizon_band_open", "1", "the open part of the horizon band the plane sees",
                [](const R& r) { return r.views.band_open; });
    add_plane_fields(s);
    s.number("sun_zenith_deg", "deg", "the sun (one sky)",
             [](const R& r) -> std::optional<double> {
               if (!r.one) return std::nullopt;
               return rad_to_deg(r.sun.zenith);
             })
        .number("sun_azimuth_deg", "deg", "the sun, from north towards east (one sky)",
                [](const R& r) -> std::optional<double> {
                  if (!r.one) return std::nullopt;
                  return rad_to_deg(r.sun.azimuth);
                })
        .number("angle_of_incidence_deg", "deg", "between the sun and the plane's normal (one sky)",
                one([](const PlaneChannels& c) { return rad_to_deg(c.angle_of_incidence); }))
        .flag("sun_visible", "the sun is up and above the horizon profile (one sky)",
              [](const R& r) -> std::optional<bool> {
                if (!r.one) return std::nullopt;
                return r.one->sun_open;
              });
    add_perez_fields(s);
    s.texts("notes", "what a channel or part lacks, and why (one sky)",
            [](const R& r) -> std::optional<std::vector<std::string>> {
              if (!r.one) return std::nullopt;
              return r.one->notes;
            })
        .integer("hours", "1", "the series' rows: hours with the sun up (--epw)",
                 [](const R& r) -> std::optional<long long> {
                   if (!r.series) return std::nullopt;
                   return static_cast<long long>(r.series->hours);
                 })
        .integer("records_sun_down", "1", "records with the sun below the horizon (--epw)",
                 [](const R& r) -> std::optional<long long> {
                   if (!r.series) return std::nullopt;
                   return static_cast<long long>(r.series->sun_down);
                 })
        .integer("skies", "1", "the model's skies the series' table computed (--epw, sky)",
                 [](const R& r) -> std::optional<long long> {
                   if (!r.series) return std::nullopt;
                   return static_cast<long long>(r.series->skies);
                 })
        .texts("columns", "the series' columns (--epw)",
               [](const R& r) -> std::optional<std::vector<std::string>> {
                 if (!r.series) return std::nullopt;
                 return r.series->columns;
               });
    return s;
  }();
  return s;
}

// The horizon of the request: its file parsed, or the flat horizon.
io::HorizonProfile request_horizon(const Request& r, std::string& described) {
  if (!r.given("horizon")) {
    described = "flat";
    return {};
  }
  io::HorizonProfile h = io::parse_horizon(r.text_file("horizon"), r.source("horizon"));
  described = fmt::format("{} {}", h.format(), r.source("horizon"));
  return h;
}

IrradianceResult one_sky(const Request& r, IrradianceResult out,
                         const io::HorizonProfile& horizon) {
  const auto model = make_sky(r);
  for (const auto& issue : model->domain().issues)
    r.warn(fmt::format("{} ({}): {}", model->name(), to_string(issue.validity), issue.message));
  const auto plane =
      daylight::plane_context(out.settings.plane(), out.settings.transposition, horizon);
  out.views = plane.views;
  out.sun = model->sun();
  out.albedo = out.settings.albedo.value_or(daylight::kDefaultGroundAlbedo);
  out.one = daylight::plane_light(*model, plane, out.albedo);
  return out;
}

IrradianceResult series(const Request& r, IrradianceResult out, const io::HorizonProfile& horizon,
                        Result& result) {
  const ModelInfo& info = require_model(*r.text("model"), "model");
  const io::EpwFile epw = io::parse_epw(r.text_file("epw"), r.source("epw"));
  const auto plane =
      daylight::plane_context(out.settings.plane(), out.settings.transposition, horizon);
  out.views = plane.views;
  daylight::SeriesSettings settings;
  settings.hours = r.text("hours").value_or("");
  settings.albedo = out.settings.albedo;
  settings.weather_sky = info.weather_sky;
  if (plane.method == Transposition::sky && !info.weather_sky)
    settings.model = daylight::sky_for_sun(info.name, r.values().only(info.parameters));
  if (plane.method != Transposition::sky)
    r.warn(fmt::format("with {}, {} {} transposes each record's light: model '{}' is not read",
                       spelled("epw"), spelled("transposition"), out.transposition, info.name));
  const daylight::PlaneSeries s =
      daylight::plane_series(epw, plane, settings, r.source("epw"),
                             [&](std::size_t done, std::size_t total, std::string_view step) {
                               r.progress(static_cast<int>(done), static_cast<int>(total), step);
                             });
  SeriesSummary sum;
  sum.hours = s.year.hours.size();
  sum.sun_down = s.year.sun_down;
  sum.skies = s.sky_models_built;
  sum.columns = daylight::series_columns(plane);
  const std::size_t keys = daylight::plane_keys("").size();
  sum.irradiation_wh_m2.assign(keys, 0.0);
  if (plane.method != Transposition::perez1990) sum.exposure_lxh.assign(keys, 0.0);
  for (const PlaneChannels& c : s.light)
    for (std::size_t k = 0; k < keys; ++k) {
      sum.irradiation_wh_m2[k] += daylight::plane_value(*c.irradiance, k).value_or(0.0);
      if (!sum.exposure_lxh.empty())
        sum.exposure_lxh[k] += daylight::plane_value(*c.illuminance, k).value_or(0.0);
    }
  const std::vector<double> values = daylight::series_values(s, plane);
  const std::string ext = std::filesystem::path(r.output_path("output")).extension().string();
  r.write_text(result, "output",
               ext == ".npy" ? io::table_npy(sum.columns.size(), values)
                             : io::table_csv(sum.columns, values));
  out.series = std::move(sum);
  return out;
}

OperationInfo irradiance_operation() {
  ParameterSpec epw = input_file("epw", "EnergyPlus weather file: the plane's light every hour",
                                 {".epw"}, "one sky (the model's flags and the sun)");
  ParameterSpec hours;
  for (const ParameterSpec& spec : daylight::MatrixSettings::schema().specs())
    if (spec.name == "hours") hours = spec;
  OperationInfo op{
      .name = "irradiance",
      .summary = "light on a plane: irradiance, illuminance, melanopic EDI; horizons",
      .description =
          "the light of a sky on a tilted plane (tilt, azimuth, the ground's albedo, a horizon "
          "profile): the model's own sky integrated over the plane's view, Perez et al. 1990's "
          "transposition or the isotropic sky; direct, sky and ground parts and the sky's "
          "circumsolar and horizon-band parts; for one sky, or every hour of a weather file "
          "(docs/IRRADIANCE.md)",
      .parameters = concat({model_specs(),
                            daylight::PlaneSettings::schema().specs(),
                            {epw, hours,
                             output_file("output", "the hourly series of --epw", {".csv", ".npy"},
                                         "one sky: its values are the result")}}),
      .relations = model_relations(),
      .model_parameters = true,
      .result = irradiance_result().fields(),
      .result_type = "daylight::PlaneChannels, or the summary of daylight::PlaneSeries"};
  for (ParameterSpec& s : op.parameters)
    if (s.name == "horizon") s.file = FileRole::input;
  for (const char* name : {"sun-zenith", "sun-elevation", "sun-azimuth", "time"})
    op.relations.push_back(unread_with(name, "epw", "the sun of each record"));
  op.relations.push_back(unread_without("hours", "epw"));
  op.relations.push_back(needs("output", "epw", "one sky prints its values"));
  op.check = [](Request& r) {
    if (r.given("epw") && !r.output_wanted("output"))
      throw InvalidArgument(
          fmt::format("{} needs {} FILE.csv or FILE.npy", spelled("epw"), spelled("output")));
  };
  op.run = [](const Request& r, const ProgressSink&) {
    IrradianceResult out;
    out.model = *r.text("model");
    out.settings = r.bind(daylight::PlaneSettings::schema());
    out.transposition = std::get<std::string>(
        *daylight::PlaneSettings::schema().values_of(out.settings).find("transposition"));
    const io::HorizonProfile horizon = request_horizon(r, out.horizon);
    Result result;
    out = r.given("epw") ? series(r, std::move(out), horizon, result)
                         : one_sky(r, std::move(out), horizon);
    result.record = irradiance_result().record(out);
    return result;
  };
  return op;
}

}  // namespace

std::vector<OperationInfo> irradiance_operations() {
  return {irradiance_operation()};
}

}  // namespace skylight::operations::detail
