#include "skylight/render/sky_render.h"

#include <gtest/gtest.h>

#include "skylight/core/error.h"

namespace skylight::render {
namespace {

// The disc is supersampled so that it spans >= 16 samples across: the area of a 16-sample-wide
// disc on a square grid is right to ~1 %; 2 % leaves margin.
constexpr double kSunEnergyRelTol = 0.02;

std::unique_ptr<SkyModel> preetham(double sun_zenith_deg, double sun_azimuth_deg) {
  SkyParameters p;
  p.values.set("turbidity", 3.0);
  p.sun = {deg_to_rad(sun_zenith_deg), deg_to_rad(sun_azimuth_deg)};
  return make_sky_model("preetham", p);
}

// Integral of Y over the sphere for an equirect luminance map: sum of Y * pixel solid angle,
// Omega = (2 pi / W) (cos theta_top - cos theta_bottom).
double equirect_integral(const SkyImage& img) {
  double sum = 0.0;
  const int W = img.xyz.width, H = img.xyz.height;
  for (int row = 0; row < H; ++row) {
    const double omega = 2.0 * kPi / W * (std::cos(kPi * row / H) - std::cos(kPi * (row + 1) / H));
    for (int col = 0; col < W; ++col) sum += img.xyz.pixel(col, row)[1] * omega;
  }
  return sum;
}

TEST(SkyRender, SunEnergyIndependentOfResolution) {
  const auto m = preetham(45.0, 200.0);
  const double r = m->sun_angular_radius();
  const double L_sun = m->sun_tristimulus(m->sun().direction()).Y;
  const double expected = L_sun * 2.0 * kPi * (1.0 - std::cos(r));  // uniform disc, cd/m^2 * sr
  for (int W : {128, 256, 1024, 2048}) {
    RenderSettings s;
    s.width = W;
    s.height = W / 2;
    s.sun = SunMode::sun_only;
    const SkyImage img = render_sky(*m, s);
    EXPECT_NEAR(equirect_integral(img), expected, expected * kSunEnergyRelTol) << "width " << W;
  }
}

TEST(SkyRender, SunOnlyIsZeroAwayFromTheDiscAndSkyAddsUp) {
  const auto m = preetham(30.0, 90.0);
  RenderSettings s;
  s.width = 64;
  s.height = 32;
  s.sun = SunMode::sun_only;
  const SkyImage sun = render_sky(*m, s);
  s.sun = SunMode::sky;
  const SkyImage sky = render_sky(*m, s);
  s.sun = SunMode::sky_and_sun;
  const SkyImage both = render_sky(*m, s);
  int lit = 0;
  for (std::size_t i = 0; i < sun.xyz.data.size(); ++i) {
    lit += sun.xyz.data[i] > 0.0f;
    EXPECT_FLOAT_EQ(both.xyz.data[i], sky.xyz.data[i] + sun.xyz.data[i]);
  }
  EXPECT_GT(lit, 0);
  EXPECT_LE(lit, 3 * 4) << "a disc of 0.54 deg touches at most 4 pixels of 5.6 deg";
}

TEST(SkyRender, PixelsMatchTheModelAndLayout) {
  const auto m = preetham(50.0, 10.0);
  RenderSettings s;
  s.projection = Projection::fisheye;
  s.width = 33;
  s.height = 33;
  const SkyImage img = render_sky(*m, s);
  EXPECT_EQ(img.mask[0], 1) << "corner outside the fisheye circle";
  EXPECT_EQ(img.xyz.pixel(0, 0)[1], 0.0f);
  const auto d = s.direction(16.5, 16.5);
  ASSERT_TRUE(d);
  EXPECT_NEAR(d->z, 1.0, 1e-12);
  // Float batch vs double scalar (batch_test.cpp bound).
  const double ref = m->tristimulus(*d).Y;
  EXPECT_NEAR(img.xyz.pixel(16, 16)[1], ref, ref * 3e-5);
  // RGB is XYZ -> linear sRGB of the same pixel.
  const float* x = img.xyz.pixel(16, 16);
  const Rgb rgb = xyz_to_linear_srgb({x[0], x[1], x[2]});
  EXPECT_NEAR(img.rgb.pixel(16, 16)[0], rgb.r, std::abs(rgb.r) * 1e-6);
}

TEST(SkyRender, RejectsBadSettings) {
  RenderSettings s;
  s.width = 0;
  EXPECT_THROW(validate(s), InvalidArgument);
  s.width = 100;
  s.height = 10;
  s.projection = Projection::cubemap;
  EXPECT_THROW(validate(s), InvalidArgument);
  s.projection = Projection::fisheye;
  s.fisheye.lens = FisheyeLens::orthographic;
  s.fisheye.fov = deg_to_rad(200.0);
  EXPECT_THROW(validate(s), InvalidArgument);
  EXPECT_FALSE(parse_projection("mercator"));
}

}  // namespace
}  // namespace skylight::render

