#include "skylight/render/sky_render.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/system.h"
#include "skylight/core/parallel.h"

namespace skylight::render {

namespace {
// Upper bound of the supersampling grid for a pixel that sees part of the solar disc.
constexpr int kMaxSunSamplesPerAxis = 256;
}  // namespace

std::optional<Projection> parse_projection(std::string_view name) {
  if (name == "equirect") return Projection::equirect;
  if (name == "hemisphere") return Projection::hemisphere;
  if (name == "fisheye") return Projection::fisheye;
  if (name == "cubemap") return Projection::cubemap;
  if (name == "camera") return Projection::camera;
  return std::nullopt;
}

std::string_view to_string(Projection p) {
  switch (p) {
    case Projection::equirect:
      return "equirect";
    case Projection::hemisphere:
      return "hemisphere";
    case Projection::fisheye:
      return "fisheye";
    case Projection::cubemap:
      return "cubemap";
    case Projection::camera:
      return "camera";
  }
  return "equirect";
}

void validate(const RenderSettings& s) {
  constexpr int kMaxSide = kMaxImageSide;
  if (s.width < 1 || s.width > kMaxSide)
    throw InvalidArgument(fmt::format("width = {} is outside [1, {}]", s.width, kMaxSide));
  if (s.height < 1 || s.height > kMaxSide)
    throw InvalidArgument(fmt::format("height = {} is outside [1, {}]", s.height, kMaxSide));
  if (s.projection == Projection::cubemap && s.width != 6 * s.height)
    throw InvalidArgument(
        fmt::format("cubemap needs width = 6 x height (six square faces); got "
                    "{} x {}",
                    s.width, s.height));
  if (s.projection == Projection::camera) {
    const CameraLayout& c = s.camera;
    if (!(c.vertical_fov > 0.0 && c.vertical_fov < kPi))
      throw InvalidArgument(fmt::format("fov = {} deg is outside (0, 180) for the camera",
                                        rad_to_deg(c.vertical_fov)));
    if (!(c.look_zenith >= 0.0 && c.look_zenith <= kPi) || !std::isfinite(c.look_azimuth))
      throw InvalidArgument(
          fmt::format("camera look direction (zenith {} deg, azimuth {} deg) is "
                      "not a direction",
                      rad_to_deg(c.look_zenith), rad_to_deg(c.look_azimuth)));
  }
  if (s.projection == Projection::fisheye) {
    const double fov_deg = rad_to_deg(s.fisheye.fov);
    const double max_deg = s.fisheye.lens == FisheyeLens::orthographic ? 180.0 : 360.0;
    if (!(fov_deg > 0.0 && fov_deg <= max_deg) ||
        (s.fisheye.lens == FisheyeLens::stereographic && fov_deg >= 360.0))
      throw InvalidArgument(fmt::format(
          "fov = {} deg is outside (0, {}{} for the {} lens", fov_deg, max_deg,
          s.fisheye.lens == FisheyeLens::stereographic ? ")" : "]", to_string(s.fisheye.lens)));
    if (!std::isfinite(s.fisheye.north_angle))
      throw InvalidArgument(fmt::format("north-angle = {} is not finite", s.fisheye.north_angle));
  }
}

namespace {
// Pinhole camera: d = normalize(f + x tan(fov/2) right + y tan(fov/2) up), x in [-w/h, w/h],
// y in [-1, 1] (image up), right = f x zenith (f x north when f is vertical), up = right x f.
Vec3 camera_direction(double u, double v, int width, int height, const CameraLayout& c) {
  const Vec3 f = direction_from_angles(c.look_zenith, c.look_azimuth);
  Vec3 right = cross(f, Vec3{0, 0, 1});
  if (dot(right, right) < 1e-12) right = cross(f, Vec3{0, 1, 0});
  right = normalize(right);
  const Vec3 up = cross(right, f);
  const double t = std::tan(0.5 * c.vertical_fov);
  const double x = (2.0 * u / height - static_cast<double>(width) / height) * t;
  const double y = (1.0 - 2.0 * v / height) * t;
  return normalize(f + x * right + y * up);
}
}  // namespace

std::optional<Vec3> pixel_direction(const RenderSettings& s, double u, double v) {
  switch (s.projection) {
    case Projection::equirect:
      return equirect_direction(u, v, s.width, s.height);
    case Projection::hemisphere:
      return hemisphere_direction(u, v, s.width, s.height);
    case Projection::fisheye:
      return fisheye_direction(u, v, s.width, s.height, s.fisheye);
    case Projection::cubemap:
      return cubemap_direction(u, v, s.width, s.height);
    case Projection::camera:
      return camera_direction(u, v, s.width, s.height, s.camera);
  }
  return std::nullopt;
}

PixelDirections pixel_directions(const RenderSettings& s) {
  validate(s);
  const std::size_t n = static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height);
  PixelDirections d;
  d.x.resize(n);
  d.y.resize(n);
  d.z.resize(n);
  d.valid.assign(n, 1);
  parallel_for(static_cast<std::size_t>(s.height), 16, [&](std::size_t r0, std::size_t r1) {
    for (std::size_t row = r0; row < r1; ++row) {
      for (int col = 0; col < s.width; ++col) {
        auto dir = pixel_direction(s, col + 0.5, static_cast<double>(row) + 0.5);
        const std::size_t i =
            row * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(col);
        if (!dir) {
          d.valid[i] = 0;
          dir = Vec3{0.0, 0.0, 1.0};
        }
        d.x[i] = static_cast<float>(dir->x);
        d.y[i] = static_cast<float>(dir->y);
        d.z[i] = static_cast<float>(dir->z);
      }
    }
  });
  return d;
}

