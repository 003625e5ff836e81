// Camera models of sky photographs: the project's fisheye and equirect mappings (core/frame.h).
#include "skylight/estimate/camera.h"

#include <fmt/format.h>

#include <cmath>

#include "skylight/core/error.h"

namespace skylight::estimate {

std::optional<PhotoProjection> parse_photo_projection(std::string_view name) {
  if (name == "fisheye") return PhotoProjection::fisheye;
  if (name == "equirect") return PhotoProjection::equirect;
  return std::nullopt;
}

std::string_view to_string(PhotoProjection p) {
  return p == PhotoProjection::fisheye ? "fisheye" : "equirect";
}

std::optional<Vec3> SkyCamera::direction(double col, double row) const {
  if (projection == PhotoProjection::fisheye)
    return fisheye_direction(col, row, width, height, fisheye);
  if (col < 0.0 || col > width || row < 0.0 || row > height) return std::nullopt;
  return equirect_direction(col, row, width, height);
}

std::optional<std::array<double, 2>> SkyCamera::pixel(Vec3 d) const {
  if (projection == PhotoProjection::fisheye) return fisheye_pixel(d, width, height, fisheye);
  // Inverse of equirect_direction: theta = pi row / height, phi = 2 pi col / width
  // (docs/CONVENTIONS.md, pixel centres at +0.5).
  const ZenithAzimuth za = angles_from_direction(d);
  return std::array<double, 2>{za.azimuth / (2.0 * kPi) * width, za.zenith / kPi * height};
}

void validate(const SkyCamera& c) {
  if (c.width < 1 || c.height < 1)
    throw InvalidArgument(fmt::format("photo size {} x {} is empty", c.width, c.height));
  if (c.projection != PhotoProjection::fisheye) return;
  const double fov_deg = rad_to_deg(c.fisheye.fov);
  const double max_deg = c.fisheye.lens == FisheyeLens::orthographic ? 180.0 : 360.0;
  if (!(fov_deg > 0.0 && fov_deg <= max_deg) ||
      (c.fisheye.lens == FisheyeLens::stereographic && fov_deg >= 360.0))
    throw InvalidArgument(fmt::format(
        "fov = {} deg is outside (0, {}{} for the {} lens", fov_deg, max_deg,
        c.fisheye.lens == FisheyeLens::stereographic ? ")" : "]", to_string(c.fisheye.lens)));
  if (!std::isfinite(c.fisheye.north_angle))
    throw InvalidArgument(fmt::format("north-angle = {} is not finite", c.fisheye.north_angle));
}

SkyCamera image_camera(PhotoProjection projection, const FisheyeLayout& layout, int width,
                       int height) {
  SkyCamera camera;
  camera.projection = projection;
  camera.width = width;
  camera.height = height;
  camera.fisheye = layout;
  validate(camera);
  return camera;
}

}  // namespace skylight::estimate
