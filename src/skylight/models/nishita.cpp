#include "skylight/models/nishita.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/parameters.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/preetham.h"

namespace skylight {
namespace {

std::array<double, kNishitaXyzCount> xyz_wavelengths() {
  std::array<double, kNishitaXyzCount> w{};
  for (int k = 0; k < kNishitaXyzCount; ++k) w[k] = kNishitaXyzFirst + kNishitaXyzStep * k;
  return w;
}

}  // namespace

double solar_spectral_irradiance(double nm) {
  return atmosphere::bruneton_spectra().solar_irradiance(nm);
}

const ParameterSchema<NishitaParameters>& NishitaParameters::schema() {
  static const auto s = [] {
    namespace a = atmosphere;
    using P = NishitaParameters;
    const P d;
    ParameterSchema<P> s;
    s.number(&P::observer_altitude_m, {.name = "observer-altitude",
                                       .unit = "m",
                                       .min = 0.0,
                                       .max = kNishitaMaxAltitude,
                                       .default_value = ParameterValue(d.observer_altitude_m),
                                       .description = "observer above the ground"});
    s.optional_number(
        &P::solar_irradiance,
        {.name = "solar-irradiance",
         .unit = "W m^-2 nm^-1",
         .min = 1e-30,
         .max = 1e30,
         .default_value = Absent{"the ASTM G-173 extraterrestrial spectrum"},
         .description = "flat extraterrestrial solar spectral irradiance (1 = radiance per unit "
                        "irradiance)"});
    s.optional_number(&P::albedo,
                      {.name = "albedo",
                       .unit = "1",
                       .min = 0.0,
                       .max = 1.0,
                       .default_value = Absent{"no ground reflection"},
                       .description = "Lambertian ground albedo (direct sunlight reflected by the "
                                      "ground)"});
    s.number(&P::ground_radius_m, {.name = "ground-radius",
                                   .unit = "m",
                                   .min = 1.0,
                                   .max = 1e9,
                                   .default_value = ParameterValue(d.ground_radius_m),
                                   .description = "planet radius R0"});
    s.custom(
        // Twice the largest ground radius, so that every ground radius has a top above it.
        {.name = "top-radius",
         .unit = "m",
         .min = 1.0,
         .max = 2e9,
         .default_value = Absent{"ground radius + 60 km"},
         .description = "top of the atmosphere (> ground radius)"},
        [](P& p, const ParameterValue& v) { p.top_radius_m = std::get<double>(v); },
        [](const P& p) -> std::optional<ParameterValue> { return p.top_radius(); });
    s.number(&P::rayleigh_scale_height_m,
             {.name = "rayleigh-scale-height",
              .unit = "m",
              .min = 1.0,
              .max = 1e7,
              .default_value = ParameterValue(d.rayleigh_scale_height_m),
              .description = "Rayleigh scale height H_R"});
    s.number(&P::mie_scale_height_m, {.name = "mie-scale-height",
                                      .unit = "m",
                                      .min = 1.0,
                                      .max = 1e7,
                                      .default_value = ParameterValue(d.mie_scale_height_m),
                                      .description = "Mie scale height H_M"});
    s.number(&P::mie_g, {.name = "mie-g",
                         .unit = "1",
                         .min = -0.999,
                         .max = 0.999,
                         .default_value = ParameterValue(d.mie_g),
                         .description = "Cornette-Shanks asymmetry g"});
    s.optional_number(&P::aerosol_optical_depth,
                      {.name = "aerosol-optical-depth",
                       .unit = "1",
                       .min = 0.0,
                       .max = 5.0,
                       .default_value = Absent{"Earth's default Mie layer, 4.44e-6 m^-1 at the "
                                               "ground (0.0053 for H_M = 1.2 km)"},
                       .description = "aerosol optical depth at 550 nm (the Mie layer's column)"});
    s.optional_number(&P::angstrom_exponent,
                      {.name = "angstrom-exponent",
                       .unit = "1",
                       .min = -1.0,
                       .max = 4.0,
                       .default_value = Absent{"0 (grey), 1.3 with --turbidity"},
                       .description = "Angstrom exponent alpha of the aerosols: beta ~ "
                                      "(550 nm / lambda)^alpha"});
    s.number(&P::aerosol_albedo, {.name = "aerosol-albedo",
                                  .unit = "1",
                                  .min = 0.0,
                                  .max = 1.0,
                                  .default_value = ParameterValue(d.aerosol_albedo),
                                  .description = "the aerosols' single-scattering albedo "
                                                 "beta_s / beta_e"});
    s.optional_number(&P::turbidity,
                      {.name = "turbidity",
                       .unit = "1",
                       .min = 1.0,
                       .max = 20.0,
                       .default_value = Absent{"the aerosol flags"},
                       .description = "Preetham's turbidity as aerosols: tau_550 = beta "
                                      "0.55^-1.3, beta = 0.04608 T - 0.04586, alpha = 1.3"});
    s.optional_number(
        &P::ozone_du,
        {.name = "ozone",
         .unit = "DU",
         .min = 0.0,
         .max = 1000.0,
         .default_value = Absent{"no ozone layer"},
         .description = "ozone column of an absorbing layer at 10-40 km (Bruneton 2017 profile; "
                        "Earth ~300 DU)"});
    return s;
  }();
  return s;
}

double NishitaParameters::top_radius() const {
  return top_radius_m.value_or(ground_radius_m +
                               (atmosphere::kEarthTopRadius - atmosphere::kEarthGroundRadius));
}

void NishitaParameters::set_aerosols(atmosphere::Component& mie) const {
  mie.scale_height_m = mie_scale_height_m;
  mie.g = mie_g;
  if (turbidity && (aerosol_optical_depth || angstrom_exponent))
    throw InvalidArgument(fmt::format(
        "{} and {} exclude each other (the turbidity gives the aerosols' depth and exponent)",
        spelled("turbidity"),
        spelled(aerosol_optical_depth ? "aerosol-optical-depth" : "angstrom-exponent")));
  const bool earth = !turbidity && !aerosol_optical_depth && !angstrom_exponent &&
                     aerosol_albedo == NishitaParameters{}.aerosol_albedo;
  if (earth) return;  // earth_mie() as it is
  const double height = top_radius() - ground_radius_m;
  // The column of the exponential layer up to the top: H_M (1 - exp(-height / H_M)).
  const double column_m = mie_scale_height_m * -std::expm1(-height / mie_scale_height_m);
  double tau = mie.extinction_per_m * column_m, alpha = angstrom_exponent.value_or(0.0);
  if (turbidity) {
    const PreethamAerosol p = preetham_aerosol(*turbidity);
    tau = p.optical_depth(550.0);
    alpha = p.alpha;
  } else if (aerosol_optical_depth) {
    tau = *aerosol_optical_depth;
  }
  mie.reference_nm = 550.0;
  mie.extinction_per_m = tau / column_m;
  mie.scattering_per_m = aerosol_albedo * mie.extinction_per_m;
  mie.angstrom_exponent = alpha;
}

NishitaSetup NishitaParameters::setup() const {
  schema().validate(*this, model_context(NishitaModel::kName));
  NishitaSetup s;
  s.sun = sun;
  s.observer_altitude_m = observer_altitude_m;
  s.solar_irradiance = solar_irradiance;
  atmosphere::AtmosphereParameters& a = s.atmosphere;
  a.ground_radius_m = ground_radius_m;
  a.top_radius_m = top_radius();
  if (!(a.top_radius_m > a.ground_radius_m))
    throw InvalidArgument(fmt::format("{} {} must exceed {} {}", spelled("top-radius"),
                                      a.top_radius_m, spelled("ground-radius"), a.ground_radius_m));
  a.components[0].scale_height_m = rayleigh_scale_height_m;
  set_aerosols(a.components[1]);
  if (ozone_du) a.components.push_back(atmosphere::earth_ozone(*ozone_du));
  a.ground_albedo = albedo;
  return s;
}

NishitaModel::NishitaModel(const NishitaParameters& p, const atmosphere::FastSettings& settings)
    : NishitaModel(p.setup(), settings) {
  params_ = p;
}

NishitaModel::NishitaModel(const NishitaSetup& setup, const atmosphere::FastSettings& settings)
    : SkyModel(setup.sun), setup_(setup) {
  require_in_range("observer_altitude [m]", setup.observer_altitude_m, 0.0, kNishitaMaxAltitude);
  if (setup.solar_irradiance)
    require_in_range("solar_irradiance [W m^-2 nm^-1]", *setup.solar_irradiance, 1e-30, 1e30);
  const atmosphere::AtmosphereParameters& ap = setup.atmosphere;
  atmosphere_ = std::make_unique<atmosphere::Atmosphere>(ap, settings);
  observer_ = {0.0, 0.0, ap.ground_radius_m + setup.observer_altitude_m};
  sun_ = setup.sun.direction();
  const auto nm = xyz_wavelengths();
  std::array<double, kNishitaXyzCount> solar{};
  for (int k = 0; k < kNishitaXyzCount; ++k) solar[k] = irradiance(nm[k]);
  xyz_spectral_ = atmosphere::make_spectral(ap, nm, solar);
  for (int k = 0; k < kNishitaXyzCount; ++k) cmf_[k] = cie1931_cmf(nm[k]);
}

ParameterValues NishitaModel::parameter_values() const {
  if (params_) return NishitaParameters::schema().values_of(*params_);
  // A custom planet: what its setup states in the schema's terms.
  ParameterValues v;
  v.set("observer-altitude", setup_.observer_altitude_m);
  if (setup_.solar_irradiance) v.set("solar-irradiance", *setup_.solar_irradiance);
  if (setup_.atmosphere.ground_albedo) v.set("albedo", *setup_.atmosphere.ground_albedo);
  v.set("ground-radius", setup_.atmosphere.ground_radius_m);
  v.set("top-radius", setup_.atmosphere.top_radius_m);
  return v;
}

double NishitaModel::irradiance(double nm) const {
  return setup_.solar_irradiance ? *setup_.solar_irradiance : solar_spectral_irradiance(nm);
}

// X = K_m sum_k x-bar(lambda_k) I(lambda_k) d lambda (midpoint rule over 20 nm bins), same for Y,
// Z.
Xyz NishitaModel::to_xyz(const std::array<double, kNishitaXyzCount>& radiance) const {
  Xyz c{0, 0, 0};
  for (int k = 0; k < kNishitaXyzCount; ++k) {
    const Cmf& m = cmf_[k];
    c.X += m.x * radiance[k];
    c.Y += m.y * radiance[k];
    c.Z += m.z * radiance[k];
  }
  const double f = kMaxLuminousEfficacy * kNishitaXyzStep;
  return {c.X * f, c.Y * f, c.Z * f};
}

Xyz NishitaModel::tristimulus(Vec3 view) const {
  std::array<double, kNishitaXyzCount> r{};
  atmosphere_->single_scattering(observer_, normalize(view), sun_, xyz_spectral_, r);
  return to_xyz(r);
}

Xyz NishitaModel::tristimulus_reference(Vec3 view, const atmosphere::ReferenceSettings& rs) const {
  std::array<double, kNishitaXyzCount> r{};
  atmosphere_->single_scattering_reference(observer_, normalize(view), sun_, xyz_spectral_, r, rs);
  return to_xyz(r);
}

atmosphere::Spectral NishitaModel::spectral_at(std::span<const double> nm) const {
  std::vector<double> solar;
  for (double l : nm) solar.push_back(irradiance(l));
  return atmosphere::make_spectral(atmosphere_->parameters(), nm, solar);
}

std::optional<double> NishitaModel::spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= kNishitaMinNm && nm <= kNishitaMaxNm)) return std::nullopt;
  const auto spec = spectral_at(std::span<const double>(&nm, 1));
  double out[1] = {0.0};
  atmosphere_->single_scattering(observer_, normalize(view), sun_, spec, out);
  return out[0];
}

