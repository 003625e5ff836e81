// Per-target helpers shared by the Highway SIMD sky kernels (perez_kernel.cpp, hosek_kernel.cpp).
// Highway "-inl.h" convention: re-included once per SIMD target by foreach_target.h, hence the
// toggle guard instead of #pragma once.
#if defined(SKYLIGHT_MODELS_SKY_KERNEL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SKYLIGHT_MODELS_SKY_KERNEL_INL_H_
#undef SKYLIGHT_MODELS_SKY_KERNEL_INL_H_
#else
#define SKYLIGHT_MODELS_SKY_KERNEL_INL_H_
#endif

#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include "skylight/core/math.h"

HWY_BEFORE_NAMESPACE();
namespace skylight {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Angle gamma between unit view vectors (x, y, z) and the sun (sx, sy, sz), well conditioned
// everywhere: 2 asin(|v - s| / 2) up to pi/2 and pi - 2 asin(|v + s| / 2) beyond (acos(v.s) in
// float loses half its digits near the sun, exactly where the aureole is).
// Also returns |v - s|^2 = 2 (1 - cos gamma) without the cancellation of 1 - v.s.
template <class D, class V = hn::Vec<D>>
struct SunAngle {
  V gamma;
  V chord2_minus;
};
template <class D, class V = hn::Vec<D>>
HWY_INLINE SunAngle<D> AngleToSun(D d, V x, V y, V z, V sx, V sy, V sz, V cos_gamma) {
  const V one = hn::Set(d, 1.0f);
  const V dx = hn::Sub(x, sx), dy = hn::Sub(y, sy), dz = hn::Sub(z, sz);
  const V ax = hn::Add(x, sx), ay = hn::Add(y, sy), az = hn::Add(z, sz);
  const V chord2_minus = hn::MulAdd(dx, dx, hn::MulAdd(dy, dy, hn::Mul(dz, dz)));
  const V chord2_plus = hn::MulAdd(ax, ax, hn::MulAdd(ay, ay, hn::Mul(az, az)));
  const auto near_side = hn::Ge(cos_gamma, hn::Zero(d));
  const V half_chord = hn::Min(
      one,
      hn::Mul(hn::Set(d, 0.5f), hn::Sqrt(hn::IfThenElse(near_side, chord2_minus, chord2_plus))));
  const V a = hn::Mul(hn::Set(d, 2.0f), hn::Asin(d, half_chord));
  return {hn::IfThenElse(near_side, a, hn::Sub(hn::Set(d, static_cast<float>(kPi)), a)),
          chord2_minus};
}

// Calls process(x, y, z, out0, out1, out2) on every full vector of n directions (structure of
// arrays), then once on a padded copy of the tail (padding: the zenith direction), writing back
// only the real results.
template <class D, class Process>
HWY_INLINE void ForEachDirectionVector(D d, const float* HWY_RESTRICT px,
                                       const float* HWY_RESTRICT py, const float* HWY_RESTRICT pz,
                                       float* HWY_RESTRICT o0, float* HWY_RESTRICT o1,
                                       float* HWY_RESTRICT o2, size_t n, const Process& process) {
  const size_t N = hn::Lanes(d);
  size_t i = 0;
  for (; i + N <= n; i += N) process(px + i, py + i, pz + i, o0 + i, o1 + i, o2 + i);
  if (i == n) return;
  HWY_ALIGN float bx[hn::MaxLanes(d)], by[hn::MaxLanes(d)], bz[hn::MaxLanes(d)];
  HWY_ALIGN float r0[hn::MaxLanes(d)], r1[hn::MaxLanes(d)], r2[hn::MaxLanes(d)];
  for (size_t k = 0; k < N; ++k) {
    const bool real = i + k < n;
    bx[k] = real ? px[i + k] : 0.0f;
    by[k] = real ? py[i + k] : 0.0f;
    bz[k] = real ? pz[i + k] : 1.0f;
  }
  process(bx, by, bz, r0, r1, r2);
  for (size_t k = 0; i + k < n; ++k) {
    o0[i + k] = r0[k];
    o1[i + k] = r1[k];
    o2[i + k] = r2[k];
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight
HWY_AFTER_NAMESPACE();

#endif  // toggle guard
