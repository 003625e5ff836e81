// The hot loop of the fast table evaluation (sh/polynomial.h, evaluate_table): eq. 1 of Habel,
// Mustata & Wimmer 2008 for every stored coefficient at once, as a matrix-vector product of the
// float coefficient rows with the float tensor Chebyshev vector T_i(u) T_j(v) (Highway SIMD,
// dynamic dispatch to the best instruction set of the running CPU).
#pragma once

#include <cstddef>

namespace skylight::sh::detail {

// out[r] = sum_t p[r * terms + t] x[t], r = 0 .. rows - 1, accumulated in float (four rows at a
// time, one vector accumulator per row; the lane sums are reduced at the end of each row).
void dot_rows(const float* p, const float* x, std::size_t rows, std::size_t terms, float* out);

}  // namespace skylight::sh::detail
