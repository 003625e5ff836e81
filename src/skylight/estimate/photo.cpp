// Sky photographs: luminance, sky masks and the sun in the image (docs/ESTIMATE.md).
#include "skylight/estimate/photo.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>

#include "skylight/core/colorimetry.h"
#include "skylight/core/error.h"
#include "skylight/core/random.h"

namespace skylight::estimate {

ImageSchemaOptions photo_image_options(Projection default_projection, std::string projection_flag,
                                       std::string description) {
  ImageSchemaOptions o;
  o.projections = {Projection::fisheye, Projection::equirect};
  o.default_projection = default_projection;
  o.size = false;
  o.projection_flag = std::move(projection_flag);
  o.description = std::move(description);
  return o;
}

const ParameterSchema<MaskSettings>& MaskSettings::schema() {
  static const ParameterSchema<MaskSettings> s = [] {
    ParameterSchema<MaskSettings> s;
    s.number(&MaskSettings::min_elevation,
             {.name = "min-elevation",
              .unit = "deg",
              .min = 0.0,
              .max = 89.0,
              .default_value = ParameterValue(0.0),
              .description = "mask: sky pixels above this elevation only"},
             kDegree)
        .number(
            &MaskSettings::sun_exclusion,
            {.name = "sun-exclusion",
             .unit = "deg",
             .min = 0.0,
             .max = 90.0,
             .default_value = ParameterValue(5.0),
             .description =
                 "mask: pixels within this angle of the sun are not sky (disc, aureole, flare)"},
            kDegree)
        .number(
            &MaskSettings::saturation_fraction,
            {.name = "saturation",
             .unit = "1",
             .min = 1e-6,
             .max = 1.0,
             .default_value = ParameterValue(0.999),
             .description =
                 "mask: pixels with a channel >= this fraction of the image's largest value are "
                 "not sky (a clipped sun)"});
    return s;
  }();
  return s;
}
namespace {

// Which pixels a camera images above an elevation, decided from the pixel position alone (no
// trigonometry per pixel): for a fisheye, the zenith angle grows with the distance r from the
// image circle's centre (calibrated or centred), so theta < pi/2 - e  <=>  r < r(pi/2 - e); for an
// equirect map, row by row.
class HorizonTest {
 public:
  HorizonTest(const Camera& c, double min_elevation) : camera_(c) {
    const double theta_max = kPi / 2 - min_elevation;
    if (c.projection == Projection::fisheye) {
      circle_ = fisheye_image_circle(c.width, c.height, c.fisheye);
      if (theta_max > 0.5 * c.fisheye.fov) {
        limit_ = 1.0;  // every imaged direction is high enough
        inclusive_ = true;
      } else {
        limit_ = fisheye_radius(c.fisheye, theta_max).value_or(0.0);
      }
    } else {
      // theta = pi (row + 0.5) / height < theta_max
      limit_ = theta_max;
    }
  }
  bool operator()(int col, int row) const {
    if (camera_.projection == Projection::equirect)
      return kPi * (row + 0.5) / camera_.height < limit_;
    const double dx = (col + 0.5 - circle_.col) / circle_.radius;
    const double dy = (row + 0.5 - circle_.row) / circle_.radius;
    const double r2 = dx * dx + dy * dy;
    return inclusive_ ? r2 <= limit_ * limit_ : r2 < limit_ * limit_;
  }

