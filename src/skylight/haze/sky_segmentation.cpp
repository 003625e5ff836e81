// Morales et al. 2017 §4 (eq. 12's sky segmentation and horizon region); Meyer's flooding
// (F. Meyer, "Topographic distance and watershed lines", Signal Processing 38, 1994) as a
// watershed cut on edge weights (Cousty et al., IEEE PAMI 31, 2009); docs/HAZE.md.
#include "skylight/haze/sky_segmentation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <queue>

#include "skylight/core/error.h"
#include "skylight/core/statistics.h"

namespace skylight::haze {
namespace {

enum Label : std::uint8_t { kUnlabelled = 0, kSky = 1, kGround = 2, kOutside = 3 };

struct Grid {
  int w = 0, h = 0;
  std::size_t at(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
  }
};

// The Sobel gradient magnitude of `f` per pixel (the kernels divided by 8: a unit ramp gives 1),
// neighbours outside the image or the image circle taken as the centre value.
std::vector<float> sobel(const std::vector<float>& f, const std::vector<std::uint8_t>& imaged,
                         const Grid& g) {
  std::vector<float> out(f.size(), 0.0f);
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      const std::size_t c = g.at(x, y);
      if (!imaged[c]) continue;
      const auto v = [&](int dx, int dy) {
        const int xx = x + dx, yy = y + dy;
        if (xx < 0 || yy < 0 || xx >= g.w || yy >= g.h || !imaged[g.at(xx, yy)]) return f[c];
        return f[g.at(xx, yy)];
      };
      const float gx = (v(1, -1) + 2 * v(1, 0) + v(1, 1) - v(-1, -1) - 2 * v(-1, 0) - v(-1, 1)) / 8;
      const float gy = (v(-1, 1) + 2 * v(0, 1) + v(1, 1) - v(-1, -1) - 2 * v(0, -1) - v(1, -1)) / 8;
      out[c] = std::sqrt(gx * gx + gy * gy);
    }
  return out;
}

// The mean of `f` over the imaged pixels of the (2r + 1)^2 box around each pixel (summed-area
// tables in double).
std::vector<float> box_mean(const std::vector<float>& f, const std::vector<std::uint8_t>& imaged,
                            const Grid& g, int r) {
  const std::size_t W = static_cast<std::size_t>(g.w) + 1;
  std::vector<double> sum(W * static_cast<std::size_t>(g.h + 1), 0.0), cnt(sum.size(), 0.0);
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y + 1) * W + static_cast<std::size_t>(x + 1);
      const std::size_t c = g.at(x, y);
      sum[i] = (imaged[c] ? f[c] : 0.0) + sum[i - 1] + sum[i - W] - sum[i - W - 1];
      cnt[i] = (imaged[c] ? 1.0 : 0.0) + cnt[i - 1] + cnt[i - W] - cnt[i - W - 1];
    }
  std::vector<float> out(f.size(), 0.0f);
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      const std::size_t x0 = static_cast<std::size_t>(std::max(x - r, 0));
      const std::size_t x1 = static_cast<std::size_t>(std::min(x + r, g.w - 1)) + 1;
      const std::size_t y0 = static_cast<std::size_t>(std::max(y - r, 0));
      const std::size_t y1 = static_cast<std::size_t>(std::min(y + r, g.h - 1)) + 1;
      const auto box = [&](const std::vector<double>& t) {
        return t[y1 * W + x1] - t[y0 * W + x1] - t[y1 * W + x0] + t[y0 * W + x0];
      };
      const double n = box(cnt);
      out[g.at(x, y)] = n > 0.0 ? static_cast<float>(box(sum) / n) : 0.0f;
    }
  return out;
}

}  // namespace

void validate(const SegmentationSettings& s) {
  if (!(s.sky_seed_elevation >= 0.0 && s.sky_seed_elevation < kPi / 2) ||
      !(s.sky_seed_texture > 0.0 && std::isfinite(s.sky_seed_texture)) ||
      !(s.sky_seed_brightness >= 0.0 && s.sky_seed_brightness <= 1.0) ||
      !(s.ground_texture > s.sky_seed_texture && std::isfinite(s.ground_texture)) ||
      !(s.texture_radius >= 1 && s.texture_radius <= 64))
    throw InvalidArgument(fmt::format(
        "segmentation settings out of range: sky seed elevation {} deg (0 .. 90), sky seed "
        "texture {} (> 0), brightness {} (0 .. 1), ground texture {} (> sky seed texture), "
        "texture radius {} px (1 .. 64)",
        rad_to_deg(s.sky_seed_elevation), s.sky_seed_texture, s.sky_seed_brightness,
        s.ground_texture, s.texture_radius));
}

