// Preetham, Shirley & Smits 1999, "A Practical Analytic Model for Daylight" (SIGGRAPH '99),
// Appendix A: sky luminance and chromaticity as Perez functions of turbidity, zenith values, the
// spectral sky radiance through the CIE daylight basis, and the attenuated solar disc.
// Validity after Zotti, Wilkie & Purgathofer 2007 ("A Critical Review of the Preetham Skylight
// Model"): fitted for T in [2, 6]; negative zenith luminance near T < 1.9 / low sun / T >~ 10.
#pragma once

#include <array>

#include "skylight/models/perez_kernel.h"
#include "skylight/models/sky_model.h"

namespace skylight {

// Fitted turbidity range of the model (Preetham 1999 §3; Zotti 2007 §3).
inline constexpr double kPreethamFittedTurbidityMin = 2.0;
inline constexpr double kPreethamFittedTurbidityMax = 6.0;
// Zotti 2007 §7: "breaks down numerically for T < 1.9 and T >~ 10".
inline constexpr double kPreethamUsableTurbidityMin = 1.9;
inline constexpr double kPreethamUsableTurbidityMax = 10.0;

// Perez coefficients for Y, x, y at turbidity T (Preetham 1999 eq. A.2 table):
// each of A..E = T_coefficient * T + constant (data/preetham/preetham_perez_coefficients.csv).
struct PreethamPerez {
  PerezCoefficients Y, x, y;
};
PreethamPerez preetham_perez_coefficients(double turbidity);

// chi = (4/9 - T/120)(pi - 2 theta_s)  [rad]  (Preetham 1999 A.2; Zotti 2007 eq. 2).
double preetham_chi(double turbidity, double sun_zenith);
// Zenith luminance Yz = 1000 [(4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192]  [cd/m^2]
// (Preetham A.2 gives kcd/m^2; Zotti 2007 eq. 1). The raw closed form: negative in the region of
// Zotti's Fig. 1. Defined for sun_zenith in [0, pi/2].
double preetham_zenith_luminance(double turbidity, double sun_zenith);
// Zenith chromaticity x_z (and y_z) = [T^2 T 1] M [theta_s^3 theta_s^2 theta_s 1]^T
// (Preetham A.2 matrices, data/preetham/preetham_zenith_chromaticity_matrices.csv).
Chromaticity preetham_zenith_chromaticity(double turbidity, double sun_zenith);

// Relative optical air mass m = 1 / (cos theta_s + 0.15 (93.885 - theta_s[deg])^-1.253)
// (Kasten 1966, as used by Preetham's appendix). Defined for theta_s <= 90 deg.
double relative_optical_mass(double sun_zenith);

// Preetham et al. 1999's aerosol for turbidity T (appendix A.3): the Angstrom law
// tau(lambda) = beta lambda[um]^-alpha with beta = 0.04608 T - 0.04586 and alpha = 1.3. The
// physical atmospheres' --turbidity is this mapping (docs/MEASURED.md).
struct PreethamAerosol {
  double beta = 0.0, alpha = 1.3;
  double optical_depth(double nm) const;  // tau at nm
};
PreethamAerosol preetham_aerosol(double turbidity);

// Transmittances of the direct solar beam (Preetham 1999 Appendix A.1 after Iqbal 1983), all
// dimensionless, for solar zenith theta_s, turbidity T, wavelength nm.
struct SolarTransmittance {
  double rayleigh = 1.0;  // exp(-0.008735 lambda[um]^-4.08 m)
  double aerosol = 1.0;   // exp(-beta lambda[um]^-alpha m), alpha = 1.3, beta = 0.04608 T - 0.04586
  double ozone = 1.0;     // exp(-k_o l m), l = 0.35 cm
  double mixed_gas = 1.0;  // exp(-1.41 k_g m / (1 + 118.93 k_g m)^0.45)
  double water = 1.0;      // exp(-0.2385 k_wa w m / (1 + 20.07 k_wa w m)^0.45), w = 2 cm
  double total() const { return rayleigh * aerosol * ozone * mixed_gas * water; }
};
SolarTransmittance preetham_solar_transmittance(double sun_zenith, double turbidity, double nm);

// Extraterrestrial solar spectral radiance [W m^-2 sr^-1 nm^-1], 380-750 nm (10 nm table,
// linearly interpolated; data/preetham/preetham_sun_spectral_radiance.csv); nullopt outside.
std::optional<double> extraterrestrial_sun_radiance(double nm);
// Wavelength range of Preetham's sun table [nm].
inline constexpr double kPreethamSunMinNm = 380.0;
inline constexpr double kPreethamSunMaxNm = 750.0;

// Angular radius of the solar disc used by the Preetham sun: 0.5 * 0.5358 deg.
inline constexpr double kPreethamSunAngularRadius = 0.5 * 0.5358 * kDegree;

// Turbidity accepted by the model (beyond the fitted range it is flagged, not refused; Zotti et al.
// 2007 Fig. 1 studies T up to 64).
inline constexpr double kPreethamTurbidityMin = 1.0;
inline constexpr double kPreethamTurbidityMax = 64.0;
// Turbidity range of the photo fit (Morales et al. 2017 §3.4, eq. 8; fit/luminance_fit.h). Eq. 8
// searches [1, 20]; below T = 1.643 Preetham's gradation factor 1 + A_Y exp(B_Y) changes sign at
// the zenith (docs/MODELS.md), so the relative luminance has no logarithm there: the fit starts at
// 1.7.
inline constexpr double kPreethamFitTurbidityMin = 1.7;
inline constexpr double kPreethamFitTurbidityMax = 20.0;
// ln f(T) = ln F(theta, gamma; T) - ln F(0, theta_s; T): Preetham's luminance relative to the
// zenith luminance Yz (Preetham 1999 A.2, Perez coefficients of Y). F > 0 for T in the fit range.
double preetham_log_relative_luminance(double turbidity, Vec3 view, const SunPosition& sun);

struct PreethamParameters {
  SunPosition sun;
  double turbidity = 3.0;  // --turbidity T [1], [kPreethamTurbidityMin, kPreethamTurbidityMax]

