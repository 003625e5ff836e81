// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/models/atmosphere/scatter_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <cmath>
//
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include "skylight/models/atmosphere/scatter_kernel.h"

HWY_BEFORE_NAMESPACE();
namespace skylight::atmosphere {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void AccumulateInScatterImpl(const float* HWY_RESTRICT extinction, const float* HWY_RESTRICT t,
                             const float* HWY_RESTRICT rho, size_t nc, size_t nl,
                             float* HWY_RESTRICT acc) {
  const hn::ScalableTag<float> d;
  const size_t N = hn::Lanes(d);
  size_t l = 0;
  for (; l + N <= nl; l += N) {
    auto tau = hn::Zero(d);
    for (size_t i = 0; i < nc; ++i)
      tau = hn::MulAdd(hn::LoadU(d, extinction + i * nl + l), hn::Set(d, t[i]), tau);
    const auto T = hn::Exp(d, hn::Neg(tau));
    for (size_t i = 0; i < nc; ++i) {
      float* a = acc + i * nl + l;
      hn::StoreU(hn::MulAdd(hn::Set(d, rho[i]), T, hn::LoadU(d, a)), d, a);
    }
  }
  for (; l < nl; ++l) {  // the remainder (fewer than one vector of wavelengths)
    float tau = 0.0f;
    for (size_t i = 0; i < nc; ++i) tau += extinction[i * nl + l] * t[i];
    const float T = std::exp(-tau);
    for (size_t i = 0; i < nc; ++i) acc[i * nl + l] += rho[i] * T;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight::atmosphere
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight::atmosphere {

HWY_EXPORT(AccumulateInScatterImpl);

void detail::accumulate_in_scatter(const float* extinction, const float* t, const float* rho,
                                   std::size_t nc, std::size_t nl, float* acc) {
  HWY_DYNAMIC_DISPATCH(AccumulateInScatterImpl)(extinction, t, rho, nc, nl, acc);
}

}  // namespace skylight::atmosphere
#endif  // HWY_ONCE