namespace {

// A photo's pixels as segment_sky sees them: which are imaged, their elevation [rad], luminance
// and its logarithm (floored at 1e-6 of the brightest: black pixels and clipped shadows stay
// finite), and the texture (the box mean of the Sobel relief of log luminance).
struct PixelFeatures {
  std::vector<std::uint8_t> imaged;
  std::vector<float> elevation, lum, log_lum, texture;
};
PixelFeatures pixel_features(const io::ImageF& photo, const Camera& camera, const Grid& g,
                             int texture_radius) {
  const std::size_t n = static_cast<std::size_t>(g.w) * static_cast<std::size_t>(g.h);
  PixelFeatures f{std::vector<std::uint8_t>(n, 0),
                  std::vector<float>(n, 0.0f),
                  std::vector<float>(n, 0.0f),
                  std::vector<float>(n, 0.0f),
                  {}};
  double brightest = 0.0;
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      const std::optional<Vec3> d = camera.pixel_direction(x, y);
      if (!d) continue;
      const std::size_t c = g.at(x, y);
      const double l = estimate::pixel_luminance(photo, x, y);
      if (!std::isfinite(l)) continue;
      f.imaged[c] = 1;
      f.elevation[c] = static_cast<float>(kPi / 2 - std::acos(std::clamp(d->z, -1.0, 1.0)));
      f.lum[c] = static_cast<float>(std::max(l, 0.0));
      brightest = std::max(brightest, l);
    }
  const double floor = brightest > 0.0 ? 1e-6 * brightest : 1e-30;
  for (std::size_t c = 0; c < n; ++c)
    if (f.imaged[c]) f.log_lum[c] = static_cast<float>(std::log(std::max<double>(f.lum[c], floor)));
  f.texture = box_mean(sobel(f.log_lum, f.imaged, g), f.imaged, g, texture_radius);
  return f;
}

// The markers: outside the image, ground below the horizon, sky where smooth, high and bright;
// textured pixels darker than the sky seeds' median are ground.
std::vector<std::uint8_t> markers(const PixelFeatures& f, const SegmentationSettings& settings) {
  const std::size_t n = f.imaged.size();
  std::vector<std::uint8_t> label(n, kUnlabelled);
  std::vector<double> smooth_top;
  for (std::size_t c = 0; c < n; ++c)
    if (f.imaged[c] && f.elevation[c] > 0.0f && f.elevation[c] >= settings.sky_seed_elevation &&
        f.texture[c] <= settings.sky_seed_texture)
      smooth_top.push_back(f.lum[c]);
  if (smooth_top.empty())
    throw InvalidArgument(fmt::format(
        "sky segmentation: no smooth pixel {} deg or more above the horizon to seed the sky",
        rad_to_deg(settings.sky_seed_elevation)));
  const double bright =
      settings.sky_seed_brightness * kth_smallest(smooth_top, smooth_top.size() / 2);
  std::vector<double> seed_lum;
  for (std::size_t c = 0; c < n; ++c) {
    if (!f.imaged[c]) {
      label[c] = kOutside;
    } else if (f.elevation[c] <= 0.0f) {
      label[c] = kGround;
    } else if (f.elevation[c] >= settings.sky_seed_elevation &&
               f.texture[c] <= settings.sky_seed_texture && f.lum[c] >= bright) {
      label[c] = kSky;
      seed_lum.push_back(f.lum[c]);
    }
  }
  // At least the upper half of smooth_top (bright <= its median) is in seed_lum.
  const double sky_median = median(seed_lum);
  for (std::size_t c = 0; c < n; ++c)
    if (label[c] == kUnlabelled && f.texture[c] >= settings.ground_texture && f.lum[c] < sky_median)
      label[c] = kGround;
  return label;
}

// Meyer's flooding: the unlabelled neighbours of labelled pixels wait in a priority queue by the
// log-luminance step of the edge that reached them (ties first in, first out); the lowest is
// labelled from that pixel. On the edges rather than on the Sobel relief of the pixels: the
// relief is as high on the sky's side of a skyline as on the terrain's, and the marker next to
// the ridge (the textured terrain) would win every tie.
void flood(std::vector<std::uint8_t>& label, const std::vector<float>& log_lum, const Grid& g) {
  struct Item {
    float level;
    std::uint64_t order;
    std::size_t pixel;
    std::uint8_t label;
    bool operator>(const Item& o) const {
      return level != o.level ? level > o.level : order > o.order;
    }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  std::uint64_t order = 0;
  const auto push_neighbours = [&](std::size_t c) {
    const int x = static_cast<int>(c % static_cast<std::size_t>(g.w));
    const int y = static_cast<int>(c / static_cast<std::size_t>(g.w));
    const int dx[] = {1, -1, 0, 0}, dy[] = {0, 0, 1, -1};
    for (int k = 0; k < 4; ++k) {
      const int xx = x + dx[k], yy = y + dy[k];
      if (xx < 0 || yy < 0 || xx >= g.w || yy >= g.h) continue;
      const std::size_t q = g.at(xx, yy);
      if (label[q] == kUnlabelled)
        queue.push({std::abs(log_lum[q] - log_lum[c]), order++, q, label[c]});
    }
  };
  for (std::size_t c = 0; c < label.size(); ++c)
    if (label[c] == kSky || label[c] == kGround) push_neighbours(c);
  while (!queue.empty()) {
    const Item it = queue.top();
    queue.pop();
    if (label[it.pixel] != kUnlabelled) continue;
    label[it.pixel] = it.label;
    push_neighbours(it.pixel);
  }
}

}  // namespace

