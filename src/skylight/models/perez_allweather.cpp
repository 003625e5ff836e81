#include "skylight/models/perez_allweather.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/parameters.h"

namespace skylight {
namespace {

// Perez, Seals & Michalsky 1993, Table 1: per clearness bin, x1..x4 of a, b, c, d, e in
// x = x1 + x2 Z + Delta (x3 + x4 Z) (eq. 6; bin 1's c and d: eqs. 7, 8). The same values are in
// Radiance's gendaylit.c and gendaymtx.c.
constexpr double kAllWeather[8][5][4] = {
    {{1.3525, -0.2576, -0.2690, -1.4366},
     {-0.7670, 0.0007, 1.2734, -0.1233},
     {2.8000, 0.6004, 1.2375, 1.0000},
     {1.8734, 0.6297, 0.9738, 0.2809},
     {0.0356, -0.1246, -0.5718, 0.9938}},
    {{-1.2219, -0.7730, 1.4148, 1.1016},
     {-0.2054, 0.0367, -3.9128, 0.9156},
     {6.9750, 0.1774, 6.4477, -0.1239},
     {-1.5798, -0.5081, -1.7812, 0.1080},
     {0.2624, 0.0672, -0.2190, -0.4285}},
    {{-1.1000, -0.2515, 0.8952, 0.0156},
     {0.2782, -0.1812, -4.5000, 1.1766},
     {24.7219, -13.0812, -37.7000, 34.8438},
     {-5.0000, 1.5218, 3.9229, -2.6204},
     {-0.0156, 0.1597, 0.4199, -0.5562}},
    {{-0.5484, -0.6654, -0.2672, 0.7117},
     {0.7234, -0.6219, -5.6812, 2.6297},
     {33.3389, -18.3000, -62.2500, 52.0781},
     {-3.5000, 0.0016, 1.1477, 0.1062},
     {0.4659, -0.3296, -0.0876, -0.0329}},
    {{-0.6000, -0.3566, -2.5000, 2.3250},
     {0.2937, 0.0496, -5.6812, 1.8415},
     {21.0000, -4.7656, -21.5906, 7.2492},
     {-3.5000, -0.1554, 1.4062, 0.3988},
     {0.0032, 0.0766, -0.0656, -0.1294}},
    {{-1.0156, -0.3670, 1.0078, 1.4051},
     {0.2875, -0.5328, -3.8500, 3.3750},
     {14.0000, -0.9999, -7.1406, 7.5469},
     {-3.4000, -0.1078, -1.0750, 1.5702},
     {-0.0672, 0.4016, 0.3017, -0.4844}},
    {{-1.0000, 0.0211, 0.5025, -0.5119},
     {-0.3000, 0.1922, 0.7023, -1.6317},
     {19.0000, -5.0000, 1.2438, -1.9094},
     {-4.0000, 0.0250, 0.3844, 0.2656},
     {1.0468, -0.3788, -2.4517, 1.4656}},
    {{-1.0500, 0.0289, 0.4260, 0.3590},
     {-0.3250, 0.1156, 0.7781, 0.0025},
     {31.0625, -14.5000, -46.1148, 55.3750},
     {-7.2312, 0.4050, 13.3500, 0.6234},
     {1.5000, -0.6426, 1.8564, 0.5636}},
};

// Perez et al. 1990, Table 4: a, b, c, d per bin of the global (eq. 6), diffuse (eq. 7) and
// direct (eq. 8) luminous efficacies [lm/W] and of the zenith luminance (eq. 10: a, c, c', d).
constexpr double kGlobalEfficacy[8][4] = {
    {96.63, -0.47, 11.50, -9.16}, {107.54, 0.79, 1.79, -1.19}, {98.73, 0.70, 4.40, -6.95},
    {92.72, 0.56, 8.36, -8.31},   {86.73, 0.98, 7.10, -10.94}, {88.34, 1.39, 6.06, -7.60},
    {78.63, 1.47, 4.93, -11.37},  {99.65, 1.86, -4.46, -3.15}};
constexpr double kDiffuseEfficacy[8][4] = {
    {97.24, -0.46, 12.00, -8.91},   {107.22, 1.15, 0.59, -3.95},    {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90}, {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03}, {152.23, 0.35, -45.27, -7.98}};
constexpr double kDirectEfficacy[8][4] = {
    {57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},  {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56}, {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29}};
constexpr double kZenithLuminance[8][4] = {
    {40.86, 26.77, -29.59, -45.75}, {26.58, 14.73, 58.46, -21.25},   {19.34, 2.28, 100.00, 0.25},
    {13.25, -1.39, 124.79, 15.66},  {14.47, -5.09, 160.09, 9.13},    {19.76, -3.88, 154.61, -19.21},
    {28.39, -9.67, 151.58, -69.39}, {42.91, -19.62, 130.80, -164.08}};

// gendaylit's normalisation points (its defangle table): rows at view zenith 84, 72, ..., 12 deg
// with 30, 30, 24, 24, 18, 12 points at azimuths from the sun's in equal steps from 0, and the
// zenith; an equal-weight sum of lv cos(theta) times 2 pi / 145.
constexpr int kRadianceRows = 8;
constexpr double kRadianceRowZenithDeg[kRadianceRows] = {84, 72, 60, 48, 36, 24, 12, 0};
constexpr int kRadianceRowPoints[kRadianceRows] = {30, 30, 24, 24, 18, 12, 6, 1};
constexpr int kRadiancePoints = 145;
// The papers' normalisation: a midpoint rule in view zenith (exact cos-weighted ring areas) and
// in azimuth from the sun's (the sky is symmetric about the sun's vertical), fine enough that the
// quadrature's error is far below the 0.5 % bound of docs/DAYLIGHT.md
// (PerezAllWeather.ThePapersQuadratureHasConverged).
constexpr int kIntegralRings = 360;
constexpr int kIntegralSectors = 360;

int bin_index(int bin) {
  if (bin < 1 || bin > 8)
    throw InvalidArgument(fmt::format("Perez clearness bin {} is outside 1..8", bin));
  return bin - 1;
}

double table_value(double v, PerezCompat compat) {
  return compat == PerezCompat::radiance ? static_cast<double>(static_cast<float>(v)) : v;
}

// cos(gamma) between a view at zenith angle theta and azimuth phi from the sun's, and a sun at
// zenith angle z.
double cos_gamma(double z, double theta, double phi) {
  return std::clamp(std::cos(z) * std::cos(theta) + std::sin(z) * std::sin(theta) * std::cos(phi),
                    -1.0, 1.0);
}

double papers_integral(const std::array<double, 5>& abcde, double z) {
  const double dtheta = 0.5 * kPi / kIntegralRings, dphi = kPi / kIntegralSectors;
  double sum = 0.0;
  for (int i = 0; i < kIntegralRings; ++i) {
    const double t0 = i * dtheta, t1 = t0 + dtheta, theta = t0 + 0.5 * dtheta;
    // The ring's integral of cos(theta) d(omega) per radian of azimuth.
    const double ring = 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0));
    // The model evaluates the gradation with cos(theta) at least kPerezMinCosTheta.
    const double theta_eval = std::min(theta, std::acos(0.01));
    double row = 0.0;
    for (int j = 0; j < kIntegralSectors; ++j) {
      const double gamma = std::acos(cos_gamma(z, theta, (j + 0.5) * dphi));
      row += std::max(0.0, allweather_relative_luminance(abcde, theta_eval, gamma));
    }
    sum += row * ring * dphi;
  }
  return 2.0 * sum;
}

