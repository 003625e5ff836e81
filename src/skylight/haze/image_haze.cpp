// Morales et al. 2017 eqs. 10, 12, 13, 19 and 26; docs/HAZE.md.
#include "skylight/haze/image_haze.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/core/parameters.h"
#include "skylight/estimate/photo.h"
#include "skylight/haze/detail/pixel_kernel.h"

namespace skylight::haze {
namespace {

Atmosphere target_atmosphere(const HazeSettings& s) {
  Atmosphere t = s.source;
  t.turbidity = *s.target_turbidity;
  return t;
}

void check_settings(const HazeSettings& s) {
  validate(s.source);
  if (s.operation == HazeOperation::retarget) {
    if (!s.target_turbidity) throw InvalidArgument("retarget needs the target turbidity");
    validate(target_atmosphere(s));
  }
  for (const Rgb3* a : {&s.airlight_source, &s.airlight_target})
    for (double v : *a)
      if (!(v > 0.0 && std::isfinite(v)))
        throw InvalidArgument(fmt::format("airlight {} is not a finite number > 0", v));
  if (!(s.min_transmission > 0.0 && s.min_transmission <= 1.0))
    throw InvalidArgument(
        fmt::format("minimum transmission {} is outside (0, 1]", s.min_transmission));
  SKYLIGHT_CHECK(s.table_error > 0.0, "table error must be > 0");
  if (s.airlight_target_map && !s.airlight_source_map)
    throw InvalidArgument("a per-pixel target airlight needs a per-pixel source airlight");
  if (s.operation == HazeOperation::retarget && s.airlight_source_map && !s.airlight_target_map)
    throw InvalidArgument("retarget with a per-pixel airlight needs it at both turbidities");
}

void check_pair(const io::ImageF& image, const io::ImageF& depth_m, const HazeSettings& s) {
  if (image.channels != 3)
    throw InvalidArgument(
        fmt::format("the image has {} channel(s); haze needs R, G, B", image.channels));
  SKYLIGHT_CHECK(
      depth_m.channels == 1 && depth_m.width == image.width && depth_m.height == image.height,
      "depth map must be one channel of the image's size (depth_in_metres)");
  for (const auto* map : {s.airlight_source_map.get(), s.airlight_target_map.get()})
    if (map && (map->rgb().width != image.width || map->rgb().height != image.height))
      throw InvalidArgument(fmt::format("the per-pixel airlight is {}x{} but the image {}x{}",
                                        map->rgb().width, map->rgb().height, image.width,
                                        image.height));
}

// The two airlights and Gamma's role per operation (eq. 26 with Gamma_s = 1 for add, Gamma_t = 1
// for remove).
struct Roles {
  bool source_is_one = false, target_is_one = false;
  Rgb3 a_s{}, a_t{};
  const AirlightMap* map_s = nullptr;  // per pixel; null: the constants
  const AirlightMap* map_t = nullptr;
};

Roles roles(const HazeSettings& s) {
  Roles r;
  switch (s.operation) {
    case HazeOperation::add:
      r.source_is_one = true;
      r.a_s = r.a_t = s.airlight_source;
      r.map_s = r.map_t = s.airlight_source_map.get();
      break;
    case HazeOperation::remove:
      r.target_is_one = true;
      r.a_s = r.a_t = s.airlight_source;
      r.map_s = r.map_t = s.airlight_source_map.get();
      break;
    case HazeOperation::retarget:
      r.a_s = s.airlight_source;
      r.a_t = s.airlight_target;
      r.map_s = s.airlight_source_map.get();
      r.map_t = s.airlight_target_map.get();
      break;
  }
  return r;
}

// The largest depth; the kernel's table index needs every depth finite and >= 0.
float max_depth(const io::ImageF& depth_m) {
  float m = 0.0f;
  for (float v : depth_m.data) {
    if (!(v >= 0.0f && std::isfinite(v)))
      throw InvalidArgument(fmt::format("depth {} m: depths must be finite and >= 0", v));
    m = std::max(m, v);
  }
  return m;
}

}  // namespace

AirlightMap::AirlightMap(io::ImageF rgb) : rgb_(std::move(rgb)) {
  if (rgb_.channels != 3)
    throw InvalidArgument(
        fmt::format("a per-pixel airlight has {} channel(s); expected R, G, B", rgb_.channels));
  for (std::size_t i = 0; i < rgb_.data.size(); ++i)
    if (!(rgb_.data[i] > 0.0f && std::isfinite(rgb_.data[i])))
      throw InvalidArgument(
          fmt::format("the per-pixel airlight at pixel ({}, {}) is {}; expected "
                      "a finite number > 0",
                      i / 3 % static_cast<std::size_t>(rgb_.width),
                      i / 3 / static_cast<std::size_t>(rgb_.width), rgb_.data[i]));
}

double depth_from_normalised(double s_bar, double near_m, double far_m) {
  return near_m / (1.0 - s_bar * (1.0 - near_m / far_m));
}

void validate(const DepthEncoding& encoding) {
  if (encoding.near_m.has_value() != encoding.far_m.has_value())
    throw InvalidArgument(fmt::format("{} and {} go together (normalised depth, eq. 19)",
                                      spelled("near"), spelled("far")));
  if (encoding.near_m && !(*encoding.near_m > 0.0 && *encoding.far_m > *encoding.near_m))
    throw InvalidArgument(fmt::format("near {} m and far {} m must satisfy 0 < near < far",
                                      *encoding.near_m, *encoding.far_m));
}

io::ImageF depth_in_metres(const io::ImageF& depth, const DepthEncoding& encoding, int image_width,
                           int image_height, std::string_view what) {
  if (depth.width != image_width || depth.height != image_height)
    throw InvalidArgument(fmt::format("{} is {}x{} but the image is {}x{}", what, depth.width,
                                      depth.height, image_width, image_height));
  validate(encoding);
  const bool normalised = encoding.near_m.has_value();
  io::ImageF out(depth.width, depth.height, 1);
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      const float v = depth.pixel(x, y)[0];
      if (!std::isfinite(v) || v < 0.0f || (normalised && v > 1.0f))
        throw InvalidArgument(fmt::format("{} pixel ({}, {}) is {}; depth must be {}", what, x, y,
                                          v, normalised ? "in [0, 1]" : "finite and >= 0 m"));
      out.pixel(x, y)[0] =
          normalised
              ? static_cast<float>(depth_from_normalised(v, *encoding.near_m, *encoding.far_m))
              : v;
    }
  return out;
}

