#include "skylight/models/perez.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/parameters.h"

namespace skylight {

namespace {

// The parameters of a sky from irradiance (shared by the model and `skylight daylight`).
void add_irradiance_entries(ParameterSchema<PerezParameters>& s) {
  const auto light = [&](std::optional<double> PerezParameters::*field, const char* name,
                         const char* unit, double max, const char* what) {
    s.optional_number(field, {.name = name,
                              .unit = unit,
                              .min = 0.0,
                              .max = max,
                              .default_value = Absent{"the sky from --perez"},
                              .description = what});
  };
  light(&PerezParameters::dni, "dni", "W/m^2", kMaxIrradianceInput,
        "direct normal irradiance: the all-weather sky from irradiance (Perez et al. 1990, 1993)");
  light(&PerezParameters::dhi, "dhi", "W/m^2", kMaxIrradianceInput,
        "diffuse horizontal irradiance (with --dni)");
  light(&PerezParameters::dni_illuminance, "dni-illuminance", "lx", kMaxIlluminanceInput,
        "direct normal illuminance: the all-weather sky from illuminance");
  light(&PerezParameters::dhi_illuminance, "dhi-illuminance", "lx", kMaxIlluminanceInput,
        "diffuse horizontal illuminance (with --dni-illuminance)");
  s.optional_integer(&PerezParameters::day_of_year,
                     {.name = "day-of-year",
                      .unit = "1",
                      .min = 1,
                      .max = 366,
                      .default_value = Absent{"the date of --time"},
                      .description = "day of the year (extraterrestrial irradiance) of a sky "
                                     "from irradiance"});
  s.optional_number(&PerezParameters::dew_point,
                    {.name = "dew-point",
                     .unit = "degC",
                     .min = -70.0,
                     .max = 70.0,
                     .default_value = Absent{"precipitable water 2 cm"},
                     .description = "surface dew point: the precipitable water of the efficacy "
                                    "models (Perez et al. 1990 eq. 3)"});
  s.optional_number(&PerezParameters::precipitable_water,
                    {.name = "precipitable-water",
                     .unit = "cm",
                     .min = 0.0,
                     .max = 20.0,
                     .default_value = Absent{"from --dew-point, else 2 cm"},
                     .description = "precipitable water of the efficacy models"});
  s.choice(&PerezParameters::compat,
           {.name = "compat",
            .default_value = ParameterValue(std::string("papers")),
            .description = "a sky from irradiance as the papers define it, or as Radiance's "
                           "gendaylit computes it (docs/DAYLIGHT.md)"},
           {{"papers", PerezCompat::papers}, {"radiance", PerezCompat::radiance}});
}

}  // namespace

const ParameterSchema<PerezParameters>& PerezParameters::schema() {
  static const auto s = [] {
    ParameterSchema<PerezParameters> s;
    s.optional_numbers(
        &PerezParameters::coefficients,
        {.name = "perez",
         .unit = "1",
         .kind = ParameterKind::numbers,
         .min = -kPerezCoefficientLimit,
         .max = kPerezCoefficientLimit,
         .count = 5,
         .default_value = Absent{"from --dni/--dhi (or their illuminances)"},
         .description = "coefficients A,B,C,D,E of F = (1 + A e^{B/cos theta})(1 + C e^{D gamma} "
                        "+ E cos^2 gamma)"});
    s.optional_number(&PerezParameters::zenith_luminance,
                      {.name = "zenith-luminance",
                       .unit = "cd/m^2",
                       .min = kMinZenithLuminance,
                       .max = kMaxZenithLuminance,
                       .default_value = Absent{"required with --perez; from irradiance the diffuse "
                                               "horizontal illuminance sets the level"},
                       .description = "absolute zenith luminance Lz"});
    add_irradiance_entries(s);
    return s;
  }();
  return s;
}

const ParameterSchema<PerezParameters>& PerezParameters::irradiance_schema() {
  static const auto s = [] {
    ParameterSchema<PerezParameters> s;
    add_irradiance_entries(s);
    return s;
  }();
  return s;
}

namespace {

// The all-weather sky of irradiance parameters (models/perez_allweather.h).
PerezSky irradiance_sky_of(const PerezParameters& p) {
  if (p.coefficients || p.zenith_luminance)
    throw InvalidArgument(
        fmt::format("{} / {} and {} / {} are two ways to give the Perez sky: give one",
                    spelled("perez"), spelled("zenith-luminance"), spelled("dni"), spelled("dhi")));
  if (!p.day_of_year)
    throw InvalidArgument(fmt::format("a Perez sky from irradiance needs the date: {} or --time",
                                      spelled("day-of-year")));
  PerezIrradianceInput in;
  in.sun = p.sun;
  in.dni_w_m2 = p.dni;
  in.dhi_w_m2 = p.dhi;
  in.dni_lux = p.dni_illuminance;
  in.dhi_lux = p.dhi_illuminance;
  in.day_of_year = *p.day_of_year;
  in.dew_point_c = p.dew_point;
  in.precipitable_water_cm = p.precipitable_water;
  in.compat = p.compat;
  return perez_sky_from_irradiance(in);
}

}  // namespace

PerezModel::PerezModel(const PerezParameters& p) : SkyModel(p.sun), params_(p) {
  PerezParameters::schema().validate(p, model_context(kName));
  sun_up_ = p.sun.zenith <= 0.5 * kPi;
  std::array<double, 5> k{};
  double zenith_luminance = 0.0;
  SunPosition sky_sun = p.sun;
  if (p.from_irradiance()) {
    sky_ = irradiance_sky_of(p);
    sky_sun = sky_->sun;
    k = sky_->coefficients;
    zenith_luminance = sky_->zenith_luminance_cd_m2;
    if (sky_->dark) {
      sun_up_ = false;
      k = {0.0, 0.0, 0.0, 0.0, 0.0};
    }
  } else {
    if (!p.coefficients)
      throw InvalidArgument(fmt::format(
          "model 'perez' needs {} A,B,C,D,E with {}, or {} and {} (or their illuminances)",
          spelled("perez"), spelled("zenith-luminance"), spelled("dni"), spelled("dhi")));
    if (!p.zenith_luminance)
      throw InvalidArgument(
          fmt::format("model 'perez': {} needs {}", spelled("perez"), spelled("zenith-luminance")));
    k = *p.coefficients;
    zenith_luminance = *p.zenith_luminance;
  }
  const PerezCoefficients c{k[0], k[1], k[2], k[3], k[4], 1.0};
  // From irradiance the scale is the normalisation itself (F(0, theta_s) may be <= 0 for a low
  // sun: the fitted coefficients make the zenith dark, and the kernel returns 0 there).
  const double f0 = sky_ ? 1.0 : perez_function(c, 1.0, sky_sun.zenith);
  if (sky_) zenith_luminance = sky_->normalisation;
  if (sun_up_ && !(f0 > 0.0)) {
    throw InvalidArgument(fmt::format(
        "perez coefficients {},{},{},{},{} give F(zenith) = {} <= 0 at sun zenith {} deg: the "
        "relative distribution cannot be normalised",
        k[0], k[1], k[2], k[3], k[4], f0, rad_to_deg(sky_sun.zenith)));
  }
  // Bounds of |F|'s two factors over the sky (with the kernel's clamps): the float batch path
  // multiplies them, so each must stay far inside the float range, and so must Lz F / F(0, ts).
  const double grad_bound =
      1.0 + std::abs(c.A) * std::exp(std::clamp(std::max(c.B, c.B / kPerezMinCosTheta),
                                                -kPerezMaxExponent, kPerezMaxExponent));
  const double ind_bound =
      1.0 +
      std::abs(c.C) *
          std::max(1.0, std::exp(std::clamp(c.D * kPi, -kPerezMaxExponent, kPerezMaxExponent))) +
      std::abs(c.E);
  const double max_luminance = sun_up_ ? zenith_luminance / f0 * grad_bound * ind_bound : 0.0;
  if (grad_bound > kPerezMaxFactor || ind_bound > kPerezMaxFactor ||
      !(max_luminance <= kPerezMaxLuminance))
    throw InvalidArgument(fmt::format(
        "{} {},{},{},{},{} with {} {} overflows: F's factors reach {:.3g} (gradation) and {:.3g} "
        "(indicatrix), the luminance up to {:.3g} cd/m^2 (limits {:g} and {:g})",
        spelled("perez"), k[0], k[1], k[2], k[3], k[4], spelled("zenith-luminance"),
        zenith_luminance, grad_bound, ind_bound, max_luminance, kPerezMaxFactor,
        kPerezMaxLuminance));
  distribution_.mode = PerezDistribution::Mode::luminance;
  distribution_.coefficients[0] = c;
  distribution_.sun = sky_sun.direction();
  distribution_.scale[0] = sun_up_ ? zenith_luminance / f0 : 0.0;
}

ParameterValues PerezModel::parameter_values() const {
  ParameterValues v = PerezParameters::schema().values_of(params_);
  // What this sky does not read is left out (the CLI warns about a flag given but not read).
  if (!params_.from_irradiance()) {
    for (const char* name : {"day-of-year", "dew-point", "precipitable-water", "compat"})
      v.erase(name);
  } else if (params_.precipitable_water) {
    v.erase("dew-point");
  }
  return v;
}

Xyz PerezModel::tristimulus(Vec3 view) const {
  return distribution_.evaluate(view);
}

void PerezModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  distribution_.evaluate_batch(dirs, out);
}

