#include "skylight/io/camera_calibration.h"

#include <gtest/gtest.h>

#include <string>

#include "skylight/core/error.h"
#include "support/error_message.h"

namespace skylight::io {
namespace {

using testing_support::error_message;

// Pixel <-> direction round trips: double arithmetic through atan2, hypot and the lens's inverse.
constexpr double kRoundTrip = 1e-9;

const char* const kFull = R"({
  "projection": "fisheye", "lens": "equisolid", "fov_deg": 190, "centre_px": [130.5, 95.25],
  "radius_px": 80, "mirrored": true, "north_angle_deg": 30, "image_size": [240, 200],
  "comment": "a test camera"
})";

TEST(CameraCalibration, EveryFieldIsRead) {
  const CameraCalibration c = parse_camera_calibration(kFull, "cam.json");
  EXPECT_EQ(c.projection, Projection::fisheye);
  EXPECT_EQ(c.fisheye.lens, FisheyeLens::equisolid);
  EXPECT_DOUBLE_EQ(c.fisheye.fov, deg_to_rad(190.0));
  EXPECT_DOUBLE_EQ(c.fisheye.north_angle, deg_to_rad(30.0));
  EXPECT_EQ(c.fisheye.centre, (std::array<double, 2>{130.5, 95.25}));
  EXPECT_EQ(c.fisheye.radius, 80.0);
  EXPECT_TRUE(c.fisheye.mirrored);
  const Camera cam = c.camera(240, 200);
  EXPECT_TRUE(cam.fisheye.calibrated());
  EXPECT_EQ(error_message([&] { c.camera(200, 240); }),
            "cam.json is for 240 x 200 photos, not 200 x 240");
  // Defaults: the centred circle of `render`.
  const CameraCalibration d = parse_camera_calibration(R"({"projection": "fisheye"})", "d.json");
  EXPECT_FALSE(d.fisheye.calibrated());
  EXPECT_EQ(d.fisheye.lens, FisheyeLens::equidistant);
  EXPECT_DOUBLE_EQ(d.fisheye.fov, kPi);
}

TEST(CameraCalibration, MalformedFilesAreRefusedByNameAndKey) {
  const auto message = [](const char* json) {
    return error_message([&] { parse_camera_calibration(json, "c.json"); });
  };
  EXPECT_EQ(message(R"({"projection": "fisheye", "centre": [1, 2]})"),
            "c.json: unknown key \"centre\"");
  EXPECT_EQ(message(R"({"lens": "equisolid"})"),
            "c.json: \"projection\" (\"fisheye\" or \"equirect\") is required");
  EXPECT_EQ(message(R"({"projection": "equirect", "radius_px": 10})"),
            "c.json: \"radius_px\" is a fisheye's; the projection is equirect");
  EXPECT_EQ(message(R"({"projection": "fisheye", "lens": "fish"})"),
            "c.json: \"lens\" must be equidistant, equisolid, orthographic or stereographic");
  EXPECT_EQ(message(R"({"projection": "fisheye", "radius_px": -3})"),
            "c.json: the image circle's radius -3 px is not positive");
  EXPECT_EQ(message(R"({"projection": "fisheye", "image_size": [0, 10]})"),
            "c.json: \"image_size\" must be [width, height] in pixels, 1 to 32768");
  EXPECT_EQ(message(R"({"projection": "fisheye", "centre_px": [1]})"),
            "c.json: \"centre_px\" must be [column, row]");
  EXPECT_NE(message("{").find("c.json: not JSON"), std::string::npos);
  // Beyond the double range: nlohmann's out_of_range, refused like a syntax error.
  EXPECT_NE(message(R"({"projection": "fisheye", "radius_px": 1e400})").find("c.json: not JSON"),
            std::string::npos);
  EXPECT_NE(message(R"({"projection": "fisheye", "lens": "orthographic", "fov_deg": 200})")
                .find("fov = 200 deg is outside (0, 180] for the orthographic lens"),
            std::string::npos);
}

// The image circle's radius from the EXIF focal length: r = f g(fov / 2).
TEST(CameraCalibration, RadiusFromTheFocalLength) {
  const CameraCalibration c = parse_camera_calibration(R"({"projection": "fisheye"})", "c.json");
  EXPECT_DOUBLE_EQ(*c.camera(400, 400, 100.0).fisheye.radius, 100.0 * kPi / 2);
  const CameraCalibration e =
      parse_camera_calibration(R"({"projection": "fisheye", "lens": "equisolid"})", "e.json");
  EXPECT_DOUBLE_EQ(*e.camera(400, 400, 100.0).fisheye.radius, 100.0 * 2.0 * std::sin(kPi / 4));
  // A radius in the file wins.
  const CameraCalibration r =
      parse_camera_calibration(R"({"projection": "fisheye", "radius_px": 150})", "r.json");
  EXPECT_DOUBLE_EQ(*r.camera(400, 400, 100.0).fisheye.radius, 150.0);
}

// The calibrated layout: the optical axis at the centre sees the zenith, every direction maps to a
// pixel and back, and mirroring swaps east and west about the image's vertical through the centre.
TEST(CameraCalibration, CalibratedFisheyeGeometry) {
  const Camera cam = parse_camera_calibration(kFull, "cam.json").camera(240, 200);
  const auto zenith = cam.direction(130.5, 95.25);
  ASSERT_TRUE(zenith);
  EXPECT_NEAR(zenith->z, 1.0, kRoundTrip);
  for (double theta : {0.1, 0.6, 1.2, 1.6})
    for (double phi : {0.0, 1.0, 2.5, 4.0, 5.5}) {
      const Vec3 d = direction_from_angles(theta, phi);
      const auto px = cam.pixel(d);
      ASSERT_TRUE(px);
      const auto back = cam.direction((*px)[0], (*px)[1]);
      ASSERT_TRUE(back);
      EXPECT_NEAR(angle_between(*back, d), 0.0, kRoundTrip) << theta << " " << phi;
    }
  Camera plain = cam;
  plain.fisheye.mirrored = false;
  for (double dx : {-40.0, 7.0, 33.0}) {
    const auto m = cam.direction(130.5 + dx, 120.0), p = plain.direction(130.5 - dx, 120.0);
    ASSERT_TRUE(m && p);
    EXPECT_NEAR(angle_between(*m, *p), 0.0, kRoundTrip);
  }
  // Outside the calibrated circle (radius 80 about the centre): nothing.
  EXPECT_FALSE(cam.direction(130.5 + 81.0, 95.25));
  EXPECT_TRUE(cam.direction(130.5 + 79.0, 95.25));
}

}  // namespace
}  // namespace skylight::io
