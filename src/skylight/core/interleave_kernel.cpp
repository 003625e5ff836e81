// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/core/interleave_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/highway.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "skylight/core/interleave.h"

HWY_BEFORE_NAMESPACE();
namespace skylight {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Rows one by one from `i` until rows + 3 i lies on a boundary of `bytes` (rows are 24 bytes, so
// within 8 rows when the array is 8-byte aligned); returns the next row. Vector loads and stores
// that straddle two cache lines cost twice (for float64 rows at numpy's 16-byte alignment, half
// the conversion's time on AVX-512).
template <class RowFn>
std::size_t AlignRows(const double* rows, std::size_t i, std::size_t n, std::size_t bytes,
                      const RowFn& row) {
  for (std::size_t k = 0; k < 8 && i < n; ++k, ++i)
    if (reinterpret_cast<std::uintptr_t>(rows + 3 * i) % bytes == 0)
      break;
    else
      row(i);
  return i;
}

// One pass checks the squared lengths (positive, finite, and whether all are 1) and converts; a
// second, scaling, only when some row is not a unit vector (over the rows the first left in cache
// for the caller's chunk sizes).
bool DirectionsToSoaImpl(const double* HWY_RESTRICT rows, std::size_t n, float* HWY_RESTRICT x,
                         float* HWY_RESTRICT y, float* HWY_RESTRICT z) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V inf = hn::Set(d, std::numeric_limits<double>::infinity());
  const V tolerance = hn::Set(d, kUnitLengthTolerance);
  bool all_ok = true, all_unit = true;
  const auto scalar_row = [&](std::size_t j) {
    const double* r = rows + 3 * j;
    const double l2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    all_ok &= (l2 > 0.0) & (l2 < std::numeric_limits<double>::infinity());
    all_unit &= std::abs(l2 - 1.0) <= kUnitLengthTolerance;
    x[j] = static_cast<float>(r[0]);
    y[j] = static_cast<float>(r[1]);
    z[j] = static_cast<float>(r[2]);
  };
  std::size_t i = AlignRows(rows, 0, n, lanes * sizeof(double), scalar_row);
  auto ok = hn::FirstN(d, lanes);  // all true
  auto unit = ok;
  for (; i + lanes <= n; i += lanes) {
    V vx, vy, vz;
    hn::LoadInterleaved3(d, rows + 3 * i, vx, vy, vz);
    const V l2 = hn::MulAdd(vx, vx, hn::MulAdd(vy, vy, hn::Mul(vz, vz)));
    ok = hn::And(ok, hn::And(hn::Gt(l2, zero), hn::Lt(l2, inf)));
    unit = hn::And(unit, hn::Le(hn::Abs(hn::Sub(l2, one)), tolerance));
    hn::StoreU(hn::DemoteTo(df, vx), df, x + i);
    hn::StoreU(hn::DemoteTo(df, vy), df, y + i);
    hn::StoreU(hn::DemoteTo(df, vz), df, z + i);
  }
  for (; i < n; ++i) scalar_row(i);
  all_ok &= hn::AllTrue(d, ok);
  all_unit &= hn::AllTrue(d, unit);
  if (!all_ok) return false;
  if (all_unit) return true;
  const auto scaled_row = [&](std::size_t j) {
    const double* r = rows + 3 * j;
    const double inv = 1.0 / std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    x[j] = static_cast<float>(r[0] * inv);
    y[j] = static_cast<float>(r[1] * inv);
    z[j] = static_cast<float>(r[2] * inv);
  };
  i = AlignRows(rows, 0, n, lanes * sizeof(double), scaled_row);
  for (; i + lanes <= n; i += lanes) {
    V vx, vy, vz;
    hn::LoadInterleaved3(d, rows + 3 * i, vx, vy, vz);
    const V inv = hn::Div(one, hn::Sqrt(hn::MulAdd(vx, vx, hn::MulAdd(vy, vy, hn::Mul(vz, vz)))));
    hn::StoreU(hn::DemoteTo(df, hn::Mul(vx, inv)), df, x + i);
    hn::StoreU(hn::DemoteTo(df, hn::Mul(vy, inv)), df, y + i);
    hn::StoreU(hn::DemoteTo(df, hn::Mul(vz, inv)), df, z + i);
  }
  for (; i < n; ++i) scaled_row(i);
  return true;
}

bool SoaToRowsImpl(const float* HWY_RESTRICT a, const float* HWY_RESTRICT b,
                   const float* HWY_RESTRICT c, std::size_t n, double* HWY_RESTRICT rows) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const std::size_t lanes = hn::Lanes(d);
  const auto max = hn::Set(df, std::numeric_limits<float>::max());
  bool all = true;
  const auto scalar_row = [&](std::size_t k) {
    all &= std::isfinite(a[k]) & std::isfinite(b[k]) & std::isfinite(c[k]);
    rows[3 * k] = a[k];
    rows[3 * k + 1] = b[k];
    rows[3 * k + 2] = c[k];
  };
  std::size_t i = AlignRows(rows, 0, n, lanes * sizeof(double), scalar_row);
  auto finite = hn::FirstN(df, lanes);
  for (; i + lanes <= n; i += lanes) {
    const auto fa = hn::LoadU(df, a + i), fb = hn::LoadU(df, b + i), fc = hn::LoadU(df, c + i);
    // |v| <= FLT_MAX is false for NaN and Inf.
    finite = hn::And(finite, hn::And(hn::Le(hn::Abs(fa), max),
                                     hn::And(hn::Le(hn::Abs(fb), max), hn::Le(hn::Abs(fc), max))));
    hn::StoreInterleaved3(hn::PromoteTo(d, fa), hn::PromoteTo(d, fb), hn::PromoteTo(d, fc), d,
                          rows + 3 * i);
  }
  for (; i < n; ++i) scalar_row(i);
  return all && hn::AllTrue(df, finite);
}

