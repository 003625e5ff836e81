// The common part of the multiple-scattering skies `hillaire` and `bruneton` (docs/ATMOSPHERE.md):
// nishita's single scattering computed exactly along each view ray (atmosphere.h), plus the
// radiance of the scattering orders >= 2 that each model defines (multiple_scattering()), held
// in a sky-view LUT per observer and sun (Hillaire 2020 §5.3); the batch path's whole-sky LUT;
// the solar disc (models/solar_disc.h) through the atmosphere's transmittance.
#pragma once

#include <array>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "skylight/atmosphere/ray.h"
#include "skylight/models/nishita.h"

namespace skylight {

// The sky-view LUT of the multiple scattering: view zeniths (denser toward the horizon, which is
// the middle row: Hillaire's non-linear mapping) x azimuths from the sun's (0 .. pi, the sky being
// symmetric about the sun's vertical plane). tristimulus() adds it, bilinearly interpolated, to
// the exact single scattering.
inline constexpr int kSkyViewZeniths = 64;
inline constexpr int kSkyViewAzimuths = 32;

// The batch path's LUT of the whole sky (single + multiple scattering, as XYZ) per observer and
// sun, on the same two axes (built on the first batch call): render-sized batches are bilinear
// lookups.
inline constexpr int kSkyBatchZeniths = 256;
inline constexpr int kSkyBatchAzimuths = 128;

// Trapezoid intervals per piece of a view ray for the ray integral of the multiple scattering
// (u^2-spaced toward the piece's lower end, as the brute-force reference's).
inline constexpr int kSkyViewRayNodes = 32;

// The XYZ quadrature of these skies (docs/ATMOSPHERE.md, "Spectral sampling"): the spectral
// radiance at 41 wavelengths, every 10 nm from 380 to 780 nm, weighted by spline_xyz_weights
// (core/xyz_quadrature.h) for the model's solar spectrum. Against a 5 nm integration of the
// model's own spectral radiance: within 0.04 % in X, Y and Z by day and 0.12 % at a low sun and in
// twilight (nishita's 20 CMF samples at 20 nm: 0.68 % and 2.1 %; `skylight_atmosphere_error xyz`).
inline constexpr int kPhysicalXyzCount = 41;
inline constexpr double kPhysicalXyzFirst = 380.0;  // [nm]
inline constexpr double kPhysicalXyzStep = 10.0;    // [nm]

// `nishita`'s parameters with the ozone layer on by default (Earth's 300 DU, Bruneton 2017's
// profile: the blue zenith of twilight, the Chappuis band): the base of `hillaire`'s and
// `bruneton`'s.
struct OzoneLayerParameters : NishitaParameters {
  OzoneLayerParameters() { ozone_du = atmosphere::kEarthOzoneColumn; }
  static const ParameterSchema<OzoneLayerParameters>& schema();
};

class PhysicalSkyModel : public SkyModel {
 public:
  // The single scattering alone: nishita with the same parameters.
  const NishitaModel& single_scattering() const { return *single_; }
  // The tables' wavelengths, ascending: 360 nm, nishita's XYZ wavelengths (390-770 nm every 20
  // nm), 830 nm (the ends of spectral_radiance's range; between them a table is interpolated
  // linearly in wavelength).
  const std::vector<double>& lut_wavelengths() const { return lut_nm_; }
  // Where a wavelength lies among lut_wavelengths(): v = (1 - t) v[k0] + t v[k1].
  using LutWeight = atmosphere::WavelengthWeight;
  LutWeight lut_weight(double nm) const { return atmosphere::wavelength_weight(lut_nm_, nm); }
  // The radiance of the orders >= 2 at each wavelength of `spec` (`weights`: each one's place
  // among lut_wavelengths()) seen along `view` from the observer (what the sky-view LUT holds at
  // its nodes; spectral_radiance uses it directly).
  virtual void multiple_scattering(Vec3 view, const atmosphere::Spectral& spec,
                                   const std::vector<LutWeight>& weights,
                                   std::span<double> out) const = 0;