 private:
  const Camera& camera_;
  FisheyeCircle circle_;
  double limit_ = 0.0;
  bool inclusive_ = false;
};

// Y row of the sRGB -> XYZ matrix (IEC 61966-2-1; core/colorimetry.h).
const std::array<double, 3>& luminance_weights() {
  static const std::array<double, 3> w = srgb_to_xyz_matrix()[1];
  return w;
}

bool finite_non_negative(const float* p, int channels) {
  for (int c = 0; c < channels; ++c)
    if (!(std::isfinite(p[c]) && p[c] >= 0.0f)) return false;
  return true;
}

float max_channel(const float* p, int channels) {
  float m = p[0];
  for (int c = 1; c < channels; ++c) m = std::max(m, p[c]);
  return m;
}

double luminance_of(const float* p, int channels) {
  if (channels == 1) return p[0];
  const auto& w = luminance_weights();
  return w[0] * p[0] + w[1] * p[1] + w[2] * p[2];
}

// Pixel box [c0, c1) x [r0, r1) that holds every pixel within angle `radius` of `sun`, from the
// images of a ring of directions at that angle; the whole image when the ring is not wholly imaged
// or wraps (equirect seam, a pole inside the ring).
struct Box {
  int c0, c1, r0, r1;
};
Box exclusion_box(const Camera& camera, const SunPosition& sun, double radius) {
  const Box whole{0, camera.width, 0, camera.height};
  const Vec3 s = sun.direction();
  // An orthonormal pair perpendicular to s.
  const Vec3 helper = std::abs(s.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 u = normalize(cross(s, helper));
  const Vec3 v = cross(s, u);
  constexpr int kRing = 64;
  double cmin = camera.width, cmax = 0.0, rmin = camera.height, rmax = 0.0;
  const auto centre = camera.pixel(s);
  if (!centre) return whole;
  for (int k = 0; k <= kRing; ++k) {
    const double a = 2.0 * kPi * k / kRing;
    const Vec3 d = std::cos(radius) * s + std::sin(radius) * (std::cos(a) * u + std::sin(a) * v);
    const auto p = k == kRing ? centre : camera.pixel(d);
    if (!p) return whole;
    cmin = std::min(cmin, (*p)[0]);
    cmax = std::max(cmax, (*p)[0]);
    rmin = std::min(rmin, (*p)[1]);
    rmax = std::max(rmax, (*p)[1]);
  }
  if (camera.projection == Projection::equirect &&
      (cmax - cmin > 0.5 * camera.width || sun.zenith < radius || sun.zenith > kPi - radius))
    return whole;
  // The ring's sampling misses bulges of at most a few pixels: a margin of kMargin pixels.
  constexpr int kMargin = 3;
  return {std::max(0, static_cast<int>(std::floor(cmin)) - kMargin),
          std::min(camera.width, static_cast<int>(std::ceil(cmax)) + kMargin),
          std::max(0, static_cast<int>(std::floor(rmin)) - kMargin),
          std::min(camera.height, static_cast<int>(std::ceil(rmax)) + kMargin)};
}

}  // namespace

double pixel_luminance(const io::ImageF& image, int col, int row) {
  return luminance_of(image.pixel(col, row), image.channels);
}

io::ImageF load_mask(const std::filesystem::path& path) {
  if (io::format_from_path(path) == io::ImageFormat::png) {
    const io::Image8 png = io::read_png(path);
    io::ImageF m(png.width, png.height, 1);
    for (std::size_t i = 0; i < m.data.size(); ++i)
      m.data[i] = std::max({png.data[3 * i], png.data[3 * i + 1], png.data[3 * i + 2]});
    return m;
  }
  const io::ImageF img = io::read_image(path);
  io::ImageF m(img.width, img.height, 1);
  for (std::size_t i = 0; i < m.data.size(); ++i)
    m.data[i] =
        max_channel(img.data.data() + i * static_cast<std::size_t>(img.channels), img.channels);
  return m;
}

SkyMask sky_mask(const io::ImageF& image, const Camera& camera, const MaskSettings& settings,
                 const std::optional<SunPosition>& sun, const io::ImageF* user_mask) {
  validate(camera);
  SKYLIGHT_CHECK(image.width == camera.width && image.height == camera.height,
                 "camera and image sizes differ");
  if (!(settings.min_elevation >= 0.0 && settings.min_elevation < kPi / 2) ||
      !(settings.saturation_fraction > 0.0 && settings.saturation_fraction <= 1.0) ||
      !(settings.sun_exclusion >= 0.0 && settings.sun_exclusion < kPi))
    throw InvalidArgument(
        fmt::format("mask settings out of range: min elevation {} deg, saturation fraction {}, sun "
                    "exclusion {} deg",
                    rad_to_deg(settings.min_elevation), settings.saturation_fraction,
                    rad_to_deg(settings.sun_exclusion)));
  if (user_mask && (user_mask->width != image.width || user_mask->height != image.height))
    throw InvalidArgument(fmt::format("the mask is {} x {} pixels but the image is {} x {}",
                                      user_mask->width, user_mask->height, image.width,
                                      image.height));
  const HorizonTest above(camera, settings.min_elevation);
  const int ch = image.channels;
  // The largest channel value among imaged pixels: the level of a clipped exposure.
  float peak = 0.0f;
  for (int row = 0; row < image.height; ++row)
    for (int col = 0; col < image.width; ++col) {
      const float* p = image.pixel(col, row);
      if (above(col, row) && finite_non_negative(p, ch)) peak = std::max(peak, max_channel(p, ch));
    }
  const float saturated = static_cast<float>(settings.saturation_fraction) * peak;

  SkyMask m;
  m.width = image.width;
  m.height = image.height;
  m.sky.assign(static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height), 0);
  for (int row = 0; row < image.height; ++row)
    for (int col = 0; col < image.width; ++col) {
      const float* p = image.pixel(col, row);
      bool ok = above(col, row) && finite_non_negative(p, ch) && max_channel(p, ch) < saturated &&
                luminance_of(p, ch) > 0.0;
      if (ok && user_mask)
        ok = max_channel(user_mask->pixel(col, row), user_mask->channels) != 0.0f;
      m.sky[static_cast<std::size_t>(row) * static_cast<std::size_t>(m.width) +
            static_cast<std::size_t>(col)] = ok ? 1 : 0;
    }
  if (sun && settings.sun_exclusion > 0.0) {
    const Vec3 s = sun->direction();
    const Box b = exclusion_box(camera, *sun, settings.sun_exclusion);
    for (int row = b.r0; row < b.r1; ++row)
      for (int col = b.c0; col < b.c1; ++col) {
        auto& flag = m.sky[static_cast<std::size_t>(row) * static_cast<std::size_t>(m.width) +
                           static_cast<std::size_t>(col)];
        if (!flag) continue;
        const auto d = camera.pixel_direction(col, row);
        if (!d || angle_between(*d, s) <= settings.sun_exclusion) flag = 0;
      }
  }
  m.count = static_cast<std::size_t>(std::count(m.sky.begin(), m.sky.end(), std::uint8_t{1}));
  return m;
}

SunDetection detect_sun(const io::ImageF& image, const Camera& camera, double region_fraction) {
  validate(camera);
  SKYLIGHT_CHECK(image.width == camera.width && image.height == camera.height,
                 "camera and image sizes differ");
  SKYLIGHT_CHECK(region_fraction > 0.0 && region_fraction <= 1.0, "region fraction in (0, 1]");
  const HorizonTest above(camera, 0.0);
  const int w = image.width, h = image.height;
  auto usable_luminance = [&](int col, int row) {
    const float* p = image.pixel(col, row);
    if (!above(col, row) || !finite_non_negative(p, image.channels)) return -1.0;
    return luminance_of(p, image.channels);
  };
  double peak = 0.0;
  int pc = -1, pr = -1;
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col)
      if (const double y = usable_luminance(col, row); y > peak) {
        peak = y;
        pc = col;
        pr = row;
      }
  if (pc < 0)
    throw InvalidArgument(
        "cannot find the sun: no pixel above the horizon has a positive finite luminance");
  // Flood fill (4-neighbours; equirect columns wrap) from the peak over pixels >= threshold. Each
  // pixel's offset from the peak is carried along so that a region across the seam has one
  // centroid.
  const double threshold = region_fraction * peak;
  const bool wrap = camera.projection == Projection::equirect;
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  struct Node {
    int col, row;
    double dc, dr;
  };
  std::deque<Node> queue{{pc, pr, 0.0, 0.0}};
  seen[static_cast<std::size_t>(pr) * w + pc] = 1;
  double sum_c = 0.0, sum_r = 0.0;
  std::size_t n = 0;
  while (!queue.empty()) {
    const Node q = queue.front();
    queue.pop_front();
    sum_c += q.dc;
    sum_r += q.dr;
    ++n;
    constexpr std::array<std::array<int, 2>, 4> kSteps{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    for (const auto& [sc, sr] : kSteps) {
      int c = q.col + sc;
      const int r = q.row + sr;
      if (r < 0 || r >= h) continue;
      if (c < 0 || c >= w) {
        if (!wrap) continue;
        c = (c + w) % w;
      }
      auto& s = seen[static_cast<std::size_t>(r) * w + c];
      if (s || usable_luminance(c, r) < threshold) continue;
      s = 1;
      queue.push_back({c, r, q.dc + sc, q.dr + sr});
    }
  }
  SunDetection d;
  d.col = pc + 0.5 + sum_c / static_cast<double>(n);
  d.row = pr + 0.5 + sum_r / static_cast<double>(n);
  if (wrap) d.col = std::fmod(d.col + w, static_cast<double>(w));
  d.region_pixels = n;
  d.peak_luminance = peak;
  const auto dir = camera.direction(d.col, d.row);
  if (!dir || dir->z <= 0.0)
    throw InvalidArgument(fmt::format(
        "cannot find the sun: the centroid of the brightest region (pixel {:.1f}, {:.1f}) is not "
        "above the horizon",
        d.col, d.row));
  const ZenithAzimuth za = angles_from_direction(*dir);
  d.sun = SunPosition{za.zenith, za.azimuth};
  return d;
}

std::vector<LuminanceSample> sample_sky(const io::ImageF& image, const Camera& camera,
                                        const SkyMask& mask, int samples, std::uint64_t seed) {
  SKYLIGHT_CHECK(mask.width == image.width && mask.height == image.height,
                 "mask and image sizes differ");
  if (samples < 2) throw InvalidArgument(fmt::format("samples = {} is below 2", samples));
  if (mask.count < static_cast<std::size_t>(samples))
    throw InvalidArgument(
        fmt::format("the sky mask has {} usable pixels, fewer than the {} samples asked for",
                    mask.count, samples));
  SplitMix64 rng(seed);
  const std::size_t total = mask.sky.size();
  // Rejection sampling over the image while the sky is at least 1/8 of it, else over the list of
  // sky pixels: uniform over the mask either way.
  std::vector<std::size_t> list;
  if (mask.count * 8 < total)
    for (std::size_t i = 0; i < total; ++i)
      if (mask.sky[i]) list.push_back(i);
  std::vector<LuminanceSample> out;
  out.reserve(static_cast<std::size_t>(samples));
  while (out.size() < static_cast<std::size_t>(samples)) {
    const std::size_t i = list.empty() ? rng.below(total) : list[rng.below(list.size())];
    if (!mask.sky[i]) continue;
    const int col = static_cast<int>(i % static_cast<std::size_t>(mask.width));
    const int row = static_cast<int>(i / static_cast<std::size_t>(mask.width));
    const auto d = camera.pixel_direction(col, row);
    SKYLIGHT_CHECK(d && d->z > 0.0, "sky-mask pixels see a direction above the horizon");
    out.push_back({*d, pixel_luminance(image, col, row)});
  }
  return out;
}

std::vector<LuminanceSample> every_sky_pixel(const io::ImageF& image, const Camera& camera,
                                             const SkyMask& mask) {
  SKYLIGHT_CHECK(mask.width == image.width && mask.height == image.height,
                 "mask and image sizes differ");
  std::vector<LuminanceSample> out;
  out.reserve(mask.count);
  for (int row = 0; row < mask.height; ++row)
    for (int col = 0; col < mask.width; ++col) {
      if (!mask.sky[static_cast<std::size_t>(row) * static_cast<std::size_t>(mask.width) +
                    static_cast<std::size_t>(col)])
        continue;
      const auto d = camera.pixel_direction(col, row);
      SKYLIGHT_CHECK(d && d->z > 0.0, "sky-mask pixels see a direction above the horizon");
      out.push_back({*d, pixel_luminance(image, col, row)});
    }
  return out;
}

PhotoSamples sample_photo(const io::ImageF& image, const Camera& camera,
                          const std::optional<SunPosition>& sun, const MaskSettings& mask_settings,
                          std::optional<int> samples, std::uint64_t seed,
                          const io::ImageF* user_mask) {
  PhotoSamples out;
  out.sun_detected = !sun;
  out.sun = sun ? *sun : detect_sun(image, camera).sun;
  if (!(out.sun.zenith < kPi / 2))
    throw InvalidArgument(
        fmt::format("the sun is at zenith angle {} deg: the fit needs it above the horizon",
                    rad_to_deg(out.sun.zenith)));
  out.mask = sky_mask(image, camera, mask_settings, out.sun, user_mask);
  out.sky_pixels = out.mask.count;
  if (!samples && out.mask.count <= static_cast<std::size_t>(kPhotoSamples))
    out.samples = every_sky_pixel(image, camera, out.mask);
  else
    out.samples = sample_sky(image, camera, out.mask, samples.value_or(kPhotoSamples), seed);
  return out;
}

io::ImageF photo_luminance_image(const io::ImageF& image) {
  io::ImageF out(image.width, image.height, 1);
  for (int row = 0; row < image.height; ++row)
    for (int col = 0; col < image.width; ++col)
      out.pixel(col, row)[0] = static_cast<float>(pixel_luminance(image, col, row));
  return out;
}

}  // namespace skylight::estimate