Xyz average_sun_over_pixel(const SkyModel& model, const RenderSettings& s, int col, int row) {
  const Vec3 sun = model.sun().direction();
  const double r_sun = model.sun_angular_radius();
  const auto centre = pixel_direction(s, col + 0.5, row + 0.5);
  if (!centre || r_sun <= 0.0) return {};
  const double to_sun = angle_between(*centre, sun);
  // Cheap rejection: farther than any pixel of this image can reach.
  const double coarse = std::max(10.0 * kDegree, 8.0 * kPi / std::min(s.width, s.height));
  if (to_sun > r_sun + coarse) return {};
  // The pixel's angular radius: the farthest corner from its centre (a corner outside the layout
  // counts as the coarse bound).
  double pixel_radius = 0.0;
  for (int k = 0; k < 4; ++k) {
    const auto c = pixel_direction(s, col + (k & 1), row + (k >> 1));
    pixel_radius = std::max(pixel_radius, c ? angle_between(*centre, *c) : coarse);
  }
  if (to_sun > r_sun + pixel_radius) return {};
  // Supersample the pixel on a grid fine enough that the disc spans >= 16 samples across.
  const int samples = std::clamp(static_cast<int>(std::ceil(2.0 * pixel_radius / (r_sun / 8.0))), 4,
                                 kMaxSunSamplesPerAxis);
  Xyz sum;
  for (int a = 0; a < samples; ++a) {
    for (int b = 0; b < samples; ++b) {
      const auto d = pixel_direction(s, col + (a + 0.5) / samples, row + (b + 0.5) / samples);
      if (!d) continue;
      const Xyz c = model.sun_tristimulus(*d);
      sum = {sum.X + c.X, sum.Y + c.Y, sum.Z + c.Z};
    }
  }
  const double w = 1.0 / (static_cast<double>(samples) * samples);
  return {sum.X * w, sum.Y * w, sum.Z * w};
}

std::size_t render_memory_bytes(const RenderSettings& s) {
  return static_cast<std::size_t>(std::max(s.width, 0)) *
         static_cast<std::size_t>(std::max(s.height, 0)) * kRenderBytesPerPixel;
}

SkyImage render_sky(const SkyModel& model, const RenderSettings& s) {
  validate(s);
  require_memory(render_memory_bytes(s),
                 fmt::format("rendering a {}x{} image", s.width, s.height));
  const PixelDirections d = pixel_directions(s);
  const std::size_t n = d.x.size();
  std::vector<float> X(n), Y(n), Z(n);
  if (s.sun != SunMode::sun_only) tristimulus_parallel(model, {d.x, d.y, d.z}, {X, Y, Z});
  SkyImage img{ImageF(s.width, s.height, 3), ImageF(s.width, s.height, 3), {}};
  img.mask.assign(n, 0);
  const bool add_sun = s.sun != SunMode::sky && model.has_sun();
  parallel_for(static_cast<std::size_t>(s.height), 8, [&](std::size_t r0, std::size_t r1) {
    for (std::size_t row = r0; row < r1; ++row) {
      for (int col = 0; col < s.width; ++col) {
        const std::size_t i =
            row * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(col);
        Xyz c{X[i], Y[i], Z[i]};
        if (!d.valid[i]) {
          c = {};
          img.mask[i] = 1;
        } else if (add_sun) {
          const Xyz sun = average_sun_over_pixel(model, s, col, static_cast<int>(row));
          c = {c.X + sun.X, c.Y + sun.Y, c.Z + sun.Z};
        }
        const Rgb rgb = xyz_to_linear_srgb(c);
        float* px = img.xyz.data.data() + 3 * i;
        px[0] = static_cast<float>(c.X);
        px[1] = static_cast<float>(c.Y);
        px[2] = static_cast<float>(c.Z);
        float* pr = img.rgb.data.data() + 3 * i;
        pr[0] = static_cast<float>(rgb.r);
        pr[1] = static_cast<float>(rgb.g);
        pr[2] = static_cast<float>(rgb.b);
      }
    }
  });
  return img;
}

}  // namespace skylight::render
