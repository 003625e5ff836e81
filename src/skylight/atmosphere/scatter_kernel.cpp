// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/atmosphere/scatter_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <algorithm>
#include <cmath>
#include <cstring>
//
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include "skylight/atmosphere/atmosphere.h"
#include "skylight/atmosphere/detail/scatter_kernel.h"

HWY_BEFORE_NAMESPACE();
namespace skylight::atmosphere {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// acc[i * nl + l] += rho[i] exp(-sum_j extinction[j * nl + l] t[j]) for l in [l, nl) in steps of
// the vector width of d; returns the first wavelength not done.
template <class D>
HWY_INLINE size_t AccumulateLanes(D d, size_t l, const float* HWY_RESTRICT extinction,
                                  const float* HWY_RESTRICT t, const float* HWY_RESTRICT rho,
                                  size_t nc, size_t nl, float* HWY_RESTRICT acc) {
  const size_t N = hn::Lanes(d);
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
  return l;
}

// One sample's contribution over all wavelengths: full vectors, then 8- and 4-lane vectors for
// the rest (20 wavelengths = 16 + 4 on AVX-512 rather than 2 x 16), then scalar.
HWY_INLINE void AccumulateSample(const float* HWY_RESTRICT extinction, const float* t,
                                 const float* rho, size_t nc, size_t nl, float* HWY_RESTRICT acc) {
  size_t l = AccumulateLanes(hn::ScalableTag<float>(), 0, extinction, t, rho, nc, nl, acc);
  l = AccumulateLanes(hn::CappedTag<float, 8>(), l, extinction, t, rho, nc, nl, acc);
  l = AccumulateLanes(hn::CappedTag<float, 4>(), l, extinction, t, rho, nc, nl, acc);
  for (; l < nl; ++l) {
    float tau = 0.0f;
    for (size_t i = 0; i < nc; ++i) tau += extinction[i * nl + l] * t[i];
    const float T = std::exp(-tau);
    for (size_t i = 0; i < nc; ++i) acc[i * nl + l] += rho[i] * T;
  }
}

// Level coordinate of altitude h (scatter_kernel.h, KernelTable).
template <class DF, class V>
HWY_INLINE V Level(DF df, const detail::KernelTable& t, V h) {
  if (t.exponential) return hn::Exp(df, hn::Mul(h, hn::Set(df, -t.inv_height)));
  return hn::NegMulAdd(h, hn::Set(df, t.inv_height), hn::Set(df, 1.0f));
}

// Table row of level x: integer row (clamped to [0, rows - 2]) and the fraction in it.
template <class DF, class V>
HWY_INLINE V Row(DF df, const detail::KernelTable& t, V x, V& frac) {
  const hn::Rebind<int32_t, DF> di;
  const V fx =
      hn::Min(hn::Max(hn::Mul(hn::Sub(x, hn::Set(df, t.coord_top)), hn::Set(df, t.coord_scale)),
                      hn::Zero(df)),
              hn::Set(df, static_cast<float>(t.rows - 1)));
  const V ix = hn::ConvertTo(df, hn::Min(hn::ConvertTo(di, fx), hn::Set(di, t.rows - 2)));
  frac = hn::Sub(fx, ix);
  return ix;
}

// Gather of the first `valid` lanes by scalar loads (the other lanes keep scratch's values): on
// AMD Zen 4 (this project's machines) the AVX2/AVX-512 gathers of 32-bit elements are slower
// than the same number of scalar loads. scratch holds Lanes(df) floats.
template <class DF, class VI>
HWY_INLINE hn::Vec<DF> Gather(DF df, const float* HWY_RESTRICT base, VI index, size_t valid,
                              float* HWY_RESTRICT scratch) {
  const hn::Rebind<int32_t, DF> di;
  alignas(64) int32_t idx[HWY_MAX_BYTES / sizeof(float)];
  hn::Store(index, di, idx);
  for (size_t k = 0; k < valid; ++k) scratch[k] = base[idx[k]];
  return hn::Load(df, scratch);
}

// Gather of adjacent pairs (base[index], base[index + 1]) of the first `valid` lanes by 64-bit
// scalar loads: half the loads of two Gather calls. scratch holds 2 Lanes(df) floats.
template <class DF, class VI>
HWY_INLINE void GatherPair(DF df, const float* HWY_RESTRICT base, VI index, size_t valid,
                           float* HWY_RESTRICT scratch, hn::Vec<DF>& first, hn::Vec<DF>& second) {
  const hn::Rebind<int32_t, DF> di;
  alignas(64) int32_t idx[HWY_MAX_BYTES / sizeof(float)];
  hn::Store(index, di, idx);
  for (size_t k = 0; k < valid; ++k) std::memcpy(scratch + 2 * k, base + idx[k], 2 * sizeof(float));
  hn::LoadInterleaved2(df, scratch, first, second);
}

// A direction's column coordinate (shared by all components): cell iy (as float), fraction ay,
// and which lanes point below the horizontal (reflection rule).
template <class DF>
struct MuCell {
  hn::Vec<DF> iy, ay;
  hn::Mask<DF> below;
  bool any_below;
};
template <class DF>
HWY_INLINE MuCell<DF> MakeMuCell(DF df, int cols, hn::Vec<DF> mu) {
  const hn::Rebind<int32_t, DF> di;
  const auto fy =
      hn::Mul(hn::Sqrt(hn::Min(hn::Abs(mu), hn::Set(df, 1.0f))), hn::Set(df, cols - 1.0f));
  const auto iy = hn::ConvertTo(df, hn::Min(hn::ConvertTo(di, fy), hn::Set(di, cols - 2)));
  const auto below = hn::Lt(mu, hn::Zero(df));
  return {iy, hn::Sub(fy, iy), below, !hn::AllFalse(df, below)};
}

// Optical length L[x, |mu|] by bilinear lookup, with Pietras eq. 8 (2 L[x_t, 0] - L[x, |mu|])
// in the lanes with mu < 0, x_t the level of the tangent altitude ht.
template <class DF, class V>
HWY_INLINE V OpticalLength(DF df, const detail::KernelTable& t, V ix, V ax, const MuCell<DF>& mu,
                           V ht, size_t valid, float* scratch, float* scratch2) {
  const hn::Rebind<int32_t, DF> di;
  const V cols = hn::Set(df, static_cast<float>(t.cols));
  const auto i00 = hn::ConvertTo(di, hn::MulAdd(ix, cols, mu.iy));
  const auto i10 = hn::Add(i00, hn::Set(di, t.cols));
  const float* d0 = t.data;
  V g00, g01, g10, g11;
  GatherPair(df, d0, i00, valid, scratch2, g00, g01);
  GatherPair(df, d0, i10, valid, scratch2, g10, g11);
  const V r0 = hn::MulAdd(mu.ay, hn::Sub(g01, g00), g00);
  const V r1 = hn::MulAdd(mu.ay, hn::Sub(g11, g10), g10);
  const V l = hn::MulAdd(ax, hn::Sub(r1, r0), r0);
  if (!mu.any_below) return l;
  V at;
  const V it = Row(df, t, Level(df, t, ht), at);
  const auto j0 = hn::ConvertTo(di, hn::Mul(it, cols));
  const V h0 = Gather(df, d0, j0, valid, scratch);
  const V h1 = Gather(df, d0, hn::Add(j0, hn::Set(di, t.cols)), valid, scratch);
  const V lt = hn::MulAdd(at, hn::Sub(h1, h0), h0);
  const V reflected = hn::Max(hn::MulSub(hn::Set(df, 2.0f), lt, l), hn::Zero(df));
  return hn::IfThenElse(mu.below, reflected, l);
}

// Pass 1, double precision: per sample the altitude h = |p + s v| - R0, the view and sun cosines,
// the tangent altitudes for the reflection rule, the weight (0 in the planet's shadow); stored as
// float up to n_full samples. Returns whether any sample is lit.
struct SampleGeometry {
  static constexpr size_t kArray = detail::kMaxPieceSamples + detail::kSamplePadding;
  alignas(64) float h[kArray], mv[kArray], ms[kArray], hv[kArray], hs[kArray], wf[kArray];
};
bool SampleGeometryPass(const detail::PieceSamples& ps, size_t n_full, SampleGeometry& g) {
  using DD = hn::ScalableTag<double>;
  using DH = hn::Rebind<float, DD>;  // as many floats as doubles
  const DD dd;
  const DH dh;
  const double R0 = ps.ground_radius;
  const auto zero = hn::Zero(dd);
  bool any_lit = false;
  for (size_t k0 = 0; k0 < n_full; k0 += hn::Lanes(dd)) {
    const auto s = hn::LoadU(dd, ps.s + k0);
    auto w = hn::LoadU(dd, ps.w + k0);
    const auto r2 = hn::MulAdd(s, hn::Add(s, hn::Set(dd, 2.0 * ps.pv)), hn::Set(dd, ps.pp));
    const auto r = hn::Sqrt(r2);
    const auto qv = hn::Add(s, hn::Set(dd, ps.pv));
    const auto qs = hn::MulAdd(s, hn::Set(dd, ps.vs), hn::Set(dd, ps.ps));
    const auto across_sun = hn::NegMulAdd(qs, qs, r2);  // squared distance from the sun axis
    // Planet shadow (Pietras §III): behind the planet and within R0 of the sun axis.
    const auto shadow = hn::And(hn::Lt(qs, zero), hn::Lt(across_sun, hn::Set(dd, R0 * R0)));
    w = hn::IfThenZeroElse(shadow, w);
    any_lit = any_lit || !hn::AllTrue(dd, hn::Eq(w, zero));
    const auto inv_r = hn::Div(hn::Set(dd, 1.0), r);
    const auto tangent = [&](auto q_dot) {  // altitude of the line's closest point, >= 0
      return hn::Max(
          hn::Sub(hn::Sqrt(hn::Max(hn::NegMulAdd(q_dot, q_dot, r2), zero)), hn::Set(dd, R0)), zero);
    };
    hn::StoreU(hn::DemoteTo(dh, hn::Sub(r, hn::Set(dd, R0))), dh, g.h + k0);
    hn::StoreU(hn::DemoteTo(dh, hn::Mul(ps.hits_ground ? hn::Neg(qv) : qv, inv_r)), dh, g.mv + k0);
    hn::StoreU(hn::DemoteTo(dh, hn::Mul(qs, inv_r)), dh, g.ms + k0);
    hn::StoreU(hn::DemoteTo(dh, tangent(qv)), dh, g.hv + k0);
    hn::StoreU(hn::DemoteTo(dh, tangent(qs)), dh, g.hs + k0);
    hn::StoreU(hn::DemoteTo(dh, w), dh, g.wf + k0);
  }
  return any_lit;
}

void ScatterPieceImpl(const detail::KernelTable* HWY_RESTRICT tables, size_t nc,
                      const float* HWY_RESTRICT t0, const detail::PieceSamples& ps,
                      const float* HWY_RESTRICT extinction, size_t nl, float* HWY_RESTRICT acc) {
  using DF = hn::ScalableTag<float>;
  const DF df;
  // Up to whole float vectors of pass 2 (the padding samples have w = 0), so that pass 2 reads
  // only written values.
  const size_t n_full = (ps.n + hn::Lanes(df) - 1) / hn::Lanes(df) * hn::Lanes(df);
  SampleGeometry g;
  if (!SampleGeometryPass(ps, n_full, g)) return;
  const float *h = g.h, *mv = g.mv, *ms = g.ms, *hv = g.hv, *hs = g.hs, *wf = g.wf;

  // Pass 2, single precision, full vectors: densities and table lookups per component, then
  // each lit sample's transmittance over all wavelengths.
  const size_t N = hn::Lanes(df);
  constexpr size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  float t[kMaxComponents][kMaxLanes];
  float rho[kMaxComponents][kMaxLanes];
  alignas(64) float scratch[kMaxLanes] = {};
  alignas(64) float scratch2[2 * kMaxLanes] = {};
  for (size_t k0 = 0; k0 < ps.n; k0 += N) {
    const size_t valid = std::min(N, ps.n - k0);
    const auto hk = hn::LoadU(df, h + k0);
    const MuCell<DF> cv = MakeMuCell(df, tables[0].cols, hn::LoadU(df, mv + k0));
    const MuCell<DF> cs = MakeMuCell(df, tables[0].cols, hn::LoadU(df, ms + k0));
    const auto hvk = hn::LoadU(df, hv + k0), hsk = hn::LoadU(df, hs + k0);
    const auto wk = hn::LoadU(df, wf + k0);
    for (size_t i = 0; i < nc; ++i) {
      const detail::KernelTable& tab = tables[i];
      const auto x = Level(df, tab, hk);
      const auto density =
          tab.exponential
              ? x
              : hn::Max(hn::NegMulAdd(hn::Abs(hn::Sub(hk, hn::Set(df, tab.peak))),
                                      hn::Set(df, tab.inv_half_width), hn::Set(df, 1.0f)),
                        hn::Zero(df));
      hn::Vec<DF> ax;
      const auto ix = Row(df, tab, x, ax);
      const auto lv = OpticalLength(df, tab, ix, ax, cv, hvk, valid, scratch, scratch2);
      const auto ls = OpticalLength(df, tab, ix, ax, cs, hsk, valid, scratch, scratch2);
      const auto t0i = hn::Set(df, t0[i]);
      const auto tv = hn::Max(ps.hits_ground ? hn::Sub(lv, t0i) : hn::Sub(t0i, lv), hn::Zero(df));
      hn::StoreU(hn::Add(tv, ls), df, t[i]);
      hn::StoreU(hn::Mul(density, wk), df, rho[i]);
    }
    for (size_t k = 0; k < valid; ++k) {
      if (wf[k0 + k] == 0.0f) continue;  // shadowed sample
      float tk[kMaxComponents], rk[kMaxComponents];
      for (size_t i = 0; i < nc; ++i) {
        tk[i] = t[i][k];
        rk[i] = rho[i][k];
      }
      AccumulateSample(extinction, tk, rk, nc, nl, acc);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight::atmosphere
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight::atmosphere {

HWY_EXPORT(ScatterPieceImpl);

void detail::scatter_piece(const KernelTable* tables, std::size_t nc, const float* t0,
                           const PieceSamples& samples, const float* extinction, std::size_t nl,
                           float* acc) {
  HWY_DYNAMIC_DISPATCH(ScatterPieceImpl)(tables, nc, t0, samples, extinction, nl, acc);
}

}  // namespace skylight::atmosphere
#endif  // HWY_ONCE
