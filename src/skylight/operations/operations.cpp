#include "skylight/operations/operations.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>

#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/daylight/daylight.h"
#include "skylight/estimate/capture.h"
#include "skylight/estimate/photo.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/fit/network_training.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/haze/request.h"
#include "skylight/io/camera_calibration.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/models/sh.h"
#include "skylight/models/sky_model.h"
#include "skylight/perf/bench.h"
#include "skylight/render/animation.h"
#include "skylight/render/false_colour.h"
#include "skylight/report/report.h"
#include "skylight/sh/irradiance.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::operations {
namespace {

using Specs = std::vector<ParameterSpec>;

Specs concat(std::initializer_list<Specs> parts) {
  Specs out;
  for (const Specs& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

OperationInfo render_operation() {
  ImageSchemaOptions image;
  return {"render",
          "a sky model drawn into an image in one of the project's layouts (the batch path on all "
          "threads, or the network models by GL); the chosen model's own parameters are its "
          "registry entry's (`skylight models`)",
          concat({model_specs(),
                  image_schema(image).specs(),
                  render::FalseColourOptions::schema().specs(),
                  {gpu_spec("render with OpenGL (headless EGL; the network models nn and pietras, "
                            "docs/GPU.md) instead of the CPU")}}),
          "render::SkyImage (XYZ and linear sRGB images, the mask of pixels without a direction)"};
}

OperationInfo eval_operation() {
  return {"eval",
          "a sky model evaluated in given directions (zenith, azimuth): linear sRGB, XYZ, "
          "luminance or spectral radiance, of the sky, the solar disc or both",
          concat({model_specs(), EvaluationOptions::schema().specs(),
                  ReferenceOptions::schema().specs()}),
          "one value per quantity column (models/evaluation.h, quantity_columns); with "
          "--reference a standard-error column after each"};
}

OperationInfo estimate_operation() {
  return {"estimate",
          "the turbidity of a clear sky (or another model's fitted parameters) from an HDR photo: "
          "the sun (given, from a time, or found), the sky mask, random sky samples and the fit "
          "(docs/ESTIMATE.md)",
          concat({{fit::estimation_model_spec()},
                  image_schema(estimate::photo_image_options()).specs(),
                  sun_specs("from --time, or found in the image"),
                  solar_position_specs("the sun from the angles, the EXIF time (--exif), or "
                                       "found in the image"),
                  estimate::CaptureOptions::schema().specs(),
                  estimate::MaskSettings::schema().specs(),
                  fit::EstimateSettings::schema().specs()}),
          "fit::LuminanceFit"};
}

}  // namespace

std::vector<ParameterSpec> sun_specs(const std::string& absent) {
  Specs s = sun_parameter_specs();
  if (!absent.empty())
    for (ParameterSpec& spec : s) spec.default_value = Absent{absent};
  return s;
}

std::vector<ParameterSpec> solar_position_specs(const std::string& time_absent) {
  Specs s{sun::time_spec(time_absent)};
  for (const char* name : {"lat", "lon", "elevation", "pressure", "temperature", "delta-t"})
    s.push_back(sun::spa_parameter_spec(name));
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

// The sh model's table, bands, filter and tau, and the sun, as `sh eval` and `sh render` take
// them.
Specs sh_sky_specs() {
  return concat({sun_parameter_specs(), ShParameters::schema().specs()});
}

OperationInfo sh_fit_operation() {
  return {"sh fit",
          "an SH polynomial table (Habel et al. 2008 eq. 1) fitted to a registry model's "
          "converged projections; the model's fit policy gives tau, its range and the table's "
          "structure (docs/SH.md)",
          fit::ShFitRequest::schema().specs(), "sh::PolynomialTable"};
}

std::vector<OperationInfo> sh_operations() {
  const Specs table{*ShParameters::schema().find("table")};
  return {
      sh_fit_operation(),
      {"sh eval",
       "the SH coefficients of a table's sky (eq. 1, rotation eq. 4, ringing filter eq. 5), "
       "or of its irradiance",
       concat({sh_sky_specs(), ShEvalOptions::schema().specs()}), "sh::Coefficients"},
      {"sh export", "a table as JSON or as a C header",
       concat({table, sh::ExportOptions::schema().specs()}), "text"},
      {"sh render", "a table's sky as an equirect environment map, and a diffuse sphere lit by it",
       concat({sh_sky_specs(), ShRenderOptions::schema().specs(),
               sh::SphereOptions::schema().specs()}),
       "render::SkyImage, and the sphere's linear sRGB image"},
      {"sh error", "E_mean (eq. 3) and E_max (eq. 2) of a table per band count",
       concat({table, fit::ShErrorOptions::schema().specs()}), "fit::ShTableError"}};
}

// The sky photo of `haze sky-mask` and of --sky: its path and projection.
Specs sky_photo_specs() {
  const auto& a = haze::AirlightOptions::schema();
  return concat({{*a.find("sky")},
                 image_schema(estimate::photo_image_options(Projection::fisheye, "sky-projection",
                                                            "--sky: the sky photo's layout"))
                     .specs()});
}

std::vector<OperationInfo> haze_operations() {
  const Specs air = haze::atmosphere_schema().specs();
  const Specs camera = haze::SensitivityOptions::schema().specs();
  const auto& h = haze::HazeOptions::schema();
  const Specs image = concat({air,
                              camera,
                              {*h.find("near"), *h.find("far")},
                              haze::AirlightOptions::schema().specs(),
                              haze::ImageCameraOptions::schema().specs()});
  const ParameterSpec gpu =
      gpu_spec("run the operation as a fragment shader on the headless GL context (docs/GPU.md)");
  const ParameterSpec min_t = *h.find("min-transmission");
  ParameterSpec target = *h.find("target-turbidity");
  target.default_value = Required{};
  return {{"haze coefficients", "Rayleigh and Mie scattering coefficients and the weather class",
           concat({air, haze::CoefficientsOptions::schema().specs()}), "per-km coefficients"},
          {"haze attenuation", "the attenuation factor Gamma_c (eq. 11) of a horizontal path",
           concat({air, camera, haze::AttenuationOptions::schema().specs()}), "haze::Rgb3"},
          {"haze add", "haze added to an image with depth (eq. 10)", concat({image, {min_t, gpu}}),
           "io::ImageF"},
          {"haze retarget", "haze re-targeted from T to T_t (eq. 26)",
           concat({image, {target, min_t, gpu}}), "io::ImageF"},
          {"haze remove", "haze removed (eq. 10 inverted)", concat({image, {min_t, gpu}}),
           "io::ImageF"},
          {"haze composite", "a virtual object given the haze of T over a background photo",
           concat({image, {gpu}}), "io::ImageF"},
          {"haze sky-mask", "the sky of a photo by a marker-controlled watershed (eq. 12)",
           sky_photo_specs(), "estimate::SkyMask"}};
}

// The network options of `nn animate`: a sky network's turbidity, a Pietras network's altitude.
Specs animate_network_specs() {
  ParameterSpec turbidity = *NeuralSkyParameters::schema().find("turbidity");
  turbidity.default_value = Absent{"3; sky networks only"};
  ParameterSpec altitude = *PietrasParameters::schema().find("observer-altitude");
  altitude.default_value = Absent{"0; Pietras networks only"};
  altitude.description = "observer above the ground, a Pietras network's density input";
  return {turbidity, altitude};
}

std::vector<OperationInfo> nn_operations() {
  return {
      {"nn train",
       "a neural sky network trained on a registered model (the paper's protocol) or on a "
       "sequence of HDR sky images, or a Pietras network on nishita (docs/NN.md, "
       "docs/PIETRAS.md)",
       concat({fit::NetworkTrainingRequest::schema().specs(),
               fit::ImageTrainingOptions::schema().specs()}),
       "nn::SkyNetwork or nn::PietrasNetwork (the weights file)"},
      {"nn validate", "the errors of a weights file on the validation sets of its source",
       fit::ValidationOptions::schema().specs(), "fit::NeuralValidation or fit::PietrasValidation"},
      {"nn animate", "an environment-map sequence of a sky or Pietras network with the sun moving",
       concat({animate_network_specs(), render::AnimationOptions::schema().specs()}),
       "one render::SkyImage per frame"},
      {"nn study", "the hidden-layer study of Satilmis et al. 2016 (Fig. 5, eq. 8)",
       fit::HiddenLayerStudy::schema().specs(), "fit::StudyRow per width"},
      {"nn planet",
       "a Pietras network shading an icosphere planet in a GL vertex shader (the GPU module)",
       PlanetViewOptions::schema().specs(), "linear sRGB image"}};
}

const std::vector<OperationInfo>& registry() {
  static const std::vector<OperationInfo> ops = [] {
    std::vector<OperationInfo> ops{render_operation(), eval_operation(), estimate_operation()};
    Specs spa{sun::time_spec("")};
    spa.front().default_value = Required{};
    for (const auto& spec : sun::spa_parameter_specs()) spa.push_back(spec);
    ops.push_back({"sun",
                   "the solar position of the NREL SPA (Reda & Andreas 2004) for a time and "
                   "place: topocentric zenith and azimuth, and the day's sunrise, transit, sunset",
                   spa, "sun::SpaResult and sun::SunEvents"});
    ops.push_back(
        {"daylight",
         "the Perez all-weather sky from measured direct and diffuse light (Perez et al. 1990, "
         "1993): epsilon, delta, the bin, a..e, the zenith luminance and the illuminances; with "
         "--epw, the annual sky matrix of a weather file (docs/DAYLIGHT.md)",
         concat({sun_specs("from --time (one sky); from each record (--epw)"),
                 solar_position_specs("the sun from the angles"),
                 daylight::DaylightRequest::schema().specs()}),
         "models::PerezSky, or daylight::SkyMatrix"});
    ops.push_back({"bench",
                   "each model's batch path timed against its scalar loop, with the comparisons "
                   "and workloads its registry entry declares; --estimate, --haze",
                   perf::BenchSettings::schema().specs(), "text: medians and ratios"});
    ops.push_back({"report",
                   "the validation and comparison report: Zotti et al. 2007's analyses for every "
                   "model, a sky-luminance scan (docs/REPORT.md)",
                   report::ReportOptions::schema().specs(), "report::ReportSummary"});
    for (auto& op : sh_operations()) ops.push_back(std::move(op));
    for (auto& op : haze_operations()) ops.push_back(std::move(op));
    for (auto& op : nn_operations()) ops.push_back(std::move(op));
    return ops;
  }();
  return ops;
}

const OperationInfo& find(std::string_view name) {
  for (const OperationInfo& op : registry())
    if (op.name == name) return op;
  SKYLIGHT_CHECK(false, "operations::find: no such operation");
  return registry().front();
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

std::string markdown(const OperationInfo& op) {
  return fmt::format("<!-- operation {0} -->\n{1}<!-- end operation {0} -->\n", op.name,
                     markdown_table(op.parameters));
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
  return j;
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
    list.push_back({{"name", op.name},
                    {"description", op.description},
                    {"parameters", params},
                    {"result", op.result}});
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

}  // namespace skylight::operations
