#include "skylight/operations/operations.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/core/text.h"
#include "skylight/daylight/daylight.h"
#include "skylight/estimate/capture.h"
#include "skylight/estimate/photo.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/fit/network_training.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/haze/request.h"
#include "skylight/io/camera_calibration.h"
#include "skylight/io/file.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/models/sh.h"
#include "skylight/models/sky_model.h"
#include "skylight/operations/detail/families.h"
#include "skylight/perf/bench.h"
#include "skylight/render/animation.h"
#include "skylight/render/false_colour.h"
#include "skylight/report/report.h"
#include "skylight/sh/irradiance.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"
#include "skylight/version.h"

namespace skylight::operations {

using Specs = std::vector<ParameterSpec>;

namespace detail {

Specs concat(std::initializer_list<Specs> parts) {
  Specs out;
  for (const Specs& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

namespace {
ParameterSpec file_spec(std::string name, std::string description, std::vector<std::string> formats,
                        std::string absent, FileRole role) {
  ParameterSpec s{
      .name = std::move(name), .kind = ParameterKind::text, .description = std::move(description)};
  if (!absent.empty()) s.default_value = Absent{std::move(absent)};
  s.file = role;
  s.formats = std::move(formats);
  return s;
}
}  // namespace

ParameterSpec input_file(std::string name, std::string description,
                         std::vector<std::string> formats, std::string absent) {
  return file_spec(std::move(name), std::move(description), std::move(formats), std::move(absent),
                   FileRole::input);
}

ParameterSpec output_file(std::string name, std::string description,
                          std::vector<std::string> formats, std::string absent) {
  return file_spec(std::move(name), std::move(description), std::move(formats), std::move(absent),
                   FileRole::output);
}

void check_input_folder(const Request& r, const std::string& name) {
  if (const auto dir = r.text(name)) {
    std::error_code ec;
    if (!std::filesystem::is_directory(*dir, ec))
      throw InvalidArgument(
          fmt::format("{} '{}': {}", spelled(name), io::shown_path(*dir),
                      std::filesystem::exists(*dir, ec) ? "not a folder" : "no such folder"));
  }
}

std::vector<Relation> solar_position_relations(const std::vector<std::string>& angles) {
  std::vector<Relation> r;
  for (const std::string& a : angles) r.push_back(excludes("time", a, "time gives the sun"));
  for (const char* name : kSolarPositionNames) r.push_back(needs(name, "time"));
  return r;
}

}  // namespace detail

using detail::concat;

std::vector<ParameterSpec> sun_specs(const std::string& absent) {
  Specs s = sun_parameter_specs();
  if (!absent.empty())
    for (ParameterSpec& spec : s) spec.default_value = Absent{absent};
  return s;
}

std::vector<ParameterSpec> solar_position_specs(const std::string& time_absent) {
  Specs s{sun::time_spec(time_absent)};
  for (const char* name : detail::kSolarPositionNames) {
    s.push_back(sun::spa_parameter_spec(name));
    // The place is required with a time only (the relations say so: each needs --time).
    if (s.back().required()) s.back().default_value = Absent{"required with a time"};
  }
  return s;
}

std::vector<ParameterSpec> model_specs() {
  Specs sun = sun_parameter_specs();
  return concat({{model_spec(), sun[0], sun_elevation_spec(), sun[1]},
                 solar_position_specs("the sun from the angles"),
                 SolarDisc::schema().specs()});
}

std::vector<ParameterSpec> without_model_specs(const OperationInfo& op) {
  const Specs model = model_specs();
  Specs own;
  for (const ParameterSpec& spec : op.parameters)
    if (std::none_of(model.begin(), model.end(),
                     [&](const ParameterSpec& m) { return m.name == spec.name; }))
      own.push_back(spec);
  return own;
}

ParameterSpec gpu_spec(const std::string& what) {
  return {.name = "gpu",
          .kind = ParameterKind::flag,
          .default_value = ParameterValue(false),
          .description = what};
}

const std::vector<OperationInfo>& registry() {
  static const std::vector<OperationInfo> ops = [] {
    std::vector<OperationInfo> ops;
    for (auto family :
         {detail::sky_operations, detail::estimate_operations, detail::measured_operations,
          detail::sun_operations, detail::irradiance_operations, detail::report_operations,
          detail::sh_operations, detail::haze_operations, detail::nn_operations,
          detail::view_operations})
      for (OperationInfo& op : family()) ops.push_back(std::move(op));
    return ops;
  }();
  return ops;
}

const std::vector<Family>& families() {
  static const std::vector<Family> f{
      {"sh", "spherical-harmonics sky lighting: fit, eval, export, render, error",
       "Spherical-harmonics sky lighting: polynomial tables of SH coefficients over the sun's "
       "zenith and turbidity (Habel et al. 2008; docs/SH.md)."},
      {"haze", "aerial perspective: add, remove or retarget the haze of a photo",
       "Aerial perspective (Morales et al. 2017; docs/HAZE.md): scattering coefficients, "
       "attenuation, cameras, add/retarget/remove haze on an image with depth, composite, "
       "sky-mask."},
      {"nn", "neural sky models: train, validate, export, animate, study, planet",
       "Neural sky models (Satilmis et al. 2016; docs/NN.md) and the per-vertex network of the "
       "atmosphere (Pietras; docs/PIETRAS.md)."}};
  return f;
}

const OperationInfo& find(std::string_view name) {
  for (const OperationInfo& op : registry())
    if (op.name == name) return op;
  SKYLIGHT_CHECK(false, "operations::find: no such operation");
  return registry().front();
}

const OperationInfo& require_operation(std::string_view name) {
  std::vector<std::string> names;
  for (const OperationInfo& op : registry()) {
    if (op.name == name) return op;
    names.push_back(op.name);
  }
  throw InvalidArgument(fmt::format("'{}' is not an operation{} (operations: {})", excerpt(name),
                                    did_you_mean(name, names), fmt::join(names, ", ")));
}

std::vector<ParameterSpec> select(const OperationInfo& op, const std::vector<std::string>& names) {
  Specs out;
  for (const std::string& n : names) {
    const auto it = std::find_if(op.parameters.begin(), op.parameters.end(),
                                 [&](const ParameterSpec& s) { return s.name == n; });
    SKYLIGHT_CHECK(it != op.parameters.end(), "operations::select: no such parameter");
    out.push_back(*it);
  }
  return out;
}

namespace {

// "`a` excludes `b`", "`a` requires `b` (unread without it)".
std::string relation_text(const Relation& r) {
  return fmt::format("`--{}` {} `--{}`{}{}", r.a, to_string(r.kind), r.b,
                     r.unread ? (r.kind == RelationKind::excludes ? " (not read with it)"
                                                                  : " (not read without it)")
                              : "",
                     r.why.empty() ? "" : ": " + r.why);
}

std::string fields_table(const std::vector<FieldSpec>& fields, const std::string& prefix) {
  std::string out;
  for (const FieldSpec& f : fields) {
    out += fmt::format("| `{}{}` | {} | {} | {}{} |\n", prefix, f.name, f.unit, to_string(f.kind),
                       f.meaning, f.nullable ? " (may be null)" : "");
    if (!f.fields.empty()) out += fields_table(f.fields, prefix + f.name + "[].");
  }
  return out;
}

}  // namespace

std::string markdown(const OperationInfo& op) {
  std::string out =
      fmt::format("<!-- operation {} -->\n{}", op.name, markdown_table(op.parameters));
  if (!op.relations.empty()) {
    out += "\nRelations: ";
    for (std::size_t i = 0; i < op.relations.size(); ++i)
      out += (i == 0 ? "" : "; ") + relation_text(op.relations[i]);
    out += ".\n";
  }
  out += "\n| result field | unit | kind | meaning |\n|---|---|---|---|\n" +
         fields_table(op.result, "");
  return out + fmt::format("<!-- end operation {} -->\n", op.name);
}

namespace {

nlohmann::ordered_json value_json(const ParameterValue& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* l = std::get_if<std::vector<double>>(&v)) return *l;
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  return std::get<bool>(v);
}

// A parameter as JSON: the schema entry with a typed default ("required" when the model needs
// it; null when absent, with `when_absent` saying what the model does then).
nlohmann::ordered_json spec_json(const ParameterSpec& s) {
  nlohmann::ordered_json j{
      {"name", s.name}, {"unit", s.unit}, {"kind", std::string(to_string(s.kind))}};
  if (s.kind != ParameterKind::text && s.kind != ParameterKind::flag) {
    j["min"] = s.min;
    j["max"] = s.max;
  }
  if (s.kind == ParameterKind::numbers) j["count"] = s.count;
  j["required"] = s.required();
  if (s.required()) {
    j["default"] = "required";
  } else if (const auto* a = std::get_if<Absent>(&s.default_value)) {
    j["default"] = nullptr;
    j["when_absent"] = a->meaning;
  } else {
    j["default"] = value_json(std::get<ParameterValue>(s.default_value));
  }
  j["description"] = s.description;
  if (!s.choices.empty()) j["choices"] = s.choices;
  if (s.file != FileRole::none) {
    j["file"] = s.file == FileRole::input    ? "input"
                : s.file == FileRole::output ? "output"
                                             : "output_directory";
    j["formats"] = s.formats;
    j["standard_stream"] = s.standard_stream;
  }
  if (s.repeated) j["repeated"] = true;
  return j;
}

nlohmann::ordered_json fields_json(const std::vector<FieldSpec>& fields) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const FieldSpec& f : fields) {
    nlohmann::ordered_json j{{"name", f.name},
                             {"unit", f.unit},
                             {"kind", std::string(to_string(f.kind))},
                             {"meaning", f.meaning},
                             {"nullable", f.nullable}};
    if (!f.fields.empty()) j["fields"] = fields_json(f.fields);
    list.push_back(j);
  }
  return list;
}

}  // namespace