HazeKernel haze_kernel(double max_depth_m, const CameraSensitivity& camera,
                       const HazeSettings& settings) {
  check_settings(settings);
  const Roles r = roles(settings);
  // Both tables on one grid, fine enough for the more curved of the two.
  const Atmosphere target_air =
      settings.operation == HazeOperation::retarget ? target_atmosphere(settings) : settings.source;
  const Attenuation source_att(settings.source, camera), target_att(target_air, camera);
  const double curvature = std::max(r.source_is_one ? 0.0 : source_att.max_curvature_per_m2(),
                                    r.target_is_one ? 0.0 : target_att.max_curvature_per_m2());
  HazeKernel k;
  if (!r.source_is_one)
    k.source = make_attenuation_table(source_att, max_depth_m, settings.table_error, curvature);
  if (!r.target_is_one)
    k.target = make_attenuation_table(target_att, max_depth_m, settings.table_error, curvature);
  const AttenuationTable& any = k.source.gamma.empty() ? k.target : k.source;
  k.step_m = any.step_m;
  k.entries = any.size();
  k.min_transmission = settings.min_transmission;
  for (std::size_t c = 0; c < 3; ++c) {
    k.airlight_target[c] = r.a_t[c];
    k.scale[c] = r.a_t[c] / r.a_s[c];
  }
  if (r.map_t) {
    k.airlight_target_map = r.map_t == settings.airlight_source_map.get()
                                ? settings.airlight_source_map
                                : settings.airlight_target_map;
    if (r.map_s != r.map_t) k.airlight_source_map = settings.airlight_source_map;
  }
  return k;
}

