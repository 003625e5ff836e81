#include "skylight/sh/projection.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/math.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/rotation.h"

namespace skylight::sh {
namespace {

// A band-limited function is integrated exactly by the product rule: round-off only.
// Closed forms of a few terms: double round-off only.
constexpr double kProjectionRoundOff = 1e-15;
constexpr double kProjectionExact = 1e-12;

TEST(ShProjection, GaussLegendreIntegratesPolynomialsExactly) {
  std::vector<double> x, w;
  gauss_legendre(5, 0.0, 1.0, x, w);
  double s0 = 0.0, s9 = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    s0 += w[i];
    s9 += w[i] * std::pow(x[i], 9);
  }
  EXPECT_NEAR(s0, 1.0, kProjectionRoundOff);
  EXPECT_NEAR(s9, 0.1, kProjectionRoundOff);  // degree 2n - 1 = 9 is exact
}

TEST(ShProjection, AKnownShFunctionReproducesItsCoefficients) {
  constexpr int kBands = 6;
  Coefficients known{kBands, std::vector<Triple>(coefficient_count(kBands))};
  for (int i = 0; i < coefficient_count(kBands); ++i) {
    known.c[static_cast<std::size_t>(i)] = {std::sin(1.0 + i), 0.5 * std::cos(3.0 * i),
                                            1.0 / (i + 1)};
  }
  ProjectionOptions o;
  o.region = Region::full_sphere;
  o.min_nodes = 8;
  const auto p = project([&](Vec3 d) { return reconstruct(known, d); }, kBands, o);
  ASSERT_TRUE(p.converged);
  for (std::size_t i = 0; i < known.c.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(p.coefficients.c[i][ch], known.c[i][ch], kProjectionExact);
  }
}

// P_l(0): 0 for odd l, (-1)^k (2k)! / (4^k (k!)^2) for l = 2k.
double legendre_at_zero(int l) {
  if (l % 2 == 1) return 0.0;
  double p = 1.0;
  for (int k = 1; 2 * k <= l; ++k) p *= -(2.0 * k - 1.0) / (2.0 * k);
  return p;
}

TEST(ShProjection, AConstantSkyGivesTheClosedForm) {
  // c_l0 = 2 pi L K_l0 integral_0^1 P_l(mu) d mu, with integral_0^1 P_l = (P_{l-1}(0) -
  // P_{l+1}(0)) / (2l + 1) (l >= 1) and 1 (l = 0); c_lm = 0 for m != 0.
  constexpr int kBands = 8;
  constexpr double kL = 2.5;
  ProjectionOptions o;
  o.tolerance = 1e-12;
  const auto p = project([](Vec3) { return Triple{kL, 2 * kL, 3 * kL}; }, kBands, o);
  ASSERT_TRUE(p.converged);
  for (int l = 0; l < kBands; ++l) {
    const double integral =
        l == 0 ? 1.0 : (legendre_at_zero(l - 1) - legendre_at_zero(l + 1)) / (2.0 * l + 1.0);
    for (int m = -l; m <= l; ++m) {
      const double expect = m == 0 ? 2.0 * kPi * kL * normalisation(l, 0) * integral : 0.0;
      const auto& c = p.coefficients.c[static_cast<std::size_t>(index(l, m))];
      EXPECT_NEAR(c[0], expect, kProjectionExact) << "l=" << l << " m=" << m;
      EXPECT_NEAR(c[2], 3 * expect, 3 * kProjectionExact) << "l=" << l << " m=" << m;
    }
  }
}

}  // namespace
}  // namespace skylight::sh
