// SIMD kernel of the Levenberg-Marquardt trainer (train_kernel.cpp, Highway dynamic dispatch):
// the products behind J^T J. Internal to train.cpp.
//
// Eigen at the library's baseline instruction set (SSE2) spent half of an LM iteration packing
// operands and page-faulting its per-call workspace for these short-and-wide products; this kernel
// needs no workspace and uses FMA on AVX2 / AVX-512 machines.
#pragma once

#include <cstddef>

namespace skylight::nn::detail {

// Rows of A and B read by gemm_abt are padded up to a multiple of this (the caller's buffers must
// hold that many readable rows per column; what the padding holds does not matter).
std::size_t gemm_abt_row_padding();

// C(i, j) += sum_{k < depth} A(i, k) B(j, k) for i < m, j < n; A, B, C column-major with leading
// dimensions lda, ldb, ldc (A(i, k) = A[i + k lda]). lower: only j <= i is needed (C symmetric,
// A == B); entries above the diagonal may then also be updated, with meaningless values.
// Deterministic: the summation order depends on the sizes and the instruction set only.
void gemm_abt(const double* A, std::size_t lda, const double* B, std::size_t ldb, std::size_t m,
              std::size_t n, std::size_t depth, double* C, std::size_t ldc, bool lower);

}  // namespace skylight::nn::detail