void apply_haze_in_place(io::ImageF& image, const io::ImageF& depth_m,
                         const CameraSensitivity& camera, const HazeSettings& settings,
                         HazeReport* report) {
  check_settings(settings);
  check_pair(image, depth_m, settings);
  const HazeKernel k = haze_kernel(max_depth(depth_m), camera, settings);
  detail::PixelUniforms u;
  u.gs = k.source.gamma.empty() ? nullptr : k.source.gamma.data();
  u.gt = k.target.gamma.empty() ? nullptr : k.target.gamma.data();
  u.inv_step = static_cast<float>(1.0 / k.step_m);
  u.last = static_cast<int>(k.entries) - 2;
  u.min_t = static_cast<float>(k.min_transmission);
  for (std::size_t c = 0; c < 3; ++c) {
    u.a_t[c] = static_cast<float>(k.airlight_target[c]);
    u.scale[c] = static_cast<float>(k.scale[c]);
  }
  const float* a_t_map = k.airlight_target_map ? k.airlight_target_map->rgb().data.data() : nullptr;
  const float* a_s_map = k.airlight_source_map ? k.airlight_source_map->rgb().data.data() : nullptr;
  std::atomic<std::size_t> clamped{0};
  const auto width = static_cast<std::size_t>(image.width);
  parallel_for(static_cast<std::size_t>(image.height), 8, [&](std::size_t y0, std::size_t y1) {
    float* px = image.data.data() + y0 * width * 3;
    const float* d = depth_m.data.data() + y0 * width;
    const std::size_t n = (y1 - y0) * width;
    const float* at = a_t_map ? a_t_map + y0 * width * 3 : nullptr;
    const float* as = a_s_map ? a_s_map + y0 * width * 3 : nullptr;
    clamped += detail::haze_pixels(u, px, d, at, as, n);
  });
  if (report) {
    report->table_error_bound = k.error_bound();
    report->table_entries = k.entries;
    report->clamped_transmission_pixels = clamped.load();
  }
}

io::ImageF apply_haze(const io::ImageF& image, const io::ImageF& depth_m,
                      const CameraSensitivity& camera, const HazeSettings& settings,
                      HazeReport* report) {
  io::ImageF out = image;
  apply_haze_in_place(out, depth_m, camera, settings, report);
  return out;
}

io::ImageF apply_haze_exact(const io::ImageF& image, const io::ImageF& depth_m,
                            const CameraSensitivity& camera, const HazeSettings& settings) {
  check_settings(settings);
  check_pair(image, depth_m, settings);
  const Roles r = roles(settings);
  const Attenuation source(settings.source, camera);
  const std::optional<Attenuation> target =
      settings.operation == HazeOperation::retarget
          ? std::optional<Attenuation>(std::in_place, target_atmosphere(settings), camera)
          : std::nullopt;
  io::ImageF out(image.width, image.height, 3);
  for (std::size_t p = 0; p < depth_m.data.size(); ++p) {
    const double s = depth_m.data[p];
    const Rgb3 one{1.0, 1.0, 1.0};
    const Rgb3 g_s = r.source_is_one ? one : source.gamma(s);
    const Rgb3 g_t = r.target_is_one ? one : target ? target->gamma(s) : source.gamma(s);
    for (std::size_t c = 0; c < 3; ++c) {
      const double ratio = g_t[c] / std::max(g_s[c], settings.min_transmission);
      const double a_t = r.map_t ? r.map_t->rgb().data[3 * p + c] : r.a_t[c];
      const double a_s = r.map_s ? r.map_s->rgb().data[3 * p + c] : r.a_s[c];
      const double v = image.data[3 * p + c] * (a_t / a_s) * ratio + a_t * (1.0 - ratio);
      out.data[3 * p + c] = static_cast<float>(std::max(0.0, v));
    }
  }
  return out;
}

