// Test helper: synthetic sky photographs. A sky model drawn through an Camera (the
// scalar reference path per pixel centre, linear sRGB), and synthetic clouds painted over it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/colorimetry.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"

namespace skylight::testing_support {

inline io::ImageF render_photo(const SkyModel& model, const Camera& camera) {
  io::ImageF img(camera.width, camera.height, 3);
  for (int row = 0; row < camera.height; ++row)
    for (int col = 0; col < camera.width; ++col) {
      const auto d = camera.pixel_direction(col, row);
      if (!d) continue;
      const Rgb c = xyz_to_linear_srgb(model.tristimulus(*d));
      float* p = img.pixel(col, row);
      p[0] = static_cast<float>(c.r);
      p[1] = static_cast<float>(c.g);
      p[2] = static_cast<float>(c.b);
    }
  return img;
}

// A fixed LCG (the same numbers on every platform): uniform in (0, 1) from its top 24 bits, and
// standard normal by Box-Muller.
struct FixedLcg {
  std::uint32_t state;
  double uniform() {
    state = state * 1664525u + 1013904223u;
    return (static_cast<double>(state >> 8) + 0.5) / static_cast<double>(1u << 24);
  }
  double gaussian() {
    return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2 * kPi * uniform());
  }
};

// img with multiplicative Gaussian noise of relative standard deviation `sigma`, independent per
// pixel and channel (FixedLcg), clamped at 0.
inline io::ImageF with_noise(const io::ImageF& img, double sigma, std::uint32_t seed) {
  io::ImageF out = img;
  FixedLcg rng{seed};
  for (float& v : out.data)
    v = static_cast<float>(std::max(0.0, v * (1.0 + sigma * rng.gaussian())));
  return out;
}

// Round cloud patches at pseudo-random places (a fixed LCG), alternately brighter (x bright) and
// darker (x dark), added until at least `fraction` of the `sky` pixels (nonzero entries) are
// covered. Returns the covered fraction.
inline double paint_clouds(io::ImageF& img, const std::vector<std::uint8_t>& sky, double fraction,
                           double radius_px, double bright, double dark, std::uint32_t seed) {
  std::vector<std::uint8_t> covered(sky.size(), 0);
  std::size_t sky_count = 0, cover = 0;
  for (auto s : sky) sky_count += s != 0;
  std::uint32_t state = seed;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
  };
  for (int patch = 0; static_cast<double>(cover) < fraction * static_cast<double>(sky_count);
       ++patch) {
    const double cx = next() * img.width, cy = next() * img.height;
    const double factor = patch % 2 == 0 ? bright : dark;
    for (int row = 0; row < img.height; ++row)
      for (int col = 0; col < img.width; ++col) {
        const std::size_t i = static_cast<std::size_t>(row) * img.width + col;
        if (!sky[i] || covered[i] || std::hypot(col + 0.5 - cx, row + 0.5 - cy) > radius_px)
          continue;
        covered[i] = 1;
        ++cover;
        float* p = img.pixel(col, row);
        for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(p[c] * factor);
      }
  }
  return static_cast<double>(cover) / static_cast<double>(sky_count);
}

}  // namespace skylight::testing_support
