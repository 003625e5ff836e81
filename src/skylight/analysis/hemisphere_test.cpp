#include "skylight/analysis/hemisphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "skylight/core/error.h"

namespace skylight::analysis {
namespace {

TEST(HemisphereGrid, SolidAnglesSumToTheHemisphere) {
  const auto g = hemisphere_grid(18, 36);
  ASSERT_EQ(g.directions.size(), 18u * 36u);
  double sum = 0.0;
  for (double w : g.solid_angle) sum += w;
  EXPECT_NEAR(sum, 2 * kPi, 1e-12);
  for (const auto& d : g.directions) EXPECT_GT(d.z, 0.0);
  EXPECT_THROW(hemisphere_grid(0, 10), InvalidArgument);
}

}  // namespace
}  // namespace skylight::analysis
