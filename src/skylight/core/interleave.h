// Conversions between interleaved float64 arrays (rows of x, y, z: numpy's (N, 3) layout, the
// Python package's) and the float structure-of-arrays the models' SIMD batch paths take, in one
// vectorised pass each (Highway, dynamic dispatch), with the checks the batch path needs on the
// way: directions finite and non-zero, results finite.
#pragma once

#include <cstddef>

#include "skylight/core/frame.h"

namespace skylight {

// |v|^2 within this of 1 counts as a unit vector: v / |v| in float64 arithmetic has |v|^2 within a
// few 1e-16 of 1, and the float conversion of such a vector is exact to float precision without a
// division.
inline constexpr double kUnitLengthTolerance = 1e-14;

// Row i of `rows` (x, y, z) as a unit vector; InvalidArgument naming it ("direction i = (...)")
// when it is not a finite non-zero vector.
Vec3 row_direction(const double* rows, std::size_t i);

// |v|^2 within this of 1 counts as a unit vector in float: a float64 unit vector rounded to float
// has |v|^2 within ~4e-7 of 1, one normalised in float arithmetic within ~1e-6.
inline constexpr float kFloatUnitLengthTolerance = 1e-5f;

// n rows (x, y, z) of `rows` -> x[i], y[i], z[i] as float, each row normalised unless all n are
// unit already (kUnitLengthTolerance). False (outputs unspecified) when some row's |v|^2 is zero,
// NaN or infinite.
bool directions_to_soa(const double* rows, std::size_t n, float* x, float* y, float* z);

// n values a[i], b[i], c[i] -> rows (a, b, c) of float64 in `rows`. False when some value is NaN
// or infinite (all n rows are written either way).
bool soa_to_rows(const float* a, const float* b, const float* c, std::size_t n, double* rows);

// n floats -> n float64; false when some value is NaN or infinite (all are written either way).
bool widen(const float* a, std::size_t n, double* out);

// Whether all n vectors (x[i], y[i], z[i]) are unit to kFloatUnitLengthTolerance (false for NaN
// and Inf).
bool unit_soa(const float* x, const float* y, const float* z, std::size_t n);

// Whether all n values are finite.
bool all_finite(const float* a, std::size_t n);

}  // namespace skylight