std::vector<double> NishitaModel::reference_wavelengths(const EvaluationOptions& o) const {
  return reference_wavelengths_of(o, name(), xyz_spectral_.nm, kNishitaMinNm, kNishitaMaxNm);
}

ReferenceValue NishitaModel::reference_value(const EvaluationOptions& o,
                                             std::span<const double> radiance,
                                             std::span<const double> se) const {
  // The midpoint sum's weights: the CMFs times the bins' width.
  std::array<Cmf, kNishitaXyzCount> w{};
  for (int k = 0; k < kNishitaXyzCount; ++k)
    w[k] = {cmf_[k].x * kNishitaXyzStep, cmf_[k].y * kNishitaXyzStep, cmf_[k].z * kNishitaXyzStep};
  return weighted_reference_value(o, w, radiance, se);
}

Domain NishitaModel::domain() const {
  return sun_below_horizon(Validity::extrapolated,
                           "single scattering only (planet shadow included); twilight skies are "
                           "dominated by multiple scattering, not modelled");
}

namespace {

NishitaParameters at_ground(NishitaParameters p) {
  p.observer_altitude_m = 0.0;
  p.sun = SunPosition{};
  return p;
}

}  // namespace

NishitaSampler::NishitaSampler(const NishitaParameters& atmosphere)
    : params_(at_ground(atmosphere)), model_(params_) {
  std::array<double, kNishitaXyzCount> nm{}, solar{};
  for (int k = 0; k < kNishitaXyzCount; ++k) {
    nm[k] = kNishitaXyzFirst + kNishitaXyzStep * k;
    solar[k] =
        params_.solar_irradiance ? *params_.solar_irradiance : solar_spectral_irradiance(nm[k]);
    cmf_[k] = cie1931_cmf(nm[k]);
  }
  spectral_ = atmosphere::make_spectral(model_.atmosphere().parameters(), nm, solar);
  const std::array<double, 3> unit{1.0, 1.0, 1.0};
  channels_ = atmosphere::make_spectral(model_.atmosphere().parameters(), kSurfaceChannelNm, unit);
}

