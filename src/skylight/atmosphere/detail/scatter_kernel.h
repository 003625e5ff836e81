// The per-piece inner loops of the fast single-scattering path (atmosphere.cpp) in SIMD (Highway,
// dynamic dispatch), see scatter_kernel.cpp: the samples of one lit piece of a view ray are
// processed together — their geometry in double precision, their table lookups (gathers) and
// densities in single precision — and each sample's transmittance exp(-tau) over all wavelengths
// in single precision. Float suffices: the optical depths stay below ~100, so the exponent's
// rounding error (1e-7 relative) changes T by < 1e-5 relative, and each pixel sums at most a few
// dozen samples; altitudes are formed in double before rounding to float.
#pragma once

#include <cstddef>

namespace skylight::atmosphere::detail {

// One component's optical-length table L[row][col] (row = level, col = sqrt(mu) cell) and level
// coordinate, as Atmosphere builds them.
struct KernelTable {
  const float* data = nullptr;
  int rows = 0, cols = 0;
  bool exponential = true;  // level x = exp(-h inv_height) (= density) or 1 - h inv_height (tent)
  float inv_height = 0;     // [m^-1]
  float coord_top = 0, coord_scale = 0;  // fractional row = (x - coord_top) * coord_scale
  float peak = 0, inv_half_width = 0;    // tent density max(0, 1 - |h - peak| inv_half_width)
};

// A piece has at most kMaxPieceSamples samples; arrays s and w must hold n + kSamplePadding
// values, the padding lanes a finite s and w = 0. All tables have the same number of columns.
inline constexpr std::size_t kMaxPieceSamples = 64;
inline constexpr std::size_t kSamplePadding = 16;

// The samples q_k = p + s[k] view (k < n) of one lit piece of a view ray and their quadrature
// weights w[k] [m], with the ray's invariants.
struct PieceSamples {
  const double* s = nullptr;
  const double* w = nullptr;
  std::size_t n = 0;
  double pp = 0, pv = 0, ps = 0, vs = 0;  // |p|^2, p.view, p.sun, view.sun  (p in planet frame)
  double ground_radius = 0;
  // The ray ends on the ground: the view optical length of a sample is L(q, -view) - t0 (upward
  // rays); otherwise t0 - L(q, view).
  bool hits_ground = false;
};

// For every sample k not in the planet's shadow, with per-component optical lengths
// t_j = view part (from t0, the optical lengths at the start of the ray) + L(q_k, sun), adds
//   acc[i * nl + l] += w_k rho_i(q_k) exp(-sum_j extinction[j * nl + l] t_j)
// for components i < nc and wavelengths l < nl (nl a multiple of 4; zero-padded rows).
void scatter_piece(const KernelTable* tables, std::size_t nc, const float* t0,
                   const PieceSamples& samples, const float* extinction, std::size_t nl,
                   float* acc);

}  // namespace skylight::atmosphere::detail