std::string models_json() {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& m : model_registry()) {
    nlohmann::ordered_json params = nlohmann::ordered_json::array();
    for (const auto& p : all_parameters(m)) params.push_back(spec_json(p));
    list.push_back({{"name", m.name},
                    {"description", m.description},
                    {"output", m.output},
                    {"parameters", params},
                    {"domain", m.domain},
                    {"spectral", m.spectral},
                    {"sun", m.sun},
                    {"luminance_only", m.luminance_only},
                    {"colour", m.colour_note()}});
  }
  return list.dump(2);
}

std::string operations_json() {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& op : registry()) {
    nlohmann::ordered_json params = nlohmann::ordered_json::array();
    for (const auto& p : op.parameters) params.push_back(spec_json(p));
    nlohmann::ordered_json relations = nlohmann::ordered_json::array();
    for (const Relation& r : op.relations)
      relations.push_back({{"kind", std::string(to_string(r.kind))},
                           {"parameters", {r.a, r.b}},
                           {"unread", r.unread},
                           {"why", r.why}});
    list.push_back({{"name", op.name},
                    {"summary", op.summary},
                    {"description", op.description},
                    {"parameters", params},
                    {"model_parameters", op.model_parameters},
                    {"relations", relations},
                    {"result", {{"type", op.result_type}, {"fields", fields_json(op.result)}}}});
  }
  return list.dump(2);
}

