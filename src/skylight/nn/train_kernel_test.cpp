#include "skylight/nn/detail/train_kernel.h"

#include <gtest/gtest.h>

#include <vector>

#include "skylight/nn/random.h"

namespace skylight::nn::detail {
namespace {

// The kernel's sums of <= 300 products of O(1) numbers differ from the naive order by a few ulps
// of the sum's magnitude (~1e-16 x 300).
constexpr double kGemmTolerance = 1e-12;

TEST(GemmAbt, MatchesNaiveProductOnOddSizes) {
  const std::size_t pad = gemm_abt_row_padding();
  Rng rng(1);
  for (std::size_t m : {1u, 5u, 17u, 40u}) {
    for (std::size_t n : {1u, 3u, 4u, 9u}) {
      for (std::size_t depth : {1u, 7u, 300u}) {
        const std::size_t lda = (m + pad - 1) / pad * pad + pad, ldb = n + 2, ldc = m + 1;
        std::vector<double> A(lda * depth), B(ldb * depth), C(ldc * n), ref(ldc * n);
        for (auto& v : A) v = rng.uniform(-1.0, 1.0);
        for (auto& v : B) v = rng.uniform(-1.0, 1.0);
        for (std::size_t k = 0; k < C.size(); ++k) C[k] = ref[k] = rng.uniform(-1.0, 1.0);
        for (std::size_t j = 0; j < n; ++j) {
          for (std::size_t i = 0; i < m; ++i) {
            for (std::size_t k = 0; k < depth; ++k)
              ref[i + j * ldc] += A[i + k * lda] * B[j + k * ldb];
          }
        }
        gemm_abt(A.data(), lda, B.data(), ldb, m, n, depth, C.data(), ldc, false);
        for (std::size_t j = 0; j < n; ++j) {
          for (std::size_t i = 0; i < ldc; ++i) {
            // Row m of each column (i == m) is outside C: it must be left untouched.
            EXPECT_NEAR(C[i + j * ldc], ref[i + j * ldc], kGemmTolerance)
                << m << "x" << n << "x" << depth << " at " << i << "," << j;
          }
        }
      }
    }
  }
}

TEST(GemmAbt, LowerTriangleOfASymmetricUpdate) {
  const std::size_t pad = gemm_abt_row_padding();
  const std::size_t m = 23, depth = 50, lda = (m + pad - 1) / pad * pad;
  Rng rng(2);
  std::vector<double> A(lda * depth), C(m * m, 0.0);
  for (auto& v : A) v = rng.uniform(-1.0, 1.0);
  gemm_abt(A.data(), lda, A.data(), lda, m, m, depth, C.data(), m, true);
  for (std::size_t j = 0; j < m; ++j) {
    for (std::size_t i = j; i < m; ++i) {
      double ref = 0.0;
      for (std::size_t k = 0; k < depth; ++k) ref += A[i + k * lda] * A[j + k * lda];
      EXPECT_NEAR(C[i + j * m], ref, kGemmTolerance);
    }
  }
}

}  // namespace
}  // namespace skylight::nn::detail
