// The solar disc of the physical models: its angular size, its limb darkening and the
// normalisation that makes the disc's integral the extraterrestrial irradiance (the atmosphere's
// transmittance along the line of sight is the model's).
#pragma once

namespace skylight {

// The Sun's angular radius at 1 AU [rad]: the IAU 2015 nominal solar radius (695 700 km, Resolution
// B3) over the astronomical unit (149 597 870.7 km): 0.26645 deg. ASTM G-173's extraterrestrial
// spectrum is for 1 AU.
inline constexpr double kSolarAngularRadius = 4.650467e-3;

// L(gamma, nm) / E0(nm) [sr^-1]: the radiance of the disc at angle gamma [rad] from its centre per
// unit extraterrestrial spectral irradiance E0 (0 outside the disc). Limb darkening D(mu) =
// sum_k ld_k(nm) mu^k with Hosek & Wilkie 2013's coefficients (hw_limb_darkening; 320-720 nm,
// the 720 nm ones beyond), mu = sqrt(1 - sin^2 gamma / sin^2 r); normalised so that the integral
// over the disc is 1: D / (pi r^2 sum_k ld_k 2 / (k + 2)).
double solar_disc_factor(double gamma, double nm);

}  // namespace skylight
