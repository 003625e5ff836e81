#include "skylight/estimate/sky_type.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/error.h"
#include "skylight/models/cie_sky.h"

namespace skylight::estimate {
namespace {

// Samples of the type's own distribution: ln-residual at double round-off.
constexpr double kExactResidual = 1e-12;

std::vector<LuminanceSample> cie_samples(int type, const SunPosition& sun, double scale, int n) {
  std::vector<LuminanceSample> out;
  std::uint32_t s = 12345u + static_cast<std::uint32_t>(type);
  auto next = [&] {
    s = s * 1664525u + 1013904223u;
    return static_cast<double>(s >> 8) / static_cast<double>(1u << 24);
  };
  for (int i = 0; i < n; ++i) {
    const double Z = std::acos(0.05 + 0.95 * next());
    const Vec3 v = direction_from_angles(Z, 2 * kPi * next());
    out.push_back({v, scale * cie_relative_luminance(type, Z, angle_between(v, sun.direction()),
                                                     sun.zenith)});
  }
  return out;
}

TEST(SkyType, EachStandardTypeIsRecognisedFromItsOwnSkyAtAnyScale) {
  const SunPosition sun{50 * kDegree, 200 * kDegree};
  for (int type = 1; type <= 15; ++type) {
    const auto ranking = rank_cie_types(cie_samples(type, sun, 7300.0, 100), sun, 0.1);
    ASSERT_EQ(ranking.size(), 15u);
    EXPECT_EQ(ranking.front().type, type);
    EXPECT_EQ(ranking.front().inliers, 100);
    EXPECT_LT(ranking.front().residual, kExactResidual);
    EXPECT_NEAR(std::exp(ranking.front().log_scale), 7300.0, 7300.0 * kExactResidual);
  }
}

// Clouds on 30 % of the samples (x 3 and x 0.3) leave the median scale and the type unchanged.
TEST(SkyType, CloudySamplesAreOutliers) {
  const SunPosition sun{35 * kDegree, 90 * kDegree};
  for (const int type : {3, 8, 12}) {
    auto samples = cie_samples(type, sun, 1.0, 100);
    for (std::size_t i = 0; i < samples.size(); i += 10) {
      samples[i].luminance *= 3.0;
      samples[i + 1].luminance *= 0.3;
      samples[i + 2].luminance *= 3.0;
    }
    const auto ranking = rank_cie_types(samples, sun, 0.1);
    EXPECT_EQ(ranking.front().type, type);
    EXPECT_EQ(ranking.front().inliers, 70);
  }
  EXPECT_THROW(rank_cie_types(cie_samples(1, sun, 1.0, 5), SunPosition{100 * kDegree, 0.0}, 0.1),
               InvalidArgument);
}

}  // namespace
}  // namespace skylight::estimate
