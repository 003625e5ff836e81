#include "skylight/sh/basis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/sh/projection.h"

namespace skylight::sh {
namespace {

// The reference's alternating factorial sum (long double) keeps ~1e-13 relative up to l = 15.
// Closed forms of a few terms: double round-off only.
constexpr double kRoundOff = 1e-15;
constexpr int kReferenceBands = 16;
// Fast recurrence vs reference: both near double round-off for |Y| <= ~2.
constexpr double kFastVsReference = 1e-12;
// Gauss-Legendre x trapezoid quadrature of Y_i Y_j is exact up to round-off.
constexpr double kOrthonormality = 1e-12;

std::vector<Vec3> test_directions() {
  std::vector<Vec3> dirs;
  for (double theta : {0.0, 1e-9, 0.3, 1.0, kPi / 2, 2.0, 3.0, kPi}) {
    for (double phi : {0.0, 0.7, 2.5, 4.0, 6.0}) dirs.push_back(direction_from_angles(theta, phi));
  }
  return dirs;
}

TEST(ShBasis, IndexConventionRoundTrips) {
  EXPECT_EQ(index(0, 0), 0);
  EXPECT_EQ(index(1, -1), 1);
  EXPECT_EQ(index(1, 1), 3);
  EXPECT_EQ(index(7, 7), 63);
  for (int i = 0; i < coefficient_count(kMaxBands); ++i) {
    const auto lm = degree_order(i);
    EXPECT_EQ(index(lm.l, lm.m), i);
    EXPECT_LE(std::abs(lm.m), lm.l);
  }
  EXPECT_THROW(check_bands(0), InvalidArgument);
  EXPECT_THROW(check_bands(kMaxBands + 1), InvalidArgument);
}

TEST(ShBasis, FastRecurrenceMatchesTheExplicitReference) {
  double worst = 0.0;
  for (const Vec3& d : test_directions()) {
    const auto za = angles_from_direction(d);
    const auto fast = evaluate_basis(kReferenceBands, d);
    for (int i = 0; i < coefficient_count(kReferenceBands); ++i) {
      const auto lm = degree_order(i);
      const double ref = basis_reference(lm.l, lm.m, za.zenith, za.azimuth);
      worst = std::max(worst, std::abs(fast[static_cast<std::size_t>(i)] - ref));
      ASSERT_NEAR(fast[static_cast<std::size_t>(i)], ref, kFastVsReference)
          << "l=" << lm.l << " m=" << lm.m << " theta=" << za.zenith << " phi=" << za.azimuth;
    }
  }
  RecordProperty("worst_abs_difference", std::to_string(worst));
}

TEST(ShBasis, LowOrderClosedForms) {
  // Y_00 = 1 / (2 sqrt(pi)); Y_1,-1..1 = sqrt(3 / (4 pi)) (x, z, y) in the frame of core/frame.h.
  const Vec3 d = normalize({0.3, -0.5, 0.8});
  const auto y = evaluate_basis(2, d);
  const double k1 = std::sqrt(3.0 / (4.0 * kPi));
  EXPECT_NEAR(y[0], 0.5 / std::sqrt(kPi), kRoundOff);
  EXPECT_NEAR(y[1], k1 * d.x, kRoundOff);
  EXPECT_NEAR(y[2], k1 * d.z, kRoundOff);
  EXPECT_NEAR(y[3], k1 * d.y, kRoundOff);
}

TEST(ShBasis, OrthonormalOverTheSphereToTheLargestBandCount) {
  for (int bands : {8, kMaxBands}) {
    const int n = bands + 1, n_phi = 2 * bands + 2;
    std::vector<double> mu, w;
    gauss_legendre(n, -1.0, 1.0, mu, w);
    const auto count = static_cast<std::size_t>(coefficient_count(bands));
    std::vector<double> gram(count * count, 0.0);
    std::vector<double> y(count);
    for (int r = 0; r < n; ++r) {
      for (int j = 0; j < n_phi; ++j) {
        const Vec3 d = direction_from_angles(std::acos(mu[static_cast<std::size_t>(r)]),
                                             2.0 * kPi * (j + 0.5) / n_phi);
        evaluate_basis(bands, d, y);
        const double wt = w[static_cast<std::size_t>(r)] * 2.0 * kPi / n_phi;
        for (std::size_t a = 0; a < count; ++a) {
          for (std::size_t b = 0; b < count; ++b) gram[a * count + b] += wt * y[a] * y[b];
        }
      }
    }
    for (std::size_t a = 0; a < count; ++a) {
      for (std::size_t b = 0; b < count; ++b) {
        ASSERT_NEAR(gram[a * count + b], a == b ? 1.0 : 0.0, kOrthonormality)
            << "bands=" << bands << " i=" << a << " j=" << b;
      }
    }
  }
}

}  // namespace
}  // namespace skylight::sh
