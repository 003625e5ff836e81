#include "skylight/core/camera.h"

#include <gtest/gtest.h>

#include "skylight/core/error.h"

namespace skylight {
namespace {

// pixel -> direction -> pixel goes through asin/atan2 and back: double round-off, a few ulps of a
// pixel coordinate of ~1000.
constexpr double kRoundTripPx = 1e-9;

TEST(Camera, FisheyePixelDirectionRoundTripsForEveryLens) {
  for (const FisheyeLens lens : {FisheyeLens::equidistant, FisheyeLens::equisolid,
                                 FisheyeLens::orthographic, FisheyeLens::stereographic}) {
    Camera cam{Projection::fisheye, 301, 257, {lens, kPi, 0.3}};
    validate(cam);
    int imaged = 0;
    for (int row = 0; row < cam.height; row += 7)
      for (int col = 0; col < cam.width; col += 5) {
        const auto d = cam.pixel_direction(col, row);
        if (!d) continue;
        ++imaged;
        const auto p = cam.pixel(*d);
        ASSERT_TRUE(p) << to_string(lens) << " " << col << "," << row;
        EXPECT_NEAR((*p)[0], col + 0.5, kRoundTripPx) << to_string(lens);
        EXPECT_NEAR((*p)[1], row + 0.5, kRoundTripPx) << to_string(lens);
        // The same mapping as render's (core/frame.h).
        const auto ref = fisheye_direction(col + 0.5, row + 0.5, 301, 257, cam.fisheye);
        EXPECT_EQ(ref->x, d->x);
        EXPECT_EQ(ref->z, d->z);
      }
    EXPECT_GT(imaged, 1000) << to_string(lens);
  }
}

TEST(Camera, EquirectPixelDirectionRoundTrips) {
  const Camera cam{Projection::equirect, 360, 180, {}};
  for (int row = 0; row < cam.height; row += 3)
    for (int col = 0; col < cam.width; col += 7) {
      const auto d = cam.pixel_direction(col, row);
      ASSERT_TRUE(d);
      const Vec3 ref = equirect_direction(col + 0.5, row + 0.5, 360, 180);
      EXPECT_EQ(ref.y, d->y);
      const auto p = cam.pixel(*d);
      ASSERT_TRUE(p);
      EXPECT_NEAR((*p)[0], col + 0.5, kRoundTripPx);
      EXPECT_NEAR((*p)[1], row + 0.5, kRoundTripPx);
    }
}

TEST(Camera, ValidateRefusesBadGeometry) {
  EXPECT_THROW(validate(Camera{Projection::fisheye, 0, 10, {}}), InvalidArgument);
  EXPECT_THROW(
      validate(Camera{Projection::fisheye, 10, 10, {FisheyeLens::orthographic, 1.1 * kPi}}),
      InvalidArgument);
  EXPECT_THROW(validate(Camera{Projection::cubemap, 600, 99, {}}), InvalidArgument);
  EXPECT_EQ(parse_projection("equirect"), Projection::equirect);
  EXPECT_EQ(parse_projection("cubemap"), Projection::cubemap);
  EXPECT_FALSE(parse_projection("cube"));
}

}  // namespace
}  // namespace skylight