Vec3 NishitaSampler::position(double altitude_m) const {
  return {0.0, 0.0, model_.atmosphere().parameters().ground_radius_m + altitude_m};
}

Rgb NishitaSampler::to_rgb(const std::array<double, kNishitaXyzCount>& r) const {
  Xyz c{0, 0, 0};
  for (int k = 0; k < kNishitaXyzCount; ++k) {
    c.X += cmf_[k].x * r[k];
    c.Y += cmf_[k].y * r[k];
    c.Z += cmf_[k].z * r[k];
  }
  const double f = kMaxLuminousEfficacy * kNishitaXyzStep;
  return xyz_to_linear_srgb({c.X * f, c.Y * f, c.Z * f});
}

Rgb NishitaSampler::aerial_perspective(double altitude_m, Vec3 view, double distance_m,
                                       double albedo, Vec3 sun) const {
  std::array<double, kNishitaXyzCount> a{}, r{};
  a.fill(albedo);
  model_.atmosphere().aerial_perspective(position(altitude_m), view, distance_m, a, sun, spectral_,
                                         r);
  return to_rgb(r);
}

Rgb NishitaSampler::reflected(double altitude_m, Vec3 view, double distance_m, double albedo,
                              Vec3 sun) const {
  std::array<double, kNishitaXyzCount> a{}, with{}, without{};
  a.fill(albedo);
  const Vec3 p = position(altitude_m);
  model_.atmosphere().aerial_perspective(p, view, distance_m, a, sun, spectral_, with);
  a.fill(0.0);
  model_.atmosphere().aerial_perspective(p, view, distance_m, a, sun, spectral_, without);
  for (int k = 0; k < kNishitaXyzCount; ++k) with[k] -= without[k];
  return to_rgb(with);
}

