// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
// Morales et al. 2017 eq. 26; docs/HAZE.md "Speed".
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/haze/pixel_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>

#include "skylight/haze/detail/pixel_kernel.h"

HWY_BEFORE_NAMESPACE();
namespace skylight::haze::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Lanes pixels at a time: the depth's table index and fraction, two gathers per table and
// channel, the RGB planes de-interleaved. The arithmetic is the scalar loop's, operation by
// operation (no fused multiply-add), so both round alike.
template <bool kSource, bool kTarget, bool kMap>
std::size_t Pixels(const PixelUniforms& u, float* HWY_RESTRICT px, const float* HWY_RESTRICT depth,
                   const float* HWY_RESTRICT a_t_map, const float* HWY_RESTRICT a_s_map,
                   std::size_t n) {
  const hn::ScalableTag<float> d;
  const hn::RebindToSigned<decltype(d)> di;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  const V inv_step = hn::Set(d, u.inv_step), min_t = hn::Set(d, u.min_t);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
  const auto last = hn::Set(di, u.last);
  std::size_t low = 0;
  // The tail runs through padded copies (depth 0, airlight 1) of the last pixels.
  constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(float);
  HWY_ALIGN float tail_px[3 * kMaxLanes], tail_depth[kMaxLanes], tail_at[3 * kMaxLanes],
      tail_as[3 * kMaxLanes];
  for (std::size_t x = 0; x < n; x += lanes) {
    const std::size_t count = std::min(lanes, n - x);
    float* p = px + 3 * x;
    const float* s = depth + x;
    const float* at = kMap ? a_t_map + 3 * x : nullptr;
    const float* as = kMap && a_s_map ? a_s_map + 3 * x : nullptr;
    if (count < lanes) {
      std::fill(tail_px, tail_px + 3 * lanes, 0.0f);
      std::fill(tail_depth, tail_depth + lanes, 0.0f);
      std::copy(p, p + 3 * count, tail_px);
      std::copy(s, s + count, tail_depth);
      p = tail_px;
      s = tail_depth;
      if (at) {
        std::fill(tail_at, tail_at + 3 * lanes, 1.0f);
        std::copy(at, at + 3 * count, tail_at);
        at = tail_at;
      }
      if (as) {
        std::fill(tail_as, tail_as + 3 * lanes, 1.0f);
        std::copy(as, as + 3 * count, tail_as);
        as = tail_as;
      }
    }
    const V pos = hn::Mul(hn::LoadU(d, s), inv_step);
    const auto i = hn::Min(hn::ConvertTo(di, pos), last);
    const V f = hn::Sub(pos, hn::ConvertTo(d, i));
    const auto k = hn::Add(hn::Add(i, i), i);  // 3 i: the entry's first float
    V v[3];
    hn::LoadInterleaved3(d, p, v[0], v[1], v[2]);
    V a_t[3] = {one, one, one}, a_s[3] = {one, one, one};
    if constexpr (kMap) {
      hn::LoadInterleaved3(d, at, a_t[0], a_t[1], a_t[2]);
      if (as) hn::LoadInterleaved3(d, as, a_s[0], a_s[1], a_s[2]);
    }
    auto below = hn::Lt(zero, zero);
    for (std::size_t c = 0; c < 3; ++c) {
      V ratio = one;
      if constexpr (kTarget) {
        const V g0 = hn::GatherIndex(d, u.gt + c, k), g1 = hn::GatherIndex(d, u.gt + 3 + c, k);
        ratio = hn::Add(g0, hn::Mul(f, hn::Sub(g1, g0)));
      }
      if constexpr (kSource) {
        const V g0 = hn::GatherIndex(d, u.gs + c, k), g1 = hn::GatherIndex(d, u.gs + 3 + c, k);
        const V g_s = hn::Add(g0, hn::Mul(f, hn::Sub(g1, g0)));
        below = hn::Or(below, hn::Lt(g_s, min_t));
        ratio = hn::Div(ratio, hn::Max(g_s, min_t));
      }
      V airlight = hn::Set(d, u.a_t[c]), scale = hn::Set(d, u.scale[c]);
      if constexpr (kMap) {
        airlight = a_t[c];
        scale = as ? hn::Div(a_t[c], a_s[c]) : one;
      }
      v[c] = hn::Max(zero, hn::Add(hn::Mul(hn::Mul(v[c], scale), ratio),
                                   hn::Mul(airlight, hn::Sub(one, ratio))));
    }
    if constexpr (kSource) {
      if (count < lanes) below = hn::And(below, hn::FirstN(d, count));
      low += hn::CountTrue(d, below);
    }
    hn::StoreInterleaved3(v[0], v[1], v[2], d, p);
    if (count < lanes) std::copy(tail_px, tail_px + 3 * count, px + 3 * x);
  }
  return low;
}

template <bool kMap>
std::size_t ByOperation(const PixelUniforms& u, float* px, const float* depth, const float* a_t_map,
                        const float* a_s_map, std::size_t n) {
  if (!u.gs) return Pixels<false, true, kMap>(u, px, depth, a_t_map, a_s_map, n);  // add
  if (!u.gt) return Pixels<true, false, kMap>(u, px, depth, a_t_map, a_s_map, n);  // remove
  return Pixels<true, true, kMap>(u, px, depth, a_t_map, a_s_map, n);              // retarget
}

std::size_t HazePixelsImpl(const PixelUniforms& u, float* px, const float* depth,
                           const float* a_t_map, const float* a_s_map, std::size_t n) {
  return a_t_map ? ByOperation<true>(u, px, depth, a_t_map, a_s_map, n)
                 : ByOperation<false>(u, px, depth, a_t_map, a_s_map, n);
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight::haze::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight::haze::detail {

HWY_EXPORT(HazePixelsImpl);

std::size_t haze_pixels(const PixelUniforms& u, float* px, const float* depth, const float* a_t_map,
                        const float* a_s_map, std::size_t n) {
  return HWY_DYNAMIC_DISPATCH(HazePixelsImpl)(u, px, depth, a_t_map, a_s_map, n);
}

std::size_t haze_pixels_scalar(const PixelUniforms& u, float* px, const float* depth,
                               const float* a_t_map, const float* a_s_map, std::size_t n) {
  std::size_t low = 0;
  for (std::size_t x = 0; x < n; ++x) {
    // Linear interpolation in the tables (a 1D texture lookup on a GPU).
    const float pos = depth[x] * u.inv_step;
    const int i = std::min(static_cast<int>(pos), u.last);
    const float f = pos - static_cast<float>(i);
    const std::size_t k = 3 * static_cast<std::size_t>(i);
    bool below = false;
    for (std::size_t c = 0; c < 3; ++c) {
      float ratio = 1.0f;
      if (u.gt) ratio = u.gt[k + c] + f * (u.gt[k + 3 + c] - u.gt[k + c]);
      if (u.gs) {
        const float g_s = u.gs[k + c] + f * (u.gs[k + 3 + c] - u.gs[k + c]);
        below |= g_s < u.min_t;
        ratio /= std::max(g_s, u.min_t);
      }
      float a_t = u.a_t[c], scale = u.scale[c];
      if (a_t_map) {
        a_t = a_t_map[3 * x + c];
        scale = a_s_map ? a_t / a_s_map[3 * x + c] : 1.0f;
      }
      float& v = px[3 * x + c];
      v = std::max(0.0f, v * scale * ratio + a_t * (1.0f - ratio));
    }
    low += below ? 1 : 0;
  }
  return low;
}

}  // namespace skylight::haze::detail
#endif  // HWY_ONCE
