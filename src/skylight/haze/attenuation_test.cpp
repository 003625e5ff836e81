#include "skylight/haze/attenuation.h"

#include <gtest/gtest.h>

#include <cmath>

namespace skylight::haze {
namespace {

constexpr double kClosedFormRelTol = 1e-12;  // sums of the same terms in another order
// The table holds floats: each entry carries up to half an ulp near 1 besides the bound.
constexpr double kFloatStorageTol = 1e-7;

// A camera with flat channels: Gamma = sum of trapezoid-weighted e^(-beta s) / 400 nm.
CameraSensitivity flat_camera() {
  CameraSensitivity c;
  c.name = "flat";
  for (auto& q : c.channel) q = Spectrum({380.0, 780.0}, {1.0, 1.0});
  return c;
}

TEST(HazeAttenuation, GammaIsTheCameraWeightedMeanOfEquation11) {
  const Atmosphere air{2.5, 40.0, ScatteringVariant::improved};
  const Attenuation att(air, flat_camera());
  for (double g : att.gamma(0.0)) EXPECT_NEAR(g, 1.0, kClosedFormRelTol);
  const double s = 5000.0;
  double expected = 0.0;
  for (std::size_t i = 0; i < kGridSamples; ++i) {
    const double w = (i == 0 || i + 1 == kGridSamples) ? 0.5 : 1.0;
    expected += w * std::exp(-total_per_m(380.0 + 5.0 * i, air) * s) / 80.0;
  }
  for (double g : att.gamma(s)) EXPECT_NEAR(g, expected, expected * kClosedFormRelTol);
  // A real camera: blue is attenuated more than red (beta falls with wavelength).
  const Attenuation eos(air, find_camera("canon-eos-5d"));
  const Rgb3 g = eos.gamma(s);
  EXPECT_LT(g[2], g[1]);
  EXPECT_LT(g[1], g[0]);
  // More turbidity, less transmission.
  EXPECT_LT(Attenuation(Atmosphere{5.0, 40.0}, find_camera("canon-eos-5d")).gamma(s)[1], g[1]);
}

TEST(HazeAttenuation, TableInterpolationStaysWithinItsStatedBound) {
  for (double t : {1.5, 3.0, 8.0}) {
    const Attenuation att(Atmosphere{t, 0.0}, find_camera("sony-ilce-7m3"));
    const double far = 30000.0;
    const AttenuationTable table = make_attenuation_table(att, far, 1e-5);
    EXPECT_LE(table.error_bound, 1e-5);
    double worst = 0.0;
    for (int k = 0; k <= 4000; ++k) {  // points between the entries too
      const double s = far * k / 4000.0 + 0.37;
      const double u = std::min(s / table.step_m, static_cast<double>(table.size() - 1));
      const auto i = std::min(static_cast<std::size_t>(u), table.size() - 2);
      const double f = u - static_cast<double>(i);
      const Rgb3 exact = att.gamma(std::min(s, far));
      for (std::size_t c = 0; c < 3; ++c) {
        const double v =
            table.gamma[3 * i + c] + f * (table.gamma[3 * i + 3 + c] - table.gamma[3 * i + c]);
        worst = std::max(worst, std::abs(v - exact[c]));
      }
    }
    EXPECT_LE(worst, table.error_bound + kFloatStorageTol)
        << "T " << t << " entries " << table.size() << " bound " << table.error_bound;
  }
}

}  // namespace
}  // namespace skylight::haze
