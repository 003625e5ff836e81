#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/polynomial.h"
#include "support/sh_tables.h"

namespace skylight::sh {
namespace {

// The monomial form evaluated in long double against the Chebyshev form: the expansion is exact up
// to long double round-off, amplified by the monomials' cancellation (small degrees here).
constexpr double kMonomialRelTol = 1e-9;

TEST(ShExport, MonomialFormEqualsTheChebyshevForm) {
  const PolynomialTable t = testing_support::synthetic_sh_table(3, 5, 3);
  const std::vector<double> p = monomial_coefficients(t);
  ASSERT_EQ(p.size(), t.coefficients.size());
  const int ni = t.degree_theta + 1, nj = t.degree_tau + 1;
  for (double theta : {0.0, 0.4, 1.2, kPi / 2}) {
    for (double tau : {2.5, 3.3, 6.0}) {
      const Coefficients c = evaluate_table_reference(t, theta, tau, 0.0, 3, false);
      for (int l = 0; l < 3; ++l) {
        for (int m = 0; m <= l; ++m) {
          for (int ch = 0; ch < 3; ++ch) {
            const std::size_t base =
                static_cast<std::size_t>(((l * (l + 1) / 2 + m) * 3 + ch) * t.terms());
            long double sum = 0.0L;
            for (int i = 0; i < ni; ++i)
              for (int j = 0; j < nj; ++j)
                sum += static_cast<long double>(p[base + static_cast<std::size_t>(i * nj + j)]) *
                       std::pow(static_cast<long double>(theta), i) *
                       std::pow(static_cast<long double>(tau), j);
            const double expected = c.c[static_cast<std::size_t>(index(l, m))][ch];
            EXPECT_NEAR(static_cast<double>(sum), expected,
                        kMonomialRelTol * (std::abs(expected) + 1e3));
          }
        }
      }
    }
  }
}

TEST(ShExport, CHeaderHoldsBothArraysAndRefusesBadNames) {
  const PolynomialTable t = testing_support::synthetic_sh_table(2, 1, 1);
  const std::string h = table_to_c_header(t, "sky", true);
  EXPECT_NE(h.find("#define SKY_BANDS 2"), std::string::npos);
  EXPECT_NE(h.find("static const float sky_chebyshev[36]"), std::string::npos);
  EXPECT_NE(h.find("static const double sky_monomial[36]"), std::string::npos);
  EXPECT_EQ(table_to_c_header(t, "sky", false).find("monomial["), std::string::npos);
  EXPECT_THROW(table_to_c_header(t, "1x", false), InvalidArgument);
  EXPECT_THROW(table_to_c_header(t, "a-b", false), InvalidArgument);
}

}  // namespace
}  // namespace skylight::sh
