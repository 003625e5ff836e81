#include "skylight/core/frame.h"

#include <gtest/gtest.h>

#include <random>

namespace skylight {
namespace {

// Round trips of closed-form trigonometry in double: a few ulps of pi.
constexpr double kAngleTol = 1e-12;

TEST(Frame, DirectionConventionEnu) {
  // docs/CONVENTIONS.md: azimuth from north (+y) towards east (+x), zenith = +z.
  const Vec3 north = direction_from_angles(kPi / 2, 0.0);
  const Vec3 east = direction_from_angles(kPi / 2, kPi / 2);
  const Vec3 up = direction_from_angles(0.0, 1.234);
  EXPECT_NEAR(north.y, 1.0, kAngleTol);
  EXPECT_NEAR(east.x, 1.0, kAngleTol);
  EXPECT_NEAR(up.z, 1.0, kAngleTol);
  EXPECT_NEAR(length(cross(east, north) - up), 0.0, kAngleTol) << "frame must be right-handed";
}

TEST(Frame, AnglesRoundTrip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> zen(0.01, kPi - 0.01), az(0.0, 2 * kPi);
  for (int i = 0; i < 1000; ++i) {
    const double t = zen(rng), p = az(rng);
    const auto za = angles_from_direction(direction_from_angles(t, p));
    EXPECT_NEAR(za.zenith, t, kAngleTol);
    EXPECT_NEAR(std::remainder(za.azimuth - p, 2 * kPi), 0.0, kAngleTol)
        << "theta " << t << " phi " << p;
  }
}

TEST(Frame, WrapAzimuth) {
  EXPECT_NEAR(wrap_azimuth(-kPi / 2), 1.5 * kPi, kAngleTol);
  EXPECT_NEAR(wrap_azimuth(5 * kPi), kPi, kAngleTol);
  EXPECT_EQ(wrap_azimuth(0.0), 0.0);
}

TEST(Frame, AngleBetweenIsAccurateNearZeroAndPi) {
  // acos(dot) would return 0 for 1e-9 rad: the atan2 form keeps the digits.
  const Vec3 a = direction_from_angles(0.3, 1.0);
  const Vec3 b = direction_from_angles(0.3 + 1e-9, 1.0);
  // Limited only by rounding of the unit vectors' components (~1.1e-16 each).
  EXPECT_NEAR(angle_between(a, b), 1e-9, 1e-15);
  EXPECT_NEAR(angle_between(a, -1.0 * a), kPi, kAngleTol);
  EXPECT_NEAR(
      angle_between(direction_from_angles(kPi / 2, 0), direction_from_angles(kPi / 2, kPi / 2)),
      kPi / 2, kAngleTol);
}

TEST(Frame, EquirectPixelCentres) {
  // Row 0 centre is theta = pi * 0.5 / H; column u centre is phi = 2 pi (u + 0.5) / W.
  const int W = 8, H = 4;
  const auto za = angles_from_direction(equirect_direction(2.5, 0.5, W, H));
  EXPECT_NEAR(za.zenith, kPi * 0.5 / H, kAngleTol);
  EXPECT_NEAR(za.azimuth, 2 * kPi * 2.5 / W, kAngleTol);
  EXPECT_NEAR(angles_from_direction(equirect_direction(0.5, H - 0.5, W, H)).zenith,
              kPi - kPi * 0.5 / H, kAngleTol);
  EXPECT_NEAR(angles_from_direction(hemisphere_direction(0.5, H - 0.5, W, H)).zenith,
              kPi / 2 - kPi / 4 / H, kAngleTol);
}

TEST(Frame, FisheyeNorthUpEastLeft) {
  FisheyeLayout layout;  // equidistant, 180 deg, north up
  const int S = 101;
  // A pixel straight above the centre sees north; left of the centre sees east.
  auto up = fisheye_direction(50.5, 10.5, S, S, layout);
  auto left = fisheye_direction(10.5, 50.5, S, S, layout);
  ASSERT_TRUE(up && left);
  EXPECT_NEAR(angles_from_direction(*up).azimuth, 0.0, kAngleTol);
  EXPECT_NEAR(angles_from_direction(*left).azimuth, kPi / 2, kAngleTol);
  // Equidistant: r = 40 px of 50.5 px radius -> theta = 90 deg * 40/50.5.
  EXPECT_NEAR(angles_from_direction(*up).zenith, kPi / 2 * 40.0 / 50.5, kAngleTol);
  EXPECT_FALSE(fisheye_direction(0.5, 0.5, S, S, layout)) << "corner is outside the image circle";
  // Rotating north by 90 deg counter-clockwise puts north on the left.
  layout.north_angle = kPi / 2;
  auto l2 = fisheye_direction(10.5, 50.5, S, S, layout);
  ASSERT_TRUE(l2);
  EXPECT_NEAR(std::remainder(angles_from_direction(*l2).azimuth, 2 * kPi), 0.0, kAngleTol);
}

TEST(Frame, FisheyeLensesRoundTrip) {
  for (auto lens : {FisheyeLens::equidistant, FisheyeLens::equisolid, FisheyeLens::orthographic,
                    FisheyeLens::stereographic}) {
    FisheyeLayout layout{lens, kPi, 0.3};
    for (double t = 0.0; t <= kPi / 2; t += 0.1) {
      const auto r = fisheye_radius(layout, t);
      ASSERT_TRUE(r) << to_string(lens);
      EXPECT_NEAR(*fisheye_theta(layout, *r), t, 1e-9) << to_string(lens);
      const Vec3 d = direction_from_angles(t, 2.0);
      const auto px = fisheye_pixel(d, 200, 200, layout);
      ASSERT_TRUE(px);
      const auto back = fisheye_direction((*px)[0], (*px)[1], 200, 200, layout);
      ASSERT_TRUE(back);
      EXPECT_NEAR(angle_between(*back, d), 0.0, 1e-9) << to_string(lens) << " theta " << t;
    }
    EXPECT_NEAR(*fisheye_radius(layout, kPi / 2), 1.0, kAngleTol);
  }
  EXPECT_FALSE(parse_fisheye_lens("fish"));
}

TEST(Frame, CubemapFacesCoverTheSphere) {
  const int H = 16, W = 6 * H;
  // Face centres look along +X, -X, +Y, -Y, +Z, -Z.
  const std::array<Vec3, 6> axes{
      {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
  for (int f = 0; f < 6; ++f) {
    const Vec3 d = cubemap_direction(f * H + H / 2.0, H / 2.0, W, H);
    EXPECT_NEAR(dot(d, axes[f]), 1.0, kAngleTol) << "face " << f;
  }
  // Top row of a side face is above the horizon; the +Z face's top edge points north.
  EXPECT_GT(cubemap_direction(0.5 * H, 0.5, W, H).z, 0.5);
  EXPECT_GT(cubemap_direction(4 * H + H / 2.0, 0.5, W, H).y, 0.5);
  // +Z face: east on the left, as seen looking up.
  EXPECT_GT(cubemap_direction(4 * H + 0.5, H / 2.0, W, H).x, 0.5);
}

}  // namespace
}  // namespace skylight