void check_composite_inputs(const io::ImageF& background, const io::ImageF& object,
                            const io::ImageF& alpha) {
  if (background.channels != 3 || object.channels != 3)
    throw InvalidArgument("the background and the object must be R, G, B images");
  if (object.width != background.width || object.height != background.height)
    throw InvalidArgument(fmt::format("the object is {}x{} but the background is {}x{}",
                                      object.width, object.height, background.width,
                                      background.height));
  if (alpha.channels != 1 || alpha.width != object.width || alpha.height != object.height)
    throw InvalidArgument(fmt::format("the alpha is {}x{} with {} channel(s); expected {}x{}, one",
                                      alpha.width, alpha.height, alpha.channels, object.width,
                                      object.height));
  for (std::size_t p = 0; p < alpha.data.size(); ++p)
    if (!(alpha.data[p] >= 0.0f && alpha.data[p] <= 1.0f))
      throw InvalidArgument(fmt::format("alpha pixel {} is {}; expected [0, 1]", p, alpha.data[p]));
}

io::ImageF composite(const io::ImageF& background, const io::ImageF& object,
                     const io::ImageF& alpha, const io::ImageF& object_depth_m,
                     const CameraSensitivity& camera, const HazeSettings& settings) {
  check_composite_inputs(background, object, alpha);
  HazeSettings add = settings;
  add.operation = HazeOperation::add;
  const io::ImageF hazed = apply_haze(object, object_depth_m, camera, add);
  io::ImageF out(background.width, background.height, 3);
  for (std::size_t p = 0; p < alpha.data.size(); ++p) {
    const float a = alpha.data[p];
    for (std::size_t c = 0; c < 3; ++c)
      out.data[3 * p + c] = a * hazed.data[3 * p + c] + (1.0f - a) * background.data[3 * p + c];
  }
  return out;
}

Rgb3 sky_model_airlight(const SkyModel& model, Vec3 view, const CameraSensitivity& camera) {
  const SpectralWeights w(camera);
  std::array<std::optional<double>, kGridSamples> radiance;
  std::size_t first = kGridSamples, last = 0;
  for (std::size_t i = 0; i < kGridSamples; ++i) {
    radiance[i] = model.spectral_radiance(view, SpectralWeights::nm(i));
    if (!radiance[i]) continue;
    first = std::min(first, i);
    last = i;
  }
  if (first == kGridSamples)
    throw InvalidArgument(fmt::format("sky model '{}' has no spectral radiance in {}-{} nm",
                                      model.name(), SpectralWeights::nm(0),
                                      SpectralWeights::nm(kGridSamples - 1)));
  // Beyond the model's spectrum (hosek ends at 720 nm, the cameras at 780 nm) the camera sees the
  // radiance of its last wavelength: flat tails (docs/HAZE.md gives their share of the response).
  Rgb3 out{};
  for (std::size_t i = 0; i < kGridSamples; ++i) {
    const std::size_t at = std::clamp(i, first, last);
    if (!radiance[at])
      throw InvalidArgument(fmt::format("sky model '{}' has no spectral radiance at {} nm",
                                        model.name(), SpectralWeights::nm(at)));
    for (std::size_t c = 0; c < 3; ++c) out[c] += w.raw()[c][i] * *radiance[at];
  }
  return out;
}

double zeta(double turbidity, double theta, double theta_prime) {
  const auto term = [turbidity](double th) {
    const double cos_theta = std::max(std::cos(th), 0.01);
    return 1.0 + (0.178 * turbidity - 1.463) * std::exp((-0.355 * turbidity + 0.427) / cos_theta);
  };
  return term(theta) / term(theta_prime);
}

PhotoAirlight photo_airlight(const io::ImageF& sky, const Camera& camera, double turbidity,
                             double theta, double band) {
  if (sky.channels != 3) throw InvalidArgument("the sky photo must be R, G, B");
  if (camera.width != sky.width || camera.height != sky.height)
    throw InvalidArgument(fmt::format("the sky photo is {}x{} but its camera {}x{}", sky.width,
                                      sky.height, camera.width, camera.height));
  std::vector<std::uint8_t> region(sky.data.size() / 3, 0);
  const double cos_top = std::cos(kPi / 2 - band);  // z of the band's upper edge
  bool any = false;
  for (int row = 0; row < sky.height; ++row)
    for (int col = 0; col < sky.width; ++col) {
      const std::optional<Vec3> v = camera.pixel_direction(col, row);
      if (!v || v->z <= 0.0 || v->z > cos_top) continue;
      region[static_cast<std::size_t>(row) * static_cast<std::size_t>(sky.width) +
             static_cast<std::size_t>(col)] = 1;
      any = true;
    }
  if (!any)
    throw InvalidArgument(fmt::format("the sky photo has no pixel within {} deg above the horizon",
                                      rad_to_deg(band)));
  return region_airlight(sky, camera, region, turbidity, theta);
}

