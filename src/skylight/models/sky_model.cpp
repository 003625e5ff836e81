#include "skylight/models/sky_model.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parallel.h"
#include "skylight/core/text.h"

namespace skylight {

std::string_view to_string(Validity v) {
  switch (v) {
    case Validity::valid:
      return "valid";
    case Validity::extrapolated:
      return "extrapolated";
    case Validity::unphysical:
      return "unphysical";
    case Validity::undefined:
      return "undefined";
  }
  return "valid";
}

Validity Domain::worst() const {
  Validity w = Validity::valid;
  for (const auto& i : issues)
    if (!i.spectral_only) w = std::max(w, i.validity);
  return w;
}

Validity Domain::worst_spectral() const {
  Validity w = Validity::valid;
  for (const auto& i : issues) w = std::max(w, i.validity);
  return w;
}

const std::vector<ParameterSpec>& sun_parameter_specs() {
  static const std::vector<ParameterSpec> specs = {
      {.name = "sun-zenith",
       .unit = "deg",
       .min = 0.0,
       .max = 180.0,
       .default_value = ParameterValue(kDefaultSunZenithDeg),
       .description =
           "solar zenith angle (or --sun-elevation = 90 - zenith); > 90 = below the horizon"},
      {.name = "sun-azimuth",
       .unit = "deg",
       .min = -360.0,
       .max = 360.0,
       .default_value = ParameterValue(kDefaultSunAzimuthDeg),
       .description = "solar azimuth from north towards east (180 = south)"},
  };
  return specs;
}

SunPosition sun_from_degrees(double zenith_deg, double azimuth_deg) {
  const auto& specs = sun_parameter_specs();
  specs[0].check(zenith_deg);
  specs[1].check(azimuth_deg);
  return {deg_to_rad(zenith_deg), wrap_azimuth(deg_to_rad(azimuth_deg))};
}

void validate_sun(const SunPosition& sun) {
  require_in_range("sun_zenith [rad]", sun.zenith, 0.0, kPi);
  if (!std::isfinite(sun.azimuth))
    throw InvalidArgument(fmt::format("sun_azimuth = {} is not a finite angle", sun.azimuth));
}

std::string model_context(std::string_view name) {
  return fmt::format("model '{}'", name);
}

SkyModel::SkyModel(const SunPosition& sun) : sun_(sun) {
  validate_sun(sun);
}

Domain SkyModel::sun_below_horizon(Validity validity, std::string_view consequence) const {
  Domain d;
  if (sun_.zenith > 0.5 * kPi)
    d.issues.push_back(
        {"sun_zenith", validity, "sun below the horizon: " + std::string(consequence)});
  return d;
}

std::optional<double> SkyModel::spectral_radiance(Vec3, double) const {
  return std::nullopt;
}

void SkyModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  SKYLIGHT_CHECK(out.size() == dirs.size(), "tristimulus_batch: size mismatch");
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    const Xyz c = tristimulus({dirs.x[i], dirs.y[i], dirs.z[i]});
    out.X[i] = static_cast<float>(c.X);
    out.Y[i] = static_cast<float>(c.Y);
    out.Z[i] = static_cast<float>(c.Z);
  }
}

Xyz SkyModel::sun_tristimulus(Vec3) const {
  return {};
}
std::optional<double> SkyModel::sun_spectral_radiance(Vec3, double) const {
  return std::nullopt;
}

void tristimulus_parallel(const SkyModel& model, const DirectionsSoA& dirs, const XyzSoA& out) {
  SKYLIGHT_CHECK(out.size() == dirs.size(), "tristimulus_parallel: size mismatch");
  // 4096 directions per chunk: large enough to amortise the hand-out, small enough to balance.
  constexpr std::size_t kGrain = 4096;
  parallel_for(dirs.size(), kGrain, [&](std::size_t b, std::size_t e) {
    const std::size_t n = e - b;
    model.tristimulus_batch({dirs.x.subspan(b, n), dirs.y.subspan(b, n), dirs.z.subspan(b, n)},
                            {out.X.subspan(b, n), out.Y.subspan(b, n), out.Z.subspan(b, n)});
  });
}

