#include "skylight/models/preetham.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/spectrum.h"

namespace skylight {
namespace {

Spectrum load_spectral(std::string_view path) {
  return Spectrum::from_table(data::load_table(path, /*has_header=*/true, 2), 0, 1, path);
}

const Spectrum& ozone_table() {
  static const Spectrum t = load_spectral("preetham/preetham_ozone_k_o.csv");
  return t;
}
const Spectrum& mixed_gas_table() {
  static const Spectrum t = load_spectral("preetham/preetham_mixed_gas_k_g.csv");
  return t;
}
const Spectrum& water_table() {
  static const Spectrum t = load_spectral("preetham/preetham_water_vapour_k_wa.csv");
  return t;
}
const Spectrum& sun_table() {
  static const Spectrum t = load_spectral("preetham/preetham_sun_spectral_radiance.csv");
  return t;
}

// Perez coefficient table: rows (quantity, param, T_coefficient, constant).
struct PerezFit {
  std::array<std::array<double, 2>, 5> Y{}, x{}, y{};
};
const PerezFit& perez_fit() {
  static const PerezFit fit = [] {
    const auto t = data::load_table("preetham/preetham_perez_coefficients.csv", true, 4);
    PerezFit f;
    std::array<std::array<bool, 5>, 3> seen{};
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const std::string& q = t.text(r, 0);
      const std::string& p = t.text(r, 1);
      const int qi = q == "Y" ? 0 : q == "x" ? 1 : q == "y" ? 2 : -1;
      const int pi = (p.size() == 1 && p[0] >= 'A' && p[0] <= 'E') ? p[0] - 'A' : -1;
      if (qi < 0 || pi < 0)
        throw IoError(
            fmt::format("preetham/preetham_perez_coefficients.csv row {}: unknown "
                        "quantity/param '{}','{}'",
                        r + 2, q, p));
      auto& dst = qi == 0 ? f.Y : qi == 1 ? f.x : f.y;
      dst[pi] = {t.number(r, 2), t.number(r, 3)};
      seen[qi][pi] = true;
    }
    for (const auto& row : seen)
      for (bool s : row)
        if (!s) throw IoError("preetham/preetham_perez_coefficients.csv: missing coefficients");
    return f;
  }();
  return fit;
}

// Zenith chromaticity matrices: M_x, M_y [T power 2,1,0][theta^3, theta^2, theta, 1].
struct ChromaMatrices {
  std::array<std::array<double, 4>, 3> x{}, y{};
};
const ChromaMatrices& chroma_matrices() {
  static const ChromaMatrices m = [] {
    const auto t = data::load_table("preetham/preetham_zenith_chromaticity_matrices.csv", true, 6);
    ChromaMatrices out;
    std::array<std::array<bool, 3>, 2> seen{};
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const std::string& q = t.text(r, 0);
      const double power = t.number(r, 1);
      const int qi = q == "x_z" ? 0 : q == "y_z" ? 1 : -1;
      const int row = power == 2.0 ? 0 : power == 1.0 ? 1 : power == 0.0 ? 2 : -1;
      if (qi < 0 || row < 0)
        throw IoError(
            fmt::format("preetham/preetham_zenith_chromaticity_matrices.csv row {}: "
                        "unknown quantity '{}' or T power",
                        r + 2, q));
      auto& dst = qi == 0 ? out.x : out.y;
      for (int k = 0; k < 4; ++k) dst[row][k] = t.number(r, 2 + k);
      seen[qi][row] = true;
    }
    for (const auto& q : seen)
      for (bool s : q)
        if (!s) throw IoError("preetham/preetham_zenith_chromaticity_matrices.csv: missing rows");
    return out;
  }();
  return m;
}

PerezCoefficients from_fit(const std::array<std::array<double, 2>, 5>& fit, double T) {
  return {fit[0][0] * T + fit[0][1], fit[1][0] * T + fit[1][1], fit[2][0] * T + fit[2][1],
          fit[3][0] * T + fit[3][1], fit[4][0] * T + fit[4][1], 1.0};
}

double chroma(const std::array<std::array<double, 4>, 3>& m, double T, double ts) {
  const std::array<double, 3> tp{T * T, T, 1.0};
  const std::array<double, 4> sp{ts * ts * ts, ts * ts, ts, 1.0};
  double v = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) v += tp[i] * m[i][j] * sp[j];
  return v;
}

// Sun-table wavelengths used to integrate the solar disc's XYZ: 5 nm steps over 380-750 nm.
constexpr double kSunIntegrationStepNm = 5.0;

}  // namespace

PreethamPerez preetham_perez_coefficients(double T) {
  const PerezFit& f = perez_fit();
  return {from_fit(f.Y, T), from_fit(f.x, T), from_fit(f.y, T)};
}

