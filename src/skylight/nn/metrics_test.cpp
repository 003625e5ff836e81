#include "skylight/nn/metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/analytic_sky.h"

namespace skylight::nn {
namespace {

// A network whose every output is the constant y0 (zero weights, output biases b with
// f(b) = y0 for the satilmis output activation: b = sqrt(1/y0 - 1)).
SkyNetwork constant_sky(double y0) {
  SkyNetwork s;
  s.target_scale = 683.0;
  s.net = Mlp(MlpLayout::make(6, {4}, 3, Activation::satilmis, Activation::satilmis));
  auto p = s.net.parameters();
  for (int c = 0; c < 3; ++c) p[s.net.layout().bias_offset(2) + c] = std::sqrt(1.0 / y0 - 1.0);
  return s;
}

// The same sums in another order: double round-off.
constexpr double kSumRelTolerance = 1e-12;
// A maximum over the same quotients: round-off of one division.
constexpr double kMaxRelTolerance = 1e-9;

Dataset small_set() {
  SamplingSpec spec = paper_validation_spec("hosek", {2.5, 6.5}, 683.0);
  spec.sun_count = 3;
  spec.view_zeniths = 4;
  spec.view_azimuths = 6;
  return build_dataset(spec, satilmis_inputs(), testing_support::analytic_sky_source(683.0));
}

TEST(Metrics, ErrorsOfAConstantNetwork) {
  const Dataset ds = small_set();
  const double y0 = 0.1;  // L_s(0.1) = 4.5
  const ErrorStats e = evaluate_errors(constant_sky(y0), ds);
  double sum2 = 0.0, max_rel = 0.0;
  for (double L : ds.radiance) {
    const double r = y0 - 1.0 / (1.0 + 2.0 * L);
    sum2 += r * r;
    max_rel = std::max(max_rel, std::abs(4.5 - L) / L);
  }
  EXPECT_NEAR(e.rmse, std::sqrt(sum2 / ds.radiance.size()), kSumRelTolerance);
  EXPECT_EQ(e.samples, ds.radiance.size());
  EXPECT_EQ(e.relative_count + e.relative_excluded, ds.radiance.size());
  EXPECT_NEAR(e.relative_max, max_rel, kMaxRelTolerance * max_rel);
  EXPECT_LE(e.relative_median, e.relative_p95);
}

// For constant radiance L the integral of eq. 11 is pi L; the 32 x 64 midpoint rule is within
// 1e-3 of it (its error is O(dtheta^2) ~ 2.4e-3 / 12 relative).
constexpr double kQuadratureTolerance = 1e-3;

TEST(Metrics, IrradianceOfAConstantSkyIsPiL) {
  const Dataset ds = small_set();
  const IrradianceStats s =
      evaluate_irradiance(constant_sky(0.1), ds, testing_support::analytic_sky_source(683.0));
  ASSERT_EQ(s.network.size(), ds.states.size());
  EXPECT_NEAR(s.network[0][1], kPi * 4.5, kQuadratureTolerance * kPi * 4.5);
  EXPECT_GT(s.reference_mean, 0.0);
}

}  // namespace
}  // namespace skylight::nn