MeasuredLight measured_light_of(const PerezSky& sky) {
  MeasuredLight m;
  if (!sky.dark) {
    m.dni_w_m2 = sky.dni_w_m2;
    m.dhi_w_m2 = sky.dhi_w_m2;
    m.dni_lux = sky.direct_normal_lux;
    m.dhi_lux = sky.diffuse_horizontal_lux;
  }
  m.air_mass = sky.air_mass;
  m.extraterrestrial_w_m2 = sky.extraterrestrial_w_m2;
  return m;
}

std::optional<MeasuredLight> PerezModel::measured_light() const {
  if (!sky_) return std::nullopt;
  return measured_light_of(*sky_);
}

Domain PerezModel::domain() const {
  Domain d;
  if (sky_) {
    // compat radiance's adjustments, and why a sky from irradiance is dark.
    for (const std::string& note : sky_->notes)
      d.issues.push_back({params_.compat == PerezCompat::radiance ? "compat" : "dhi",
                          sky_->dark ? Validity::undefined : Validity::extrapolated, note});
    if (sky_->dark) return d;
    const double horizontal = sky_->extraterrestrial_w_m2 * std::cos(sky_->sun.zenith);
    if (sky_->dhi_w_m2 > horizontal)
      d.issues.push_back({"dhi", Validity::unphysical,
                          fmt::format("the diffuse horizontal irradiance {:.4g} W/m^2 exceeds the "
                                      "extraterrestrial horizontal irradiance {:.4g} W/m^2",
                                      sky_->dhi_w_m2, horizontal)});
    if (params_.compat == PerezCompat::papers &&
        (sky_->epsilon >= kRadianceClearnessMax || sky_->delta < kRadianceBrightnessMin ||
         sky_->delta > kRadianceBrightnessMax))
      d.issues.push_back(
          {"dhi", Validity::extrapolated,
           fmt::format("epsilon {:.4g}, delta {:.4g}: outside the range the 1993 coefficients "
                       "were fitted over (epsilon < 12, delta 0.01 .. 0.6)",
                       sky_->epsilon, sky_->delta)});
  }
  if (!sun_up_) {
    if (!sky_)
      d.issues.push_back(
          {"sun_zenith", Validity::undefined,
           "sun below the horizon: the Perez distribution describes daylight; sky is 0"});
    return d;
  }
  // F's sign is set by (1 + A e^{B/cos}) at the horizon and (1 + C e^{D gamma} + E cos^2) across
  // gamma; check both factors over their ranges.
  const auto k = sky_ ? sky_->coefficients : *params_.coefficients;
  const PerezCoefficients c{k[0], k[1], k[2], k[3], k[4], 1.0};
  double min_grad = 1e300, min_ind = 1e300;
  for (int i = 0; i <= 90; ++i) {
    const double theta = i * kDegree;
    min_grad = std::min(min_grad, perez_function({c.A, c.B, 0, 0, 0, 1.0}, std::cos(theta), 0.0));
  }
  for (int i = 0; i <= 180; ++i)
    min_ind = std::min(min_ind, perez_function({0, 0, c.C, c.D, c.E, 1.0}, 1.0, i * kDegree));
  if (min_grad < 0.0 || min_ind < 0.0) {
    d.issues.push_back({"perez", Validity::unphysical,
                        "the coefficients make F negative somewhere on the sky; those directions "
                        "return 0"});
  }
  return d;
}