std::optional<sun::SpaInput> solar_position_input(const ParameterValues& given) {
  const ParameterValue* time = given.find("time");
  if (!time) return std::nullopt;
  sun::SpaInput in;
  in.time = sun::parse_iso8601(std::get<std::string>(*time));
  sun::spa_input_schema().bind(given.only(sun::spa_parameter_specs()), in, spelled("time"));
  sun::validate(in);
  return in;
}

std::vector<std::string> foreign_parameters(const ModelInfo& model, const ParameterValues& given) {
  const Specs common = model_specs();
  std::vector<std::string> out;
  for (const auto& [name, value] : given.all())
    if (!model.find_parameter(name) &&
        std::none_of(common.begin(), common.end(),
                     [&, n = name](const ParameterSpec& s) { return s.name == n; }))
      out.push_back(name);
  return out;
}

SkyRequest sky_request(const ModelInfo& model, const ParameterValues& given) {
  const std::vector<std::string> foreign = foreign_parameters(model, given);
  if (!foreign.empty())
    throw InvalidArgument(
        fmt::format("{} is not a parameter of model '{}'", spelled(foreign[0]), model.name));
  SkyRequest r;
  if (given.has("sun-zenith") && given.has("sun-elevation"))
    throw InvalidArgument(fmt::format("{} and {} are two ways to give the sun: give one",
                                      spelled("sun-zenith"), spelled("sun-elevation")));
  if (given.has("time") &&
      (given.has("sun-zenith") || given.has("sun-elevation") || given.has("sun-azimuth")))
    throw InvalidArgument(
        fmt::format("{} gives the sun: leave out the sun's angles", spelled("time")));
  r.solar_position = solar_position_input(given);
  if (r.solar_position) {
    // Through the same degrees as sun-zenith / sun-azimuth, so that `skylight sun --json`'s
    // zenith_deg and azimuth_deg given as angles build the identical sky.
    const sun::SpaResult spa = sun::solar_position(*r.solar_position);
    r.parameters.sun = sun_from_degrees(rad_to_deg(spa.zenith), rad_to_deg(spa.azimuth));
    r.parameters.day_of_year = sun::day_of_year(r.solar_position->time);
  } else {
    for (const auto& spec : sun::spa_parameter_specs())
      if (given.has(spec.name))
        throw InvalidArgument(fmt::format("{} needs {}", spelled(spec.name), spelled("time")));
    const double zenith_deg = given.has("sun-zenith")      ? *given.number("sun-zenith")
                              : given.has("sun-elevation") ? 90.0 - *given.number("sun-elevation")
                                                           : kDefaultSunZenithDeg;
    r.parameters.sun =
        sun_from_degrees(zenith_deg, given.number("sun-azimuth").value_or(kDefaultSunAzimuthDeg));
  }
  for (const ParameterSpec& spec : model.parameters)
    if (const ParameterValue* v = given.find(spec.name)) r.parameters.values.set(spec.name, *v);
  SolarDisc disc;
  SolarDisc::schema().bind(given.only(SolarDisc::schema().specs()), disc, "solar disc");
  r.sun_mode = disc.mode;
  return r;
}