double preetham_chi(double T, double sun_zenith) {
  return (4.0 / 9.0 - T / 120.0) * (kPi - 2.0 * sun_zenith);
}

double preetham_zenith_luminance(double T, double sun_zenith) {
  const double chi = preetham_chi(T, sun_zenith);
  return 1000.0 * ((4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192);
}

Chromaticity preetham_zenith_chromaticity(double T, double sun_zenith) {
  const ChromaMatrices& m = chroma_matrices();
  return {chroma(m.x, T, sun_zenith), chroma(m.y, T, sun_zenith)};
}

double relative_optical_mass(double sun_zenith) {
  const double deg = std::min(rad_to_deg(sun_zenith), 90.0);
  return 1.0 / (std::cos(deg_to_rad(deg)) + 0.15 * std::pow(93.885 - deg, -1.253));
}

PreethamAerosol preetham_aerosol(double turbidity) {
  return {0.04608 * turbidity - 0.04586, 1.3};
}

double PreethamAerosol::optical_depth(double nm) const {
  return beta * std::pow(nm / 1000.0, -alpha);
}

SolarTransmittance preetham_solar_transmittance(double sun_zenith, double T, double nm) {
  const double m = relative_optical_mass(sun_zenith);
  const double um = nm / 1000.0;  // the appendix's formulas take lambda in micrometres
  SolarTransmittance t;
  t.rayleigh = std::exp(-0.008735 * std::pow(um, -4.08) * m);
  t.aerosol = std::exp(-preetham_aerosol(T).optical_depth(nm) * m);
  const double ozone_cm = 0.35;
  t.ozone = std::exp(-ozone_table()(nm) * ozone_cm * m);
  const double kg = mixed_gas_table()(nm);
  t.mixed_gas = std::exp(-1.41 * kg * m / std::pow(1.0 + 118.93 * kg * m, 0.45));
  const double water_cm = 2.0;
  const double kwa = water_table()(nm);
  t.water =
      std::exp(-0.2385 * kwa * water_cm * m / std::pow(1.0 + 20.07 * kwa * water_cm * m, 0.45));
  return t;
}

std::optional<double> extraterrestrial_sun_radiance(double nm) {
  if (!(nm >= kPreethamSunMinNm && nm <= kPreethamSunMaxNm)) return std::nullopt;
  return sun_table()(nm);
}

const ParameterSchema<PreethamParameters>& PreethamParameters::schema() {
  static const auto s = [] {
    ParameterSchema<PreethamParameters> s;
    s.number(&PreethamParameters::turbidity,
             {.name = "turbidity",
              .unit = "1",
              .min = kPreethamTurbidityMin,
              .max = kPreethamTurbidityMax,
              .default_value = ParameterValue(PreethamParameters{}.turbidity),
              .description = "atmospheric turbidity T (fitted for 2-6)"});
    return s;
  }();
  return s;
}

PreethamModel::PreethamModel(const PreethamParameters& p) : SkyModel(p.sun), params_(p) {
  PreethamParameters::schema().validate(p, model_context(kName));
  const double T = p.turbidity;
  const double ts = p.sun.zenith;
  sun_up_ = ts <= 0.5 * kPi;
  // Below the horizon the closed forms are evaluated at the horizon for reporting only.
  const double ts_eval = std::min(ts, 0.5 * kPi);
  zenith_luminance_ = preetham_zenith_luminance(T, ts_eval);
  zenith_xy_ = preetham_zenith_chromaticity(T, ts_eval);
  const PreethamPerez c = preetham_perez_coefficients(T);
  distribution_.mode = PerezDistribution::Mode::xyY;
  distribution_.coefficients = {c.Y, c.x, c.y};
  distribution_.sun = p.sun.direction();
  // Y = Yz F(theta, gamma) / F(0, theta_s) (Zotti eq. 3): at the zenith gamma = theta_s.
  const double fY0 = perez_function(c.Y, 1.0, ts_eval);
  const double fx0 = perez_function(c.x, 1.0, ts_eval);
  const double fy0 = perez_function(c.y, 1.0, ts_eval);
  const bool usable = sun_up_ && zenith_luminance_ > 0.0 && std::abs(fY0) > 0.0 &&
                      std::abs(fx0) > 0.0 && std::abs(fy0) > 0.0;
  distribution_.scale = usable ? std::array<double, 3>{zenith_luminance_ / fY0, zenith_xy_.x / fx0,
                                                       zenith_xy_.y / fy0}
                               : std::array<double, 3>{0.0, 0.0, 0.0};
  // The solar disc: XYZ of the attenuated spectrum (uniform over the disc).
  if (sun_up_) {
    std::vector<double> nm, L;
    for (double l = kPreethamSunMinNm; l <= kPreethamSunMaxNm + 1e-9; l += kSunIntegrationStepNm) {
      nm.push_back(l);
      L.push_back(*extraterrestrial_sun_radiance(l) *
                  preetham_solar_transmittance(ts, T, l).total());
    }
    sun_xyz_ = spectral_radiance_to_xyz(nm, L);
  }
}

Xyz PreethamModel::tristimulus(Vec3 view) const {
  return distribution_.evaluate(view);
}

void PreethamModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  distribution_.evaluate_batch(dirs, out);
}

