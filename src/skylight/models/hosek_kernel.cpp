// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/models/hosek_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include "skylight/core/math.h"
#include "skylight/models/detail/hosek_kernel.h"
#include "skylight/models/detail/sky_kernel-inl.h"

#ifndef SKYLIGHT_HOSEK_KERNEL_CONSTANTS
#define SKYLIGHT_HOSEK_KERNEL_CONSTANTS
namespace skylight::detail {
// v1.4a's offset in B / (cos theta + 0.01) (Hosek & Wilkie 2012 eq. 9).
inline constexpr float kHosekCosThetaOffset = 0.01f;
// exp() arguments are clamped to [-80, 80] (e^80 ~ 5.5e34 fits in float): B / (cos theta + 0.01)
// reaches 100 B at the horizon, and E gamma stays below 10 pi for every published state.
inline constexpr float kHosekMaxExponent = 80.0f;
}  // namespace skylight::detail
#endif

HWY_BEFORE_NAMESPACE();
namespace skylight {
namespace HWY_NAMESPACE {

void HosekBatchImpl(const detail::HosekBatchParams& p, const float* HWY_RESTRICT px,
                    const float* HWY_RESTRICT py, const float* HWY_RESTRICT pz,
                    float* HWY_RESTRICT o0, float* HWY_RESTRICT o1, float* HWY_RESTRICT o2,
                    size_t n) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const V zero = hn::Zero(d);
  const V one = hn::Set(d, 1.0f);
  const V offset = hn::Set(d, detail::kHosekCosThetaOffset);
  const V max_exp = hn::Set(d, detail::kHosekMaxExponent);
  const V min_exp = hn::Neg(max_exp);
  const V sx = hn::Set(d, p.sx), sy = hn::Set(d, p.sy), sz = hn::Set(d, p.sz);

  auto process = [&](const float* x_in, const float* y_in, const float* z_in, float* out0,
                     float* out1, float* out2) {
    const V x = hn::LoadU(d, x_in), y = hn::LoadU(d, y_in), z = hn::LoadU(d, z_in);
    const auto above = hn::Ge(z, zero);
    const V cos_theta = hn::Min(one, hn::Max(z, zero));
    const V inv_cos = hn::Div(one, hn::Add(cos_theta, offset));
    const V zenith = hn::Sqrt(cos_theta);
    const V cos_gamma = hn::MulAdd(x, sx, hn::MulAdd(y, sy, hn::Mul(z, sz)));
    // gamma, and |v - s|^2 = 2 (1 - cos gamma) for chi below.
    const auto angle = AngleToSun(d, x, y, z, sx, sy, sz, cos_gamma);
    const V gamma = angle.gamma, chord2_minus = angle.chord2_minus;
    const V cos2_gamma = hn::Mul(cos_gamma, cos_gamma);
    const V mie_num = hn::Add(one, cos2_gamma);

    auto channel = [&](int c) {
      // chi: 1 + H^2 - 2 H cos gamma = (1 - H)^2 + H |v - s|^2.
      const V den = hn::MulAdd(hn::Set(d, p.H[c]), chord2_minus, hn::Set(d, p.one_minus_H_sq[c]));
      const V mie = hn::Div(mie_num, hn::Mul(den, hn::Sqrt(den)));
      const V e_arg = hn::Min(max_exp, hn::Max(min_exp, hn::Mul(hn::Set(d, p.E[c]), gamma)));
      const V b_arg = hn::Min(max_exp, hn::Max(min_exp, hn::Mul(hn::Set(d, p.B[c]), inv_cos)));
      const V gradation = hn::MulAdd(hn::Set(d, p.A[c]), hn::Exp(d, b_arg), one);
      V ind = hn::MulAdd(hn::Set(d, p.D[c]), hn::Exp(d, e_arg), hn::Set(d, p.C[c]));
      ind = hn::MulAdd(hn::Set(d, p.F[c]), cos2_gamma, ind);
      ind = hn::MulAdd(hn::Set(d, p.G[c]), mie, ind);
      ind = hn::MulAdd(hn::Set(d, p.I[c]), zenith, ind);
      // Clamped at 0 like the scalar path (the fit dips below 0 at the horizon for low suns).
      const V value = hn::Mul(hn::Mul(hn::Set(d, p.scale[c]), gradation), ind);
      return hn::IfThenElseZero(above, hn::Max(zero, value));
    };
    hn::StoreU(channel(0), d, out0);
    hn::StoreU(channel(1), d, out1);
    hn::StoreU(channel(2), d, out2);
  };

  ForEachDirectionVector(d, px, py, pz, o0, o1, o2, n, process);
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight {

HWY_EXPORT(HosekBatchImpl);

void detail::hosek_batch(const HosekBatchParams& p, const float* x, const float* y, const float* z,
                         float* out0, float* out1, float* out2, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(HosekBatchImpl)(p, x, y, z, out0, out1, out2, n);
}

}  // namespace skylight
#endif  // HWY_ONCE