ModelInfo PerezModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "Perez all-weather sky (Perez et al. 1993): user coefficients A..E, or from "
          "direct and diffuse irradiance (Perez et al. 1990)",
      .output = "luminance Y [cd/m^2] = Lz F(theta,gamma)/F(0,theta_s); XYZ at D65 chromaticity",
      .parameters = PerezParameters::schema().specs(),
      .domain =
          "any coefficients that keep F > 0; from irradiance: epsilon < 12, delta 0.01 .. "
          "0.6 (the 1993 fit); sun above the horizon (below: 0)",
      .luminance_only = true,
      // The date of --time gives the day of the year when --day-of-year is not given.
      .make = [](const SkyParameters& sp) -> std::unique_ptr<SkyModel> {
        PerezParameters p = bind_parameters<PerezParameters>(sp, kName);
        if (!p.day_of_year && sp.day_of_year) p.day_of_year = sp.day_of_year;
        return std::make_unique<PerezModel>(p);
      },
      // A clear sky: the CIE S 011 type 12 gradation and indicatrix coefficients as A..E.
      .example = ParameterValues()
                     .set("perez", std::vector<double>{-1.0, -0.32, 10.0, -3.0, 0.45})
                     .set("zenith-luminance", 5000.0),
      // With a weather file, each hour's sky is the all-weather sky of the record's light.
      .weather_sky = true,
      .neural = NeuralPolicy{},
      .sh_fit = ShFitPolicy{},
      // The report's Perez sky: the example's clear-sky coefficients.
      // On planes with a weather year: each hour's all-weather sky (weather_sky).
      .report = ReportPolicy{.title = "Perez (example coefficients)",
                             .colour = "#8c564b",
                             .planes = ParameterValues()},
  };
}