std::optional<double> PreethamModel::spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= 300.0 && nm <= 830.0)) return std::nullopt;
  const Xyz c = tristimulus(view);
  if (!(c.Y > 0.0)) return 0.0;
  // L(lambda) = Y / (K_m integral S y-bar) S(lambda): the daylight spectrum with the sky's
  // chromaticity, scaled to the sky's luminance.
  const DaylightSpectrum s(chromaticity(c));
  const auto& I = daylight_basis_ybar_integrals();
  const double norm = I[0] + s.m1() * I[1] + s.m2() * I[2];
  if (!(std::abs(norm) > 0.0)) return 0.0;
  // Far from the daylight locus (low sun, high or low T) S0 + M1 S1 + M2 S2 goes negative at
  // short wavelengths: returned as 0 and reported by domain() (`spectral_radiance`).
  return std::max(c.Y / (kMaxLuminousEfficacy * norm) * s(nm), 0.0);
}

PreethamModel::NegativeSpectrum PreethamModel::most_negative_spectrum() const {
  NegativeSpectrum worst;
  if (!sun_up_) return worst;
  // Probe grid: every 5 deg in zenith (0-90) and 10 deg in azimuth, every 10 nm of 300-830 nm.
  const auto& I = daylight_basis_ybar_integrals();
  for (int it = 0; it <= 18; ++it) {
    for (int ip = 0; ip < 36; ++ip) {
      const Vec3 v = direction_from_angles(it * 5.0 * kDegree, ip * 10.0 * kDegree);
      const Xyz c = tristimulus(v);
      if (!(c.Y > 0.0)) continue;
      const DaylightSpectrum s(chromaticity(c));
      const double norm = I[0] + s.m1() * I[1] + s.m2() * I[2];
      if (!(std::abs(norm) > 0.0)) continue;
      for (double nm = 300.0; nm <= 830.0; nm += 10.0) {
        const double L = c.Y / (kMaxLuminousEfficacy * norm) * s(nm);
        if (L < worst.radiance) worst = {L, nm, v};
      }
    }
  }
  return worst;
}

// The part of the disc below the horizon is hidden by the ground: 0 there (view.z < 0).
bool PreethamModel::in_disc(Vec3 view) const {
  return sun_up_ && view.z >= 0.0 &&
         angle_between(view, sun().direction()) <= kPreethamSunAngularRadius;
}

Xyz PreethamModel::sun_tristimulus(Vec3 view) const {
  return in_disc(view) ? sun_xyz_ : Xyz{};
}

std::optional<double> PreethamModel::sun_spectral_radiance(Vec3 view, double nm) const {
  const auto e = extraterrestrial_sun_radiance(nm);
  if (!e) return std::nullopt;
  if (!in_disc(view)) return 0.0;
  return *e * preetham_solar_transmittance(sun().zenith, params_.turbidity, nm).total();
}

ParameterValues PreethamModel::parameter_values() const {
  return PreethamParameters::schema().values_of(params_);
}

Domain PreethamModel::domain() const {
  Domain d = sun_below_horizon(Validity::undefined, "the Preetham model has no twilight; sky is 0");
  const double T = params_.turbidity;
  if (!sun_up_) return d;
  if (T < kPreethamUsableTurbidityMin || T > kPreethamUsableTurbidityMax) {
    d.issues.push_back({"turbidity", Validity::unphysical,
                        fmt::format("T = {} is outside [{}, {}], where Zotti et al. 2007 show the "
                                    "model breaks down",
                                    T, kPreethamUsableTurbidityMin, kPreethamUsableTurbidityMax)});
  } else if (T < kPreethamFittedTurbidityMin || T > kPreethamFittedTurbidityMax) {
    d.issues.push_back({"turbidity", Validity::extrapolated,
                        fmt::format("T = {} is outside the fitted range [{}, {}]", T,
                                    kPreethamFittedTurbidityMin, kPreethamFittedTurbidityMax)});
  }
  if (const NegativeSpectrum n = most_negative_spectrum(); n.radiance < 0.0) {
    d.issues.push_back(
        {"spectral_radiance", Validity::unphysical,
         fmt::format("the CIE daylight basis at the sky's chromaticity gives negative spectral "
                     "radiance (down to {:.3g} W m^-2 sr^-1 nm^-1 at {:g} nm, view zenith {:.0f} "
                     "deg); returned as 0",
                     n.radiance, n.nm, rad_to_deg(std::acos(clamp_cosine(n.view.z)))),
         /*spectral_only=*/true});
  }
  if (zenith_luminance_ < 0.0) {
    d.issues.push_back({"zenith_luminance", Validity::unphysical,
                        fmt::format("zenith luminance Yz = {:.6g} cd/m^2 is negative (Zotti et al. "
                                    "2007 Fig. 1); the sky is returned as 0",
                                    zenith_luminance_)});
  }
  return d;
}

