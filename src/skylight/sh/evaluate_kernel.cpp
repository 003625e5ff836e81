// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/sh/evaluate_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/highway.h>

#include <cstddef>

#include "skylight/sh/detail/evaluate_kernel.h"

HWY_BEFORE_NAMESPACE();
namespace skylight::sh::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Four rows share each load of x; their four accumulators hide the FMA latency.
void DotRowsImpl(const float* HWY_RESTRICT p, const float* HWY_RESTRICT x, std::size_t rows,
                 std::size_t terms, float* HWY_RESTRICT out) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t r = 0;
  for (; r + 4 <= rows; r += 4) {
    const float* p0 = p + r * terms;
    const float* p1 = p0 + terms;
    const float* p2 = p1 + terms;
    const float* p3 = p2 + terms;
    V a0 = hn::Zero(d), a1 = hn::Zero(d), a2 = hn::Zero(d), a3 = hn::Zero(d);
    std::size_t t = 0;
    for (; t + lanes <= terms; t += lanes) {
      const V xv = hn::LoadU(d, x + t);
      a0 = hn::MulAdd(hn::LoadU(d, p0 + t), xv, a0);
      a1 = hn::MulAdd(hn::LoadU(d, p1 + t), xv, a1);
      a2 = hn::MulAdd(hn::LoadU(d, p2 + t), xv, a2);
      a3 = hn::MulAdd(hn::LoadU(d, p3 + t), xv, a3);
    }
    float s0 = hn::GetLane(hn::SumOfLanes(d, a0)), s1 = hn::GetLane(hn::SumOfLanes(d, a1));
    float s2 = hn::GetLane(hn::SumOfLanes(d, a2)), s3 = hn::GetLane(hn::SumOfLanes(d, a3));
    for (; t < terms; ++t) {
      s0 += p0[t] * x[t];
      s1 += p1[t] * x[t];
      s2 += p2[t] * x[t];
      s3 += p3[t] * x[t];
    }
    out[r] = s0;
    out[r + 1] = s1;
    out[r + 2] = s2;
    out[r + 3] = s3;
  }
  for (; r < rows; ++r) {
    const float* p0 = p + r * terms;
    V a0 = hn::Zero(d);
    std::size_t t = 0;
    for (; t + lanes <= terms; t += lanes) {
      a0 = hn::MulAdd(hn::LoadU(d, p0 + t), hn::LoadU(d, x + t), a0);
    }
    float s0 = hn::GetLane(hn::SumOfLanes(d, a0));
    for (; t < terms; ++t) s0 += p0[t] * x[t];
    out[r] = s0;
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight::sh::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight::sh::detail {

HWY_EXPORT(DotRowsImpl);

void dot_rows(const float* p, const float* x, std::size_t rows, std::size_t terms, float* out) {
  HWY_DYNAMIC_DISPATCH(DotRowsImpl)(p, x, rows, terms, out);
}

}  // namespace skylight::sh::detail
#endif  // HWY_ONCE