PhotoEstimate estimate_photo(const io::ImageF& image, const ParameterValues& given,
                             const io::ImageF* user_mask,
                             const std::optional<estimate::Capture>& capture) {
  if (given.has("sun-zenith") != given.has("sun-azimuth"))
    throw InvalidArgument(
        fmt::format("{} and {} go together", spelled("sun-zenith"), spelled("sun-azimuth")));
  const auto bound = [&](const auto& schema, auto value) {
    schema.bind(given.only(schema.specs()), value, "estimate");
    return value;
  };
  const ImageSchemaOptions photo = estimate::photo_image_options();
  const ImageOptions layout = bound(image_schema(photo), photo.defaults());
  const auto co = bound(estimate::CaptureOptions::schema(), estimate::CaptureOptions{});
  PhotoEstimate r;
  r.camera = io::photo_camera(layout, image.width, image.height,
                              capture ? capture->focal_length_px : std::nullopt);
  std::optional<SunPosition> sun;
  std::optional<sun::SpaInput> spa;
  r.sun_source = "image";
  if (given.has("sun-zenith")) {
    r.sun_source = "given";
    sun = sun_from_degrees(*given.number("sun-zenith"), *given.number("sun-azimuth"));
  } else if ((spa = solar_position_input(given))) {
    r.sun_source = "time";
  } else if (capture && capture->exif.date_time) {
    spa = estimate::capture_solar_input(*capture, co, given);
    r.sun_source = "exif";
  } else {
    for (const auto& spec : sun::spa_parameter_specs())
      if (given.has(spec.name))
        throw InvalidArgument(fmt::format("{} needs {}, or {} with an EXIF time",
                                          spelled(spec.name), spelled("time"), spelled("exif")));
  }
  if (spa) {
    const sun::SpaResult p = sun::solar_position(*spa);
    sun = sun_from_degrees(rad_to_deg(p.zenith), rad_to_deg(p.azimuth));
  }
  const auto ms = bound(estimate::MaskSettings::schema(), estimate::MaskSettings{});
  r.settings = bound(fit::EstimateSettings::schema(), fit::EstimateSettings{});
  r.model = given.has("model") ? std::get<std::string>(*given.find("model"))
                               : fit::default_estimated_model();
  r.samples = estimate::sample_photo(image, r.camera, sun, ms, r.settings.samples, r.settings.seed,
                                     user_mask);
  r.fit = fit::fit_luminance(r.model, r.samples.samples, r.samples.sun, r.settings);
  if (r.samples.sun_detected) r.sun_source = "image";
  return r;
}