  // The wavelengths, solar irradiance and coefficients of the XYZ quadrature (kPhysicalXyzCount).
  const atmosphere::Spectral& xyz_spectral() const { return xyz_; }
  // XYZ (Y in cd/m^2) of spectral radiances at those wavelengths.
  Xyz to_xyz(std::span<const double> radiance) const;
  Xyz tristimulus(Vec3 view) const override;
  // The fast path: the whole-sky LUT (kSkyBatchZeniths x kSkyBatchAzimuths), bilinear, in float;
  // its error against tristimulus() is bounded in the models' tests.
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  // The batch path as a shader's function: the whole-sky LUT as a table, looked up and
  // interpolated as tristimulus_batch does (in float on the GPU).
  std::optional<GpuSky> gpu_sky() const override;
  std::optional<double> spectral_radiance(Vec3 view, double nm) const override;
  // The solar disc (models/solar_disc.h: kSolarAngularRadius, Hosek & Wilkie 2013's limb
  // darkening) seen through the atmosphere's transmittance from the observer (0 when the sun is
  // below the observer's horizon, behind the planet).
  bool has_sun() const override { return true; }
  double sun_angular_radius() const override;
  Xyz sun_tristimulus(Vec3 view) const override;
  std::optional<double> sun_spectral_radiance(Vec3 view, double nm) const override;

  // The start of a registry entry of these models, `name`: nishita's, with their output (the XYZ
  // quadrature, the spectral range, the solar disc; `orders`: the orders of in-scattered light it
  // holds), their domain (nishita's, and `error`: the error against the path tracer), the path
  // tracer of the same atmosphere as `eval --reference` (at the XYZ quadrature's wavelengths, or
  // the spectral ones), the bench of the precomputation and a costly set-up.
  static ModelInfo registry_entry_of(std::string_view name, std::string_view orders,
                                     std::string_view error);
  // Its wavelengths for the options and the quantity's values from the spectral radiances there
  // (as NishitaModel's, with this model's XYZ quadrature).
  std::vector<double> reference_wavelengths(const EvaluationOptions& options) const;
  ReferenceValue reference_value(const EvaluationOptions& options, std::span<const double> radiance,
                                 std::span<const double> standard_error) const;

 protected:
  explicit PhysicalSkyModel(const NishitaParameters& params);
  // Fills the sky-view LUT: the derived model's constructor calls it last, once
  // multiple_scattering() can run. `tables_key`: what multiple_scattering() depends on besides the
  // solar spectrum, the observer and the sun (the atmosphere's key, the model's own settings); a
  // model with the same key, solar spectrum, observer and sun reuses the LUTs of the last built.
  void build_sky_view(const std::string& tables_key);
  const atmosphere::Atmosphere& atmosphere() const { return single_->atmosphere(); }
  Vec3 observer_, sun_;

 private:
  std::unique_ptr<NishitaModel> single_;
  std::vector<double> lut_nm_;
  atmosphere::Spectral xyz_;        // the XYZ quadrature's wavelengths
  std::vector<Cmf> xyz_weights_;    // and weights (spline_xyz_weights)
  std::vector<LutWeight> xyz_lut_;  // the XYZ wavelengths' places among lut_nm_
  // The transmittance from the observer to the top along the sun's direction, per XYZ wavelength.
  std::array<double, kPhysicalXyzCount> sun_transmittance_{};
  // That transmittance at the wavelengths of `spec` (0 behind the planet).
  void sun_transmittance(const atmosphere::Spectral& spec, std::span<double> out) const;
  // The sky-view LUT: [zenith row][azimuth column][XYZ wavelength] multiple-scattering radiance.
  std::shared_ptr<const std::vector<double>> sky_;
  std::string lut_key_;          // build_sky_view's key with the solar spectrum, observer and sun
  double horizon_zenith_ = 0.0;  // [rad] of the observer's horizon (pi/2 on the ground)
  // A LUT's row coordinate of a view zenith [rad] and back, for `rows` rows.
  double sky_row(double zenith, int rows) const;
  double sky_zenith(double row, int rows) const;
  // The batch LUT: [row][column] X, Y, Z in float, built once (thread-safe) on first use.
  // The whole-sky LUT, built on first use (kSkyBatchZeniths x kSkyBatchAzimuths XYZ, row-major).
  const std::vector<float>& batch_lut() const;
  mutable std::once_flag batch_once_;
  mutable std::shared_ptr<const std::vector<float>> batch_;
  std::vector<float> build_batch_lut() const;
};

}  // namespace skylight
