#include "skylight/core/frame.h"

#include <algorithm>

#include "skylight/core/error.h"

namespace skylight {

Vec3 normalize(Vec3 a) {
  const double len = length(a);
  SKYLIGHT_CHECK(len > 0.0 && std::isfinite(len), "normalize() of a zero or non-finite vector");
  return (1.0 / len) * a;
}

Vec3 direction_from_angles(double zenith, double azimuth) {
  const double st = std::sin(zenith);
  return {st * std::sin(azimuth), st * std::cos(azimuth), std::cos(zenith)};
}

double wrap_azimuth(double phi) {
  const double two_pi = 2.0 * kPi;
  double w = std::fmod(phi, two_pi);
  if (w < 0.0) w += two_pi;
  if (w >= two_pi) w = 0.0;  // fmod of a value just below 0 can round up to 2 pi
  return w;
}

ZenithAzimuth angles_from_direction(Vec3 d) {
  const double horizontal = std::hypot(d.x, d.y);
  ZenithAzimuth za;
  za.zenith = std::atan2(horizontal, d.z);
  za.azimuth = horizontal > 0.0 ? wrap_azimuth(std::atan2(d.x, d.y)) : 0.0;
  return za;
}

double angle_between(Vec3 a, Vec3 b) {
  return std::atan2(length(cross(a, b)), dot(a, b));
}

Vec3 equirect_direction(double col_centre, double row_centre, int width, int height) {
  const double theta = kPi * row_centre / height;
  const double phi = 2.0 * kPi * col_centre / width;
  return direction_from_angles(theta, phi);
}

Vec3 hemisphere_direction(double col_centre, double row_centre, int width, int height) {
  const double theta = 0.5 * kPi * row_centre / height;
  const double phi = 2.0 * kPi * col_centre / width;
  return direction_from_angles(theta, phi);
}

std::optional<FisheyeLens> parse_fisheye_lens(std::string_view name) {
  if (name == "equidistant") return FisheyeLens::equidistant;
  if (name == "equisolid") return FisheyeLens::equisolid;
  if (name == "orthographic") return FisheyeLens::orthographic;
  if (name == "stereographic") return FisheyeLens::stereographic;
  return std::nullopt;
}

std::string_view to_string(FisheyeLens lens) {
  switch (lens) {
    case FisheyeLens::equidistant:
      return "equidistant";
    case FisheyeLens::equisolid:
      return "equisolid";
    case FisheyeLens::orthographic:
      return "orthographic";
    case FisheyeLens::stereographic:
      return "stereographic";
  }
  return "equidistant";
}

std::optional<double> fisheye_lens_mapping(FisheyeLens lens, double theta) {
  switch (lens) {
    case FisheyeLens::equidistant:
      return theta;
    case FisheyeLens::equisolid:
      return 2.0 * std::sin(0.5 * theta);
    case FisheyeLens::orthographic:
      if (theta > 0.5 * kPi) return std::nullopt;
      return std::sin(theta);
    case FisheyeLens::stereographic:
      if (theta >= kPi) return std::nullopt;
      return 2.0 * std::tan(0.5 * theta);
  }
  return std::nullopt;
}

std::optional<double> fisheye_radius(const FisheyeLayout& layout, double theta) {
  if (theta < 0.0 || theta > 0.5 * layout.fov) return std::nullopt;
  const auto g = fisheye_lens_mapping(layout.lens, theta);
  const auto g_max = fisheye_lens_mapping(layout.lens, 0.5 * layout.fov);
  if (!g || !g_max || *g_max <= 0.0) return std::nullopt;
  return *g / *g_max;
}

std::optional<double> fisheye_theta(const FisheyeLayout& layout, double r) {
  if (r < 0.0 || r > 1.0) return std::nullopt;
  const auto g_max = fisheye_lens_mapping(layout.lens, 0.5 * layout.fov);
  if (!g_max || *g_max <= 0.0) return std::nullopt;
  const double g = r * *g_max;
  switch (layout.lens) {
    case FisheyeLens::equidistant:
      return g;
    case FisheyeLens::equisolid:
      return 2.0 * std::asin(std::min(0.5 * g, 1.0));
    case FisheyeLens::orthographic:
      return std::asin(std::min(g, 1.0));
    case FisheyeLens::stereographic:
      return 2.0 * std::atan(0.5 * g);
  }
  return std::nullopt;
}

FisheyeCircle fisheye_image_circle(int width, int height, const FisheyeLayout& layout) {
  const auto centre = layout.centre.value_or(std::array<double, 2>{0.5 * width, 0.5 * height});
  return {centre[0], centre[1], layout.radius.value_or(0.5 * std::min(width, height))};
}

std::optional<Vec3> fisheye_direction(double col_centre, double row_centre, int width, int height,
                                      const FisheyeLayout& layout) {
  const FisheyeCircle c = fisheye_image_circle(width, height, layout);
  // Image offsets: +dx to the right (to the left in a mirrored image), +dy downwards, in units
  // of the image-circle radius.
  const double dx = (layout.mirrored ? -1.0 : 1.0) * (col_centre - c.col) / c.radius;
  const double dy = (row_centre - c.row) / c.radius;
  const double r = std::hypot(dx, dy);
  const auto theta = fisheye_theta(layout, r);
  if (!theta) return std::nullopt;
  // Looking up with north drawn north_angle counter-clockwise from image-up and east on the left:
  // dx = -r sin(phi + north_angle), dy = -r cos(phi + north_angle).
  const double phi = r > 0.0 ? std::atan2(-dx, -dy) - layout.north_angle : 0.0;
  return direction_from_angles(*theta, wrap_azimuth(phi));
}

std::optional<std::array<double, 2>> fisheye_pixel(Vec3 d, int width, int height,
                                                   const FisheyeLayout& layout) {
  const auto za = angles_from_direction(d);
  const auto r = fisheye_radius(layout, za.zenith);
  if (!r) return std::nullopt;
  const FisheyeCircle c = fisheye_image_circle(width, height, layout);
  const double a = za.azimuth + layout.north_angle;
  return std::array<double, 2>{c.col - (layout.mirrored ? -1.0 : 1.0) * *r * c.radius * std::sin(a),
                               c.row - *r * c.radius * std::cos(a)};
}

Vec3 cubemap_direction(double col_centre, double row_centre, int width, int height) {
  struct Face {
    Vec3 forward, right, up;
  };
  static constexpr std::array<Face, 6> kFaces{{
      {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}},   // +X east: south on the right
      {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}},   // -X west: north on the right
      {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},    // +Y north: east on the right
      {{0, -1, 0}, {-1, 0, 0}, {0, 0, 1}},  // -Y south: west on the right
      {{0, 0, 1}, {-1, 0, 0}, {0, 1, 0}},   // +Z up: north at the top, east on the left
      {{0, 0, -1}, {1, 0, 0}, {0, 1, 0}},   // -Z down: north at the top, east on the right
  }};
  const double size = static_cast<double>(height);
  const int face_index = std::clamp(static_cast<int>(col_centre / size), 0, 5);
  (void)width;
  const Face& f = kFaces[static_cast<size_t>(face_index)];
  const double a = 2.0 * (col_centre - face_index * size) / size - 1.0;  // right, [-1, 1]
  const double b = 1.0 - 2.0 * row_centre / size;                        // up, [-1, 1]
  return normalize(f.forward + a * f.right + b * f.up);
}

}  // namespace skylight
