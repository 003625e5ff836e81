// The `nishita` sky model: single scattering in a spherical planet's exponential atmosphere
// (Nishita et al. 1993; fast path of Pietras with optical-length tables), see atmosphere.h.
//
// Outputs, for an observer at observer_altitude_m above the ground at the
// north pole of the planet frame (ENU = planet frame), looking in any direction (below the
// horizon included: the in-scattered light up to the ground; from orbit: the planet and its limb):
//  * spectral_radiance(view, nm) = I(lambda) [W m^-2 sr^-1 nm^-1] for the ASTM G-173 solar
//    spectrum (data/bruneton/), or [sr^-1] x the flat irradiance SkyParameters::solar_irradiance;
//    360-830 nm (the solar table's range).
//  * tristimulus(view) = K_m sum_k (x, y, z)-bar(lambda_k) I(lambda_k) d lambda over
//  kXyzWavelengths
//    (20 nm bins, 390-770 nm midpoints): Y in cd/m^2 for the real spectrum; with a flat unit
//    irradiance Y is in "cd/m^2 per W m^-2 nm^-1". Difference against a 5 nm trapezoid
//    integration: see nishita_model_test.cpp.
//  * No solar disc (has_sun() = false); the ground reflects only if atmosphere->ground_albedo.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "skylight/atmosphere/atmosphere.h"
#include "skylight/models/sky_model.h"

namespace skylight {

// Wavelengths of the XYZ integration [nm]: midpoints of 20 nm bins 380-780 nm.
inline constexpr int kNishitaXyzCount = 20;
inline constexpr double kNishitaXyzStep = 20.0;    // [nm]
inline constexpr double kNishitaXyzFirst = 390.0;  // [nm]
// Spectral range of spectral_radiance (the solar table's) [nm].
inline constexpr double kNishitaMinNm = 360.0;
inline constexpr double kNishitaMaxNm = 830.0;
// Observer altitude range [m]: ground to 10 000 km.
inline constexpr double kNishitaMaxAltitude = 1e7;

// Extraterrestrial solar spectral irradiance [W m^-2 nm^-1] at nm (ASTM G-173 ETR in 10 nm bins,
// Bruneton 2017), linear between bin values; 0 outside 360-830 nm.
double solar_spectral_irradiance(double nm);

// What a `nishita` sky evaluates, in physical terms: the sun, the observer, the sun's spectrum and
// the planet with its atmosphere (any components, e.g. off-Earth test planets).
struct NishitaSetup {
  SunPosition sun;
  double observer_altitude_m = 0.0;  // above the ground [m], [0, kNishitaMaxAltitude]
  // Flat extraterrestrial solar spectral irradiance [W m^-2 nm^-1], (0, inf); nullopt = the ASTM
  // G-173 spectrum. With 1, radiances are per unit irradiance [sr^-1].
  std::optional<double> solar_irradiance;
  atmosphere::AtmosphereParameters atmosphere;  // Earth defaults; its ground_albedo is the ground
};

// The `nishita` model's parameters as a user gives them (an Earth-like planet: Rayleigh + Mie with
// adjustable scale heights and asymmetry, an optional ozone layer). setup() builds the planet.
struct NishitaParameters {
  SunPosition sun;
  double observer_altitude_m = 0.0;        // --observer-altitude [m], [0, kNishitaMaxAltitude]
  std::optional<double> solar_irradiance;  // --solar-irradiance [W m^-2 nm^-1]; none: ASTM G-173
  std::optional<double> albedo;            // --albedo [1], [0, 1]; none: no ground reflection
  double ground_radius_m = atmosphere::kEarthGroundRadius;  // --ground-radius [m]
  // --top-radius [m], > ground radius; none: ground radius + Earth's atmosphere height (60 km).
  std::optional<double> top_radius_m;
  double rayleigh_scale_height_m = atmosphere::kRayleighScaleHeight;  // [m]
  double mie_scale_height_m = atmosphere::kMieScaleHeight;            // [m]
  double mie_g = atmosphere::kMieG;  // Cornette-Shanks asymmetry [1], [-0.999, 0.999]
  // The aerosols (the Mie component; docs/MEASURED.md): their optical depth at 550 nm (the
  // column of the exponential layer, tau = beta_e H_M; none: Earth's default beta_e = 4.44e-6 m^-1
  // at the ground), the Angstrom exponent of beta(lambda) = beta_550 (550 / lambda)^alpha and the
  // single-scattering albedo beta_s / beta_e; or --turbidity, Preetham's mapping (tau_550 and
  // alpha = 1.3 of models/preetham.h), which excludes the first two.
  std::optional<double> aerosol_optical_depth;  // [1] at 550 nm, [0, 5]
  std::optional<double> angstrom_exponent;      // [1], [-1, 4]; none: 0 (grey), or 1.3
  double aerosol_albedo = atmosphere::kMieScattering / atmosphere::kMieExtinction;  // [0, 1]
  std::optional<double> turbidity;                                                  // [1], [1, 20]
  std::optional<double> ozone_du;  // --ozone column [DU], [0, 1000]; none: no ozone layer

