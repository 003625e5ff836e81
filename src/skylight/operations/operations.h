// The library's operations (docs/ARCHITECTURE.md, "Operations"): every operation's declaration
// and work (operation.h), composed from the schemas of the settings it takes; the CLI and the
// Python package are generated from them (`skylight operations --json`). The models' own
// parameters are the registry's (models/sky_model.h, `skylight models --json`).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/parameters.h"
#include "skylight/estimate/capture.h"
#include "skylight/estimate/photo.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/io/image.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/sky_model.h"
#include "skylight/operations/operation.h"
#include "skylight/sun/spa.h"

namespace skylight::operations {

// Every operation, in the command line's order.
const std::vector<OperationInfo>& registry();
// The groups of operations the command line nests ("sh", "haze", "nn"): name, summary, page.
struct Family {
  std::string name, summary, description;
};
const std::vector<Family>& families();
// The operation named `name` (a programming error if there is none).
const OperationInfo& find(std::string_view name);
// The same for a name a user gave: InvalidArgument naming the nearest operation otherwise.
const OperationInfo& require_operation(std::string_view name);
// A sky as render and eval take it, declared alone (the Python package's Sky): the model, the sun,
// the solar disc and the chosen model's parameters, with their relations; it has no work of its
// own (make_sky builds the model of a request prepared with it).
const OperationInfo& sky_declaration();

// The specs of a named subset of an operation's parameters (a programming error for a name the
// operation does not have), e.g. the solar-position flags.
std::vector<ParameterSpec> select(const OperationInfo& op, const std::vector<std::string>& names);

// The sun of an operation that takes it as angles or from a time and place: --sun-zenith and
// --sun-azimuth (their defaults replaced by `absent` when not empty), --time (absent: `time`) and
// the SPA's --lat --lon --elevation --pressure --temperature --delta-t.
std::vector<ParameterSpec> sun_specs(const std::string& absent = {});
std::vector<ParameterSpec> solar_position_specs(const std::string& time_absent);

// The model of an operation on one sky (render, eval): --model, the sun (--sun-zenith or
// --sun-elevation, --sun-azimuth, or --time and the SPA's flags) and the solar-disc switches. The
// chosen model's own parameters are the registry's (`skylight models --json`).
std::vector<ParameterSpec> model_specs();
// An operation's parameters without its model_specs() (those the front end's model options take).
std::vector<ParameterSpec> without_model_specs(const OperationInfo& op);
// The GL path of an operation (--gpu; the optional gpu/ module, docs/GPU.md).
ParameterSpec gpu_spec(const std::string& what);

// The operation as Markdown (docs/OPERATIONS.md): its parameters, relations and result fields,
// one block per operation.
std::string markdown(const OperationInfo& op);

// `skylight models --json` and `skylight operations --json` (the Python package's models() and
// operations()): every model (name, description, output, parameters with unit, kind, range,
// typed default or `when_absent`, description, choices; domain, spectral, sun, luminance_only,
// colour) and every operation (name, summary, description, parameters with their file roles,
// "relations" ({"kind": "excludes"|"requires", "parameters": [a, b], "unread", "why"}), "result"
// ({"type", "fields": [{name, unit, kind, meaning, nullable, fields}]})), as JSON text.
std::string models_json();
std::string operations_json();

// The SPA input of `time` and the SPA's parameters among `given` (sun::spa_input_schema() binds
// them; a missing lat/lon throws), nullopt without `time`.
std::optional<sun::SpaInput> solar_position_input(const ParameterValues& given);

// One sky as a front end asks for it (`render`, `eval`, the Python package's Sky).
struct SkyRequest {
  SkyParameters parameters;  // the sun, the model's own values and the day of the year of `time`
  std::optional<sun::SpaInput> solar_position;  // when the sun came from `time`
  SunMode sun_mode = SunMode::sky;
};
// The sky of a request of an operation with the model's parameters (render, eval; the Python
// package's Sky): sky_request of its values, the model built, and a warning for each value the
// model does not read with these parameters (e.g. nn's turbidity for a network trained without
// one); the solar disc's mode checked against the model.
std::unique_ptr<SkyModel> make_sky(const Request& request);
// Metadata of an output made from `model`: version, model, the sun and every parameter the model
// read (ParameterSpec::metadata_key()), the solar disc mode and what the colours mean
// (skylight:colour, ModelInfo::colour_note()).
io::Metadata model_metadata(const SkyModel& model, std::string_view sun_mode);
// The inputs of a solar position as metadata (skylight:time, skylight:latitude_deg, ...).
io::Metadata solar_position_metadata(const sun::SpaInput& in);

// From named values: model_specs()'s (the sun as `sun-zenith` or `sun-elevation` and
// `sun-azimuth`, or `time` with the SPA's parameters; `include-sun`, `sun-only`) and the model's
// own parameters. Names the model does not declare are refused (InvalidArgument naming them), so
// a front end that only warns removes them first (foreign_parameters).
SkyRequest sky_request(const ModelInfo& model, const ParameterValues& given);
// The given names that are neither model_specs()'s nor the model's own.
std::vector<std::string> foreign_parameters(const ModelInfo& model, const ParameterValues& given);

// `skylight estimate` on a photo already in memory (the CLI reads the file and the EXIF; the
// Python package passes arrays): the layout, mask and fit settings bound from `given` (the
// estimate operation's values), the sun from the given angles, from `time` with the SPA's
// parameters, from the capture's EXIF time, or found in the image; then the samples and the fit.
struct PhotoEstimate {
  std::string model;
  Camera camera;
  estimate::PhotoSamples samples;
  fit::EstimateSettings settings;
  fit::LuminanceFit fit;
  std::string sun_source;  // "given", "time", "exif" or "image"
};
PhotoEstimate estimate_photo(const io::ImageF& image, const ParameterValues& given,
                             const io::ImageF* user_mask,
                             const std::optional<estimate::Capture>& capture = std::nullopt);

}  // namespace skylight::operations
