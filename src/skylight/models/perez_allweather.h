// Perez skies from measured irradiance: the sky clearness and brightness, the luminous efficacy
// and zenith luminance models of Perez, Ineichen, Seals, Michalsky & Stewart 1990 ("Modeling
// daylight availability and irradiance components from direct and global irradiance", Solar
// Energy 44(5)), and the all-weather coefficients a..e of Perez, Seals & Michalsky 1993 (Solar
// Energy 50(3), Table 1), normalised so that the sky's integral is the diffuse horizontal
// illuminance. docs/DAYLIGHT.md gives the source of every constant and the differences between
// the default (the papers) and `compat radiance` (Radiance's gendaylit, version 2.21 of 2021).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "skylight/core/frame.h"

namespace skylight {

// The default follows the papers; `radiance` reproduces gendaylit's own choices (its clamps of
// epsilon, Delta and the sun's altitude, Delta >= 0.2 for 1.065 < epsilon < 2.8 in the luminance
// coefficients, single-precision coefficient tables, the 145-point normalisation sum, the 9-step
// illuminance inversion, and a zero sky where gendaylit prints its "error sky").
enum class PerezCompat { papers, radiance };

// Solar constant [W/m^2] of both papers' era and of gendaylit; its luminous counterpart [lx]
// (gendaylit's start of the illuminance inversion).
inline constexpr double kSolarConstantWm2 = 1367.0;
inline constexpr double kSolarConstantLux = 127500.0;
// kappa of the sky clearness (Perez 1990 eq. 1, zenith angle in radians).
inline constexpr double kPerezClearnessKappa = 1.041;
// Precipitable water [cm] when neither the dew point nor the water is given: 2 cm, what
// gendaylit's default dew point (10.97353115 degC) gives through eq. 3.
inline constexpr double kDefaultPrecipitableWaterCm = 2.0;
inline constexpr double kRadianceDefaultDewPointC = 10.97353115;
// gendaylit's limits: epsilon in [1, 12.01) (above: 12.01 - 0.001), Delta in [0.01, 0.6], the
// sun's altitude at most 87 deg.
inline constexpr double kRadianceClearnessMax = 12.01;
inline constexpr double kRadianceBrightnessMin = 0.01;
inline constexpr double kRadianceBrightnessMax = 0.6;
inline constexpr double kRadianceMaxSunAltitudeDeg = 87.0;

// The lower bounds of the 8 sky-clearness bins (Perez 1990 Table 1; bin 8 is open above).
inline constexpr std::array<double, 8> kPerezClearnessBinLower = {1.0,   1.065, 1.230, 1.500,
                                                                  1.950, 2.800, 4.500, 6.200};

// Eccentricity correction (R0/R)^2 for day of year n (1..366): Spencer's Fourier series with the
// day angle 2 pi (n - 1) / 365 (as gendaylit computes it).
double eccentricity_correction(int day_of_year);
// Relative optical air mass at solar zenith angle z [rad] (Kasten 1966; z above 90 deg taken as
// 90 deg, as gendaylit does).
double kasten_air_mass(double zenith);
// Precipitable water [cm] from the surface dew point [degC] (Perez 1990 eq. 3).
double precipitable_water_from_dew_point(double dew_point_c);
// Sky clearness epsilon (Perez 1990 eq. 1) from the diffuse horizontal and direct normal
// irradiance (any common unit, dhi > 0) and the solar zenith angle [rad].
double sky_clearness(double dhi, double dni, double zenith);
// The bin 1..8 of epsilon.
int clearness_bin(double epsilon);
// a..e of the all-weather model (Perez 1993 eqs. 6-8 with Table 1) for bin 1..8 at solar zenith
// z [rad] and brightness delta. With compat radiance the table entries are rounded to float as
// gendaylit stores them.
std::array<double, 5> allweather_coefficients(int bin, double zenith, double delta,
                                              PerezCompat compat = PerezCompat::papers);
// The relative luminance lv (Perez 1993 eq. 1) at view zenith angle theta and angle gamma from
// the sun [rad], without clamps.
double allweather_relative_luminance(const std::array<double, 5>& abcde, double theta,
                                     double gamma);
// The integral of max(lv, 0) cos(theta) over the sky [sr] for a sun at zenith z [rad]: the
// papers' mode by a midpoint rule (360 x 360 over the half sky on the sun's side, the view's
// cos(theta) floored at 0.01 as the model evaluates it); compat radiance by gendaylit's
// equal-weight sum over its 145 points (lv in single precision).
double allweather_sky_integral(const std::array<double, 5>& abcde, double zenith,
                               PerezCompat compat);
// Luminous efficacies [lm/W] (Perez 1990 eqs. 6-8, Table 4) and the zenith luminance [cd/m^2]
// (eq. 10) for bin 1..8, precipitable water w [cm], zenith z [rad], brightness delta and the
// diffuse horizontal irradiance dhi [W/m^2] (zenith luminance only). Direct efficacy is >= 0.
double global_luminous_efficacy(int bin, double w, double zenith, double delta);
double diffuse_luminous_efficacy(int bin, double w, double zenith, double delta);
double direct_luminous_efficacy(int bin, double w, double zenith, double delta);
double zenith_luminance_model(int bin, double dhi, double zenith, double delta);

// One set of inputs: the sun, either irradiance [W/m^2] or illuminance [lx] (direct normal and
// diffuse horizontal), the day of the year and the air's water.
struct PerezIrradianceInput {
  SunPosition sun;
  std::optional<double> dni_w_m2, dhi_w_m2;
  std::optional<double> dni_lux, dhi_lux;
  int day_of_year = 1;
  std::optional<double> dew_point_c;            // precipitable water from eq. 3
  std::optional<double> precipitable_water_cm;  // or given
  PerezCompat compat = PerezCompat::papers;
  // false: stop after the coefficients (sky_integral, normalisation and the zenith luminances
  // stay 0), for callers that normalise on their own samples (daylight/sky_matrix.h).
  bool normalise = true;
};

// The sky the inputs give: L(theta, gamma) = normalisation * lv(theta, gamma) [cd/m^2] above
// the horizon, with lv from `coefficients` and gamma from `sun`.
struct PerezSky {
  SunPosition sun;  // the sun the sky uses (compat radiance: at most 87 deg high)
  double epsilon = 1.0, delta = 0.0;
  int bin = 1;
  std::array<double, 5> coefficients{};  // a..e
  double air_mass = 0.0, extraterrestrial_w_m2 = 0.0, precipitable_water_cm = 0.0;
  double dni_w_m2 = 0.0, dhi_w_m2 = 0.0;                         // the irradiance used
  double direct_normal_lux = 0.0, diffuse_horizontal_lux = 0.0;  // from the efficacy models
  double diffuse_efficacy = 0.0, direct_efficacy = 0.0;          // [lm/W]
  double sky_integral = 0.0;                  // the quadrature of lv cos(theta) over the sky [sr]
  double normalisation = 0.0;                 // diffuse_horizontal_lux / sky_integral [cd/m^2]
  double zenith_luminance_cd_m2 = 0.0;        // normalisation * lv(0, sun zenith)
  double zenith_luminance_model_cd_m2 = 0.0;  // eq. 10, for comparison
  // No sky (all 0): the sun below the horizon, no diffuse light, or gendaylit's error sky.
  bool dark = false;
  // What was adjusted or why the sky is dark, one sentence each (compat radiance's clamps).
  std::vector<std::string> notes;
};

// The sky for one set of inputs. Throws InvalidArgument naming the parameter (spelled()) for
// inconsistent inputs in the default mode: both or neither of irradiance and illuminance, the
// direct normal irradiance above the extraterrestrial, the diffuse horizontal above it, direct
// light with the sun below the horizon. With compat radiance, the cases where gendaylit prints a
// zero sky give a dark sky with a note.
PerezSky perez_sky_from_irradiance(const PerezIrradianceInput& input);

}  // namespace skylight
