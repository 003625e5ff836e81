#include "skylight/sh/approximation_error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

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

}  // namespace skylight::sh
