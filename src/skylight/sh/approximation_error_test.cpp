#include "skylight/sh/approximation_error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/sh/basis.h"

namespace skylight::sh {
namespace {

// Sums of a few exact binary fractions: round-off only.
constexpr double kExact = 1e-15;

TEST(ShError, EquationsTwoAndThreeOnAKnownDifference) {
  Coefficients ref{3, std::vector<Triple>(9, Triple{1.0, 1.0, 1.0})};
  Coefficients rec = ref;
  rec.c[static_cast<std::size_t>(index(0, 0))][0] += 0.5;    // band 0
  rec.c[static_cast<std::size_t>(index(1, -1))][0] -= 0.25;  // band 1
  rec.c[static_cast<std::size_t>(index(2, 2))][0] += 0.125;  // band 2
  const Triple l_min{2.0, 1.0, 1.0};
  const auto e1 = error_measures(ref, rec, 1, l_min);
  EXPECT_NEAR(e1.e_max[0], 0.25, kExact);
  EXPECT_NEAR(e1.e_mean[0], 0.25, kExact);
  const auto e3 = error_measures(ref, rec, 3, l_min);
  EXPECT_NEAR(e3.e_max[0], (0.5 + 0.25 + 0.125) / 2.0, kExact);
  EXPECT_NEAR(e3.e_mean[0], std::sqrt(0.25 + 0.0625 + 0.015625) / 2.0, kExact);
  EXPECT_EQ(e3.e_max[1], 0.0);
  EXPECT_EQ(e3.e_mean[2], 0.0);
}

}  // namespace
}  // namespace skylight::sh