namespace skylight::render {
namespace {

constexpr double kDirTol = 1e-12;  // a few vector operations in double

// A `width` x `height` camera image looking at (zenith, azimuth) with a vertical field of view
// `fov_deg`, all in degrees.
RenderSettings camera_settings(int width, int height, double look_zenith_deg,
                               double look_azimuth_deg, double fov_deg) {
  RenderSettings s;
  s.projection = Projection::camera;
  s.width = width;
  s.height = height;
  s.pinhole = {deg_to_rad(look_zenith_deg), deg_to_rad(look_azimuth_deg), deg_to_rad(fov_deg)};
  return s;
}

void expect_same_direction(const Vec3& got, const Vec3& want) {
  EXPECT_NEAR(got.x, want.x, kDirTol);
  EXPECT_NEAR(got.y, want.y, kDirTol);
  EXPECT_NEAR(got.z, want.z, kDirTol);
}

TEST(SkyRender, CameraLooksWhereAsked) {
  RenderSettings s = camera_settings(200, 100, 120, 30, 60);
  // The image centre is the look direction; the top edge centre is 30 deg above it (fov / 2).
  const Vec3 f = direction_from_angles(deg_to_rad(120), deg_to_rad(30));
  const Vec3 c = *s.direction(100, 50);
  expect_same_direction(c, f);
  const Vec3 top = *s.direction(100, 0);
  EXPECT_NEAR(angle_between(top, f), deg_to_rad(30), kDirTol);
  EXPECT_GT(top.z, c.z);  // image up is towards the zenith
  // Square pixels: the right edge centre is atan(2 tan 30 deg) away.
  EXPECT_NEAR(angle_between(*s.direction(200, 50), f), std::atan(2 * std::tan(deg_to_rad(30))),
              kDirTol);
  // Straight down works too (image up = north).
  s.pinhole.look_zenith = kPi;
  EXPECT_NEAR(s.direction(100, 50)->z, -1.0, kDirTol);
  s.pinhole.vertical_fov = kPi;
  EXPECT_THROW(validate(s), InvalidArgument);
}

TEST(SkyRender, CameraLayoutIsTheOneInConventions) {
  // docs/CONVENTIONS.md, "Camera": d = normalize(f + x r + y u) at pixel centres, r = f x z
  // (f x north when f is vertical), u = r x f.
  RenderSettings s = camera_settings(12, 8, 65, 60, 50);
  const Vec3 f = direction_from_angles(s.pinhole.look_zenith, s.pinhole.look_azimuth);
  const Vec3 r = normalize(cross(f, Vec3{0, 0, 1}));
  const Vec3 u = cross(r, f);
  const double t = std::tan(0.5 * s.pinhole.vertical_fov);
  const auto dirs = pixel_directions(s);
  for (int row = 0; row < s.height; ++row)
    for (int col = 0; col < s.width; ++col) {
      const double x = (2.0 * (col + 0.5) / s.height - 1.0 * s.width / s.height) * t;
      const double y = (1.0 - 2.0 * (row + 0.5) / s.height) * t;
      const Vec3 want = normalize(f + x * r + y * u);
      expect_same_direction(*s.direction(col + 0.5, row + 0.5), want);
      EXPECT_TRUE(dirs.valid[static_cast<std::size_t>(row * s.width + col)]);  // no mask
    }
  // Looking north at the horizon, east is on the right.
  s.pinhole = {kPi / 2, 0.0, deg_to_rad(60)};
  EXPECT_GT(s.direction(12, 4)->x, 0.0);
  // Looking up: west on the right, north at the top; looking down: east on the right, north up.
  s.pinhole.look_zenith = 0.0;
  EXPECT_LT(s.direction(12, 4)->x, 0.0);
  EXPECT_GT(s.direction(6, 0)->y, 0.0);
  s.pinhole.look_zenith = kPi;
  EXPECT_GT(s.direction(12, 4)->x, 0.0);
  EXPECT_GT(s.direction(6, 0)->y, 0.0);
}

}  // namespace
}  // namespace skylight::render