double radiance_integral(const std::array<double, 5>& abcde, double z) {
  double sum = 0.0;
  for (int r = 0; r < kRadianceRows; ++r) {
    const double theta = deg_to_rad(kRadianceRowZenithDeg[r]);
    for (int j = 0; j < kRadianceRowPoints[r]; ++j) {
      const double phi = deg_to_rad(360.0 / kRadianceRowPoints[r] * j);
      const double c =
          std::cos(z) * std::cos(theta) + std::sin(z) * std::sin(theta) * std::cos(phi);
      const double gamma = c > 1.0 ? 0.0 : std::acos(c);
      // gendaylit keeps each value in single precision.
      sum += static_cast<double>(
                 static_cast<float>(allweather_relative_luminance(abcde, theta, gamma))) *
             std::cos(theta);
    }
  }
  return sum * 2.0 * kPi / kRadiancePoints;
}

}  // namespace

double eccentricity_correction(int day_of_year) {
  const double g = 2.0 * kPi * (day_of_year - 1) / 365.0;
  return 1.00011 + 0.034221 * std::cos(g) + 0.00128 * std::sin(g) + 0.000719 * std::cos(2.0 * g) +
         0.000077 * std::sin(2.0 * g);
}

double kasten_air_mass(double zenith) {
  const double z_deg = std::min(rad_to_deg(zenith), 90.0);
  return 1.0 / (std::cos(deg_to_rad(z_deg)) + 0.15 * std::pow(93.885 - z_deg, -1.253));
}

