#include "skylight/operations/operations.h"

#include <fmt/format.h>

#include <algorithm>

#include "skylight/core/camera.h"
#include "skylight/core/error.h"
#include "skylight/estimate/photo.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/models/sky_model.h"
#include "skylight/sun/spa.h"

namespace skylight::operations {
namespace {

using Specs = std::vector<ParameterSpec>;

Specs concat(std::initializer_list<Specs> parts) {
  Specs out;
  for (const Specs& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

OperationInfo estimate_operation() {
  return {"estimate",
          "the turbidity of a clear sky (or another model's fitted parameters) from an HDR photo: "
          "the sun (given, from a time, or found), the sky mask, random sky samples and the fit "
          "(docs/ESTIMATE.md)",
          concat({{fit::estimation_model_spec()},
                  image_schema(estimate::photo_image_options()).specs(),
                  sun_specs("from --time, or found in the image"),
                  solar_position_specs("the sun from the angles, or found in the image"),
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

const std::vector<OperationInfo>& registry() {
  static const std::vector<OperationInfo> ops{estimate_operation()};
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

}  // namespace skylight::operations
