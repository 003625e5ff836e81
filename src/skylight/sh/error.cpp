#include "skylight/sh/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "skylight/analysis/hemisphere.h"
#include "skylight/core/error.h"
#include "skylight/sh/basis.h"

namespace skylight::sh {

ErrorMeasures error_measures(const Coefficients& reference, const Coefficients& reconstructed,
                             int bands, const Triple& l_min) {
  check_bands(bands);
  SKYLIGHT_CHECK(reference.bands >= bands && reconstructed.bands >= bands,
                 "error_measures: fewer bands than asked for");
  ErrorMeasures e;
  for (int ch = 0; ch < 3; ++ch) {
    SKYLIGHT_CHECK(l_min[ch] > 0.0, "error_measures: L_min must be positive");
    double sum_abs = 0.0, sum_sq = 0.0;
    for (int i = 0; i < coefficient_count(bands); ++i) {
      const double d = reconstructed.c[static_cast<std::size_t>(i)][ch] -
                       reference.c[static_cast<std::size_t>(i)][ch];
      sum_abs += std::abs(d);
      sum_sq += d * d;
    }
    e.e_max[ch] = sum_abs / l_min[ch];
    e.e_mean[ch] = std::sqrt(sum_sq) / l_min[ch];
  }
  return e;
}

Triple minimum_over_sky(const SkyModel& model, Channels channels, int n_theta) {
  SKYLIGHT_CHECK(n_theta >= 1, "minimum_over_sky: n_theta >= 1");
  const auto grid = analysis::hemisphere_grid(n_theta, 4 * n_theta);
  Triple lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
            std::numeric_limits<double>::infinity()};
  for (const Vec3& d : grid.directions) {
    const Triple v = model_value(model, channels, d);
    for (int ch = 0; ch < 3; ++ch) lo[ch] = std::min(lo[ch], v[ch]);
  }
  for (int ch = 0; ch < 3; ++ch) {
    if (!(lo[ch] > 0.0)) {
      throw InvalidArgument("model '" + std::string(model.name()) + "': channel " +
                            std::to_string(ch) + " has minimum " + std::to_string(lo[ch]) +
                            " over the sky; the relative SH errors need L_min > 0");
    }
  }
  return lo;
}

}  // namespace skylight::sh
