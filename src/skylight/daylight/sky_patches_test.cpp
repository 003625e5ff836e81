#include "skylight/daylight/sky_patches.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "skylight/core/math.h"

namespace skylight::daylight {
namespace {

// Sums of a few thousand solid angles in double: round-off only.
constexpr double kSolidAngleTol = 1e-9;
// Angles built from degrees and back: round-off only.
constexpr double kAngleTolDeg = 1e-9;

TEST(SkyPatches, CountsAndSolidAnglesOfTregenzaAndReinhart) {
  for (const auto& [name, mf, count] :
       {std::tuple{"tregenza", 1, 145u}, std::tuple{"reinhart2", 2, 577u},
        std::tuple{"reinhart4", 4, 2305u}}) {
    const auto set = PatchSet::named(name);
    ASSERT_TRUE(set.has_value()) << name;
    EXPECT_EQ(set->mf(), mf);
    EXPECT_EQ(set->size(), count + 1) << name;  // and the ground
    EXPECT_EQ(count, 144u * mf * mf + 1);
    double sky = 0.0;
    for (std::size_t i = 1; i < set->size(); ++i) sky += set->patches()[i].solid_angle;
    EXPECT_NEAR(sky, 2.0 * kPi, kSolidAngleTol) << name;
    EXPECT_EQ(set->patches()[0].solid_angle, 2.0 * kPi);
  }
  EXPECT_FALSE(PatchSet::named("klems").has_value());
}

TEST(SkyPatches, TregenzaRowsAndCentresAsPublished) {
  // Tregenza 1987: 12-degree rows of 30, 30, 24, 24, 18, 12, 6 patches and a 6-degree cap;
  // patch 1 faces north at the horizon, numbering runs towards east.
  const PatchSet t(1);
  const int counts[] = {30, 30, 24, 24, 18, 12, 6};
  std::size_t i = 1;
  for (int r = 0; r < 7; ++r) {
    for (int j = 0; j < counts[r]; ++j, ++i) {
      const SkyPatch& p = t.patches()[i];
      EXPECT_EQ(p.row, r);
      EXPECT_NEAR(p.altitude_lo_deg, 12.0 * r, kAngleTolDeg);
      EXPECT_NEAR(p.altitude_hi_deg, 12.0 * (r + 1), kAngleTolDeg);
      const double step = 360.0 / counts[r];
      EXPECT_NEAR(p.azimuth_hi_deg - p.azimuth_lo_deg, step, kAngleTolDeg);
      const auto a = angles_from_direction(p.centre);
      EXPECT_NEAR(90.0 - rad_to_deg(a.zenith), 12.0 * r + 6.0, kAngleTolDeg);
      EXPECT_NEAR(std::remainder(rad_to_deg(a.azimuth) - j * step, 360.0), 0.0, kAngleTolDeg);
      // Solid angle of the band's share: 2 pi (sin hi - sin lo) / n.
      EXPECT_NEAR(p.solid_angle,
                  2.0 * kPi *
                      (std::sin(deg_to_rad(12.0 * (r + 1))) - std::sin(deg_to_rad(12.0 * r))) /
                      counts[r],
                  kSolidAngleTol);
    }
  }
  EXPECT_EQ(i, 145u);
  EXPECT_NEAR(t.patches()[145].altitude_lo_deg, 84.0, kAngleTolDeg);
  EXPECT_NEAR(t.patches()[145].solid_angle, 2.0 * kPi * (1.0 - std::cos(deg_to_rad(6.0))),
              kSolidAngleTol);
  // Patch 1 faces north, patch 8 (the 8th of the first row) east of north by 84 degrees.
  EXPECT_NEAR(t.patches()[1].centre.x, 0.0, 1e-12);
  EXPECT_GT(t.patches()[1].centre.y, 0.0);
  EXPECT_GT(t.patches()[8].centre.x, 0.0);  // east
}

TEST(SkyPatches, FindReturnsThePatchWhoseBoundsHoldTheDirection) {
  for (int mf : {1, 2, 4}) {
    const PatchSet set(mf);
    for (std::size_t i = 0; i < set.size(); ++i) EXPECT_EQ(set.find(set.patches()[i].centre), i);
    std::mt19937 rng(static_cast<unsigned>(mf));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < 2000; ++k) {
      const Vec3 d = normalize({u(rng), u(rng), u(rng)});
      const std::size_t i = set.find(d);
      const SkyPatch& p = set.patches()[i];
      const auto a = angles_from_direction(d);
      const double alt = 90.0 - rad_to_deg(a.zenith);
      EXPECT_GE(alt, p.altitude_lo_deg - kAngleTolDeg);
      EXPECT_LE(alt, p.altitude_hi_deg + kAngleTolDeg);
      if (i == 0 || i + 1 == set.size()) continue;  // ground and cap span every azimuth
      double az = rad_to_deg(a.azimuth);
      if (az >= p.azimuth_hi_deg) az -= 360.0;
      EXPECT_GE(az, p.azimuth_lo_deg - kAngleTolDeg);
      EXPECT_LT(az, p.azimuth_hi_deg + kAngleTolDeg);
    }
  }
}

}  // namespace
}  // namespace skylight::daylight
