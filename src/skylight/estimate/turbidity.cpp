// Turbidity from luminance samples (Morales et al. 2017 §3.4, eq. 8, with a free luminance scale;
// docs/ESTIMATE.md).
#include "skylight/estimate/turbidity.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "skylight/core/error.h"
#include "skylight/core/random.h"
#include "skylight/models/perez_kernel.h"
#include "skylight/models/preetham.h"

namespace skylight::estimate {
namespace {

// The samples in the form the fit evaluates: cos theta_i, gamma_i, ln Y_i, and the sun.
struct Prepared {
  std::vector<double> cos_theta, gamma, log_y;
  double sun_zenith = 0.0;  // theta_s: gamma of the zenith
  std::size_t size() const { return log_y.size(); }
};

Prepared prepare(std::span<const LuminanceSample> samples, const SunPosition& sun) {
  if (!(sun.zenith >= 0.0 && sun.zenith < kPi / 2))
    throw InvalidArgument(fmt::format(
        "the sun is at zenith angle {} deg: the turbidity fit needs it above the horizon",
        rad_to_deg(sun.zenith)));
  Prepared p;
  p.sun_zenith = sun.zenith;
  const Vec3 s = sun.direction();
  for (const auto& x : samples) {
    SKYLIGHT_CHECK(x.luminance > 0.0 && std::isfinite(x.luminance) && x.view.z > 0.0,
                   "samples are sky pixels with positive luminance above the horizon");
    p.cos_theta.push_back(x.view.z);
    p.gamma.push_back(angle_between(x.view, s));
    p.log_y.push_back(std::log(x.luminance));
  }
  return p;
}

// ln f_i(T) for the samples `idx` of p (all when idx is empty), into out.
void log_relative(const Prepared& p, std::span<const std::size_t> idx, double turbidity,
                  std::vector<double>& out) {
  const PerezCoefficients c = preetham_perez_coefficients(turbidity).Y;
  const double log_f0 = std::log(perez_function(c, 1.0, p.sun_zenith));
  const std::size_t n = idx.size();
  out.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = idx[k];
    out[k] = std::log(perez_function(c, p.cos_theta[i], p.gamma[i])) - log_f0;
  }
}

struct Point {
  double turbidity = 0.0, log_scale = 0.0, cost = 0.0;  // cost = sum r_i^2
};

// The profile: for fixed T the best ln s is the mean of ln Y_i - ln f_i(T).
Point profile(const Prepared& p, std::span<const std::size_t> idx, double turbidity,
              std::vector<double>& work) {
  log_relative(p, idx, turbidity, work);
  double mean = 0.0;
  for (std::size_t k = 0; k < idx.size(); ++k) mean += p.log_y[idx[k]] - work[k];
  mean /= static_cast<double>(idx.size());
  double cost = 0.0;
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const double r = p.log_y[idx[k]] - mean - work[k];
    cost += r * r;
  }
  return {turbidity, mean, std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity()};
}

// Points of the coarse scan over [kFitTurbidityMin, kFitTurbidityMax]: a step of 0.5 in T.
constexpr int kScanPoints = 38;
// Golden-section search ends when the bracket is this narrow in T (far below any use of T).
constexpr double kGoldenTolerance = 1e-9;

struct Bracket {
  Point best;
  double lo = 0.0, hi = 0.0;
};

Bracket scan(const Prepared& p, std::span<const std::size_t> idx, std::vector<double>& work) {
  Bracket b;
  b.best.cost = std::numeric_limits<double>::infinity();
  int best_k = 0;
  const double step = (kFitTurbidityMax - kFitTurbidityMin) / (kScanPoints - 1);
  for (int k = 0; k < kScanPoints; ++k) {
    const Point q = profile(p, idx, kFitTurbidityMin + step * k, work);
    if (q.cost < b.best.cost) {
      b.best = q;
      best_k = k;
    }
  }
  b.lo = kFitTurbidityMin + step * std::max(0, best_k - 1);
  b.hi = kFitTurbidityMin + step * std::min(kScanPoints - 1, best_k + 1);
  return b;
}

