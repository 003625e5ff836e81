// Test helpers: SH polynomial tables. A synthetic one (deterministic pseudo-random coefficients,
// SplitMix64) for tests of evaluation, reconstruction and export that need no fit, and a reduced
// fit of Preetham for those that need a real one.
#pragma once

#include <cstdint>

#include "skylight/core/math.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/sh/polynomial.h"

namespace skylight::testing_support {

// A Preetham-labelled table over theta in [0, pi/2], T in [2.5, 6]: c_00 terms ~1000 (a positive
// sky), the others uniform in [-200, 200].
inline sh::PolynomialTable synthetic_sh_table(int bands, int degree_theta, int degree_tau,
                                              sh::Channels channels = sh::Channels::xyz) {
  sh::PolynomialTable t;
  t.model = "preetham";
  t.parameter = "turbidity";
  t.channels = channels;
  t.bands = bands;
  t.degree_theta = degree_theta;
  t.degree_tau = degree_tau;
  t.theta_min = 0.0;
  t.theta_max = kPi / 2;
  t.tau_min = 2.5;
  t.tau_max = 6.0;
  std::uint64_t state = 0x5eed;
  const auto next = [&state] {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  const int terms = t.terms();
  const int series = bands * (bands + 1) / 2 * 3;
  for (int s = 0; s < series; ++s) {
    for (int k = 0; k < terms; ++k) {
      const double v = (s < 3 && k == 0) ? 1000.0 : 400.0 * next() - 200.0;
      t.coefficients.push_back(static_cast<float>(v));
    }
  }
  return t;
}

// A reduced fit (3 bands, degrees (8, 6) on a 13 x 10 grid, Preetham over theta in [0, 60 deg],
// T in [2.5, 6], projections to 1e-5) that the test suite can afford; docs/SH.md has the full
// study.
inline fit::ShFitSettings small_sh_fit_settings() {
  fit::ShFitSettings s;
  s.polynomial.bands = 3;
  s.polynomial.degree_theta = 8;
  s.polynomial.degree_tau = 6;
  s.polynomial.grid_theta = 13;
  s.polynomial.grid_tau = 10;
  s.polynomial.theta_max = deg_to_rad(60.0);
  s.projection.tolerance = 1e-5;
  return s;
}

// The table of small_sh_fit_settings(), fitted once per process.
inline const sh::PolynomialTable& small_sh_fit_table() {
  static const sh::PolynomialTable t = fit::fit_sh_table(small_sh_fit_settings());
  return t;
}

}  // namespace skylight::testing_support