std::array<double, 3> NishitaSampler::channel_transmittance(double altitude_m, Vec3 view,
                                                            double distance_m) const {
  std::array<double, 3> t{};
  model_.atmosphere().transmittance(position(altitude_m), view, distance_m, channels_, t);
  return t;
}

// NishitaModel::tristimulus at another observer and sun: the same sum as nishita.cpp's to_xyz.
Rgb NishitaSampler::rgb(double altitude_m, Vec3 view, Vec3 sun) const {
  std::array<double, kNishitaXyzCount> r{};
  model_.atmosphere().single_scattering(position(altitude_m), view, sun, spectral_, r);
  return to_rgb(r);
}

EstimationPolicy aerosol_estimation(std::string name) {
  // The grid: clean to very hazy air, grey to fine aerosols, the usual range of g.
  return registry_estimation(
      std::move(name),
      {{.parameter = "aerosol-optical-depth",
        .label = "aerosol optical depth (550 nm)",
        .min = 0.0,
        .max = 1.0,
        .grid_points = 6},
       {.parameter = "angstrom-exponent",
        .label = "Angstrom exponent",
        .min = 0.0,
        .max = 2.5,
        .grid_points = 3},
       {.parameter = "mie-g",
        .label = "Mie asymmetry g",
        .min = 0.5,
        .max = 0.95,
        .grid_points = 3}},
      "aerosol optical depth at 550 nm, Angstrom exponent and Mie g, free luminance scale");
}

