// Operations on SH coefficients of a sky (Habel, Mustata & Wimmer 2008 §3.2-3.3): the exact
// rotation about the zenith (eq. 4), the ringing (Gibbs) suppression of the zonal coefficients
// (eq. 5), and reconstruction of the signal in a direction.
#pragma once

#include <array>

#include "skylight/core/math.h"
#include "skylight/sh/projection.h"

namespace skylight::sh {

// Habel 2008 eq. 4 (after Kautz, Sloan & Snyder 2002): rotation by phi about the zenith, in the
// direction of increasing azimuth (north towards east), so that the sky of a sun at azimuth 0
// becomes the sky of a sun at azimuth phi:
//   c_lm(phi) = c_lm cos(|m| phi) - sgn(m) c_l,-m sin(|m| phi),  m != 0;  c_l0 unchanged.
// cos(m phi), sin(m phi) by the angle-addition recurrence. Exact (no error introduced).
Coefficients rotate_about_zenith(const Coefficients& c, double phi);

// A rotation matrix in the project's frame (x east, y north, z up), row-major: d' = R d.
using RotationMatrix = std::array<std::array<double, 3>, 3>;

// General rotation (optional in Habel 2008 §3.2): the coefficients of g(d) = f(R^T d), i.e. of f
// turned by R, band by band with the recurrence of Ivanic & Ruedenberg 1996 (J. Phys. Chem. 100,
// 6342; erratum 1998, 102, 9099) for real SH. In this basis (no Condon-Shortley phase, phi from
// north) the l = 1 functions are proportional to (x, z, y), so the band-1 matrix is R in that
// order; bands l >= 2 follow from band l - 1 and band 1 (O(N^4) in total). R must be orthogonal
// with det +1 (not checked beyond the sizes). rotate_about_zenith is the special case of a turn
// about +z (the exact and cheaper eq. 4).
Coefficients rotate(const Coefficients& c, const RotationMatrix& r);

// Habel 2008 eq. 5: c'_l0 = c_l0 sinc(pi l / N), sinc(x) = sin(x) / x, N = c.bands; only the
// zonal (m = 0) coefficients change, a one-dimensional box filter in theta that suppresses the
// ringing below the horizon caused by the horizon's jump discontinuity.
Coefficients ringing_filter(const Coefficients& c);
// The factor sinc(pi l / N) of eq. 5.
double ringing_factor(int l, int bands);

// The reconstructed signal sum_lm c_lm Y_lm(d) at unit direction d, every direction (below the
// horizon too), unclamped: it may be negative.
Triple reconstruct(const Coefficients& c, Vec3 d);

// Energy of the reconstructed signal below a zenith angle theta_from >= pi/2: the integral over
// theta in [theta_from, pi] of f_rec^2 d omega, per channel [unit^2 sr] (Gauss-Legendre in
// mu = cos theta x uniform phi, exact for the polynomial f_rec^2 of degree 2 (N - 1)).
// theta_from = pi/2: the whole lower hemisphere, where the sky is black.
Triple energy_below(const Coefficients& c, double theta_from = kPi / 2);

}  // namespace skylight::sh
