// Test helper: rendered sky-image sequences standing in for HDR time-lapses (no calibrated public
// one exists; docs/NN.md). A sky model drawn per sun position through an Camera
// (render_photo), with the defects of a real capture: a clipped sun (a disc at a saturation level
// above every sky pixel), multiplicative noise and an occluder (a dark block above the horizon)
// with its mask.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/frame.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"
#include "support/sky_photo.h"

namespace skylight::testing_support {

struct SequenceDefects {
  double sun_radius = 0.0;       // [rad]; > 0: a clipped disc of this radius at the sun
  double clip_factor = 4.0;      // the disc's value: this x the image's largest sky channel
  double noise = 0.0;            // relative standard deviation of multiplicative noise
  bool occluder = false;         // a block at azimuth 200-260 deg, elevation 0-20 deg
  double occluder_factor = 0.1;  // its value relative to the sky behind it
  std::uint32_t seed = 1;
};

// True where the occluder of SequenceDefects covers direction d.
inline bool occluded(Vec3 d) {
  const double az = std::atan2(d.x, d.y);  // from north towards east
  const double az_deg = (az < 0 ? az + 2 * kPi : az) / kDegree;
  const double el_deg = std::asin(std::clamp(d.z, -1.0, 1.0)) / kDegree;
  return az_deg >= 200.0 && az_deg <= 260.0 && el_deg >= 0.0 && el_deg <= 20.0;
}

// One capture: `model` (built for `sun`) through `camera`, with the defects.
inline io::ImageF render_capture(const SkyModel& model, const SunPosition& sun,
                                 const Camera& camera, const SequenceDefects& x) {
  io::ImageF img = render_photo(model, camera);
  float peak = 0.0f;
  for (float v : img.data) peak = std::max(peak, v);
  FixedLcg rng{x.seed};  // the same images on every platform
  const Vec3 s = sun.direction();
  for (int row = 0; row < camera.height; ++row)
    for (int col = 0; col < camera.width; ++col) {
      const auto d = camera.pixel_direction(col, row);
      if (!d) continue;
      float* p = img.pixel(col, row);
      double f = 1.0;
      if (x.noise > 0.0) f = std::max(0.0, 1.0 + x.noise * rng.gaussian());
      if (x.occluder && occluded(*d)) f *= x.occluder_factor;
      for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(p[c] * f);
      if (x.sun_radius > 0.0 && angle_between(*d, s) <= x.sun_radius)
        for (int c = 0; c < 3; ++c) p[c] = static_cast<float>(x.clip_factor * peak);
    }
  return img;
}

// The occluder's mask for `camera`: 1 = sky, 0 = occluder (one channel).
inline io::ImageF occluder_mask(const Camera& camera) {
  io::ImageF m(camera.width, camera.height, 1);
  for (int row = 0; row < camera.height; ++row)
    for (int col = 0; col < camera.width; ++col) {
      const auto d = camera.pixel_direction(col, row);
      m.pixel(col, row)[0] = d && occluded(*d) ? 0.0f : 1.0f;
    }
  return m;
}

}  // namespace skylight::testing_support
