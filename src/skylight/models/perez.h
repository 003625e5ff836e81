// The Perez all-weather relative luminance distribution (Perez, Seals & Michalsky 1993;
// Satilmis et al. 2016 eq. 1) with user-given coefficients A..E and a given zenith luminance:
//   L(theta, gamma) = Lz F(theta, gamma) / F(0, theta_s),
//   F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma).
#pragma once

#include <array>
#include <optional>

#include "skylight/models/perez_allweather.h"
#include "skylight/models/perez_kernel.h"
#include "skylight/models/sky_model.h"

namespace skylight {

// Range accepted for each coefficient: wide enough for every published set (Perez 1993 and
// Preetham's fits stay within |value| < 10), narrow enough that F stays finite.
inline constexpr double kPerezCoefficientLimit = 50.0;
// Coefficient sets whose F factors exceed kPerezMaxFactor anywhere on the sky, or whose luminance
// exceeds kPerezMaxLuminance [cd/m^2], are refused: the float batch path multiplies the two factors
// (1e18^2 = 1e36 < FLT_MAX = 3.4e38) and outputs must stay finite.
inline constexpr double kPerezMaxFactor = 1e18;
inline constexpr double kPerezMaxLuminance = 1e30;
// Accepted irradiance [W/m^2] and illuminance [lx] inputs; the physical bounds (the
// extraterrestrial irradiance of the day) are checked by the sky (models/perez_allweather.h).
inline constexpr double kMaxIrradianceInput = 2000.0;
inline constexpr double kMaxIlluminanceInput = 250000.0;

// Parameters of the `perez` model: either the coefficients and the zenith luminance (direct use),
// or the irradiance (or illuminance) from which the all-weather sky follows
// (models/perez_allweather.h).
struct PerezParameters {
  SunPosition sun;
  // --perez A,B,C,D,E: the coefficients [1], each in [-kPerezCoefficientLimit, +limit].
  std::optional<std::array<double, 5>> coefficients;
  // --zenith-luminance: absolute zenith luminance Lz [cd/m^2], [kMinZenithLuminance, kMax...].
  std::optional<double> zenith_luminance;
  // --dni, --dhi [W/m^2] or --dni-illuminance, --dhi-illuminance [lx].
  std::optional<double> dni, dhi, dni_illuminance, dhi_illuminance;
  // --day-of-year (1..366), or the date of --time.
  std::optional<int> day_of_year;
  // --dew-point [degC] or --precipitable-water [cm] (the efficacy models' water).
  std::optional<double> dew_point, precipitable_water;
  // --compat papers|radiance.
  PerezCompat compat = PerezCompat::papers;

  // The sky is given by irradiance or illuminance (not by coefficients).
  bool from_irradiance() const { return dni || dhi || dni_illuminance || dhi_illuminance; }
  static const ParameterSchema<PerezParameters>& schema();
  // The irradiance parameters only (--dni .. --compat), for operations that make the sky from
  // measured light (`skylight daylight`).
  static const ParameterSchema<PerezParameters>& irradiance_schema();
};

// The `perez` model: luminance only; XYZ with the D65 chromaticity (0.3127, 0.3290), so rgb() is
// neutral. From irradiance, the sky is the all-weather distribution normalised to the diffuse
// horizontal illuminance (L = normalisation * lv). Views below the horizon and a sun below the
// horizon: 0. Negative F (possible with arbitrary coefficients) is returned as 0 and reported by
// domain().
class PerezModel final : public SkyModel {
 public:
  explicit PerezModel(const PerezParameters& params);
  static constexpr std::string_view kName = "perez";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  const PerezParameters& parameters() const { return params_; }
  // The all-weather sky when the parameters give irradiance or illuminance (else nullopt).
  const std::optional<PerezSky>& irradiance_sky() const { return sky_; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  Domain domain() const override;
  std::optional<GpuSky> gpu_sky() const override;
  // From irradiance: the light of irradiance_sky() (0 for a dark sky).
  std::optional<MeasuredLight> measured_light() const override;

 private:
  PerezParameters params_;
  std::optional<PerezSky> sky_;
  bool sun_up_ = true;
  PerezDistribution distribution_;
};

// The measured light of an all-weather sky: its direct and diffuse irradiance and illuminance (0
// for a dark sky), air mass and extraterrestrial irradiance.
MeasuredLight measured_light_of(const PerezSky& sky);

}  // namespace skylight
