#include "skylight/core/interleave.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "skylight/core/error.h"

namespace skylight {
namespace {

// Lengths around every vector width (2..16 lanes) and its multiples, and starts at every 8-byte
// offset of a 64-byte line (the kernels align their vector loop by converting a few rows first).
constexpr std::size_t kLengths[] = {0, 1, 3, 7, 8, 9, 15, 16, 17, 31, 33, 64, 100, 1027};
constexpr std::size_t kOffsets = 8;

std::vector<double> random_rows(std::size_t n, bool unit, std::mt19937& rng) {
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> len(0.1, 10.0);
  std::vector<double> rows(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 v = normalize(Vec3{g(rng), g(rng), g(rng)});
    const double s = unit ? 1.0 : len(rng);
    rows[3 * i] = s * v.x;
    rows[3 * i + 1] = s * v.y;
    rows[3 * i + 2] = s * v.z;
  }
  return rows;
}

TEST(Interleave, DirectionsToSoaMatchesTheScalarConversion) {
  std::mt19937 rng(7);
  for (const bool unit : {true, false})
    for (const std::size_t n : kLengths)
      for (std::size_t off = 0; off < kOffsets; ++off) {
        const std::vector<double> rows = random_rows(n, unit, rng);
        std::vector<double> shifted(3 * n + off);
        std::copy(rows.begin(), rows.end(), shifted.begin() + static_cast<std::ptrdiff_t>(off));
        std::vector<float> x(n), y(n), z(n);
        ASSERT_TRUE(directions_to_soa(shifted.data() + off, n, x.data(), y.data(), z.data()));
        for (std::size_t i = 0; i < n; ++i) {
          // Unit rows are converted as they are (exactly the float of each value); others are
          // divided by their length in double first.
          const double inv =
              unit ? 1.0
                   : 1.0 / std::sqrt(rows[3 * i] * rows[3 * i] + rows[3 * i + 1] * rows[3 * i + 1] +
                                     rows[3 * i + 2] * rows[3 * i + 2]);
          ASSERT_EQ(x[i], static_cast<float>(rows[3 * i] * inv)) << n << " " << off << " " << i;
          ASSERT_EQ(y[i], static_cast<float>(rows[3 * i + 1] * inv));
          ASSERT_EQ(z[i], static_cast<float>(rows[3 * i + 2] * inv));
        }
      }
}

TEST(Interleave, DirectionsToSoaRefusesZeroNanAndInfiniteRows) {
  std::mt19937 rng(8);
  const double bad[] = {0.0, std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(), 1e200};
  for (const double b : bad)
    for (const std::size_t at : {std::size_t{0}, std::size_t{5}, std::size_t{26}}) {
      std::vector<double> rows = random_rows(27, true, rng);
      rows[3 * at] = rows[3 * at + 1] = rows[3 * at + 2] = b;
      std::vector<float> x(27), y(27), z(27);
      EXPECT_FALSE(directions_to_soa(rows.data(), 27, x.data(), y.data(), z.data())) << b << at;
      // row_direction names it.
      try {
        row_direction(rows.data(), at);
        ADD_FAILURE() << "no error for " << b;
      } catch (const InvalidArgument& e) {
        EXPECT_NE(std::string(e.what()).find("direction " + std::to_string(at)), std::string::npos);
      }
    }
}

TEST(Interleave, SoaToRowsAndWidenAreExactAndFlagNonFinite) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1e30f, 1e30f);
  for (const std::size_t n : kLengths)
    for (std::size_t off = 0; off < kOffsets; ++off) {
      std::vector<float> a(n), b(n), c(n);
      for (std::size_t i = 0; i < n; ++i) a[i] = u(rng), b[i] = u(rng), c[i] = u(rng);
      std::vector<double> rows(3 * n + off, -1.0), wide(n + off, -1.0);
      ASSERT_TRUE(soa_to_rows(a.data(), b.data(), c.data(), n, rows.data() + off));
      ASSERT_TRUE(widen(b.data(), n, wide.data() + off));
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(rows[off + 3 * i], a[i]);
        ASSERT_EQ(rows[off + 3 * i + 1], b[i]);
        ASSERT_EQ(rows[off + 3 * i + 2], c[i]);
        ASSERT_EQ(wide[off + i], b[i]);
      }
      if (n == 0) continue;
      for (const float v :
           {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::infinity()}) {
        std::vector<float> c2 = c;
        c2[n - 1] = v;
        EXPECT_FALSE(soa_to_rows(a.data(), b.data(), c2.data(), n, rows.data() + off));
        EXPECT_FALSE(widen(c2.data(), n, wide.data() + off));
        EXPECT_FALSE(all_finite(c2.data(), n));
      }
      EXPECT_TRUE(all_finite(c.data(), n));
    }
}

TEST(Interleave, UnitSoaChecksLengthsToFloatPrecision) {
  std::mt19937 rng(10);
  for (const std::size_t n : kLengths) {
    const std::vector<double> rows = random_rows(n, true, rng);
    std::vector<float> x(n), y(n), z(n);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = static_cast<float>(rows[3 * i]);
      y[i] = static_cast<float>(rows[3 * i + 1]);
      z[i] = static_cast<float>(rows[3 * i + 2]);
    }
    ASSERT_TRUE(unit_soa(x.data(), y.data(), z.data(), n)) << n;
    if (n == 0) continue;
    // One row 0.1 % too long or short (|v|^2 off by 2e-3), or NaN.
    for (const float f : {1.001f, 0.999f, std::numeric_limits<float>::quiet_NaN()}) {
      std::vector<float> x2 = x, y2 = y, z2 = z;
      x2[n / 2] *= f;
      y2[n / 2] *= f;
      z2[n / 2] *= f;
      EXPECT_FALSE(unit_soa(x2.data(), y2.data(), z2.data(), n)) << n << " " << f;
    }
  }
}

}  // namespace
}  // namespace skylight
