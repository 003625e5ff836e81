#include "skylight/models/evaluation.h"

#include <fmt/format.h>

#include "skylight/core/error.h"
#include "skylight/core/parameters.h"

namespace skylight {

std::string_view to_string(SunMode mode) {
  switch (mode) {
    case SunMode::sky:
      return "sky";
    case SunMode::sky_and_sun:
      return "sky+sun";
    case SunMode::sun_only:
      return "sun-only";
  }
  return "sky";
}

const ParameterSchema<SolarDisc>& SolarDisc::schema() {
  static const ParameterSchema<SolarDisc> s = [] {
    ParameterSchema<SolarDisc> s;
    s.custom(
         {.name = "include-sun",
          .kind = ParameterKind::flag,
          .default_value = ParameterValue(false),
          .description = "add the solar disc (models with a sun)"},
         [](SolarDisc& m, const ParameterValue& v) {
           if (std::get<bool>(v)) m.mode = SunMode::sky_and_sun;
         },
         [](const SolarDisc& m) -> std::optional<ParameterValue> {
           return m.mode == SunMode::sky_and_sun;
         })
        .custom(
            {.name = "sun-only",
             .kind = ParameterKind::flag,
             .default_value = ParameterValue(false),
             .description = "the solar disc alone, without the sky"},
            [](SolarDisc& m, const ParameterValue& v) {
              if (std::get<bool>(v)) m.mode = SunMode::sun_only;
            },
            [](const SolarDisc& m) -> std::optional<ParameterValue> {
              return m.mode == SunMode::sun_only;
            });
    return s;
  }();
  return s;
}

void check_sun_mode(const SkyModel& model, SunMode mode) {
  if (mode != SunMode::sky && !model.has_sun())
    throw InvalidArgument(fmt::format("{}/{}: model '{}' has no sun", spelled("include-sun"),
                                      spelled("sun-only"), model.name()));
}

ParameterSpec model_spec() {
  std::string names;
  std::vector<std::string> choices;
  for (const auto& m : model_registry()) {
    names += (names.empty() ? "" : "|") + m.name;
    choices.push_back(m.name);
  }
  ParameterSpec s{.name = "model",
                  .kind = ParameterKind::text,
                  .default_value = Required{},
                  .description = "sky model: " + names + " (see `skylight models`)"};
  s.choices = std::move(choices);
  return s;
}

ParameterSpec sun_elevation_spec() {
  const ParameterSpec& z = sun_parameter_specs()[0];
  return {.name = "sun-elevation",
          .unit = "deg",
          .min = 90.0 - z.max,
          .max = 90.0 - z.min,
          .default_value = Absent{"90 - sun zenith"},
          .description = "solar elevation (alternative to --sun-zenith)"};
}

const ParameterSchema<EvaluationOptions>& EvaluationOptions::schema() {
  static const ParameterSchema<EvaluationOptions> s = [] {
    using E = EvaluationOptions;
    ParameterSchema<E> s;
    s.choice(
         &E::quantity,
         {.name = "quantity",
          .kind = ParameterKind::text,
          .default_value = ParameterValue(std::string("rgb")),
          .description =
              "rgb (linear sRGB), xyz (Y in cd/m^2), luminance (cd/m^2), spectral (W m^-2 sr^-1 "
              "nm^-1)"},
         {{"rgb", Quantity::rgb},
          {"xyz", Quantity::xyz},
          {"luminance", Quantity::luminance},
          {"spectral", Quantity::spectral}})
        .numbers(&E::wavelengths_nm,
                 {.name = "wavelengths",
                  .unit = "nm",
                  .kind = ParameterKind::numbers,
                  .min = 1.0,
                  .max = 10000.0,
                  .count = 0,
                  .default_value = Absent{"none"},
                  .description = "wavelengths for --quantity spectral, e.g. 450,550,650"});
    return s;
  }();
  return s;
}

void validate(const EvaluationOptions& o) {
  const bool spectral = o.quantity == Quantity::spectral;
  if (spectral && o.wavelengths_nm.empty())
    throw InvalidArgument(fmt::format("{} spectral needs {} NM[,NM...]", spelled("quantity"),
                                      spelled("wavelengths")));
  if (!spectral && !o.wavelengths_nm.empty())
    throw InvalidArgument(fmt::format("{} is only used with {} spectral", spelled("wavelengths"),
                                      spelled("quantity")));
}

void validate(const EvaluationOptions& o, const SkyModel& model) {
  validate(o);
  check_sun_mode(model, o.sun);
  if (o.quantity == Quantity::spectral && !find_model(model.name())->spectral)
    throw InvalidArgument(fmt::format("{} spectral: model '{}' has no spectral output",
                                      spelled("quantity"), model.name()));
}

std::vector<std::string> quantity_columns(const EvaluationOptions& o) {
  switch (o.quantity) {
    case Quantity::rgb:
      return {"r", "g", "b"};
    case Quantity::xyz:
      return {"x", "y", "z"};
    case Quantity::luminance:
      return {"luminance"};
    case Quantity::spectral: {
      std::vector<std::string> out;
      for (double nm : o.wavelengths_nm) out.push_back(fmt::format("L{}", nm));
      return out;
    }
  }
  return {};
}

std::vector<double> evaluate(const SkyModel& model, Vec3 v, const EvaluationOptions& o) {
  const bool sky = o.sun != SunMode::sun_only, sun = o.sun != SunMode::sky;
  if (o.quantity == Quantity::spectral) {
    std::vector<double> out;
    for (double nm : o.wavelengths_nm) {
      double L = 0.0;
      if (sky) {
        const auto s = model.spectral_radiance(v, nm);
        if (!s)
          throw InvalidArgument(fmt::format("{}: {} nm is outside the range of model '{}'",
                                            spelled("wavelengths"), nm, model.name()));
        L += *s;
      }
      if (sun) {
        const auto s = model.sun_spectral_radiance(v, nm);
        if (!s)
          throw InvalidArgument(fmt::format("{}: {} nm is outside the sun's range of model '{}'",
                                            spelled("wavelengths"), nm, model.name()));
        L += *s;
      }
      out.push_back(L);
    }
    return out;
  }
  Xyz c;
  if (sky) c = model.tristimulus(v);
  if (sun) {
    const Xyz s = model.sun_tristimulus(v);
    c = {c.X + s.X, c.Y + s.Y, c.Z + s.Z};
  }
  switch (o.quantity) {
    case Quantity::xyz:
      return {c.X, c.Y, c.Z};
    case Quantity::luminance:
      return {c.Y};
    default: {
      const Rgb rgb = (sky && !sun) ? model.rgb(v) : xyz_to_linear_srgb(c);
      return {rgb.r, rgb.g, rgb.b};
    }
  }
}

}  // namespace skylight