GpuSky PerezDistribution::gpu_sky() const {
  // The three channels' coefficients side by side (x: Y, y: x, z: y of xyY; luminance mode: x).
  GpuSky g;
  g.glsl =
      "uniform vec3 skylight_perez_A, skylight_perez_B, skylight_perez_C, skylight_perez_D,\n"
      "    skylight_perez_E, skylight_perez_K, skylight_perez_scale;\n"
      "uniform vec3 skylight_perez_sun;  // unit vector, z up\n"
      "uniform vec2 skylight_perez_white;  // X / Y and Z / Y of the luminance mode's white\n"
      "uniform int skylight_perez_xyY;     // 1: channels (Y, x, y); 0: Y alone\n"
      "vec3 skylight_perez(vec3 dir) {  // models/perez_kernel.h, PerezDistribution::evaluate\n"
      "  if (dir.z < 0.0) return vec3(0.0);\n"
      "  float gamma = skylight_angle(dir, skylight_perez_sun);\n"
      "  float inv_cos = 1.0 / max(dir.z, " +
      fmt::format("{:.9e}", kPerezMinCosTheta) +
      ");\n"
      "  vec3 m = vec3(" +
      fmt::format("{:.9e}", kPerezMaxExponent) +
      ");\n"
      "  vec3 grad = 1.0 + skylight_perez_A * exp(clamp(skylight_perez_B * inv_cos, -m, m));\n"
      "  float cg = cos(gamma);\n"
      "  vec3 ind = skylight_perez_K + skylight_perez_C * exp(clamp(skylight_perez_D * gamma, -m, "
      "m))\n"
      "      + skylight_perez_E * (cg * cg);\n"
      "  vec3 f = skylight_perez_scale * grad * ind;\n"
      "  float Y = max(0.0, f.x);\n"
      "  if (skylight_perez_xyY == 0) return vec3(skylight_perez_white.x * Y, Y,\n"
      "                                            skylight_perez_white.y * Y);\n"
      "  if (!(f.z > 0.0)) return vec3(0.0);\n"
      "  return vec3(f.y * Y / f.z, Y, (1.0 - f.y - f.z) * Y / f.z);\n"
      "}\n";
  g.expression = "skylight_perez(dir)";
  const auto channel = [&](auto member) {
    return std::vector<double>{coefficients[0].*member, coefficients[1].*member,
                               coefficients[2].*member};
  };
  g.uniforms = {gpu_uniform("skylight_perez_A", channel(&PerezCoefficients::A)),
                gpu_uniform("skylight_perez_B", channel(&PerezCoefficients::B)),
                gpu_uniform("skylight_perez_C", channel(&PerezCoefficients::C)),
                gpu_uniform("skylight_perez_D", channel(&PerezCoefficients::D)),
                gpu_uniform("skylight_perez_E", channel(&PerezCoefficients::E)),
                gpu_uniform("skylight_perez_K", channel(&PerezCoefficients::K)),
                gpu_uniform("skylight_perez_scale", {scale[0], scale[1], scale[2]}),
                gpu_uniform("skylight_perez_sun", {sun.x, sun.y, sun.z})};
  const Xyz w = xyY_to_xyz(white, 1.0);
  g.uniforms.push_back(gpu_uniform("skylight_perez_white", {w.X, w.Z}));
  g.uniforms.push_back(gpu_int_uniform("skylight_perez_xyY", mode == Mode::xyY ? 1 : 0));
  g.comment = mode == Mode::xyY ? "the Perez function in Y, x and y (Zotti et al. 2007 eqs. 3-4)"
                                : "the Perez function in luminance";
  return g;
}

std::optional<GpuSky> PerezModel::gpu_sky() const {
  return distribution_.gpu_sky();
}

}  // namespace skylight
