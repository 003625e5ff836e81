// ISO 15469:2004 / CIE S 011/E:2003 Standard General Sky (15 types) and the traditional CIE
// overcast sky (type 16, Moon & Spencer 1942), with the Kittler & Darula typical absolute zenith
// luminance (Kittler & Darula 2006, Lighting Res. Technol. 38(2); Darula & Kittler, eSim 2002).
#pragma once

#include <array>
#include <optional>

#include "skylight/models/perez_kernel.h"
#include "skylight/models/sky_model.h"

namespace skylight {

inline constexpr int kCieTypeCount = 16;  // 15 standard types + the traditional overcast sky

// Parameters of one standard type (data/cie_standard_sky/cie_s011_2003_sky_types.csv).
struct CieSkyType {
  int type = 0;
  double a = 0, b = 0;         // gradation phi(Z) = 1 + a exp(b / cos Z)
  double c = 0, d = 0, e = 0;  // indicatrix f(chi) = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi
};
// Types 1..15; throws InvalidArgument otherwise.
const CieSkyType& cie_sky_type(int type);

// Gradation phi(Z) = 1 + a exp(b / cos Z) (CIE S 011 eq. 2), Z view zenith angle [rad];
// phi(pi/2) = 1 (the horizon). cos Z is clamped as in kPerezMinCosTheta.
double cie_gradation(const CieSkyType& t, double Z);
// Scattering indicatrix f(chi) = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi (CIE S 011 eq. 3),
// chi angle between view and sun [rad].
double cie_indicatrix(const CieSkyType& t, double chi);
// Relative luminance L / Lz = phi(Z) f(chi) / (phi(0) f(Zs)) (eq. 1); type 16: (1 + 2 cos Z) / 3.
double cie_relative_luminance(int type, double Z, double chi, double Zs);

// Kittler-Darula typical parameters per type 1..15 (data/cie_standard_sky/
// kittler_darula_zenith_luminance.csv).
struct KittlerDarulaParameters {
  double Tv = 0, A = 0, A1 = 0, A2 = 0, B = 0, C = 0, D = 0, E = 0, Dv_over_Ev = 0;
};
const KittlerDarulaParameters& kittler_darula_parameters(int type);

// Typical absolute zenith luminance [cd/m^2] for type 1..15 at solar elevation gamma_s [rad]:
//  * overcast types 1-6 (or Tv > 12): Lvz = (Dv/Ev) [B sin^C gs / cos^D gs + E sin gs]  kcd/m^2
//  * other types: Lvz = A sin gs + 0.7 (Tv + 1) sin^C gs / cos^D gs + 0.04 Tv  kcd/m^2
// Recommended for gamma_s in [10, 80] deg (CIE advice). gamma_s is clamped to
// [0, kKittlerDarulaMaxElevation] because the cos^-D term diverges as the sun reaches the zenith.
// Type 16 (traditional overcast): Lz = 9/(7 pi) Dv with the typical overcast Dv/Ev = 0.10 of
// type 1 and Ev = 133.8 klx sin gs (Moon & Spencer's zenith-to-diffuse ratio).
double kittler_darula_zenith_luminance(int type, double sun_elevation);
inline constexpr double kKittlerDarulaMinElevation = 10.0 * kDegree;
inline constexpr double kKittlerDarulaMaxElevation = 80.0 * kDegree;
// Where the formula is evaluated at most (beyond it the cos^-D term explodes): 85 deg.
inline constexpr double kKittlerDarulaClampElevation = 85.0 * kDegree;
// A band around the typical zenith luminance, derived by us (docs/REPORT.md, "Kittler-Darula
// band"): Kittler & Darula publish only the typical parameters per type and the relation
// A = A1 Tv + A2 for a measured Linke turbidity Tv, not the minimum/maximum values that Zotti
// 2007 draws in his Fig. 5. Types 7-15: the formula above with A = A1 Tv + A2 for Tv over
// [kKittlerDarulaBandTvMin, kKittlerDarulaBandTvMax]; types 1-6 and 16: Dv/Ev over the range of the
// typical Dv/Ev of types 1-15 (0.10-0.42). low <= typical <= high.
struct ZenithLuminanceBand {
  double low = 0.0, typical = 0.0, high = 0.0;  // [cd/m^2]
};
ZenithLuminanceBand kittler_darula_zenith_luminance_band(int type, double sun_elevation);
// Linke turbidity range of the band: a very clean sky (Tv = 2) to the value above which the
// overcast formula is used (Tv = 12).
inline constexpr double kKittlerDarulaBandTvMin = 2.0, kKittlerDarulaBandTvMax = 12.0;
// Extraterrestrial horizontal illuminance at the sun's zenith: 133.8 klx (Kittler & Darula).
inline constexpr double kExtraterrestrialIlluminanceKlx = 133.8;

struct CieParameters {
  SunPosition sun;
  int type = 12;  // --cie-type: 1..15 (CIE S 011 types), 16 = traditional overcast
  // --zenith-luminance Lz [cd/m^2], [kMinZenithLuminance, kMaxZenithLuminance]; absent: the
  // Kittler-Darula typical value for the type and sun elevation.
  std::optional<double> zenith_luminance;

  static const ParameterSchema<CieParameters>& schema();
};

// The `cie` model: luminance only. tristimulus() returns Y = Lz L/Lz [cd/m^2] with the chromaticity
// of D65 (x, y) = (0.3127, 0.3290), so rgb() is neutral grey with r = g = b = Y. Views below the
// horizon: 0. Sun below the horizon: 0 everywhere (undefined; daylight only).
class CieSkyModel final : public SkyModel {
 public:
  explicit CieSkyModel(const CieParameters& params);
  static constexpr std::string_view kName = "cie";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  const CieParameters& parameters() const { return params_; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  Domain domain() const override;
  std::optional<GpuSky> gpu_sky() const override;
  double zenith_luminance() const { return zenith_luminance_; }

 private:
  CieParameters params_;
  int type_ = 12;
  bool sun_up_ = true;
  bool typical_luminance_ = true;
  double zenith_luminance_ = 0.0;
  PerezDistribution distribution_;  // types 1-15
};

}  // namespace skylight
