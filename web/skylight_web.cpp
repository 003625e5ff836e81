// The library in `skylight view`'s page (docs/VIEWER.md): WebAssembly built by Emscripten from the
// library's own sources (web/CMakeLists.txt), called from viewer.js through embind. It holds no
// model code of its own: each call binds text parameters with the models' schemas, builds the model
// through the registry and returns what the library computes (the model's GPU form, its
// luminance, a camera's GLSL, the sun's position). Results are JSON text; an error is
// {"error": "<the library's one-line message>"}.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/models/gpu_sky.h"
#include "skylight/models/sky_model.h"
#include "skylight/render/glsl_camera.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::web {
namespace {

using nlohmann::ordered_json;

// "name=value" lines: the page's form and URL as the command line's flags (without "--").
std::vector<std::pair<std::string, std::string>> lines_of(std::string_view text) {
  std::vector<std::pair<std::string, std::string>> out;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    if (trim(line).empty()) continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos)
      throw InvalidArgument("'" + std::string(line) + "' is not name=value");
    out.emplace_back(std::string(trim(line.substr(0, eq))), std::string(trim(line.substr(eq + 1))));
  }
  return out;
}

// The model `name` with the sun and its parameters from the text, through the registry.
std::unique_ptr<SkyModel> build(const std::string& name, const std::string& text) {
  const ModelInfo& info = require_model(name);
  double zenith = kDefaultSunZenithDeg, azimuth = kDefaultSunAzimuthDeg;
  SkyParameters params;
  const std::vector<ParameterSpec> specs = all_parameters(info);  // the sun's, then the model's
  for (const auto& line : lines_of(text)) {
    const std::string& key = line.first;
    const std::string& value = line.second;
    const auto spec = std::find_if(specs.begin(), specs.end(),
                                   [&key](const ParameterSpec& s) { return s.name == key; });
    if (spec == specs.end())
      throw InvalidArgument("--" + key + " is not a parameter of model '" + name + "'");
    const ParameterValue v = spec->parse(value);
    if (key == "sun-zenith" || key == "sun-azimuth") {
      (key == "sun-zenith" ? zenith : azimuth) = std::get<double>(v);
      continue;
    }
    params.values.set(key, v);
  }
  params.sun = sun_from_degrees(zenith, azimuth);
  return make_sky_model(name, params);
}

ordered_json tables_json(const std::vector<GpuSky::Table>& tables) {
  ordered_json out = ordered_json::array();
  for (const GpuSky::Table& t : tables)
    out.push_back({{"name", t.name},
                   {"width", t.width},
                   {"height", t.height},
                   {"channels", t.channels},
                   {"data", t.data}});
  return out;
}

ordered_json uniforms_json(const std::vector<GpuSky::Uniform>& uniforms) {
  ordered_json out = ordered_json::array();
  for (const GpuSky::Uniform& u : uniforms)
    out.push_back({{"name", u.name}, {"values", u.values}, {"integer", u.integer}});
  return out;
}

std::string error_json(const std::exception& e) {
  return ordered_json{{"error", e.what()}}.dump();
}

// The registered models this build can compute, in registry order.
std::string models() {
  ordered_json out = ordered_json::array();
  for (const ModelInfo& m : model_registry()) out.push_back(m.name);
  return out.dump();
}

// The model's GPU form: {"glsl", "output", "uniforms", "tables", "comment", "validity", "issues",
// "parameters"}.
std::string sky(const std::string& name, const std::string& text) {
  try {
    const auto model = build(name, text);
    const std::optional<GpuSky> g = model->gpu_sky();
    if (!g) throw InvalidArgument("model '" + name + "' has no GPU form");
    ordered_json issues = ordered_json::array();
    const Domain d = model->domain();
    for (const DomainIssue& i : d.issues) {
      if (i.spectral_only) continue;
      issues.push_back({{"parameter", i.parameter},
                        {"validity", std::string(to_string(i.validity))},
                        {"message", i.message}});
    }
    ordered_json values = ordered_json::object();
    const ModelInfo& info = require_model(name);
    const ParameterValues read = model->parameter_values();
    for (const auto& [key, value] : read.all()) {
      if (const ParameterSpec* spec = info.find_parameter(key)) values[key] = spec->format(value);
    }
    return ordered_json{{"glsl", glsl_sky_function(*g)},
                        {"output", g->output == GpuSky::Output::xyz ? "xyz" : "rgb"},
                        {"uniforms", uniforms_json(g->uniforms)},
                        {"tables", tables_json(g->tables)},
                        {"comment", g->comment},
                        {"validity", std::string(to_string(d.worst()))},
                        {"issues", issues},
                        {"parameters", values}}
        .dump();
  } catch (const std::exception& e) {
    return error_json(e);
  }
}

