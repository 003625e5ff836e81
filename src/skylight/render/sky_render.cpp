#include "skylight/render/sky_render.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/core/system.h"

namespace skylight::render {

namespace {
// Upper bound of the supersampling grid for a pixel that sees part of the solar disc.
constexpr int kMaxSunSamplesPerAxis = 256;
}  // namespace

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
        auto dir = s.direction(col + 0.5, static_cast<double>(row) + 0.5);
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
  const auto centre = s.direction(col + 0.5, row + 0.5);
  if (!centre || r_sun <= 0.0) return {};
  const double to_sun = angle_between(*centre, sun);
  // Cheap rejection: farther than any pixel of this image can reach.
  const double coarse = std::max(10.0 * kDegree, 8.0 * kPi / std::min(s.width, s.height));
  if (to_sun > r_sun + coarse) return {};
  // The pixel's angular radius: the farthest corner from its centre (a corner outside the layout
  // counts as the coarse bound).
  double pixel_radius = 0.0;
  for (int k = 0; k < 4; ++k) {
    const auto c = s.direction(col + (k & 1), row + (k >> 1));
    pixel_radius = std::max(pixel_radius, c ? angle_between(*centre, *c) : coarse);
  }
  if (to_sun > r_sun + pixel_radius) return {};
  // Supersample the pixel on a grid fine enough that the disc spans >= 16 samples across.
  const int samples = std::clamp(static_cast<int>(std::ceil(2.0 * pixel_radius / (r_sun / 8.0))), 4,
                                 kMaxSunSamplesPerAxis);
  Xyz sum;
  for (int a = 0; a < samples; ++a) {
    for (int b = 0; b < samples; ++b) {
      const auto d = s.direction(col + (a + 0.5) / samples, row + (b + 0.5) / samples);
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
  require_memory(render_memory_bytes(s), fmt::format("rendering a {}x{} image", s.width, s.height));
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
        img.set(i, c, xyz_to_linear_srgb(c));
      }
    }
  });
  return img;
}

}  // namespace skylight::render