double precipitable_water_from_dew_point(double dew_point_c) {
  return std::exp(0.07 * dew_point_c - 0.075);
}

double sky_clearness(double dhi, double dni, double zenith) {
  const double k = kPerezClearnessKappa * zenith * zenith * zenith;
  return ((dhi + dni) / dhi + k) / (1.0 + k);
}

int clearness_bin(double epsilon) {
  int bin = 1;
  for (int i = 1; i < 8; ++i)
    if (epsilon >= kPerezClearnessBinLower[i]) bin = i + 1;
  return bin;
}

std::array<double, 5> allweather_coefficients(int bin, double zenith, double delta,
                                              PerezCompat compat) {
  const auto& t = kAllWeather[bin_index(bin)];
  auto x = [&](int k, int i) { return table_value(t[k][i], compat); };
  std::array<double, 5> out{};
  for (int k = 0; k < 5; ++k)
    out[k] = x(k, 0) + x(k, 1) * zenith + delta * (x(k, 2) + x(k, 3) * zenith);
  if (bin == 1) {  // eqs. 7 and 8
    out[2] = std::exp(std::pow(delta * (x(2, 0) + x(2, 1) * zenith), x(2, 2))) - x(2, 3);
    out[3] = -std::exp(delta * (x(3, 0) + x(3, 1) * zenith)) + x(3, 2) + delta * x(3, 3);
  }
  return out;
}

double allweather_relative_luminance(const std::array<double, 5>& c, double theta, double gamma) {
  const double cg = std::cos(gamma);
  return (1.0 + c[0] * std::exp(c[1] / std::cos(theta))) *
         (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * cg * cg);
}

double allweather_sky_integral(const std::array<double, 5>& abcde, double zenith,
                               PerezCompat compat) {
  return compat == PerezCompat::radiance ? radiance_integral(abcde, zenith)
                                         : papers_integral(abcde, zenith);
}

double global_luminous_efficacy(int bin, double w, double zenith, double delta) {
  const auto& k = kGlobalEfficacy[bin_index(bin)];
  return k[0] + k[1] * w + k[2] * std::cos(zenith) + k[3] * std::log(delta);
}

double diffuse_luminous_efficacy(int bin, double w, double zenith, double delta) {
  const auto& k = kDiffuseEfficacy[bin_index(bin)];
  return k[0] + k[1] * w + k[2] * std::cos(zenith) + k[3] * std::log(delta);
}

double direct_luminous_efficacy(int bin, double w, double zenith, double delta) {
  const auto& k = kDirectEfficacy[bin_index(bin)];
  return std::max(0.0, k[0] + k[1] * w + k[2] * std::exp(5.73 * zenith - 5.0) + k[3] * delta);
}

double zenith_luminance_model(int bin, double dhi, double zenith, double delta) {
  const auto& k = kZenithLuminance[bin_index(bin)];
  return dhi * (k[0] + k[1] * std::cos(zenith) + k[2] * std::exp(-3.0 * zenith) + k[3] * delta);
}

