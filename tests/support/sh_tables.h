// Test helper: a synthetic SH polynomial table (deterministic pseudo-random coefficients,
// SplitMix64) for tests of evaluation, reconstruction and export that need no fit.
#pragma once

#include <cstdint>

#include "skylight/core/math.h"
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

}  // namespace skylight::testing_support