// Luminance [cd/m^2] of the model by its scalar path (SkyModel::tristimulus, double) at
// directions given as x, y, z triples: the page's CPU reference of a frame. NaN for an error
// (the page then shows the error of sky()).
emscripten::val luminance(const std::string& name, const std::string& text,
                          const emscripten::val& xyz) {
  const std::vector<double> d = emscripten::convertJSArrayToNumberVector<double>(xyz);
  std::vector<float> out(d.size() / 3, std::nanf(""));
  try {
    const auto model = build(name, text);
    for (std::size_t i = 0; i < out.size(); ++i) {
      const Vec3 v{d[3 * i], d[3 * i + 1], d[3 * i + 2]};
      out[i] = static_cast<float>(model->tristimulus(v).Y);
    }
  } catch (const std::exception&) {
  }
  emscripten::val result = emscripten::val::global("Float32Array").new_(out.size());
  result.call<void>("set", emscripten::val(emscripten::typed_memory_view(out.size(), out.data())));
  return result;
}

// A camera's GLSL (render/glsl_camera.h): projection equirect|hemisphere|fisheye|camera, the
// size, and for `camera` the look direction and vertical field of view [deg].
std::string camera(const std::string& projection, int width, int height, double look_zenith_deg,
                   double look_azimuth_deg, double fov_deg) {
  try {
    Camera c;
    bool known = false;
    for (const Projection p : {Projection::equirect, Projection::hemisphere, Projection::fisheye,
                               Projection::cubemap, Projection::camera}) {
      if (to_string(p) == projection) c.projection = p, known = true;
    }
    if (!known) throw InvalidArgument("unknown projection '" + projection + "'");
    c.width = width;
    c.height = height;
    c.pinhole.look_zenith = deg_to_rad(look_zenith_deg);
    c.pinhole.look_azimuth = deg_to_rad(look_azimuth_deg);
    c.pinhole.vertical_fov = deg_to_rad(fov_deg);
    validate(c);
    return ordered_json{{"glsl", render::glsl_pixel_direction(c)},
                        {"uniforms", uniforms_json(render::glsl_camera_uniforms(c))}}
        .dump();
  } catch (const std::exception& e) {
    return error_json(e);
  }
}

// The sun by the SPA (sun/spa.h) from "time=<ISO 8601>", "lat=", "lon=" and the SPA's other
// flags: {"zenith_deg", "azimuth_deg"}.
std::string sun_position(const std::string& text) {
  try {
    sun::SpaInput in;
    ParameterValues values;
    bool has_time = false;
    for (const auto& [key, value] : lines_of(text)) {
      if (key == "time") {
        in.time = sun::parse_iso8601(value);
        has_time = true;
        continue;
      }
      const ParameterSpec* spec = nullptr;
      for (const ParameterSpec& s : sun::spa_parameter_specs()) {
        if (s.name == key) spec = &s;
      }
      if (!spec) throw InvalidArgument("--" + key + " is not a parameter of the sun's position");
      values.set(key, spec->parse(value));
    }
    if (!has_time) throw InvalidArgument("--time is required");
    sun::spa_input_schema().bind(values, in, "the sun's position");
    const sun::SpaResult r = sun::solar_position(in);
    return ordered_json{{"zenith_deg", rad_to_deg(r.zenith)},
                        {"azimuth_deg", rad_to_deg(r.azimuth)}}
        .dump();
  } catch (const std::exception& e) {
    return error_json(e);
  }
}

// The GLSL helpers of every sky function (models/gpu_sky.h): the page's display pass converts XYZ
// to sRGB with the library's matrix.
std::string helpers() {
  return glsl_sky_helpers();
}

// Pixel positions (col, row; centres at +0.5) of directions given as zenith, azimuth pairs [deg]
// in a camera (Camera::pixel: equirect, hemisphere and fisheye; NaN where a direction is not
// imaged or the projection has no inverse): where the page draws the sun and the measured samples.
emscripten::val project(const std::string& projection, int width, int height,
                        const emscripten::val& angles) {
  const std::vector<double> a = emscripten::convertJSArrayToNumberVector<double>(angles);
  std::vector<float> out(a.size(), std::nanf(""));
  Camera c;
  for (const Projection p : {Projection::equirect, Projection::hemisphere, Projection::fisheye}) {
    if (to_string(p) == projection) c.projection = p;
  }
  c.width = width;
  c.height = height;
  if (to_string(c.projection) == projection && width > 0 && height > 0) {
    for (std::size_t i = 0; i + 1 < a.size(); i += 2) {
      const auto px = c.pixel(direction_from_angles(deg_to_rad(a[i]), deg_to_rad(a[i + 1])));
      if (px) out[i] = static_cast<float>((*px)[0]), out[i + 1] = static_cast<float>((*px)[1]);
    }
  }
  emscripten::val result = emscripten::val::global("Float32Array").new_(out.size());
  result.call<void>("set", emscripten::val(emscripten::typed_memory_view(out.size(), out.data())));
  return result;
}

}  // namespace
}  // namespace skylight::web

EMSCRIPTEN_BINDINGS(skylight) {
  emscripten::function("models", &skylight::web::models);
  emscripten::function("sky", &skylight::web::sky);
  emscripten::function("luminance", &skylight::web::luminance);
  emscripten::function("camera", &skylight::web::camera);
  emscripten::function("sunPosition", &skylight::web::sun_position);
  emscripten::function("helpers", &skylight::web::helpers);
  emscripten::function("project", &skylight::web::project);
}
