#include "skylight/render/tonemap.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/statistics.h"

namespace skylight::render {

Image8 tonemap_preview(const ImageF& image, const ToneMapOptions& options) {
  if (!(options.percentile > 0.0 && options.percentile <= 1.0))
    throw InvalidArgument(
        fmt::format("tone-map percentile must be in (0, 1], got {}", options.percentile));
  if (!(std::isfinite(options.exposure) && options.exposure > 0.0))
    throw InvalidArgument(fmt::format("tone-map exposure must be > 0, got {}", options.exposure));
  if (image.channels != 1 && image.channels != 3)
    throw InvalidArgument(
        fmt::format("tone-map: image has {} channels, expected 1 or 3", image.channels));
  const size_t pixels = static_cast<size_t>(std::max(image.width, 0)) *
                        static_cast<size_t>(std::max(image.height, 0));
  if (image.data.size() != pixels * static_cast<size_t>(image.channels))
    throw InvalidArgument(fmt::format("tone-map: image data has {} values, expected {}",
                                      image.data.size(), pixels * image.channels));

  // Linear colour of pixel i with negative and non-finite channels set to 0, and its luminance
  // (Rec. 709 / sRGB weights).
  auto colour = [&](size_t i) {
    std::array<double, 3> c{};
    const float* p = image.data.data() + i * static_cast<size_t>(image.channels);
    for (int k = 0; k < 3; ++k) {
      const float v = p[image.channels == 3 ? k : 0];
      c[k] = std::isfinite(v) && v > 0.0f ? v : 0.0;
    }
    return c;
  };
  auto luminance = [&](const std::array<double, 3>& c) {
    return image.channels == 3 ? 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2] : c[0];
  };

  // Auto exposure: the percentile of luminance over pixels that have some light.
  std::vector<double> lum;
  lum.reserve(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const double l = luminance(colour(i));
    if (l > 0.0 && std::isfinite(l)) lum.push_back(l);
  }
  const double reference = lum.empty() ? 1.0 : nearest_rank_percentile(lum, options.percentile);
  const double k = options.exposure / reference;

  auto srgb8 = [](double x) {
    x = std::clamp(x, 0.0, 1.0);
    const double v = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
  };

  Image8 out(image.width, image.height);
  for (size_t i = 0; i < pixels; ++i) {
    const auto c = colour(i);
    const double lk = luminance(c) * k;
    // Reinhard on luminance, L' = Lk / (1 + Lk); the colour keeps its ratios: c * k * L' / (Lk).
    const double factor = lk > 0.0 && std::isfinite(lk) ? k / (1.0 + lk) : 0.0;
    for (int ch = 0; ch < 3; ++ch)
      out.data[i * 3 + static_cast<size_t>(ch)] = srgb8(c[ch] * factor);
  }
  return out;
}

void write_image_or_preview(const std::filesystem::path& path, const ImageF& image,
                            const Metadata& meta) {
  if (io::format_from_path(path) == io::ImageFormat::png)
    io::write_png(path, tonemap_preview(image), meta);
  else
    io::write_image(path, image, meta);
}

}  // namespace skylight::render