Point golden(const Prepared& p, std::span<const std::size_t> idx, const Bracket& b,
             std::vector<double>& work) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = b.lo, d = b.hi;
  double x1 = d - g * (d - a), x2 = a + g * (d - a);
  Point f1 = profile(p, idx, x1, work), f2 = profile(p, idx, x2, work);
  while (d - a > kGoldenTolerance) {
    if (f1.cost <= f2.cost) {
      d = x2;
      x2 = x1;
      f2 = f1;
      x1 = d - g * (d - a);
      f1 = profile(p, idx, x1, work);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (d - a);
      f2 = profile(p, idx, x2, work);
    }
  }
  Point best = f1.cost <= f2.cost ? f1 : f2;
  if (b.best.cost < best.cost) best = b.best;
  return best;
}

// Levenberg-Marquardt on (T, ln s) from `start`. The derivative of ln f_i in T is a central
// difference with step kDerivativeStep (ln f is smooth in T; the step's error ~1e-8 relative).
constexpr double kDerivativeStep = 1e-4;
constexpr int kMaxLmIterations = 100;
// Damping increases tried per iteration before LM stops (lambda x 10 each).
constexpr int kMaxLambdaTries = 12;
// LM stops when a step lowers the cost by less than this fraction (double round-off level).
constexpr double kLmRelativeDecrease = 1e-14;

struct LmResult {
  Point point;
  int iterations = 0;
  bool ok = false;
};

LmResult levenberg_marquardt(const Prepared& p, std::span<const std::size_t> idx, Point start,
                             std::vector<double>& work) {
  const std::size_t n = idx.size();
  std::vector<double> lo(n), hi(n), mid(n);
  double lambda = 1e-3;
  Point cur = start;
  // start.cost is the profile cost at (start.turbidity, start.log_scale).
  LmResult res;
  for (int it = 0; it < kMaxLmIterations; ++it) {
    res.iterations = it + 1;
    const double h = std::min(kDerivativeStep, 0.5 * (kFitTurbidityMax - kFitTurbidityMin));
    const double t_lo = std::max(kFitTurbidityMin, cur.turbidity - h);
    const double t_hi = std::min(kFitTurbidityMax, cur.turbidity + h);
    log_relative(p, idx, t_lo, lo);
    log_relative(p, idx, t_hi, hi);
    log_relative(p, idx, cur.turbidity, mid);
    Eigen::Matrix2d JtJ = Eigen::Matrix2d::Zero();
    Eigen::Vector2d Jtr = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < n; ++k) {
      const double r = p.log_y[idx[k]] - cur.log_scale - mid[k];
      const Eigen::Vector2d J(-(hi[k] - lo[k]) / (t_hi - t_lo), -1.0);
      JtJ += J * J.transpose();
      Jtr += J * r;
    }
    bool accepted = false, done = false;
    for (int tries = 0; tries < kMaxLambdaTries && !accepted; ++tries) {
      Eigen::Matrix2d A = JtJ;
      A.diagonal() *= 1.0 + lambda;
      const Eigen::Vector2d step = A.ldlt().solve(-Jtr);
      if (!step.allFinite()) return res;
      Point next;
      next.turbidity = std::clamp(cur.turbidity + step[0], kFitTurbidityMin, kFitTurbidityMax);
      next.log_scale = cur.log_scale + step[1];
      log_relative(p, idx, next.turbidity, work);
      next.cost = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        const double r = p.log_y[idx[k]] - next.log_scale - work[k];
        next.cost += r * r;
      }
      if (std::isfinite(next.cost) && next.cost < cur.cost) {
        const bool small = cur.cost - next.cost <= kLmRelativeDecrease * cur.cost;
        cur = next;
        lambda = std::max(lambda * 0.1, 1e-12);
        accepted = true;
        done = small;
      } else {
        lambda *= 10.0;
      }
    }
    // No step lowers the cost (a minimum to working precision), or the last one barely did.
    if (!accepted || done || cur.cost <= 0.0) break;
  }
  res.point = cur;
  res.ok = std::isfinite(cur.cost);
  return res;
}

TurbidityFit to_fit(const Point& q, std::size_t n, std::string method, int iterations) {
  return {q.turbidity, q.log_scale, std::sqrt(q.cost / static_cast<double>(n)), std::move(method),
          iterations};
}