namespace {

// Notes are appended from views (GCC 12 warns falsely about string literals moved into a
// vector<string> here).
void note(PerezSky& s, std::string_view why) {
  s.notes.emplace_back(why);
}

// The sky made dark, with the reason among its notes.
PerezSky dark(PerezSky& s, std::string_view why) {
  s.dark = true;
  note(s, why);
  return s;
}

// Refuses an input without either irradiance or illuminance, with only half of a pair, or with a
// day of the year outside [1, 366].
void check_input(const PerezIrradianceInput& in, bool irradiance, bool illuminance) {
  if (irradiance == illuminance)
    throw InvalidArgument(fmt::format("the Perez sky needs either {} and {} or {} and {}, not {}",
                                      spelled("dni"), spelled("dhi"), spelled("dni-illuminance"),
                                      spelled("dhi-illuminance"), irradiance ? "both" : "neither"));
  if (irradiance && !(in.dni_w_m2 && in.dhi_w_m2))
    throw InvalidArgument(
        fmt::format("{} and {} go together: give both", spelled("dni"), spelled("dhi")));
  if (illuminance && !(in.dni_lux && in.dhi_lux))
    throw InvalidArgument(fmt::format("{} and {} go together: give both",
                                      spelled("dni-illuminance"), spelled("dhi-illuminance")));
  if (in.day_of_year < 1 || in.day_of_year > 366)
    throw InvalidArgument(
        fmt::format("{} = {} is outside [1, 366]", spelled("day-of-year"), in.day_of_year));
}

// The air's water (eq. 3): given, from the dew point (Radiance's mode: gendaylit's default
// outside [-40, 40] degC), or the default.
void set_precipitable_water(const PerezIrradianceInput& in, bool radiance, PerezSky& s) {
  if (in.precipitable_water_cm) {
    s.precipitable_water_cm = *in.precipitable_water_cm;
  } else if (in.dew_point_c) {
    double td = *in.dew_point_c;
    if (radiance && (td < -40.0 || td > 40.0)) {
      note(s, fmt::format(
                  "dew point {:g} degC outside gendaylit's [-40, 40]: its default {:g} degC used",
                  td, kRadianceDefaultDewPointC));
      td = kRadianceDefaultDewPointC;
    }
    s.precipitable_water_cm = precipitable_water_from_dew_point(td);
  } else {
    s.precipitable_water_cm = radiance
                                  ? precipitable_water_from_dew_point(kRadianceDefaultDewPointC)
                                  : kDefaultPrecipitableWaterCm;
  }
}

// Radiance's mode: epsilon and delta within gendaylit's limits (with `say`, a note when they
// change).
void clamp_parameters(PerezSky& s, bool radiance, bool say) {
  if (!radiance) return;
  const double e0 = s.epsilon, d0 = s.delta;
  if (s.epsilon < 1.0) s.epsilon = 1.0;
  if (s.epsilon > kRadianceClearnessMax) s.epsilon = kRadianceClearnessMax - 0.001;
  s.delta = std::clamp(s.delta, kRadianceBrightnessMin, kRadianceBrightnessMax);
  if (say && (e0 != s.epsilon || d0 != s.delta))
    note(s, fmt::format(
                "epsilon {:.6g} and delta {:.6g} clamped to {:.6g} and {:.6g} (gendaylit's limits "
                "[1, 12.01) and [0.01, 0.6])",
                e0, d0, s.epsilon, s.delta));
}

// Delta and epsilon from the sky's irradiance (i0: the extraterrestrial irradiance).
void parameters_from_irradiance(PerezSky& s, double i0, double zenith) {
  s.delta = s.dhi_w_m2 * s.air_mass / i0;
  s.epsilon = s.dhi_w_m2 > 0.0 ? sky_clearness(s.dhi_w_m2, s.dni_w_m2, zenith) : HUGE_VAL;
}

// The sky from irradiance: its parameters, efficacies and illuminance; why the sky is dark, if it
// is.
std::optional<std::string_view> sky_from_irradiance(const PerezIrradianceInput& in, bool radiance,
                                                    double i0, double w, double zenith,
                                                    PerezSky& s) {
  s.dni_w_m2 = *in.dni_w_m2;
  s.dhi_w_m2 = *in.dhi_w_m2;
  if (radiance) {
    if (s.dni_w_m2 + s.dhi_w_m2 == 0.0)
      return "zero irradiance with the sun above the horizon (gendaylit: error sky)";
    if (s.dni_w_m2 > kSolarConstantWm2)
      return "direct irradiance exceeds the solar constant (gendaylit: error sky)";
  } else {
    if (s.dni_w_m2 > i0)
      throw InvalidArgument(fmt::format(
          "{} = {:g} W/m^2 exceeds the extraterrestrial irradiance {:.1f} W/m^2 of day {}",
          spelled("dni"), s.dni_w_m2, i0, in.day_of_year));
    if (s.dhi_w_m2 > i0)
      throw InvalidArgument(fmt::format(
          "{} = {:g} W/m^2 exceeds the extraterrestrial irradiance {:.1f} W/m^2 of day {}",
          spelled("dhi"), s.dhi_w_m2, i0, in.day_of_year));
    if (s.dhi_w_m2 == 0.0) return "no diffuse light (dhi = 0): sky is 0";
  }
  parameters_from_irradiance(s, i0, zenith);
  clamp_parameters(s, radiance, true);
  s.bin = clearness_bin(s.epsilon);
  s.diffuse_efficacy = diffuse_luminous_efficacy(s.bin, w, zenith, s.delta);
  s.direct_efficacy = direct_luminous_efficacy(s.bin, w, zenith, s.delta);
  s.diffuse_horizontal_lux = std::max(0.0, s.dhi_w_m2 * s.diffuse_efficacy);
  s.direct_normal_lux = s.dni_w_m2 * s.direct_efficacy;
  return std::nullopt;
}

// The sky from illuminance: its irradiance, parameters and efficacies; why the sky is dark, if it
// is.
std::optional<std::string_view> sky_from_illuminance(const PerezIrradianceInput& in, bool radiance,
                                                     double i0, double w, double zenith,
                                                     PerezSky& s) {
  s.direct_normal_lux = *in.dni_lux;
  s.diffuse_horizontal_lux = *in.dhi_lux;
  if (radiance && s.direct_normal_lux > kSolarConstantLux)
    return "direct illuminance exceeds the solar constant (gendaylit: error sky)";
  if (s.diffuse_horizontal_lux == 0.0) {
    if (radiance && s.direct_normal_lux == 0.0)
      return "zero illuminance with the sun above the horizon (gendaylit: error sky)";
    if (!radiance) return "no diffuse light (dhi-illuminance = 0): sky is 0";
  }
  // Irradiance from illuminance through the efficacies, which depend on epsilon and delta:
  // gendaylit starts at the solar constants' ratio and takes 9 steps; the papers' mode
  // iterates to the fixed point.
  s.dhi_w_m2 = s.diffuse_horizontal_lux * kSolarConstantWm2 / kSolarConstantLux;
  s.dni_w_m2 = s.direct_normal_lux * kSolarConstantWm2 / kSolarConstantLux;
  parameters_from_irradiance(s, i0, zenith);
  clamp_parameters(s, radiance, false);
  constexpr int kRadianceSteps = 9, kMaxSteps = 200;
  constexpr double kConverged = 1e-12;
  bool converged = false;
  for (int step = 0; step < (radiance ? kRadianceSteps : kMaxSteps); ++step) {
    s.bin = clearness_bin(s.epsilon);
    const double dhi =
        s.diffuse_horizontal_lux / diffuse_luminous_efficacy(s.bin, w, zenith, s.delta);
    const double eb = direct_luminous_efficacy(s.bin, w, zenith, s.delta);
    const double dni = eb < 0.1 ? 0.0 : s.direct_normal_lux / eb;
    converged = std::abs(dhi - s.dhi_w_m2) <= kConverged * dhi &&
                std::abs(dni - s.dni_w_m2) <= kConverged * std::max(dni, 1.0);
    s.dhi_w_m2 = dhi;
    s.dni_w_m2 = dni;
    parameters_from_irradiance(s, i0, zenith);
    clamp_parameters(s, radiance, false);
    if (!radiance && converged) break;
  }
  if (!radiance && !converged)
    throw InvalidArgument(fmt::format(
        "{} {:g} lx and {} {:g} lx: the irradiance from the efficacy models did not converge "
        "in {} steps",
        spelled("dni-illuminance"), s.direct_normal_lux, spelled("dhi-illuminance"),
        s.diffuse_horizontal_lux, kMaxSteps));
  if (!radiance && !(s.dhi_w_m2 > 0.0 && s.dhi_w_m2 <= i0 && s.dni_w_m2 <= i0))
    throw InvalidArgument(fmt::format(
        "{} {:g} lx and {} {:g} lx give {:.4g} and {:.4g} W/m^2 through the efficacy models, "
        "beyond the extraterrestrial {:.1f} W/m^2",
        spelled("dni-illuminance"), s.direct_normal_lux, spelled("dhi-illuminance"),
        s.diffuse_horizontal_lux, s.dni_w_m2, s.dhi_w_m2, i0));
  s.bin = clearness_bin(s.epsilon);
  s.diffuse_efficacy = s.diffuse_horizontal_lux / s.dhi_w_m2;
  s.direct_efficacy = s.dni_w_m2 > 0.0 ? s.direct_normal_lux / s.dni_w_m2 : 0.0;
  return std::nullopt;
}

}  // namespace

