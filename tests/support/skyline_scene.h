// Test helper: a synthetic daylight photo with a known sky (haze/sky_segmentation_test.cpp,
// tests/cli/haze_test.cpp): a smooth sky with the Perez gradation of Morales 2017 eq. 13 at T =
// 2.5, a sun 35 deg up and two clouds, over a dark textured mountain range with a snow field from
// 1 deg above the horizon to 2 deg below the skyline (brighter than the horizon's sky) and a
// building with windows 28 deg high; below the horizon, textured ground. Drawn through an
// Camera (3 x 3 samples a pixel, 1 % noise), with the true sky mask.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include "skylight/core/camera.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/estimate/photo.h"
#include "skylight/io/image.h"

namespace skylight::testing_support {

inline constexpr double kSceneTurbidity = 2.5;
inline constexpr double kSceneSkyColour[3] = {0.55, 0.75, 1.0};

// A hash of an integer cell in [-1, 1] (SplitMix64's finaliser).
inline double scene_noise(int a, int b) {
  std::uint64_t z = static_cast<std::uint64_t>(a) * 0x9E3779B97F4A7C15ULL ^
                    (static_cast<std::uint64_t>(b) + 0x632BE59BD9B4E019ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) / static_cast<double>(1ULL << 52) - 1.0;
}

// The Perez gradation term of eq. 13 (Preetham's coefficients at T, cos theta clamped at 0.01).
inline double scene_gradation(double theta) {
  const double cos_theta = std::max(std::cos(theta), 0.01);
  return 1.0 + (0.178 * kSceneTurbidity - 1.463) *
                   std::exp((-0.355 * kSceneTurbidity + 0.427) / cos_theta);
}

// The clear sky at the horizon: eq. 12's I^inf(T, pi/2) of the scene.
inline std::array<double, 3> skyline_scene_horizon() {
  const double g = scene_gradation(kPi / 2);
  return {kSceneSkyColour[0] * g, kSceneSkyColour[1] * g, kSceneSkyColour[2] * g};
}

// The skyline's elevation at azimuth `a` [rad] (from north towards east, core/frame.h).
inline double scene_skyline(double a) {
  double e = 6.0 + 5.0 * std::sin(3 * a) + 3.0 * std::sin(7 * a + 1) + 2.0 * std::sin(13 * a + 2);
  e += 12.0 * std::exp(-std::pow((a - 2.2) / 0.3, 2));  // the snowy peak
  e = std::max(e, 1.5);
  if (a > 0.5 && a < 0.9) e = 28.0;  // the building
  return e * kDegree;
}

inline bool scene_is_sky(Vec3 d) {
  const double e = kPi / 2 - std::acos(std::clamp(d.z, -1.0, 1.0));
  return e > 0.0 && e >= scene_skyline(std::atan2(d.x, d.y));
}

inline std::array<float, 3> scene_colour(Vec3 d) {
  const double theta = std::acos(std::clamp(d.z, -1.0, 1.0));
  const double e = kPi / 2 - theta, a = std::atan2(d.x, d.y);
  const int ca = static_cast<int>(std::floor(a / (0.7 * kDegree)));
  const int ce = static_cast<int>(std::floor(e / (0.7 * kDegree)));
  std::array<float, 3> out{};
  if (scene_is_sky(d)) {
    const Vec3 sun = direction_from_angles(kPi / 2 - 35 * kDegree, 1.5);
    const double gamma = std::acos(std::clamp(dot(d, sun), -1.0, 1.0));
    const double glow = 6.0 * std::exp(-std::pow(gamma / (2.5 * kDegree), 2)) +
                        (gamma < 0.27 * kDegree ? 40.0 : 0.0);
    double cloud = 0.0;
    for (const Vec3& c : {direction_from_angles(kPi / 2 - 60 * kDegree, -2.0),
                          direction_from_angles(kPi / 2 - 55 * kDegree, -0.4)}) {
      const double g = std::acos(std::clamp(dot(d, c), -1.0, 1.0));
      cloud = std::max(cloud, std::exp(-std::pow(g / (7 * kDegree), 2)));
    }
    for (std::size_t k = 0; k < 3; ++k) {
      const double clear = kSceneSkyColour[k] * scene_gradation(theta);
      out[k] = static_cast<float>((1 - 0.8 * cloud) * clear + 0.8 * cloud * 0.9 + glow);
    }
    return out;
  }
  if (a > 0.5 && a < 0.9 && e > 0.0) {  // the building: grey wall, dark windows
    const bool window = ca % 3 != 0 && ce % 3 != 0;
    out.fill(window ? 0.04f : 0.22f);
    return out;
  }
  if (std::abs(a - 2.2) < 0.25 && e > 1.0 * kDegree && e < scene_skyline(a) - 2.0 * kDegree) {
    out.fill(static_cast<float>(1.25 * (1 + 0.04 * scene_noise(ca, ce))));  // snow
    return out;
  }
  const double t = 1 + 0.6 * scene_noise(ca, ce);  // rock and vegetation
  return {static_cast<float>(0.08 * t), static_cast<float>(0.09 * t), static_cast<float>(0.06 * t)};
}

struct ScenePhoto {
  io::ImageF image;
  estimate::SkyMask truth;  // 1 where at least half of the pixel sees the sky
};

// Each pixel is the mean of 3 x 3 samples over its area (the skyline's pixels are mixed, as
// through a lens) times 1 + 0.01 n, n a hash noise in [-1, 1] (sensor noise).
inline ScenePhoto render_skyline_scene(const Camera& cam) {
  constexpr int kSub = 3;
  ScenePhoto p{io::ImageF(cam.width, cam.height, 3), {}};
  p.truth.width = cam.width;
  p.truth.height = cam.height;
  p.truth.sky.assign(static_cast<std::size_t>(cam.width) * static_cast<std::size_t>(cam.height), 0);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      if (!cam.pixel_direction(x, y)) continue;
      std::array<double, 3> sum{};
      int samples = 0, sky = 0;
      for (int i = 0; i < kSub; ++i)
        for (int j = 0; j < kSub; ++j) {
          const std::optional<Vec3> d = cam.direction(x + (i + 0.5) / kSub, y + (j + 0.5) / kSub);
          if (!d) continue;
          const std::array<float, 3> c = scene_colour(*d);
          for (std::size_t k = 0; k < 3; ++k) sum[k] += c[k];
          ++samples;
          sky += scene_is_sky(*d) ? 1 : 0;
        }
      const double grain = 1.0 + 0.01 * scene_noise(x + 7919, y - 104729);
      for (std::size_t k = 0; k < 3; ++k)
        p.image.pixel(x, y)[k] = static_cast<float>(sum[k] / samples * grain);
      if (2 * sky >= samples) {
        p.truth.sky[static_cast<std::size_t>(y) * static_cast<std::size_t>(cam.width) +
                    static_cast<std::size_t>(x)] = 1;
        ++p.truth.count;
      }
    }
  return p;
}

}  // namespace skylight::testing_support