NeuralPolicy NeuralPolicy::over_turbidity(double first, double last, double target_scale) {
  NeuralPolicy p;
  p.target_scale = target_scale;
  p.training_turbidities.clear();
  p.validation_turbidities.clear();
  for (double t = first; t <= last + 1e-9; t += 1.0) p.training_turbidities.push_back(t);
  for (double t = first + 0.5; t <= last - 0.5 + 1e-9; t += 1.0)
    p.validation_turbidities.push_back(t);
  p.held_out_turbidities.clear();
  const int steps = static_cast<int>(std::lround((last - first) / 0.1));
  for (int k = 0; k <= steps; ++k)
    p.held_out_turbidities.push_back(first + (last - first) * k / steps);
  return p;
}

void linear_srgb_to_xyz_in_place(const XyzSoA& out) {
  const Matrix3& m = srgb_to_xyz_matrix();
  std::array<float, 9> f{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) f[3 * r + c] = static_cast<float>(m[r][c]);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const float R = out.X[i], G = out.Y[i], B = out.Z[i];
    out.X[i] = f[0] * R + f[1] * G + f[2] * B;
    out.Y[i] = f[3] * R + f[4] * G + f[5] * B;
    out.Z[i] = f[6] * R + f[7] * G + f[8] * B;
  }
}

void require_in_range(std::string_view name, double value, double min, double max) {
  if (std::isnan(value) || value < min || value > max) {
    throw InvalidArgument(
        fmt::format("{} = {} is outside the valid range [{}, {}]", name, value, min, max));
  }
}

std::string ModelInfo::colour_note() const {
  return luminance_only ? "grey by design: luminance only (XYZ at the D65 white point)" : "colour";
}

const ParameterSpec* ModelInfo::find_parameter(std::string_view parameter) const {
  for (const auto& s : parameters)
    if (s.name == parameter) return &s;
  return nullptr;
}

std::vector<ParameterSpec> all_parameters(const ModelInfo& model) {
  std::vector<ParameterSpec> out = sun_parameter_specs();
  out.insert(out.end(), model.parameters.begin(), model.parameters.end());
  return out;
}

std::string parameter_docs_block(const ModelInfo& model) {
  return fmt::format("<!-- parameters {0} -->\n{1}<!-- end parameters {0} -->\n", model.name,
                     markdown_table(all_parameters(model)));
}

const ModelInfo* find_model(std::string_view name) {
  for (const auto& m : model_registry())
    if (m.name == name) return &m;
  return nullptr;
}

const ModelInfo& require_model(std::string_view name, std::string_view parameter) {
  if (const ModelInfo* info = find_model(name)) return *info;
  std::vector<std::string> names;
  for (const auto& m : model_registry()) names.push_back(m.name);
  throw InvalidArgument(fmt::format(
      "{}unknown model '{}'{} (known: {})", parameter.empty() ? "" : spelled(parameter) + ": ",
      excerpt(name), did_you_mean(name, names), fmt::join(names, ", ")));
}

std::unique_ptr<SkyModel> make_sky_model(std::string_view name, const SkyParameters& params) {
  const ModelInfo& info = require_model(name);
  validate_sun(params.sun);
  return info.make(params);
}

EstimationPolicy registry_estimation(std::string name, std::vector<EstimationPolicy::Axis> axes,
                                     std::string description) {
  EstimationPolicy e;
  e.method = EstimationPolicy::Method::grid_ransac;
  e.axes = std::move(axes);
  e.description = std::move(description);
  std::vector<std::string> names;
  for (const auto& a : e.axes) names.push_back(a.parameter);
  e.prepare = [name, names](const SunPosition& sun, std::span<const Vec3> views) {
    auto v = std::make_shared<std::vector<Vec3>>(views.begin(), views.end());
    return EstimationPolicy::LogLuminance([name, names, v, sun](std::span<const double> p,
                                                                std::span<const std::size_t> idx,
                                                                std::span<double> out) {
      SkyParameters sp;
      sp.sun = sun;
      for (std::size_t a = 0; a < names.size(); ++a) sp.values.set(names[a], p[a]);
      const auto model = make_sky_model(name, sp);
      for (std::size_t k = 0; k < idx.size(); ++k)
        out[k] = std::log(
            std::max(model->tristimulus((*v)[idx[k]]).Y, std::numeric_limits<double>::min()));
    });
  };
  return e;
}

}  // namespace skylight