  static const ParameterSchema<PreethamParameters>& schema();
};

// The `preetham` model.
//  * tristimulus(): sky XYZ, Y [cd/m^2] = Yz F_Y(theta, gamma) / F_Y(0, theta_s), chromaticity
//    x = x_z F_x / F_x(0, theta_s) (same for y). Views below the horizon: 0. Where the formula
//    gives negative luminance (Yz < 0, Zotti Fig. 1), 0 is returned and domain() says
//    `unphysical`. Sun below the horizon: the model is undefined; 0 everywhere.
//  * spectral_radiance(): Y / (K_m integral S y-bar) * S(lambda), S = CIE daylight spectrum at the
//    sky chromaticity, 300-830 nm. Where S is negative (short wavelengths, chromaticities far from
//    the daylight locus: low sun) 0 is returned and domain() says `unphysical`.
//  * sun: the extraterrestrial spectrum times SolarTransmittance over a uniform disc of radius
//    kPreethamSunAngularRadius, 380-750 nm (XYZ integrated over that range).
class PreethamModel final : public SkyModel {
 public:
  explicit PreethamModel(const PreethamParameters& params);
  static constexpr std::string_view kName = "preetham";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  const PreethamParameters& parameters() const { return params_; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  std::optional<double> spectral_radiance(Vec3 view, double nm) const override;
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  bool has_sun() const override { return true; }
  double sun_angular_radius() const override { return kPreethamSunAngularRadius; }
  Xyz sun_tristimulus(Vec3 view) const override;
  std::optional<double> sun_spectral_radiance(Vec3 view, double nm) const override;
  Domain domain() const override;
  std::optional<GpuSky> gpu_sky() const override;

  double zenith_luminance() const { return zenith_luminance_; }  // raw Yz [cd/m^2]
  Chromaticity zenith_chromaticity() const { return zenith_xy_; }

 private:
  bool in_disc(Vec3 view) const;  // inside the solar disc and above the horizon
  // The most negative spectral radiance the daylight basis gives on a probe grid of directions and
  // wavelengths (0 radiance when none is negative).
  struct NegativeSpectrum {
    double radiance = 0.0, nm = 0.0;
    Vec3 view{0, 0, 1};
  };
  NegativeSpectrum most_negative_spectrum() const;

  PreethamParameters params_;
  bool sun_up_ = true;
  double zenith_luminance_ = 0.0;
  Chromaticity zenith_xy_;
  PerezDistribution distribution_;
  Xyz sun_xyz_;
};

}  // namespace skylight
