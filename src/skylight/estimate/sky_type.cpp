// The best-fitting CIE standard sky type (CIE S 011/E:2003; docs/ESTIMATE.md).
#include "skylight/estimate/sky_type.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "skylight/core/error.h"
#include "skylight/core/statistics.h"
#include "skylight/models/cie_sky.h"

namespace skylight::estimate {
namespace {

// The standard types of CIE S 011 (type 16, the traditional overcast sky, is not one of them).
constexpr int kStandardTypes = 15;

}  // namespace

std::vector<CieTypeFit> rank_cie_types(std::span<const LuminanceSample> samples,
                                       const SunPosition& sun, double inlier_threshold) {
  if (samples.size() < 2) throw InvalidArgument("the sky-type fit needs at least 2 samples");
  if (!(sun.zenith >= 0.0 && sun.zenith < kPi / 2))
    throw InvalidArgument(fmt::format(
        "the sun is at zenith angle {} deg: the sky-type fit needs it above the horizon",
        rad_to_deg(sun.zenith)));
  const Vec3 s = sun.direction();
  const std::size_t n = samples.size();
  std::vector<CieTypeFit> out;
  std::vector<double> g(n);  // ln Y_i - ln(L/Lz)_i
  for (int type = 1; type <= kStandardTypes; ++type) {
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 v = samples[i].view;
      const double rel = cie_relative_luminance(type, std::acos(clamp_cosine(v.z)),
                                                angle_between(v, s), sun.zenith);
      g[i] = rel > 0.0 ? std::log(samples[i].luminance) - std::log(rel)
                       : std::numeric_limits<double>::infinity();
    }
    CieTypeFit f;
    f.type = type;
    f.log_scale = median(g);
    for (int pass = 0; pass < 2; ++pass) {
      double sum = 0.0;
      int count = 0;
      for (double x : g)
        if (std::abs(x - f.log_scale) < inlier_threshold) {
          sum += x;
          ++count;
        }
      if (count == 0) break;
      f.log_scale = sum / count;
    }
    double ss = 0.0;
    f.inliers = 0;
    for (double x : g)
      if (std::abs(x - f.log_scale) < inlier_threshold) {
        ss += (x - f.log_scale) * (x - f.log_scale);
        ++f.inliers;
      }
    f.residual = f.inliers > 0 ? std::sqrt(ss / f.inliers) : 0.0;
    f.inlier_fraction = static_cast<double>(f.inliers) / static_cast<double>(n);
    out.push_back(f);
  }
  std::stable_sort(out.begin(), out.end(), [](const CieTypeFit& a, const CieTypeFit& b) {
    return a.inliers != b.inliers ? a.inliers > b.inliers : a.residual < b.residual;
  });
  return out;
}

}  // namespace skylight::estimate
