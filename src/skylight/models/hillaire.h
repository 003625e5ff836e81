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

#include <memory>
#include <vector>

#include "skylight/models/physical_sky.h"

namespace skylight {

// The multiple-scattering LUT: altitudes (uniform from the ground to the top) x sun cosines
// (mu_s = sign(w) w^2, w uniform on [-1, 1]), 32 x 32 as the paper's.
inline constexpr int kHillaireLutAltitudes = 32;
inline constexpr int kHillaireLutSunCosines = 32;
// The LUT's sphere integral: cosines (midpoints on [-1, 1]) x azimuths (midpoints on [0, pi];
// the integrand is symmetric about the sun's vertical plane).
inline constexpr int kHillaireLutPolar = 12;
inline constexpr int kHillaireLutAzimuths = 6;
// Trapezoid intervals per piece of a ray for the LUT's ray integrals (u^2-spaced toward the
// piece's lower end; its f_ms, ~0.1-0.3, needs fewer than a view ray's kSkyViewRayNodes).
inline constexpr int kHillaireLutRayNodes = 8;

// `nishita`'s parameters, with the ozone layer on by default (OzoneLayerParameters).
struct HillaireParameters : OzoneLayerParameters {
  static const ParameterSchema<HillaireParameters>& schema();
};

class HillaireModel final : public PhysicalSkyModel {
 public:
  explicit HillaireModel(const HillaireParameters& params);
  static constexpr std::string_view kName = "hillaire";
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  ParameterValues parameter_values() const override;
  Domain domain() const override;

  // Psi_ms [sr^-1 per unit extraterrestrial irradiance] at wavelength index k of
  // lut_wavelengths(), altitude h [m] and local sun cosine mu_s (bilinear in the LUT).
  double psi(std::size_t k, double altitude_m, double mu_s) const;
  // Orders >= 2: sigma_s(y) Psi_ms(h, mu_s) E0 integrated along the view ray with its
  // transmittance (eq. 10).
  void multiple_scattering(Vec3 view, const atmosphere::Spectral& spec,
                           const std::vector<LutWeight>& weights,
                           std::span<double> out) const override;

 private:
  HillaireParameters params_;
  // [wavelength][altitude][sun cosine], per unit irradiance (shared by the models of one
  // atmosphere: AtmosphereTableCache).
  std::shared_ptr<const std::vector<double>> psi_;
};

}  // namespace skylight
