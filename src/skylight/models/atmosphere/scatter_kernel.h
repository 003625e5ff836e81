// The per-sample spectral inner loop of the fast single-scattering path (atmosphere.cpp), in
// single-precision SIMD (Highway, dynamic dispatch), see scatter_kernel.cpp. Float suffices: the
// optical depths stay below ~100, so the exponent's rounding error (1e-7 relative) changes T by
// < 1e-5 relative, and each pixel sums at most a few dozen samples.
#pragma once

#include <cstddef>

namespace skylight::atmosphere::detail {

// For every wavelength l < nl and component i < nc:
//   T_l = exp(-sum_j extinction[j * nl + l] * t[j]),   acc[i * nl + l] += rho[i] * T_l
// (the transmittance of one sample along sun and view paths, and its in-scattering weight).
// nl must be a multiple of 16 (rows zero-padded).
void accumulate_in_scatter(const float* extinction, const float* t, const float* rho,
                           std::size_t nc, std::size_t nl, float* acc);

}  // namespace skylight::atmosphere::detail
