// The Hosek-Wilkie batch kernel: F * L_M of hosek_wilkie.h for three channels over many
// directions, single precision SIMD (Highway, dynamic dispatch), see hosek_kernel.cpp.
#pragma once

#include <cstddef>

namespace skylight::detail {

// Per-state parameters of the kernel (the double state rounded to float once per call).
struct HosekBatchParams {
  // Per channel: A..I of the extended Perez form, (1 - H)^2, and the output scale (683 L_M).
  float A[3], B[3], C[3], D[3], E[3], F[3], G[3], H[3], I[3], one_minus_H_sq[3], scale[3];
  float sx, sy, sz;  // sun direction (unit, ENU)
};

// out_c[i] = max(0, scale_c F_c(dir i)) for z >= 0, 0 below the horizon.
void hosek_batch(const HosekBatchParams& p, const float* x, const float* y, const float* z,
                 float* out0, float* out1, float* out2, std::size_t n);

}  // namespace skylight::detail