std::unique_ptr<SkyModel> make_sky(const Request& request) {
  const ModelInfo& info = require_model(*request.text("model"), "model");
  ParameterValues values = request.values().only(model_specs());
  const ParameterValues own = request.values().only(info.parameters);
  for (const auto& [name, value] : own.all()) values.set(name, value);
  const SkyRequest r = sky_request(info, values);
  auto model = make_sky_model(info.name, r.parameters);
  // A parameter of the schema that this model, with these values, does not read (e.g. nn's
  // turbidity for a network trained without one): said, and not recorded (parameter_values()).
  const ParameterValues read = model->parameter_values();
  for (const auto& [name, value] : r.parameters.values.all())
    if (!read.has(name))
      request.warn(fmt::format("{} is not read by model '{}' with these parameters; ignored",
                               spelled(name), model->name()));
  check_sun_mode(*model, r.sun_mode);
  return model;
}

io::Metadata model_metadata(const SkyModel& model, std::string_view sun_mode) {
  const auto& sun = sun_parameter_specs();
  io::Metadata md{
      {"skylight:version", kVersion},
      {"skylight:model", std::string(model.name())},
      {sun[0].metadata_key(), fmt::format("{}", rad_to_deg(model.sun().zenith))},
      {sun[1].metadata_key(), fmt::format("{}", rad_to_deg(model.sun().azimuth))},
  };
  const ParameterValues values = model.parameter_values();
  const ModelInfo& info = require_model(model.name());
  for (const auto& spec : info.parameters)
    if (const ParameterValue* v = values.find(spec.name))
      md.emplace_back(spec.metadata_key(), spec.format(*v));
  md.emplace_back("skylight:sun", std::string(sun_mode));
  md.emplace_back("skylight:colour", info.colour_note());
  return md;
}

io::Metadata solar_position_metadata(const sun::SpaInput& in) {
  return {
      {"skylight:time", sun::format_iso8601(in.time, 3)},
      {"skylight:latitude_deg", fmt::format("{}", rad_to_deg(in.latitude))},
      {"skylight:longitude_deg", fmt::format("{}", rad_to_deg(in.longitude))},
      {"skylight:elevation_m", fmt::format("{}", in.elevation)},
      {"skylight:pressure_mbar", fmt::format("{}", in.pressure)},
      {"skylight:temperature_degC", fmt::format("{}", in.temperature)},
      {"skylight:delta_t_s", fmt::format("{}", in.delta_t)},
  };
}

}  // namespace skylight::operations