ModelInfo NishitaModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "Physically based single scattering (Nishita et al. 1993) in a spherical planet's "
          "exponential Rayleigh + Mie atmosphere (optional ozone layer), fast path with Pietras' "
          "optical-length tables; "
          "Earth defaults, any observer altitude (ground to orbit), planet shadow at twilight",
      .output =
          "XYZ with Y [cd/m^2] for the ASTM G-173 extraterrestrial sun (20 nm bins 380-780 nm); "
          "spectral radiance [W m^-2 sr^-1 nm^-1] 360-830 nm; with --solar-irradiance E both per "
          "flat irradiance E [W m^-2 nm^-1] (E = 1: sr^-1); in-scattered light only, the ground "
          "reflects only with an explicit --albedo; no solar disc",
      .parameters = NishitaParameters::schema().specs(),
      .domain =
          "any observer altitude 0-10000 km, any view direction, sun at any elevation (below the "
          "horizon: single scattering with the planet's shadow, flagged extrapolated); fast path "
          "within 0.5 % of the brute-force reference (tested)",
      .spectral = true,
      .make = model_factory<NishitaModel, NishitaParameters>(),
      .neural = NeuralPolicy{},
      .estimation = aerosol_estimation(std::string(kName)),
      .sh_fit = ShFitPolicy{},
      .report = ReportPolicy{.title = "Nishita (Earth defaults)",
                             .colour = "#2ca02c",
                             .physical_atmosphere = true},
      .no_gpu =
          "its fast path integrates every view ray with Pietras' optical-length tables; "
          "that integral is not written as a shader (hillaire and bruneton draw their "
          "whole-sky LUT)",
      // The brute-force single scattering (no tables), deterministic.
      .reference =
          [](const SkyModel& m, Vec3 view, const EvaluationOptions& o, const ReferenceRequest&) {
            const auto& n = static_cast<const NishitaModel&>(m);
            const std::vector<double> nm = n.reference_wavelengths(o);
            const auto spec = n.spectral_at(nm);
            std::vector<double> r(nm.size()), se(nm.size(), 0.0);
            n.atmosphere().single_scattering_reference(n.observer(), normalize(view),
                                                       n.sun().direction(), spec, r);
            return n.reference_value(o, r, se);
          },
      .reference_description =
          "the brute-force single scattering (optical lengths by "
          "quadrature along every ray, no tables; deterministic)",
  };
}

}  // namespace skylight
