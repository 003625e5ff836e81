// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/models/perez_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include "skylight/models/detail/sky_kernel-inl.h"

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/models/perez_kernel.h"

// Single-precision parameters of one batch call (defined once, outside the per-target namespace).
#ifndef SKYLIGHT_PEREZ_BATCH_PARAMS_DEFINED
#define SKYLIGHT_PEREZ_BATCH_PARAMS_DEFINED
namespace skylight::detail {
struct PerezBatchParams {
  bool xyY;
  float A[3], B[3], C[3], D[3], E[3], K[3], scale[3];
  float white_x_over_y, white_z_over_y;
  float sx, sy, sz;
};
}  // namespace skylight::detail
#endif

HWY_BEFORE_NAMESPACE();
namespace skylight {
namespace HWY_NAMESPACE {
using BatchParams = detail::PerezBatchParams;

template <class DF, class V>
HWY_INLINE V PerezF(DF d, const BatchParams& p, int c, V inv_cos_theta, V gamma, V cos2_gamma) {
  const V max_exp = hn::Set(d, static_cast<float>(kPerezMaxExponent));
  const V min_exp = hn::Neg(max_exp);
  const V one = hn::Set(d, 1.0f);
  const V grad_arg = hn::Min(max_exp, hn::Max(min_exp, hn::Mul(hn::Set(d, p.B[c]), inv_cos_theta)));
  const V gradation = hn::MulAdd(hn::Set(d, p.A[c]), hn::Exp(d, grad_arg), one);
  const V ind_arg = hn::Min(max_exp, hn::Max(min_exp, hn::Mul(hn::Set(d, p.D[c]), gamma)));
  const V indicatrix =
      hn::MulAdd(hn::Set(d, p.E[c]), cos2_gamma,
                 hn::MulAdd(hn::Set(d, p.C[c]), hn::Exp(d, ind_arg), hn::Set(d, p.K[c])));
  return hn::Mul(hn::Mul(hn::Set(d, p.scale[c]), gradation), indicatrix);
}

void PerezBatchImpl(const BatchParams& p, const float* HWY_RESTRICT px,
                    const float* HWY_RESTRICT py, const float* HWY_RESTRICT pz,
                    float* HWY_RESTRICT oX, float* HWY_RESTRICT oY, float* HWY_RESTRICT oZ,
                    size_t n) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const V zero = hn::Zero(d);
  const V one = hn::Set(d, 1.0f);
  const V sx = hn::Set(d, p.sx), sy = hn::Set(d, p.sy), sz = hn::Set(d, p.sz);
  const V min_cos = hn::Set(d, static_cast<float>(kPerezMinCosTheta));

  auto process = [&](const float* x_in, const float* y_in, const float* z_in, float* X_out,
                     float* Y_out, float* Z_out) {
    const V x = hn::LoadU(d, x_in), y = hn::LoadU(d, y_in), z = hn::LoadU(d, z_in);
    const auto above = hn::Ge(z, zero);
    const V inv_cos_theta = hn::Div(one, hn::Max(z, min_cos));
    const V cos_gamma = hn::MulAdd(x, sx, hn::MulAdd(y, sy, hn::Mul(z, sz)));
    const V gamma = AngleToSun(d, x, y, z, sx, sy, sz, cos_gamma).gamma;
    const V cos2_gamma = hn::Mul(cos_gamma, cos_gamma);

    const V Y = hn::Max(zero, PerezF(d, p, 0, inv_cos_theta, gamma, cos2_gamma));
    V X, Z;
    if (p.xyY) {
      const V cx = PerezF(d, p, 1, inv_cos_theta, gamma, cos2_gamma);
      const V cy = PerezF(d, p, 2, inv_cos_theta, gamma, cos2_gamma);
      const auto valid = hn::Gt(cy, zero);
      const V Y_over_y = hn::IfThenElseZero(valid, hn::Div(Y, hn::IfThenElse(valid, cy, one)));
      X = hn::Mul(cx, Y_over_y);
      Z = hn::Mul(hn::Sub(hn::Sub(one, cx), cy), Y_over_y);
    } else {
      X = hn::Mul(hn::Set(d, p.white_x_over_y), Y);
      Z = hn::Mul(hn::Set(d, p.white_z_over_y), Y);
    }
    hn::StoreU(hn::IfThenElseZero(above, X), d, X_out);
    hn::StoreU(hn::IfThenElseZero(above, Y), d, Y_out);
    hn::StoreU(hn::IfThenElseZero(above, Z), d, Z_out);
  };

  ForEachDirectionVector(d, px, py, pz, oX, oY, oZ, n, process);
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight {

HWY_EXPORT(PerezBatchImpl);

double perez_function(const PerezCoefficients& c, double cos_theta, double gamma) {
  const double inv_cos = 1.0 / std::max(cos_theta, kPerezMinCosTheta);
  const double grad_arg = std::clamp(c.B * inv_cos, -kPerezMaxExponent, kPerezMaxExponent);
  const double ind_arg = std::clamp(c.D * gamma, -kPerezMaxExponent, kPerezMaxExponent);
  const double cos_gamma = std::cos(gamma);
  return (1.0 + c.A * std::exp(grad_arg)) *
         (c.K + c.C * std::exp(ind_arg) + c.E * cos_gamma * cos_gamma);
}

Xyz PerezDistribution::evaluate(Vec3 view) const {
  if (view.z < 0.0) return {};
  const double gamma = angle_between(view, sun);
  const double Y = std::max(0.0, scale[0] * perez_function(coefficients[0], view.z, gamma));
  if (mode == Mode::luminance) return xyY_to_xyz(white, Y);
  const double x = scale[1] * perez_function(coefficients[1], view.z, gamma);
  const double y = scale[2] * perez_function(coefficients[2], view.z, gamma);
  if (!(y > 0.0)) return {};
  return {x * Y / y, Y, (1.0 - x - y) * Y / y};
}

void PerezDistribution::evaluate_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  SKYLIGHT_CHECK(dirs.y.size() == dirs.size() && dirs.z.size() == dirs.size() &&
                     out.size() == dirs.size() && out.Y.size() == dirs.size() &&
                     out.Z.size() == dirs.size(),
                 "evaluate_batch: span sizes differ");
  detail::PerezBatchParams p{};
  p.xyY = mode == Mode::xyY;
  for (int c = 0; c < 3; ++c) {
    p.A[c] = static_cast<float>(coefficients[c].A);
    p.B[c] = static_cast<float>(coefficients[c].B);
    p.C[c] = static_cast<float>(coefficients[c].C);
    p.D[c] = static_cast<float>(coefficients[c].D);
    p.E[c] = static_cast<float>(coefficients[c].E);
    p.K[c] = static_cast<float>(coefficients[c].K);
    p.scale[c] = static_cast<float>(scale[c]);
  }
  const Xyz w = xyY_to_xyz(white, 1.0);
  p.white_x_over_y = static_cast<float>(w.X);
  p.white_z_over_y = static_cast<float>(w.Z);
  p.sx = static_cast<float>(sun.x);
  p.sy = static_cast<float>(sun.y);
  p.sz = static_cast<float>(sun.z);
  HWY_DYNAMIC_DISPATCH(PerezBatchImpl)
  (p, dirs.x.data(), dirs.y.data(), dirs.z.data(), out.X.data(), out.Y.data(), out.Z.data(),
   dirs.size());
}

}  // namespace skylight
#endif  // HWY_ONCE
