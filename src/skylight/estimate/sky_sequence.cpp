#include "skylight/estimate/sky_sequence.h"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/random.h"

namespace skylight::estimate {

SampledImage sample_sky_image(const io::ImageF& image, const Camera& camera,
                              const std::optional<SunPosition>& sun,
                              const SequenceSampling& sampling, const io::ImageF* user_mask) {
  SampledImage r;
  SunPosition s;
  if (sun) {
    s = *sun;
  } else {
    s = detect_sun(image, camera).sun;
    r.sun_detected = true;
  }
  if (!(s.zenith >= 0.0 && s.zenith <= kPi / 2))
    throw InvalidArgument(
        fmt::format("the sun is {:.2f} deg below the horizon", rad_to_deg(s.zenith - kPi / 2)));
  const SkyMask mask = sky_mask(image, camera, sampling.mask, s, user_mask);
  if (mask.count == 0) throw InvalidArgument("the sky mask holds no pixel");
  r.sky_pixels = mask.count;
  std::vector<std::uint32_t> sky;
  sky.reserve(mask.count);
  for (std::size_t i = 0; i < mask.sky.size(); ++i)
    if (mask.sky[i]) sky.push_back(static_cast<std::uint32_t>(i));
  const std::size_t n =
      std::min(sky.size(), static_cast<std::size_t>(std::max(sampling.samples_per_image, 1)));
  SplitMix64 rng(sampling.seed);
  for (std::size_t k = 0; k < n; ++k) {  // partial Fisher-Yates: n distinct pixels
    std::swap(sky[k], sky[k + rng.below(sky.size() - k)]);
  }
  std::sort(sky.begin(), sky.begin() + static_cast<std::ptrdiff_t>(n));
  nn::ImageSamples& out = r.samples;
  out.state.turbidity = 0.0;
  out.state.sun_zenith = s.zenith;
  out.state.sun_azimuth = s.azimuth;
  for (std::size_t k = 0; k < n; ++k) {
    const int col = static_cast<int>(sky[k] % static_cast<std::uint32_t>(image.width));
    const int row = static_cast<int>(sky[k] / static_cast<std::uint32_t>(image.width));
    const auto d = camera.pixel_direction(col, row);
    if (!d) continue;
    const float* p = image.pixel(col, row);
    const Rgb c = image.channels >= 3 ? Rgb{p[0], p[1], p[2]} : Rgb{p[0], p[0], p[0]};
    out.views.push_back(*d);
    out.rgb.push_back(c);
  }
  return r;
}

}  // namespace skylight::estimate
