#include "skylight/haze/positioning.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/haze/image_haze.h"

namespace skylight::haze {
namespace {

// Double arithmetic through two 4x4 inversions of matrices with entries up to ~1e4 (far / near).
constexpr double kAngleTol = 1e-9;      // [rad]
constexpr double kWindowTol = 1e-9;     // window coordinates [1]
constexpr double kDepthRelTol = 1e-7;   // eq. 19 vs eq. 22: s_bar near 1 loses digits to far/near
constexpr double kRoundTripTol = 1e-9;  // [m] relative to the point's distance

constexpr int kWidth = 640, kHeight = 480;
constexpr double kNear = 1.0, kFar = 5000.0;

ImagePositioning camera(double heading, double pitch, double roll, double fov_y) {
  return ImagePositioning(
      view_matrix(heading, pitch, roll),
      perspective_matrix(fov_y, static_cast<double>(kWidth) / kHeight, kNear, kFar), kWidth,
      kHeight);
}

TEST(Positioning, RemapMatrixIsEquation23) {
  const Mat4 r = remap_matrix();
  const Mat4 expected{2, 0, 0, -1, 0, 2, 0, -1, 0, 0, 2, -1, 0, 0, 0, 1};
  EXPECT_EQ(r, expected);
  const Mat4 back = multiply(invert(r, "R"), r);
  for (std::size_t i = 0; i < 16; ++i) EXPECT_NEAR(back[i], identity4()[i], 1e-15);
}

TEST(Positioning, SingularMatrixIsAnError) {
  Mat4 m{};
  EXPECT_THROW(invert(m, "zero"), InvalidArgument);
  EXPECT_THROW(ImagePositioning(m, identity4(), 4, 4), InvalidArgument);
  // Invertible, but the window's far plane (s_bar = 1) is at infinity: w = 0.
  const Mat4 far_at_infinity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1};
  const ImagePositioning p(identity4(), far_at_infinity, 4, 4);
  EXPECT_THROW(p.pixel_direction(1, 1), InvalidArgument);
}

// The image centre (l = 1/2, 1/2) looks along the optical axis: zenith pi/2 - pitch, azimuth =
// heading, whatever the roll.
TEST(Positioning, CentreIsTheOpticalAxis) {
  double worst_centre = 0.0;
  for (double heading : {0.0, 0.3, kPi / 2, 2.5, 4.0})
    for (double pitch : {-0.4, 0.0, 0.2, 1.0})
      for (double roll : {0.0, 0.35, -1.2}) {
        const ImagePositioning p = camera(heading, pitch, roll, 50.0 * kDegree);
        const ZenithAzimuth a = angles_from_direction(p.direction(0.5, 0.5));
        worst_centre = std::max({worst_centre, std::abs(a.zenith - (kPi / 2 - pitch)),
                                 std::abs(std::remainder(a.azimuth - heading, 2 * kPi))});
        EXPECT_NEAR(a.zenith, kPi / 2 - pitch, kAngleTol);
        EXPECT_NEAR(std::remainder(a.azimuth - heading, 2 * kPi), 0.0, kAngleTol);
        const Vec3 eye = p.eye();
        EXPECT_NEAR(length(eye), 0.0, 1e-12);
      }
  std::cout << "[ positioning ] centre pixel vs optical axis: worst " << worst_centre << " rad\n";
}

// A level camera (pitch and roll 0): the top and bottom edge centres are fov_y / 2 above and below
// the horizon, the left and right edge centres fov_x / 2 left and right of the heading, with
// tan(fov_x / 2) = aspect tan(fov_y / 2); the corners see tan(elevation) = tan(fov_y / 2) cos of
// their azimuth offset.
TEST(Positioning, EdgesAndCornersSpanTheFieldOfView) {
  const double fov_y = 40.0 * kDegree, aspect = static_cast<double>(kWidth) / kHeight;
  const double heading = 1.1;
  const ImagePositioning p = camera(heading, 0.0, 0.0, fov_y);
  const double half_x = std::atan(aspect * std::tan(fov_y / 2));
  EXPECT_NEAR(vertical_fov(2 * half_x, aspect), fov_y, kAngleTol);
  EXPECT_NEAR(angles_from_direction(p.direction(0.5, 1.0)).zenith, kPi / 2 - fov_y / 2, kAngleTol);
  EXPECT_NEAR(angles_from_direction(p.direction(0.5, 0.0)).zenith, kPi / 2 + fov_y / 2, kAngleTol);
  EXPECT_NEAR(angles_from_direction(p.direction(1.0, 0.5)).azimuth, heading + half_x, kAngleTol);
  EXPECT_NEAR(angles_from_direction(p.direction(0.0, 0.5)).azimuth, heading - half_x, kAngleTol);
  const ZenithAzimuth corner = angles_from_direction(p.direction(1.0, 1.0));  // top right
  EXPECT_NEAR(corner.azimuth, heading + half_x, kAngleTol);
  EXPECT_NEAR(std::tan(kPi / 2 - corner.zenith), std::tan(fov_y / 2) * std::cos(half_x), kAngleTol);
  // Pixel centres sit half a pixel inside the edges.
  const ZenithAzimuth top_row = p.pixel_angles(kWidth / 2, 0);
  EXPECT_LT(top_row.zenith, kPi / 2);
  EXPECT_GT(top_row.zenith, kPi / 2 - fov_y / 2);
}

// Roll by pi/2 (clockwise): the image's right edge points down, its top edge to the camera's
// former right.
TEST(Positioning, RollTurnsTheImageClockwise) {
  const double fov_y = 30.0 * kDegree;
  const ImagePositioning p = camera(0.0, 0.0, kPi / 2, fov_y);
  const double half_x = std::atan(static_cast<double>(kWidth) / kHeight * std::tan(fov_y / 2));
  EXPECT_NEAR(angles_from_direction(p.direction(1.0, 0.5)).zenith, kPi / 2 + half_x, kAngleTol);
  const ZenithAzimuth top = angles_from_direction(p.direction(0.5, 1.0));
  EXPECT_NEAR(top.zenith, kPi / 2, kAngleTol);
  EXPECT_NEAR(top.azimuth, fov_y / 2, kAngleTol);  // east of north
}

// Eq. 22 then the forward projection is the identity, and the forward projection then eq. 22.
TEST(Positioning, RoundTripWithTheForwardProjection) {
  const ImagePositioning p = camera(2.0, 0.3, -0.2, 60.0 * kDegree);
  double worst = 0.0;
  for (double lx : {0.0, 0.13, 0.5, 0.97})
    for (double ly : {0.02, 0.5, 1.0})
      for (double s_bar : {0.0, 0.4, 0.9, 0.999}) {
        const std::array<double, 3> w = p.project(p.position(lx, ly, s_bar));
        EXPECT_NEAR(w[0], lx, kWindowTol);
        EXPECT_NEAR(w[1], ly, kWindowTol);
        EXPECT_NEAR(w[2], s_bar, kWindowTol);
        for (double e : {w[0] - lx, w[1] - ly, w[2] - s_bar}) worst = std::max(worst, std::abs(e));
      }
  std::cout << "[ positioning ] round trip: worst window error " << worst << "\n";
  const Vec3 x{120.0, -340.0, 55.0};
  const std::array<double, 3> w = p.project(x);
  EXPECT_NEAR(length(p.position(w[0], w[1], w[2]) - x), 0.0, kRoundTripTol * length(x));
}

// Eq. 19 is the eye-space depth (along the optical axis) of eq. 22's point at window depth s_bar;
// the point lies on the pixel's ray.
TEST(Positioning, Equation19IsTheDepthOfEquation22) {
  const double pitch = 0.25, heading = 3.0;
  const ImagePositioning p = camera(heading, pitch, 0.1, 45.0 * kDegree);
  const Vec3 axis = direction_from_angles(kPi / 2 - pitch, heading);
  double worst = 0.0;
  for (double lx : {0.1, 0.5, 0.8})
    for (double ly : {0.3, 0.5, 0.95})
      for (double s_bar : {0.0, 0.25, 0.5, 0.9, 0.99}) {
        const Vec3 x = p.position(lx, ly, s_bar);
        const double s = depth_from_normalised(s_bar, kNear, kFar);
        EXPECT_NEAR(dot(x, axis), s, kDepthRelTol * s);
        worst = std::max(worst, std::abs(dot(x, axis) - s) / s);
        const Vec3 d = p.direction(lx, ly);
        EXPECT_NEAR(length(x - dot(x, d) * d), 0.0, kDepthRelTol * s);
      }
  std::cout << "[ positioning ] eq. 19 vs eq. 22's eye depth: worst relative difference " << worst
            << "\n";
}

// A raw model-view with a translation: directions do not depend on where the camera stands.
TEST(Positioning, DirectionsIgnoreTheCameraPosition) {
  Mat4 view = view_matrix(0.7, 0.1, 0.0);
  const Mat4 proj = perspective_matrix(0.8, 1.5, 0.5, 900.0);
  const ImagePositioning at_origin(view, proj, 30, 20);
  // Translate the world by -(10, 20, 5): the camera stands at (10, 20, 5).
  Mat4 t = identity4();
  t[3] = -10.0;
  t[7] = -20.0;
  t[11] = -5.0;
  const ImagePositioning moved(multiply(view, t), proj, 30, 20);
  EXPECT_NEAR(moved.eye().x, 10.0, 1e-9);
  EXPECT_NEAR(moved.eye().y, 20.0, 1e-9);
  EXPECT_NEAR(moved.eye().z, 5.0, 1e-9);
  for (int row : {0, 7, 19})
    for (int col : {0, 15, 29})
      EXPECT_NEAR(length(moved.pixel_direction(col, row) - at_origin.pixel_direction(col, row)),
                  0.0, kAngleTol);
}

}  // namespace
}  // namespace skylight::haze
