// SSIM (Wang et al. 2004) and the HSV histogram correlation (Morales et al. 2017 eq. 27).
#include "skylight/haze/metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "skylight/core/error.h"

namespace skylight::haze {
namespace {

void check_same(const io::ImageF& a, const io::ImageF& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw InvalidArgument(fmt::format("images differ: {}x{}x{} and {}x{}x{}", a.width, a.height,
                                      a.channels, b.width, b.height, b.channels));
}

// One channel as doubles.
std::vector<double> plane(const io::ImageF& im, int c) {
  std::vector<double> p(static_cast<std::size_t>(im.width) * static_cast<std::size_t>(im.height));
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = im.data[i * static_cast<std::size_t>(im.channels) + static_cast<std::size_t>(c)];
  return p;
}

// Separable 'valid' filtering: out is (w - n + 1) x (h - n + 1).
std::vector<double> filter_valid(const std::vector<double>& in, int w, int h,
                                 const std::vector<double>& k) {
  const int n = static_cast<int>(k.size());
  const int ow = w - n + 1, oh = h - n + 1;
  std::vector<double> rows(static_cast<std::size_t>(ow) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int i = 0; i < n; ++i) s += k[i] * in[static_cast<std::size_t>(y) * w + x + i];
      rows[static_cast<std::size_t>(y) * ow + x] = s;
    }
  std::vector<double> out(static_cast<std::size_t>(ow) * static_cast<std::size_t>(oh));
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int i = 0; i < n; ++i) s += k[i] * rows[static_cast<std::size_t>(y + i) * ow + x];
      out[static_cast<std::size_t>(y) * ow + x] = s;
    }
  return out;
}

// H [deg], S, V of a clamped RGB triple (the hexcone model).
std::array<double, 3> to_hsv(double r, double g, double b) {
  r = std::clamp(r, 0.0, 1.0);
  g = std::clamp(g, 0.0, 1.0);
  b = std::clamp(b, 0.0, 1.0);
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b}), d = mx - mn;
  double h = 0.0;
  if (d > 0.0) {
    if (mx == r)
      h = 60.0 * std::fmod((g - b) / d + 6.0, 6.0);
    else if (mx == g)
      h = 60.0 * ((b - r) / d + 2.0);
    else
      h = 60.0 * ((r - g) / d + 4.0);
  }
  return {h, mx > 0.0 ? d / mx : 0.0, mx};
}

double correlation(const std::vector<double>& h1, const std::vector<double>& h2) {
  const double n = static_cast<double>(h1.size());
  double m1 = 0.0, m2 = 0.0;
  for (std::size_t i = 0; i < h1.size(); ++i) {
    m1 += h1[i] / n;
    m2 += h2[i] / n;
  }
  double num = 0.0, s1 = 0.0, s2 = 0.0;
  for (std::size_t i = 0; i < h1.size(); ++i) {
    num += (h1[i] - m1) * (h2[i] - m2);
    s1 += (h1[i] - m1) * (h1[i] - m1);
    s2 += (h2[i] - m2) * (h2[i] - m2);
  }
  if (s1 == 0.0 || s2 == 0.0) return h1 == h2 ? 1.0 : 0.0;
  return num / std::sqrt(s1 * s2);
}

}  // namespace

double ssim(const io::ImageF& a, const io::ImageF& b, const SsimSettings& s) {
  check_same(a, b);
  if (s.window < 1 || s.window % 2 == 0 || a.width < s.window || a.height < s.window)
    throw InvalidArgument(fmt::format("SSIM needs images of at least {}x{} pixels (got {}x{})",
                                      s.window, s.window, a.width, a.height));
  std::vector<double> k(static_cast<std::size_t>(s.window));
  double sum = 0.0;
  for (int i = 0; i < s.window; ++i) {
    const double x = i - (s.window - 1) / 2;
    k[static_cast<std::size_t>(i)] = std::exp(-x * x / (2.0 * s.sigma * s.sigma));
    sum += k[static_cast<std::size_t>(i)];
  }
  for (double& v : k) v /= sum;  // the separable 2D window then sums to 1
  const double c1 = (s.k1 * s.dynamic_range) * (s.k1 * s.dynamic_range);
  const double c2 = (s.k2 * s.dynamic_range) * (s.k2 * s.dynamic_range);
  double total = 0.0;
  for (int c = 0; c < a.channels; ++c) {
    const std::vector<double> x = plane(a, c), y = plane(b, c);
    std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      xx[i] = x[i] * x[i];
      yy[i] = y[i] * y[i];
      xy[i] = x[i] * y[i];
    }
    const auto mx = filter_valid(x, a.width, a.height, k),
               my = filter_valid(y, a.width, a.height, k);
    const auto sxx = filter_valid(xx, a.width, a.height, k);
    const auto syy = filter_valid(yy, a.width, a.height, k);
    const auto sxy = filter_valid(xy, a.width, a.height, k);
    double mean = 0.0;
    for (std::size_t i = 0; i < mx.size(); ++i) {
      const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i];
      const double cov = sxy[i] - mx[i] * my[i];
      mean += (2.0 * mx[i] * my[i] + c1) * (2.0 * cov + c2) /
              ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
    }
    total += mean / static_cast<double>(mx.size());
  }
  return total / a.channels;
}

double hsv_histogram_correlation(const io::ImageF& a, const io::ImageF& b,
                                 const HsvHistogramSettings& s) {
  check_same(a, b);
  if (a.channels != 3) throw InvalidArgument("the HSV histogram correlation needs RGB images");
  if (s.hue_bins < 1 || s.saturation_bins < 1 || s.value_bins < 1)
    throw InvalidArgument("histogram bins must be >= 1");
  const std::array<int, 3> bins{s.hue_bins, s.saturation_bins, s.value_bins};
  const std::array<double, 3> range{360.0, 1.0, 1.0};
  const auto histograms = [&](const io::ImageF& im) {
    std::array<std::vector<double>, 3> h;
    for (std::size_t c = 0; c < 3; ++c) h[c].assign(static_cast<std::size_t>(bins[c]), 0.0);
    for (std::size_t p = 0; p < im.data.size() / 3; ++p) {
      const auto hsv = to_hsv(im.data[3 * p], im.data[3 * p + 1], im.data[3 * p + 2]);
      for (std::size_t c = 0; c < 3; ++c) {
        const int bin = std::min(bins[c] - 1, static_cast<int>(hsv[c] / range[c] * bins[c]));
        h[c][static_cast<std::size_t>(bin)] += 1.0;
      }
    }
    return h;
  };
  const auto h1 = histograms(a), h2 = histograms(b);
  double sum = 0.0;
  for (std::size_t c = 0; c < 3; ++c) sum += correlation(h1[c], h2[c]);
  return sum / 3.0;
}

}  // namespace skylight::haze