bool WidenImpl(const float* HWY_RESTRICT a, std::size_t n, double* HWY_RESTRICT out) {
  const hn::ScalableTag<double> d;
  const hn::Rebind<float, decltype(d)> df;
  const std::size_t lanes = hn::Lanes(d);
  const auto max = hn::Set(df, std::numeric_limits<float>::max());
  auto finite = hn::FirstN(df, lanes);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) {
    const auto fa = hn::LoadU(df, a + i);
    finite = hn::And(finite, hn::Le(hn::Abs(fa), max));
    hn::StoreU(hn::PromoteTo(d, fa), d, out + i);
  }
  bool all = hn::AllTrue(df, finite);
  for (; i < n; ++i) {
    all &= std::isfinite(a[i]);
    out[i] = a[i];
  }
  return all;
}

bool UnitSoaImpl(const float* HWY_RESTRICT x, const float* HWY_RESTRICT y,
                 const float* HWY_RESTRICT z, std::size_t n) {
  const hn::ScalableTag<float> d;
  const std::size_t lanes = hn::Lanes(d);
  const auto one = hn::Set(d, 1.0f);
  const auto tolerance = hn::Set(d, kFloatUnitLengthTolerance);
  auto unit = hn::FirstN(d, lanes);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) {
    const auto vx = hn::LoadU(d, x + i), vy = hn::LoadU(d, y + i), vz = hn::LoadU(d, z + i);
    const auto l2 = hn::MulAdd(vx, vx, hn::MulAdd(vy, vy, hn::Mul(vz, vz)));
    // False for NaN (and for Inf, whose l2 is Inf).
    unit = hn::And(unit, hn::Le(hn::Abs(hn::Sub(l2, one)), tolerance));
  }
  bool all = hn::AllTrue(d, unit);
  for (; i < n; ++i)
    all &= std::abs(x[i] * x[i] + y[i] * y[i] + z[i] * z[i] - 1.0f) <= kFloatUnitLengthTolerance;
  return all;
}

bool FiniteImpl(const float* HWY_RESTRICT a, std::size_t n) {
  const hn::ScalableTag<float> d;
  const std::size_t lanes = hn::Lanes(d);
  const auto max = hn::Set(d, std::numeric_limits<float>::max());
  auto finite = hn::FirstN(d, lanes);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes)
    finite = hn::And(finite, hn::Le(hn::Abs(hn::LoadU(d, a + i)), max));
  bool all = hn::AllTrue(d, finite);
  for (; i < n; ++i) all &= std::isfinite(a[i]);
  return all;
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight {

HWY_EXPORT(DirectionsToSoaImpl);
HWY_EXPORT(SoaToRowsImpl);
HWY_EXPORT(WidenImpl);
HWY_EXPORT(UnitSoaImpl);
HWY_EXPORT(FiniteImpl);

bool directions_to_soa(const double* rows, std::size_t n, float* x, float* y, float* z) {
  return HWY_DYNAMIC_DISPATCH(DirectionsToSoaImpl)(rows, n, x, y, z);
}

bool soa_to_rows(const float* a, const float* b, const float* c, std::size_t n, double* rows) {
  return HWY_DYNAMIC_DISPATCH(SoaToRowsImpl)(a, b, c, n, rows);
}

bool widen(const float* a, std::size_t n, double* out) {
  return HWY_DYNAMIC_DISPATCH(WidenImpl)(a, n, out);
}

bool unit_soa(const float* x, const float* y, const float* z, std::size_t n) {
  return HWY_DYNAMIC_DISPATCH(UnitSoaImpl)(x, y, z, n);
}

bool all_finite(const float* a, std::size_t n) {
  return HWY_DYNAMIC_DISPATCH(FiniteImpl)(a, n);
}

}  // namespace skylight
#endif  // HWY_ONCE