TurbidityFit fit_indices(const Prepared& p, std::span<const std::size_t> idx,
                         std::vector<double>& work) {
  SKYLIGHT_CHECK(idx.size() >= 2, "the fit needs at least 2 samples");
  const Bracket b = scan(p, idx, work);
  Point start = b.best;
  const LmResult lm = levenberg_marquardt(p, idx, start, work);
  if (lm.ok && lm.point.cost <= b.best.cost)
    return to_fit(lm.point, idx.size(), "levenberg-marquardt", lm.iterations);
  return to_fit(golden(p, idx, b, work), idx.size(), "bracketing", lm.iterations);
}

std::vector<std::size_t> all_indices(std::size_t n) {
  std::vector<std::size_t> idx(n);
  std::iota(idx.begin(), idx.end(), std::size_t{0});
  return idx;
}

}  // namespace

double preetham_log_relative_luminance(double turbidity, Vec3 view, const SunPosition& sun) {
  const PerezCoefficients c = preetham_perez_coefficients(turbidity).Y;
  return std::log(perez_function(c, view.z, angle_between(view, sun.direction()))) -
         std::log(perez_function(c, 1.0, sun.zenith));
}

TurbidityFit fit_turbidity(std::span<const LuminanceSample> samples, const SunPosition& sun) {
  if (samples.size() < 2) throw InvalidArgument("the turbidity fit needs at least 2 samples");
  const Prepared p = prepare(samples, sun);
  std::vector<double> work;
  const auto idx = all_indices(p.size());
  return fit_indices(p, idx, work);
}

TurbidityFit fit_turbidity_bracketing(std::span<const LuminanceSample> samples,
                                      const SunPosition& sun) {
  if (samples.size() < 2) throw InvalidArgument("the turbidity fit needs at least 2 samples");
  const Prepared p = prepare(samples, sun);
  std::vector<double> work;
  const auto idx = all_indices(p.size());
  return to_fit(golden(p, idx, scan(p, idx, work), work), idx.size(), "bracketing", 0);
}

std::vector<LuminanceSample> sample_sky(const io::ImageF& image, const SkyCamera& camera,
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

TurbidityEstimate estimate_turbidity(std::span<const LuminanceSample> samples,
                                     const SunPosition& sun, const EstimateSettings& s) {
  if (samples.size() < 2) throw InvalidArgument("the turbidity fit needs at least 2 samples");
  if (s.ransac &&
      (s.ransac_minimal_set < 2 || static_cast<std::size_t>(s.ransac_minimal_set) > samples.size()))
    throw InvalidArgument(fmt::format("RANSAC minimal set of {} samples out of {}",
                                      s.ransac_minimal_set, samples.size()));
  const Prepared p = prepare(samples, sun);
  const std::size_t n = p.size();
  SplitMix64 rng(s.seed ^ 0x5851f42d4c957f2dULL);
  std::vector<double> work;
  std::vector<std::size_t> inliers = all_indices(n);
  const auto all = all_indices(n);

  // Indices of the samples with |r_i| < threshold under a fit.
  auto consensus = [&](const TurbidityFit& f, double* sum_sq) {
    log_relative(p, all, f.turbidity, work);
    std::vector<std::size_t> in;
    double ss = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double r = p.log_y[i] - f.log_scale - work[i];
      if (std::abs(r) < s.inlier_threshold) {
        in.push_back(i);
        ss += r * r;
      }
    }
    if (sum_sq) *sum_sq = ss;
    return in;
  };

  TurbidityFit fit;
  if (s.ransac) {
    std::vector<std::size_t> best;
    double best_ss = std::numeric_limits<double>::infinity();
    std::vector<std::size_t> minimal(static_cast<std::size_t>(s.ransac_minimal_set));
    for (int it = 0; it < s.ransac_iterations; ++it) {
      // A minimal set of distinct samples.
      for (std::size_t k = 0; k < minimal.size(); ++k) {
        std::size_t i;
        do i = rng.below(n);
        while (std::find(minimal.begin(), minimal.begin() + static_cast<std::ptrdiff_t>(k), i) !=
               minimal.begin() + static_cast<std::ptrdiff_t>(k));
        minimal[k] = i;
      }
      const TurbidityFit trial = fit_indices(p, minimal, work);
      double ss = 0.0;
      auto in = consensus(trial, &ss);
      if (in.size() > best.size() || (in.size() == best.size() && ss < best_ss)) {
        best = std::move(in);
        best_ss = ss;
      }
    }
    inliers = best.size() >= 2 ? best : all;
    // Refit on the consensus set, then once more on the consensus of that fit.
    fit = fit_indices(p, inliers, work);
    if (auto again = consensus(fit, nullptr); again.size() >= 2 && again != inliers) {
      inliers = std::move(again);
      fit = fit_indices(p, inliers, work);
    }
  } else {
    fit = fit_indices(p, inliers, work);
  }

  TurbidityEstimate e;
  e.turbidity = fit.turbidity;
  e.log_scale = fit.log_scale;
  e.residual = fit.residual;
  e.method = fit.method;
  e.sun = sun;
  e.samples = static_cast<int>(n);
  e.inliers = static_cast<int>(inliers.size());
  e.inlier_fraction = static_cast<double>(inliers.size()) / static_cast<double>(n);
  if (s.bootstrap >= 2) {
    std::vector<double> ts;
    std::vector<std::size_t> resample(inliers.size());
    for (int b = 0; b < s.bootstrap; ++b) {
      for (auto& i : resample) i = inliers[rng.below(inliers.size())];
      const LmResult lm =
          levenberg_marquardt(p, resample, profile(p, resample, fit.turbidity, work), work);
      ts.push_back(lm.ok ? lm.point.turbidity : fit_indices(p, resample, work).turbidity);
    }
    const double mean = std::accumulate(ts.begin(), ts.end(), 0.0) / static_cast<double>(ts.size());
    double var = 0.0;
    for (double t : ts) var += (t - mean) * (t - mean);
    e.turbidity_sigma = std::sqrt(var / static_cast<double>(ts.size() - 1));
  }
  return e;
}

