// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/nn/train_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/highway.h>

#include <algorithm>

#include "skylight/nn/detail/train_kernel.h"

// Register tile: 2 vectors of rows of C (2N rows, contiguous in a column) x up to 4 columns, 8
// accumulators; per step k two vector loads of A's column k and four broadcasts of B's feed 8
// FMAs. The depth is cut into chunks of kDepthChunk columns so that the panels of A and B being
// re-read stay in L2.

HWY_BEFORE_NAMESPACE();
namespace skylight::nn {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

constexpr size_t kDepthChunk = 256;

// Loads column segment C[0 .. rows) into two vectors (rows <= 2N; missing rows read as 0).
template <class D, class V = hn::Vec<D>>
HWY_INLINE void LoadPair(D d, const double* c, size_t rows, V& v0, V& v1) {
  const size_t N = hn::Lanes(d);
  if (rows >= 2 * N) {
    v0 = hn::LoadU(d, c);
    v1 = hn::LoadU(d, c + N);
    return;
  }
  HWY_ALIGN double t[2 * hn::MaxLanes(d)] = {};
  std::copy_n(c, rows, t);
  v0 = hn::Load(d, t);
  v1 = hn::Load(d, t + N);
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE void StorePair(D d, double* c, size_t rows, V v0, V v1) {
  const size_t N = hn::Lanes(d);
  if (rows >= 2 * N) {
    hn::StoreU(v0, d, c);
    hn::StoreU(v1, d, c + N);
    return;
  }
  HWY_ALIGN double t[2 * hn::MaxLanes(d)];
  hn::Store(v0, d, t);
  hn::Store(v1, d, t + N);
  std::copy_n(t, rows, c);
}

// C(0..rows, 0..4) += sum_k A(0..2N, k) B(0..4, k): A at A(i0, k0), B at B(j0, k0), C at
// C(i0, j0).
template <class D>
HWY_INLINE void Tile4(D d, const double* HWY_RESTRICT A, size_t lda, const double* HWY_RESTRICT B,
                      size_t ldb, size_t kc, double* HWY_RESTRICT C, size_t ldc, size_t rows) {
  using V = hn::Vec<D>;
  const size_t N = hn::Lanes(d);
  V c00, c01, c10, c11, c20, c21, c30, c31;
  LoadPair(d, C, rows, c00, c01);
  LoadPair(d, C + ldc, rows, c10, c11);
  LoadPair(d, C + 2 * ldc, rows, c20, c21);
  LoadPair(d, C + 3 * ldc, rows, c30, c31);
  for (size_t k = 0; k < kc; ++k) {
    const double* HWY_RESTRICT a = A + k * lda;
    const double* HWY_RESTRICT b = B + k * ldb;
    const V a0 = hn::LoadU(d, a), a1 = hn::LoadU(d, a + N);
    const V b0 = hn::Set(d, b[0]), b1 = hn::Set(d, b[1]);
    const V b2 = hn::Set(d, b[2]), b3 = hn::Set(d, b[3]);
    c00 = hn::MulAdd(a0, b0, c00);
    c01 = hn::MulAdd(a1, b0, c01);
    c10 = hn::MulAdd(a0, b1, c10);
    c11 = hn::MulAdd(a1, b1, c11);
    c20 = hn::MulAdd(a0, b2, c20);
    c21 = hn::MulAdd(a1, b2, c21);
    c30 = hn::MulAdd(a0, b3, c30);
    c31 = hn::MulAdd(a1, b3, c31);
  }
  StorePair(d, C, rows, c00, c01);
  StorePair(d, C + ldc, rows, c10, c11);
  StorePair(d, C + 2 * ldc, rows, c20, c21);
  StorePair(d, C + 3 * ldc, rows, c30, c31);
}

// One column: C(0..rows, 0) += sum_k A(0..2N, k) B(0, k).
template <class D>
HWY_INLINE void Tile1(D d, const double* HWY_RESTRICT A, size_t lda, const double* HWY_RESTRICT B,
                      size_t ldb, size_t kc, double* HWY_RESTRICT C, size_t rows) {
  using V = hn::Vec<D>;
  const size_t N = hn::Lanes(d);
  V c0, c1;
  LoadPair(d, C, rows, c0, c1);
  for (size_t k = 0; k < kc; ++k) {
    const V b0 = hn::Set(d, B[k * ldb]);
    c0 = hn::MulAdd(hn::LoadU(d, A + k * lda), b0, c0);
    c1 = hn::MulAdd(hn::LoadU(d, A + k * lda + N), b0, c1);
  }
  StorePair(d, C, rows, c0, c1);
}

void GemmAbtImpl(const double* A, size_t lda, const double* B, size_t ldb, size_t m, size_t n,
                 size_t depth, double* C, size_t ldc, bool lower) {
  const hn::ScalableTag<double> d;
  const size_t R = 2 * hn::Lanes(d);  // rows per tile
  for (size_t k0 = 0; k0 < depth; k0 += kDepthChunk) {
    const size_t kc = std::min(kDepthChunk, depth - k0);
    for (size_t j0 = 0; j0 < n; j0 += 4) {
      const size_t nj = std::min<size_t>(4, n - j0);
      const size_t i_begin = lower ? j0 / R * R : 0;
      for (size_t i0 = i_begin; i0 < m; i0 += R) {
        const size_t rows = std::min(R, m - i0);
        const double* a = A + i0 + k0 * lda;
        const double* b = B + j0 + k0 * ldb;
        double* c = C + i0 + j0 * ldc;
        if (nj == 4) {
          Tile4(d, a, lda, b, ldb, kc, c, ldc, rows);
        } else {
          for (size_t t = 0; t < nj; ++t) Tile1(d, a, lda, b + t, ldb, kc, c + t * ldc, rows);
        }
      }
    }
  }
}

size_t RowPaddingImpl() {
  return 2 * hn::Lanes(hn::ScalableTag<double>());
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight::nn
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight::nn {

HWY_EXPORT(GemmAbtImpl);
HWY_EXPORT(RowPaddingImpl);

namespace detail {

std::size_t gemm_abt_row_padding() {
  return HWY_DYNAMIC_DISPATCH(RowPaddingImpl)();
}

void gemm_abt(const double* A, std::size_t lda, const double* B, std::size_t ldb, std::size_t m,
              std::size_t n, std::size_t depth, double* C, std::size_t ldc, bool lower) {
  HWY_DYNAMIC_DISPATCH(GemmAbtImpl)(A, lda, B, ldb, m, n, depth, C, ldc, lower);
}

}  // namespace detail
}  // namespace skylight::nn
#endif  // HWY_ONCE
