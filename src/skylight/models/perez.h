// The Perez all-weather relative luminance distribution (Perez, Seals & Michalsky 1993;
// Satilmis et al. 2016 eq. 1) with user-given coefficients A..E and a given zenith luminance:
//   L(theta, gamma) = Lz F(theta, gamma) / F(0, theta_s),
//   F(theta, gamma) = (1 + A exp(B / cos theta)) (1 + C exp(D gamma) + E cos^2 gamma).
#pragma once

#include <array>
#include <optional>

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

// Parameters of the `perez` model (both required).
struct PerezParameters {
  SunPosition sun;
  // --perez A,B,C,D,E: the coefficients [1], each in [-kPerezCoefficientLimit, +limit].
  std::optional<std::array<double, 5>> coefficients;
  // --zenith-luminance: absolute zenith luminance Lz [cd/m^2], [kMinZenithLuminance, kMax...].
  std::optional<double> zenith_luminance;

  static const ParameterSchema<PerezParameters>& schema();
};

// The `perez` model: luminance only; XYZ with the D65 chromaticity (0.3127, 0.3290), so rgb() is
// neutral. Views below the horizon and a sun below the horizon: 0. Negative F (possible with
// arbitrary coefficients) is returned as 0 and reported by domain().
class PerezModel final : public SkyModel {
 public:
  explicit PerezModel(const PerezParameters& params);
  static constexpr std::string_view kName = "perez";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  const PerezParameters& parameters() const { return params_; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  Domain domain() const override;

 private:
  PerezParameters params_;
  bool sun_up_ = true;
  PerezDistribution distribution_;
};

}  // namespace skylight
