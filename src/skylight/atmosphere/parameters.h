// Parameters of a spherical planet with an exponential, multi-component atmosphere
// (Nishita et al. 1993, "Display of the Earth taking into account atmospheric scattering";
// Pietras, "GPU-based multi-layer perceptron as efficient method for approximation complex light
// models in per-vertex lighting", §II-III: one density exp(-h/H) per component).
//
// Kept apart from atmosphere.h so that SkyParameters can carry an AtmosphereParameters without
// pulling in the optical-length tables. SI units (m, m^-1), wavelengths in nm.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "skylight/core/earth.h"
#include "skylight/core/spectrum.h"

namespace skylight::atmosphere {

// Phase function F(mu) [sr^-1] of one component, mu = cos(scattering angle) = dot(view, sun).
enum class PhaseKind {
  rayleigh,           // 3/(16 pi) (1 + mu^2)
  henyey_greenstein,  // (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^{3/2})
  cornette_shanks,    // 3/(8 pi) (1 - g^2)(1 + mu^2) / ((2 + g^2)(1 + g^2 - 2 g mu)^{3/2})
};

// Vertical density profile of a component, rho(h) relative to its reference density (rho = 1),
// h = altitude above the ground radius [m].
enum class Profile {
  exponential,  // rho = exp(-h / scale_height_m)                (Pietras eq. 3; air, aerosols)
  tent,         // rho = max(0, 1 - |h - peak_altitude_m| / half_width_m)
                // (a layer peaking at one altitude, e.g. ozone; Bruneton 2017's ozone profile is
                // the tent with peak 25 km and half width 15 km)
};

// One atmospheric component with a density profile (above) and spectral coefficients at rho = 1.
// Scattering and extinction follow a power law from a reference wavelength:
//   beta(lambda) = beta_ref * (reference_nm / lambda)^angstrom_exponent      [m^-1 at rho = 1]
// (exponent 4 = Rayleigh's lambda^-4 law, 0 = grey Mie), and the extinction adds an optional
// tabulated absorption (a Spectrum: linear between its wavelengths, 0 outside them), e.g. ozone's
// absorption = number density x cross-section.
struct Component {
  std::string name;              // "rayleigh", "mie", ... (used in messages)
  double scale_height_m = 0;     // H > 0 [m]
  double scattering_per_m = 0;   // beta_s at reference_nm and sea level [m^-1], >= 0
  double extinction_per_m = 0;   // beta_e at reference_nm and sea level [m^-1], >= scattering_per_m
  double reference_nm = 550;     // wavelength of the two values above [nm], > 0
  double angstrom_exponent = 0;  // power-law exponent [1]
  PhaseKind phase = PhaseKind::rayleigh;
  double g = 0;  // asymmetry parameter for HG / Cornette-Shanks, (-1, 1)
  Profile profile = Profile::exponential;
  double peak_altitude_m = 0;   // tent: altitude of rho = 1 [m], finite
  double half_width_m = 0;      // tent: rho falls to 0 this far below and above the peak [m], > 0
  Spectrum absorption_per_m{};  // absorption at rho = 1 [m^-1], >= 0; empty = none

  double scattering(double nm) const;
  double extinction(double nm) const;  // power law + tabulated absorption
  double density(double altitude_m) const;
};

// Earth defaults (docs/MODELS.md, `nishita`; Bruneton 2017 demo values for the radii and Mie):
// Rayleigh: H = 8 km, beta_s = beta_e = 13.558e-6 m^-1 at 550 nm with the lambda^-4 law; this law
//   reproduces the other two given values to 4 digits: 13.558 (550/680)^4 = 5.803 (given 5.802)
//   and 13.558 (550/440)^4 = 33.10 (given 33.1), so the three RGB values are one law.
// Mie: H = 1.2 km, beta_s = 3.996e-6, beta_e = 4.440e-6 m^-1 at every wavelength (exponent 0),
//   Cornette-Shanks phase with g = 0.8.
// The radii and the Rayleigh scale height: core/earth.h (kEarthGroundRadius, kEarthTopRadius,
// kRayleighScaleHeight), shared with the Pietras networks.
using skylight::kEarthGroundRadius;
using skylight::kEarthTopRadius;
using skylight::kRayleighScaleHeight;
inline constexpr double kRayleighScattering550 = 13.558e-6;  // [m^-1] at 550 nm
inline constexpr double kRayleighExponent = 4;               // lambda^-4
inline constexpr double kMieScaleHeight = 1200;              // [m]
inline constexpr double kMieScattering = 3.996e-6;           // [m^-1], all wavelengths
inline constexpr double kMieExtinction = 4.440e-6;           // [m^-1], all wavelengths
inline constexpr double kMieG = 0.8;                         // Cornette-Shanks asymmetry

// Ozone (Bruneton 2017, demo.cc): a tent from 10 to 40 km peaking at 25 km whose column holds
// `dobson` Dobson units (1 DU = 2.687e20 molecules m^-2; the tent's column is 15 km x the peak
// number density), absorbing with the ozone cross-section of data/bruneton (IUP Bremen, 233 K,
// 360-830 nm); no scattering. Earth's typical column is ~300 DU.
inline constexpr double kOzonePeakAltitude = 25e3;  // [m]
inline constexpr double kOzoneHalfWidth = 15e3;     // [m]
inline constexpr double kDobsonUnit = 2.687e20;     // [molecules m^-2]
inline constexpr double kEarthOzoneColumn = 300;    // [DU]

Component earth_rayleigh();
Component earth_mie(double g = kMieG);
Component earth_ozone(double dobson = kEarthOzoneColumn);

// At most this many components (the fast path keeps per-sample values on the stack).
inline constexpr std::size_t kMaxComponents = 8;

struct AtmosphereParameters {
  double ground_radius_m = kEarthGroundRadius;  // R0 [m], > 0
  double top_radius_m = kEarthTopRadius;        // top of the atmosphere [m], > ground radius
  std::vector<Component> components{earth_rayleigh(), earth_mie()};  // at most kMaxComponents
  // Lambertian ground albedo [0, 1]; nullopt = the ground reflects nothing (eval returns only the
  // in-scattered light, docs/MODELS.md).
  std::optional<double> ground_albedo;

  // Throws InvalidArgument naming the field and value when out of range.
  void validate() const;
};

}  // namespace skylight::atmosphere
