// `view`: the interactive sky viewer (docs/VIEWER.md). Writes a self-contained page into a folder:
// the page and its script (web/index.html, web/viewer.js), the library compiled to WebAssembly
// (web/skylight_web.cpp: every model with a GPU form, its set-up and CPU reference, the sun's
// position) and view_data.js, what the native library declares for the page (the models'
// schemas, why a model has no GPU form, the false-colour scale, the measured captures).
#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "skylight/analysis/measured_sky.h"
#include "skylight/core/math.h"
#include "skylight/io/file.h"
#include "skylight/io/http_server.h"
#include "skylight/io/kider.h"
#include "skylight/operations/detail/families.h"
#include "skylight/operations/detail/web_bundle.h"
#include "skylight/operations/operations.h"
#include "skylight/render/false_colour.h"
#include "skylight/version.h"

namespace skylight::operations::detail {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// The file of the bundle called `name`, or nullptr.
const WebFile* bundled(std::string_view name) {
  for (const WebFile& f : web_bundle()) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

// The false-colour scale of render/false_colour.h sampled for the page's legend and map: 256
// colours over 0 .. 6 decades [log10 cd/m^2] (the page shifts the range).
ordered_json false_colour_json() {
  render::FalseColourOptions o;
  ordered_json colours = ordered_json::array();
  constexpr int kSteps = 256;
  for (int i = 0; i < kSteps; ++i) {
    const double v = o.log10_min + (o.log10_max - o.log10_min) * i / (kSteps - 1);
    const auto c = render::false_colour_of(v, o);
    colours.push_back({c[0], c[1], c[2]});
  }
  return {{"log10_min", o.log10_min},
          {"log10_max", o.log10_max},
          {"unit", o.unit},
          {"colours", colours}};
}

// The measured captures (io/kider.h) as the page draws them: each sample's direction and
// luminance, and the capture's sun by the SPA at Kider et al.'s site (analysis/measured_sky.h).
ordered_json measured_json(const std::vector<io::KiderCapture>& captures,
                           const std::string& source) {
  ordered_json list = ordered_json::array();
  const analysis::KiderSite site;
  for (const io::KiderCapture& c : captures) {
    const analysis::CaptureSun sun = analysis::capture_sun(c, site, true);
    ordered_json samples = ordered_json::array();
    for (const io::KiderSample& s : c.samples)
      samples.push_back({rad_to_deg(s.zenith), rad_to_deg(s.azimuth), s.luminance});
    list.push_back({{"name", c.name},
                    {"local_time", c.local_time},
                    {"sun_zenith_deg", rad_to_deg(sun.sun.zenith)},
                    {"sun_azimuth_deg", rad_to_deg(sun.sun.azimuth)},
                    {"samples", samples}});
  }
  return {{"source", source}, {"captures", list}};
}

std::string view_data(const Request& r) {
  ordered_json models = ordered_json::parse(models_json());
  for (auto& m : models) {
    const ModelInfo& info = require_model(m["name"].get<std::string>());
    m["no_gpu"] = info.no_gpu;
    ordered_json example = ordered_json::object();
    for (const auto& [key, value] : info.example.all()) {
      if (const ParameterSpec* spec = info.find_parameter(key)) example[key] = spec->format(value);
    }
    m["example"] = example;
    m["report_colour"] = info.report.colour;
    m["costly_setup"] = info.costly_setup;
  }
  ordered_json data{{"software", std::string("skylight ") + SKYLIGHT_VERSION},
                    {"models", models},
                    {"false_colour", false_colour_json()}};
  if (const auto dir = r.text("kider")) {
    data["measured"] = measured_json(io::read_kider(*dir), *dir);
  } else if (!r.given("no-measured")) {
    data["measured"] =
        measured_json(io::shipped_kider_subset(),
                      fmt::format("data/{} (shipped with skylight)", io::kKiderSubsetDataDir));
  }
  return "// Written by `skylight view` (docs/VIEWER.md): what the library declares for the page.\n"
         "window.SKYLIGHT_VIEW = " +
         data.dump() + ";\n";
}

struct ViewResult {
  std::string directory;
  long long bytes = 0;
  int models_on_gpu = 0;
  std::optional<std::string> url;  // --serve
};

const ResultSchema<ViewResult>& view_result() {
  static const ResultSchema<ViewResult> s = [] {
    ResultSchema<ViewResult> s;
    s.text("directory", "the page's folder (open its index.html)", &ViewResult::directory)
        .integer("bytes", "B", "the page's size, every file together", &ViewResult::bytes)
        .integer("models_on_gpu", "1", "the models the page draws on the GPU",
                 [](const ViewResult& v) { return static_cast<long long>(v.models_on_gpu); })
        .text("url", "where --serve serves the page (null without it)",
              [](const ViewResult& v) { return v.url; });
    return s;
  }();
  return s;
}

Result run_view(const Request& r, const ProgressSink&) {
  if (!bundled("skylight_web.js")) {
    throw InvalidArgument(
        "this build has no viewer: Emscripten (emcmake, em++) was not found when it was built "
        "(scripts/setup.sh installs it; docs/VIEWER.md)");
  }
  const fs::path dir = r.output_path("output");
  // The port first: one that cannot be had stops the command before anything is written.
  std::shared_ptr<io::StaticServer> server;
  if (const auto port = r.number("serve"))
    server = std::make_shared<io::StaticServer>(dir, static_cast<int>(*port));
  fs::create_directories(dir);
  ViewResult v{dir.string(), 0, 0, std::nullopt};
  const std::string data = view_data(r);
  for (const WebFile& f : web_bundle()) {
    io::write_text_file(dir / f.name, f.content);
    v.bytes += static_cast<long long>(f.content.size());
  }
  io::write_text_file(dir / "view_data.js", data);
  v.bytes += static_cast<long long>(data.size());
  for (const ModelInfo& m : model_registry()) v.models_on_gpu += m.no_gpu.empty() ? 1 : 0;
  if (server) v.url = fmt::format("http://127.0.0.1:{}/", server->port());
  Result out;
  out.record = view_result().record(v);
  out.notices.push_back(fmt::format("wrote {} (open it in a browser with WebGL2)",
                                    io::shown_path(dir / "index.html")));
  if (server) {
    out.notices.push_back(
        fmt::format("serving {} at {} until interrupted (Ctrl-C)", io::shown_path(dir), *v.url));
    out.then = [server, stop = r.frontend().interrupted] { server->serve(stop); };
  }
  return out;
}

ParameterSpec kider_spec() {
  return {.name = "kider",
          .kind = ParameterKind::text,
          .default_value = Absent{"the shipped subset, data/measured/kider2014/"},
          .description =
              "the measured captures the page draws over the sky: a folder of Kider "
              "et al. 2014's captures or of the shipped subset"};
}

ParameterSpec serve_spec() {
  return {.name = "serve",
          .unit = "1",
          .kind = ParameterKind::integer,
          .min = 0,
          .max = 65535,
          .default_value = Absent{"no server: open DIR/index.html from file://"},
          .description =
              "then serve the page on http://127.0.0.1:PORT until interrupted, for "
              "browsers that restrict file:// (--serve alone: 8000; 0: a free port)",
          .implicit = ParameterValue(8000.0)};
}

ParameterSpec no_measured_spec() {
  return {.name = "no-measured",
          .kind = ParameterKind::flag,
          .default_value = ParameterValue(false),
          .description = "leave the measured captures out of the page"};
}

OperationInfo view_operation() {
  ParameterSpec dir = output_file("output",
                                  "the page's folder (created if needed): index.html, viewer.js, "
                                  "skylight_web.js, view_data.js");
  dir.file = FileRole::output_directory;
  OperationInfo op{
      .name = "view",
      .summary = "write the interactive sky viewer (a WebGL2 page, works from file://)",
      .description =
          "an interactive viewer of every model with a GPU form: the models' own GLSL with "
          "their set-up by the library compiled to WebAssembly, side by side or split with a "
          "difference map, the frame checked against the library in the page, the measured "
          "captures over the sky (docs/VIEWER.md)",
      .relations = {excludes("kider", "no-measured", "the captures or none")},
      .result = view_result().fields(),
      .result_type = "view::ViewResult"};
  op.parameters.push_back(dir);
  op.parameters.push_back(kider_spec());
  op.parameters.push_back(no_measured_spec());
  op.parameters.push_back(serve_spec());
  op.check = [](Request& r) { check_input_folder(r, "kider"); };
  op.run = run_view;
  return op;
}

}  // namespace

std::vector<OperationInfo> view_operations() {
  return {view_operation()};
}

}  // namespace skylight::operations::detail