  static const ParameterSchema<NishitaParameters>& schema();
  // The top of the atmosphere used: top_radius_m, or the ground radius + 60 km.
  double top_radius() const;
  // The planet and atmosphere these values describe (checked: throws InvalidArgument naming the
  // flag, e.g. a top radius not above the ground radius).
  NishitaSetup setup() const;
  // The Mie component of these values: scale height, g and the aerosols above.
  void set_aerosols(atmosphere::Component& mie) const;
};

// How the physical atmospheres are fitted to measured skies (`skylight measured`, docs/MEASURED.md)
// and photos: the aerosols' optical depth at 550 nm, Angstrom exponent and Mie g of model `name`
// (built by the registry with its other parameters at their defaults), free luminance scale.
EstimationPolicy aerosol_estimation(std::string name);

class NishitaModel final : public SkyModel {
 public:
  explicit NishitaModel(const NishitaParameters& params,
                        const atmosphere::FastSettings& settings = {});
  explicit NishitaModel(const NishitaSetup& setup, const atmosphere::FastSettings& settings = {});
  static constexpr std::string_view kName = "nishita";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  ParameterValues parameter_values() const override;
  const NishitaSetup& setup() const { return setup_; }
  Xyz tristimulus(Vec3 view) const override;
  std::optional<double> spectral_radiance(Vec3 view, double nm) const override;
  Domain domain() const override;

  const atmosphere::Atmosphere& atmosphere() const { return *atmosphere_; }
  Vec3 observer() const { return observer_; }  // planet-centred position [m]
  // The reference path's XYZ (brute force; tests and benchmarks only: ~1000x slower).
  Xyz tristimulus_reference(Vec3 view, const atmosphere::ReferenceSettings& rs = {}) const;
  // The XYZ of spectral radiances at the XYZ wavelengths (the midpoint sum over 20 nm bins).
  Xyz to_xyz(const std::array<double, kNishitaXyzCount>& radiance) const;
  // The wavelengths, solar irradiance and coefficients of the XYZ integration.
  const atmosphere::Spectral& xyz_spectral() const { return xyz_spectral_; }
  // The extraterrestrial solar spectral irradiance used at nm [W m^-2 nm^-1].
  double irradiance(double nm) const;
  // The atmosphere's coefficients and that irradiance at the wavelengths nm.
  atmosphere::Spectral spectral_at(std::span<const double> nm) const;
  // `eval --reference`'s wavelengths for the options (the XYZ integration's, or the spectral
  // ones, checked against 360-830 nm; InvalidArgument for rgb), and the quantity's values and
  // standard errors from spectral radiances and their standard errors there (independent per
  // wavelength).
  std::vector<double> reference_wavelengths(const EvaluationOptions& options) const;
  ReferenceValue reference_value(const EvaluationOptions& options, std::span<const double> radiance,
                                 std::span<const double> standard_error) const;

 private:
  NishitaSetup setup_;
  std::optional<NishitaParameters> params_;  // when built from user parameters
  std::unique_ptr<atmosphere::Atmosphere> atmosphere_;
  atmosphere::Spectral xyz_spectral_;
  std::array<Cmf, kNishitaXyzCount> cmf_{};  // CIE 1931 CMFs at the XYZ wavelengths
  Vec3 observer_, sun_;
};

// Representative wavelengths of the linear sRGB channels R, G, B for a transmittance per channel
// (Pietras §IV, models/pietras.h) [nm]: the dominant wavelengths of the sRGB primaries.
inline constexpr std::array<double, 3> kSurfaceChannelNm = {612.0, 549.0, 465.0};

// nishita's rgb() for any observer altitude, view and sun with one set of optical-length tables
// (equal to NishitaModel::rgb for the same setup; tested): the source of the Pietras networks
// (models/pietras.h, fit/pietras_training.h).
class NishitaSampler {
 public:
  explicit NishitaSampler(const NishitaParameters& atmosphere);
  Rgb rgb(double altitude_m, Vec3 view, Vec3 sun) const;
  const NishitaParameters& parameters() const { return params_; }
  const atmosphere::Atmosphere& atmosphere() const { return model_.atmosphere(); }
  // Light from a surface point q = P + distance view (P the observer at altitude h): nishita's
  // aerial perspective (Atmosphere::aerial_perspective, grey Lambertian albedo) as rgb, and the
  // parts of Pietras §IV: the reflected sunlight T(P, q) albedo/pi E_sun(q) alone, and T(P, q)
  // per channel at the wavelengths kSurfaceChannelNm.
  Rgb aerial_perspective(double altitude_m, Vec3 view, double distance_m, double albedo,
                         Vec3 sun) const;
  Rgb reflected(double altitude_m, Vec3 view, double distance_m, double albedo, Vec3 sun) const;
  std::array<double, 3> channel_transmittance(double altitude_m, Vec3 view,
                                              double distance_m) const;

 private:
  Rgb to_rgb(const std::array<double, kNishitaXyzCount>& radiance) const;
  Vec3 position(double altitude_m) const;

  NishitaParameters params_;
  NishitaModel model_;  // at altitude 0: its tables and spectra
  atmosphere::Spectral spectral_, channels_;
  std::array<Cmf, kNishitaXyzCount> cmf_{};
};

}  // namespace skylight