PerezSky perez_sky_from_irradiance(const PerezIrradianceInput& in) {
  const bool radiance = in.compat == PerezCompat::radiance;
  PerezSky s;
  s.sun = in.sun;
  const bool irradiance = in.dni_w_m2.has_value() || in.dhi_w_m2.has_value();
  const bool illuminance = in.dni_lux.has_value() || in.dhi_lux.has_value();
  check_input(in, irradiance, illuminance);

  // The air's water (eq. 3).
  set_precipitable_water(in, radiance, s);
  const double w = s.precipitable_water_cm;
  s.extraterrestrial_w_m2 = kSolarConstantWm2 * eccentricity_correction(in.day_of_year);
  const double i0 = s.extraterrestrial_w_m2;

  // The sun.
  const bool sun_up = in.sun.zenith < 0.5 * kPi;
  const double direct_given = irradiance ? *in.dni_w_m2 : *in.dni_lux;
  if (!sun_up) {
    if (direct_given > 0.0 && !radiance)
      throw InvalidArgument(fmt::format(
          "{} = {:g} with the sun {:.3g} deg below the horizon: no direct light can reach the "
          "ground",
          spelled(irradiance ? "dni" : "dni-illuminance"), direct_given,
          rad_to_deg(in.sun.zenith) - 90.0));
    return dark(s, "the sun is below the horizon: the Perez sky describes daylight; sky is 0");
  }
  double zenith = in.sun.zenith;
  if (radiance && zenith < deg_to_rad(90.0 - kRadianceMaxSunAltitudeDeg)) {
    zenith = deg_to_rad(90.0 - kRadianceMaxSunAltitudeDeg);
    s.sun.zenith = zenith;
    note(s, "sun altitude reduced to 87 deg (gendaylit: sun too close to the zenith)");
  }
  s.air_mass = kasten_air_mass(zenith);

  const std::optional<std::string_view> why_dark =
      irradiance ? sky_from_irradiance(in, radiance, i0, w, zenith, s)
                 : sky_from_illuminance(in, radiance, i0, w, zenith, s);
  if (why_dark) return dark(s, *why_dark);

  // The luminance distribution (Perez 1993) and its normalisation.
  double delta_lum = s.delta;
  if (radiance && s.epsilon > 1.065 && s.epsilon < 2.8 && delta_lum < 0.2) {
    delta_lum = 0.2;
    note(s,
         "delta raised to 0.2 in the luminance coefficients (gendaylit's correction "
         "for 1.065 < epsilon < 2.8)");
  }
  s.coefficients = allweather_coefficients(s.bin, zenith, delta_lum, in.compat);
  if (radiance && s.coefficients[1] > 0.0)
    return dark(s,
                fmt::format("positive Perez b = {:.4g} (gendaylit: error sky)", s.coefficients[1]));
  if (!in.normalise) return s;
  s.sky_integral = allweather_sky_integral(s.coefficients, zenith, in.compat);
  if (!(s.sky_integral > 0.0))
    throw InvalidArgument(fmt::format(
        "the Perez coefficients of epsilon {:.4g}, delta {:.4g} give a sky whose integral is {:g}: "
        "it cannot be normalised",
        s.epsilon, s.delta, s.sky_integral));
  s.normalisation = s.diffuse_horizontal_lux / s.sky_integral;
  // Luminance is not negative: where the fitted coefficients make lv < 0 (the zenith with a low
  // sun in some bins) the sky is 0, as the model evaluates it.
  s.zenith_luminance_cd_m2 =
      s.normalisation * std::max(0.0, allweather_relative_luminance(s.coefficients, 0.0, zenith));
  s.zenith_luminance_model_cd_m2 = zenith_luminance_model(s.bin, s.dhi_w_m2, zenith, s.delta);
  return s;
}

}  // namespace skylight