double preetham_log_relative_luminance(double turbidity, Vec3 view, const SunPosition& sun) {
  const PerezCoefficients c = preetham_perez_coefficients(turbidity).Y;
  return std::log(perez_function(c, view.z, angle_between(view, sun.direction()))) -
         std::log(perez_function(c, 1.0, sun.zenith));
}

namespace {

// The photo fit's ln L: ln f(T) of preetham_log_relative_luminance, the views' cos theta and
// gamma computed once per fit.
EstimationPolicy::LogLuminance prepare_relative_luminance(const SunPosition& sun,
                                                          std::span<const Vec3> views) {
  auto cos_theta = std::make_shared<std::vector<double>>();
  auto gamma = std::make_shared<std::vector<double>>();
  const Vec3 s = sun.direction();
  for (const Vec3& v : views) {
    cos_theta->push_back(v.z);
    gamma->push_back(angle_between(v, s));
  }
  const double sun_zenith = sun.zenith;
  return [cos_theta, gamma, sun_zenith](std::span<const double> p, std::span<const std::size_t> idx,
                                        std::span<double> out) {
    const PerezCoefficients c = preetham_perez_coefficients(p[0]).Y;
    const double log_f0 = std::log(perez_function(c, 1.0, sun_zenith));
    for (std::size_t k = 0; k < idx.size(); ++k)
      out[k] = std::log(perez_function(c, (*cos_theta)[idx[k]], (*gamma)[idx[k]])) - log_f0;
  };
}

}  // namespace

ModelInfo PreethamModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "Preetham, Shirley & Smits 1999 analytic daylight: luminance, chromaticity, spectral, "
          "sun",
      .output =
          "XYZ with Y [cd/m^2]; spectral radiance [W m^-2 sr^-1 nm^-1] 300-830 nm via the CIE "
          "daylight basis; sun disc 380-750 nm",
      .parameters = PreethamParameters::schema().specs(),
      .domain =
          "fitted for turbidity 2-6; unusable below 1.9 and above 10 (Zotti et al. 2007); the "
          "zenith luminance formula is negative (Zotti Fig. 1) for T < 1.12 with a high sun "
          "(T = 1: sun zenith < 12.9 deg) and T > 11.2 with the sun at the horizon: returned as 0, "
          "flagged unphysical; sun below the horizon: 0 (undefined)",
      .spectral = true,
      .sun = true,
      .make = model_factory<PreethamModel, PreethamParameters>(),
      // the paper's Preetham protocol: T = 2..6 (validation 2.5..5.5), rgb() in kcd/m^2; every
      // network within 12 % at the 95th percentile on the held-out grid (docs/NN.md)
      .neural = NeuralPolicy::over_turbidity(2.0, 6.0).bounded(0.12),
      // Morales et al. 2017 §3.4, eq. 8 with a free scale instead of a reference pixel: 38 scan
      // points (a step of ~0.5 in T).
      .estimation =
          EstimationPolicy{
              .method = EstimationPolicy::Method::profile_scan,
              .axes = {{.parameter = "turbidity",
                        .label = "turbidity",
                        .min = kPreethamFitTurbidityMin,
                        .max = kPreethamFitTurbidityMax,
                        .grid_points = 38}},
              .prepare = prepare_relative_luminance,
              .description = "turbidity, Morales et al. 2017 eq. 8 with a free luminance scale",
              .is_default = true},
      // Habel 2008 §2.2: the Preetham fit covers T in [2.5, 6].
      .sh_fit = ShFitPolicy{.parameter = "turbidity", .range = std::array<double, 2>{2.5, 6.0}},
      .bench = BenchPolicy{.by_default = true},
      .report =
          ReportPolicy{
              .title = "Preetham", .axis = "turbidity", .axis_label = "T = ", .colour = "#000000"},
  };
}

std::optional<GpuSky> PreethamModel::gpu_sky() const {
  GpuSky g = distribution_.gpu_sky();
  g.comment = fmt::format("preetham, T = {}: {}", params_.turbidity, g.comment);
  return g;
}

}  // namespace skylight