estimate::SkyMask segment_sky(const io::ImageF& photo, const Camera& camera,
                              const SegmentationSettings& settings) {
  validate(settings);
  skylight::validate(camera);
  if (photo.width != camera.width || photo.height != camera.height)
    throw InvalidArgument(fmt::format("the sky photo is {}x{} but its camera {}x{}", photo.width,
                                      photo.height, camera.width, camera.height));
  const Grid g{photo.width, photo.height};
  const PixelFeatures f = pixel_features(photo, camera, g, settings.texture_radius);
  std::vector<std::uint8_t> label = markers(f, settings);
  flood(label, f.log_lum, g);
  estimate::SkyMask mask;
  mask.width = g.w;
  mask.height = g.h;
  mask.sky.assign(label.size(), 0);
  for (std::size_t c = 0; c < label.size(); ++c)
    if (label[c] == kSky && f.elevation[c] > 0.0f) {
      mask.sky[c] = 1;
      ++mask.count;
    }
  return mask;
}

io::Image8 mask_image(const estimate::SkyMask& mask) {
  io::Image8 out(mask.width, mask.height);
  for (std::size_t c = 0; c < mask.sky.size(); ++c)
    for (std::size_t k = 0; k < 3; ++k) out.data[3 * c + k] = mask.sky[c] ? 255 : 0;
  return out;
}

estimate::SkyMask mask_from_image(const io::ImageF& image, const Camera& camera) {
  if (image.width != camera.width || image.height != camera.height)
    throw InvalidArgument(fmt::format("the sky mask is {}x{} but the sky photo {}x{}", image.width,
                                      image.height, camera.width, camera.height));
  estimate::SkyMask mask;
  mask.width = image.width;
  mask.height = image.height;
  mask.sky.assign(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height),
                  0);
  const auto channels = static_cast<std::size_t>(image.channels);
  for (std::size_t c = 0; c < mask.sky.size(); ++c)
    for (std::size_t k = 0; k < channels; ++k)
      if (image.data[c * channels + k] != 0.0f) {
        mask.sky[c] = 1;
        ++mask.count;
        break;
      }
  return mask;
}

std::vector<std::uint8_t> horizon_region(const estimate::SkyMask& mask, const Camera& camera,
                                         double band) {
  SKYLIGHT_CHECK(mask.width == camera.width && mask.height == camera.height,
                 "mask and camera sizes differ");
  const Grid g{mask.width, mask.height};
  const std::size_t n = mask.sky.size();
  std::vector<int> bin(n, -1);
  std::vector<double> elevation(n, 0.0);
  std::vector<double> lowest(kHorizonAzimuthBins, kPi);
  for (int y = 0; y < g.h; ++y)
    for (int x = 0; x < g.w; ++x) {
      const std::size_t c = g.at(x, y);
      if (!mask.sky[c]) continue;
      const std::optional<Vec3> d = camera.pixel_direction(x, y);
      if (!d || d->z <= 0.0) continue;
      elevation[c] = kPi / 2 - std::acos(std::min(d->z, 1.0));
      const double azimuth = std::atan2(d->y, d->x) + kPi;  // [0, 2 pi]
      bin[c] = std::min(static_cast<int>(azimuth / (2 * kPi) * kHorizonAzimuthBins),
                        kHorizonAzimuthBins - 1);
      double& low = lowest[static_cast<std::size_t>(bin[c])];
      low = std::min(low, elevation[c]);
    }
  std::vector<std::uint8_t> region(n, 0);
  for (std::size_t c = 0; c < n; ++c)
    if (bin[c] >= 0 && elevation[c] <= lowest[static_cast<std::size_t>(bin[c])] + band)
      region[c] = 1;
  return region;
}

PhotoAirlight photo_airlight(const io::ImageF& sky, const Camera& camera, double turbidity,
                             double theta, const HorizonSettings& settings) {
  if (settings.region == HorizonRegion::band)
    return photo_airlight(sky, camera, turbidity, theta, settings.band);
  if (sky.channels != 3) throw InvalidArgument("the sky photo must be R, G, B");
  const estimate::SkyMask segmented =
      settings.mask ? estimate::SkyMask{} : segment_sky(sky, camera, settings.segmentation);
  const estimate::SkyMask& mask = settings.mask ? *settings.mask : segmented;
  if (mask.width != sky.width || mask.height != sky.height)
    throw InvalidArgument(fmt::format("the sky mask is {}x{} but the sky photo {}x{}", mask.width,
                                      mask.height, sky.width, sky.height));
  return region_airlight(sky, camera, horizon_region(mask, camera, settings.band), turbidity,
                         theta);
}

}  // namespace skylight::haze
