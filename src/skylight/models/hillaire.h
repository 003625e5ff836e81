// The `hillaire` sky model: single scattering plus Hillaire's multiple-scattering approximation
// (Hillaire 2020, "A Scalable and Production Ready Sky and Atmosphere Rendering Technique",
// EGSR, §5.5), in `nishita`'s atmosphere (atmosphere.h) with `nishita`'s parameters.
//
// Orders >= 2 are approximated at each point y of a view ray by an isotropic in-scattering
// sigma_s(y) Psi_ms(h, mu_s) E0 (Hillaire eq. 10), Psi_ms from a LUT over altitude h and the
// local sun cosine mu_s:
//   L_2nd = integral over the sphere of L'(x, -w) p_u dw          (eq. 5; p_u = 1 / (4 pi))
//   f_ms  = integral over the sphere of L_f(x, -w) p_u dw         (eqs. 7-8)
//   Psi_ms = L_2nd / (1 - f_ms)                                    (eq. 9: 1 + f + f^2 + ...)
// L' = the single scattering toward x with an isotropic phase function (and the ground's
// reflection of the direct sun), L_f = integral of T sigma_s along the ray: light that has been
// scattered is taken as isotropic and its further orders as the same fraction f_ms each time.
// Where this differs from the paper: the LUT is computed for every wavelength of the XYZ
// integration (the paper: three RGB channels), its sun cosines are dense at the horizon
// (mu_s = sign(w) w^2, w uniform on [-1, 1]; the paper's uniform axis: twilight errors to 64 %),
// its sphere integral has 12 x 6 (x 2 by symmetry) directions (the paper 64, without symmetry), and
// the view ray is integrated with nishita's machinery instead of a sky-view LUT
// (docs/ATMOSPHERE.md).
#pragma once

#include <array>
#include <memory>
#include <mutex>
#include <vector>

#include "skylight/models/nishita.h"

namespace skylight {

// The multiple-scattering LUT: altitudes (uniform from the ground to the top) x sun cosines
// (mu_s = sign(w) w^2, w uniform on [-1, 1]), 32 x 32 as the paper's.
inline constexpr int kHillaireLutAltitudes = 32;
inline constexpr int kHillaireLutSunCosines = 32;
// The LUT's sphere integral: cosines (midpoints on [-1, 1]) x azimuths (midpoints on [0, pi];
// the integrand is symmetric about the sun's vertical plane).
inline constexpr int kHillaireLutPolar = 12;
inline constexpr int kHillaireLutAzimuths = 6;
// Trapezoid intervals per piece of a ray for the ray integrals of the multiple scattering
// (u^2-spaced toward the piece's lower end, as the brute-force reference's): a view ray's, and
// the LUT's (whose f_ms, ~0.1-0.3, needs less).
inline constexpr int kHillaireRayNodes = 32;
inline constexpr int kHillaireLutRayNodes = 8;

// The sky-view LUT of the multiple scattering (Hillaire 2020 §5.3, there of the whole sky): view
// zeniths (denser toward the horizon, which is the middle row: Hillaire's non-linear mapping) x
// azimuths from the sun's (0 .. pi, the sky being symmetric about the sun's vertical plane).
// tristimulus() adds it, bilinearly interpolated, to the exact single scattering.
inline constexpr int kHillaireSkyZeniths = 64;
inline constexpr int kHillaireSkyAzimuths = 32;

// The batch path's LUT of the whole sky (single + multiple scattering, as XYZ) per observer and
// sun, on the same two axes (built on the first batch call): render-sized batches are bilinear
// lookups.
inline constexpr int kHillaireBatchZeniths = 256;
inline constexpr int kHillaireBatchAzimuths = 128;

// `nishita`'s parameters, with the ozone layer on by default (Earth's 300 DU: the blue zenith of
// twilight, the Chappuis band).
struct HillaireParameters : NishitaParameters {
  HillaireParameters() { ozone_du = atmosphere::kEarthOzoneColumn; }
  static const ParameterSchema<HillaireParameters>& schema();
};

class HillaireModel final : public SkyModel {
 public:
  explicit HillaireModel(const HillaireParameters& params);
  static constexpr std::string_view kName = "hillaire";
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  // The fast path: the whole-sky LUT (kHillaireBatchZeniths x kHillaireBatchAzimuths), bilinear,
  // in float; its error against tristimulus() is bounded in hillaire_test.cpp.
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  std::optional<double> spectral_radiance(Vec3 view, double nm) const override;
  Domain domain() const override;
  // The solar disc (models/solar_disc.h: kSolarAngularRadius, Hosek & Wilkie 2013's limb
  // darkening) seen through the atmosphere's transmittance from the observer (0 when the sun is
  // below the observer's horizon, behind the planet).
  bool has_sun() const override { return true; }
  double sun_angular_radius() const override;
  Xyz sun_tristimulus(Vec3 view) const override;
  std::optional<double> sun_spectral_radiance(Vec3 view, double nm) const override;

  // The single scattering alone: nishita with the same parameters.
  const NishitaModel& single_scattering() const { return *single_; }
  // Psi_ms [sr^-1 per unit extraterrestrial irradiance] at wavelength index k of the LUT's
  // wavelengths, altitude h [m] and local sun cosine mu_s (bilinear in the LUT).
  double psi(std::size_t k, double altitude_m, double mu_s) const;
  // The LUT's wavelengths, ascending: 360 nm, those of the XYZ integration, 830 nm (the ends of
  // spectral_radiance's range; between them Psi is interpolated linearly in wavelength).
  const std::vector<double>& lut_wavelengths() const { return lut_nm_; }
  // Where a wavelength lies among lut_wavelengths(): Psi = (1 - t) Psi[k0] + t Psi[k1].
  struct LutWeight {
    std::size_t k0 = 0, k1 = 0;
    double t = 0.0;
  };
  LutWeight lut_weight(double nm) const;
  // The multiple-scattering radiance (orders >= 2) at each wavelength of `spec` (`weights`: each
  // one's place in the LUT) seen along `view` from the observer, integrated along the ray (what
  // the sky-view LUT holds at its nodes; spectral_radiance uses it directly).
  void multiple_scattering(Vec3 view, const atmosphere::Spectral& spec,
                           const std::vector<LutWeight>& weights, std::span<double> out) const;

 private:
  HillaireParameters params_;
  std::unique_ptr<NishitaModel> single_;
  std::vector<double> lut_nm_;
  std::vector<LutWeight> xyz_lut_;  // the XYZ wavelengths' places in the LUT
  Vec3 observer_, sun_;
  // The transmittance from the observer to the top along the sun's direction, per XYZ wavelength.
  std::array<double, kNishitaXyzCount> sun_transmittance_{};
  // The same at one wavelength.
  double sun_transmittance(double nm) const;
  // [wavelength][altitude][sun cosine], per unit irradiance (shared by the models of one
  // atmosphere: a process-wide cache of the last 8).
  std::shared_ptr<const std::vector<double>> psi_;
  // The sky-view LUT: [zenith row][azimuth column][XYZ wavelength] multiple-scattering radiance.
  std::vector<double> sky_;
  double horizon_zenith_ = 0.0;  // [rad] of the observer's horizon (pi/2 on the ground)
  // A LUT's row coordinate of a view zenith [rad] and back, for `rows` rows.
  double sky_row(double zenith, int rows) const;
  double sky_zenith(double row, int rows) const;
  // The batch LUT: [row][column] X, Y, Z in float, built once (thread-safe) on first use.
  mutable std::once_flag batch_once_;
  mutable std::vector<float> batch_;
  void build_batch_lut() const;
};

}  // namespace skylight