TurbidityEstimate estimate_turbidity(const io::ImageF& image, const SkyCamera& camera,
                                     const SkyMask& mask, const SunPosition& sun,
                                     const EstimateSettings& settings) {
  const auto samples = sample_sky(image, camera, mask, settings.samples, settings.seed);
  return estimate_turbidity(samples, sun, settings);
}

PhotoSamples sample_photo(const io::ImageF& image, const SkyCamera& camera,
                          const std::optional<SunPosition>& sun, const MaskSettings& mask_settings,
                          const EstimateSettings& settings, const io::ImageF* user_mask) {
  PhotoSamples out;
  out.sun_detected = !sun;
  out.sun = sun ? *sun : detect_sun(image, camera).sun;
  if (!(out.sun.zenith < kPi / 2))
    throw InvalidArgument(
        fmt::format("the sun is at zenith angle {} deg: the fit needs it above the horizon",
                    rad_to_deg(out.sun.zenith)));
  out.mask = sky_mask(image, camera, mask_settings, out.sun, user_mask);
  out.sky_pixels = out.mask.count;
  out.samples = sample_sky(image, camera, out.mask, settings.samples, settings.seed);
  return out;
}

io::ImageF model_luminance_image(const SkyCamera& camera,
                                 const std::function<double(Vec3)>& luminance) {
  io::ImageF out(camera.width, camera.height, 1);
  for (int row = 0; row < camera.height; ++row)
    for (int col = 0; col < camera.width; ++col)
      if (const auto d = camera.pixel_direction(col, row); d && d->z > 0.0)
        out.pixel(col, row)[0] = static_cast<float>(luminance(*d));
  return out;
}

io::ImageF photo_luminance_image(const io::ImageF& image) {
  io::ImageF out(image.width, image.height, 1);
  for (int row = 0; row < image.height; ++row)
    for (int col = 0; col < image.width; ++col)
      out.pixel(col, row)[0] = static_cast<float>(pixel_luminance(image, col, row));
  return out;
}

PhotoEstimate estimate_from_photo(const io::ImageF& image, const SkyCamera& camera,
                                  const std::optional<SunPosition>& sun,
                                  const MaskSettings& mask_settings,
                                  const EstimateSettings& settings, const io::ImageF* user_mask) {
  const PhotoSamples ps = sample_photo(image, camera, sun, mask_settings, settings, user_mask);
  return {estimate_turbidity(ps.samples, ps.sun, settings), ps.sky_pixels, ps.sun_detected};
}

}  // namespace skylight::estimate
