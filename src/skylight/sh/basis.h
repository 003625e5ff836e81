// Real orthonormal spherical harmonics (Sloan, Kautz & Snyder 2002; the basis of Habel, Mustata &
// Wimmer 2008, "Efficient Spherical Harmonics Lighting with the Preetham Skylight Model").
//
// Conventions (docs/SH.md):
//  * N bands = degrees l = 0 .. N-1, N^2 coefficients; coefficient index i = l (l + 1) + m,
//    m = -l .. l.
//  * Angles are the project's (core/frame.h): theta from the zenith (+z), phi from north (+y)
//    towards east (+x); cos theta = z, sin theta cos phi = y, sin theta sin phi = x.
//  * Y_l0 = K_l0 P_l^0(cos theta);
//    Y_lm = sqrt(2) K_lm cos(m phi) P_l^m(cos theta) for m > 0 (the "cos" terms),
//    Y_lm = sqrt(2) K_l|m| sin(|m| phi) P_l^|m|(cos theta) for m < 0 (the "sin" terms),
//    K_lm = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!), and P_l^m WITHOUT the Condon-Shortley
//    phase (-1)^m, so every Y_lm with m >= 0 is positive towards the zenith and north.
//  * Orthonormal over the full sphere: integral Y_i Y_j d omega = delta_ij.
#pragma once

#include <span>
#include <vector>

#include "skylight/core/frame.h"

namespace skylight::sh {

// Largest band count the basis supports (degrees 0 .. 29); the fast recurrence stays within 1e-12
// relative of the reference there (sh/basis_test.cpp).
inline constexpr int kMaxBands = 30;

// Number of coefficients of N bands: N^2.
constexpr int coefficient_count(int bands) {
  return bands * bands;
}
// Index of (l, m): l (l + 1) + m.
constexpr int index(int l, int m) {
  return l * (l + 1) + m;
}
// Degree l and order m of index i (inverse of index()).
struct DegreeOrder {
  int l = 0;
  int m = 0;
};
DegreeOrder degree_order(int i);

// Throws InvalidArgument unless 1 <= bands <= kMaxBands.
void check_bands(int bands);

// K_lm = sqrt((2l + 1) / (4 pi) (l - m)! / (l + m)!), m >= 0 (tabulated once).
double normalisation(int l, int m);

// Fast path: all N^2 basis values at unit direction d into out (size >= N^2). Associated
// Legendre polynomials by the three-term recurrence in l from P_m^m = (2m - 1)!! sin^m theta,
// and sin^m theta cos(m phi), sin^m theta sin(m phi) as Re/Im of (y + i x)^m (no division by
// sin theta: exact at the poles).
void evaluate_basis(int bands, Vec3 d, std::span<double> out);
std::vector<double> evaluate_basis(int bands, Vec3 d);

// Slow reference: Y_lm at (theta, phi) from the explicit sum of the derivative of Rodrigues'
// formula, P_l^m(x) = 2^-l (1 - x^2)^(m/2) sum_k (-1)^k (2l - 2k)! / (k! (l - k)! (l - 2k - m)!)
// x^(l - 2k - m), factorials in long double, and std::cos / std::sin of m phi. Its alternating
// sum loses digits with l: use it for l <= 15.
double basis_reference(int l, int m, double theta, double phi);

}  // namespace skylight::sh