PhotoAirlight region_airlight(const io::ImageF& sky, const Camera& camera,
                              const std::vector<std::uint8_t>& region, double turbidity,
                              double theta) {
  if (sky.channels != 3) throw InvalidArgument("the sky photo must be R, G, B");
  if (camera.width != sky.width || camera.height != sky.height)
    throw InvalidArgument(fmt::format("the sky photo is {}x{} but its camera {}x{}", sky.width,
                                      sky.height, camera.width, camera.height));
  SKYLIGHT_CHECK(region.size() == sky.data.size() / 3, "region and sky photo sizes differ");
  struct Candidate {
    double luminance, zenith;
    int col, row;
    int sector;
  };
  std::vector<Candidate> candidates;
  for (int row = 0; row < sky.height; ++row)
    for (int col = 0; col < sky.width; ++col) {
      if (!region[static_cast<std::size_t>(row) * static_cast<std::size_t>(sky.width) +
                  static_cast<std::size_t>(col)])
        continue;
      const std::optional<Vec3> v = camera.pixel_direction(col, row);
      if (!v || v->z <= 0.0) continue;
      const ZenithAzimuth a = angles_from_direction(*v);
      const int sector =
          std::min(kHorizonSectors - 1, static_cast<int>(a.azimuth / (2 * kPi) * kHorizonSectors));
      candidates.push_back({estimate::pixel_luminance(sky, col, row), a.zenith, col, row, sector});
    }
  if (candidates.empty())
    throw InvalidArgument("the sky photo's horizon region holds no pixel above the horizon");
  // The brightest 1 % (at least one) of [first, last): their mean colour and zenith angle.
  const auto brightest = [&sky](std::vector<Candidate>::iterator first,
                                std::vector<Candidate>::iterator last, Rgb3& horizon,
                                double& theta_prime) {
    const auto count = static_cast<std::size_t>(last - first);
    const std::size_t n = std::max<std::size_t>(1, (count + 99) / 100);
    std::partial_sort(
        first, first + static_cast<std::ptrdiff_t>(n), last,
        [](const Candidate& a, const Candidate& b) { return a.luminance > b.luminance; });
    horizon = {};
    theta_prime = 0.0;
    for (auto it = first; it != first + static_cast<std::ptrdiff_t>(n); ++it) {
      const float* p = sky.pixel(it->col, it->row);
      for (std::size_t c = 0; c < 3; ++c) horizon[c] += p[c] / static_cast<double>(n);
      theta_prime += it->zenith / static_cast<double>(n);
    }
    return n;
  };
  PhotoAirlight out;
  // Per sector of azimuth first (the candidates grouped by sector, stable within one).
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.sector < b.sector; });
  for (auto first = candidates.begin(); first != candidates.end();) {
    const auto last = std::find_if(first, candidates.end(),
                                   [&](const Candidate& c) { return c.sector != first->sector; });
    HorizonSector sector;
    sector.azimuth = (first->sector + 0.5) * 2 * kPi / kHorizonSectors;
    sector.pixels = brightest(first, last, sector.horizon, sector.theta_prime);
    out.sectors.push_back(sector);
    first = last;
  }
  out.pixels = brightest(candidates.begin(), candidates.end(), out.horizon, out.theta_prime);
  const double z = zeta(turbidity, theta, out.theta_prime);
  for (std::size_t c = 0; c < 3; ++c) out.airlight[c] = out.horizon[c] * z;
  return out;
}

}  // namespace skylight::haze
