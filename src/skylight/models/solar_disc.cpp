#include "skylight/models/solar_disc.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "skylight/core/math.h"
#include "skylight/models/hosek_wilkie.h"

namespace skylight {

double solar_disc_factor(double gamma, double nm) {
  if (!(gamma >= 0.0) || gamma > kSolarAngularRadius) return 0.0;
  // Hosek & Wilkie's table covers 320-720 nm: the nearest end outside it.
  const std::array<double, 6> ld = hw_limb_darkening(std::clamp(nm, 320.0, 720.0));
  const double s = std::sin(gamma) / std::sin(kSolarAngularRadius);
  const double mu = safe_sqrt(1.0 - s * s);
  double d = 0.0, norm = 0.0, mu_k = 1.0;
  for (std::size_t k = 0; k < ld.size(); ++k) {
    d += ld[k] * mu_k;
    norm += ld[k] * 2.0 / static_cast<double>(k + 2);
    mu_k *= mu;
  }
  return std::max(0.0, d) / (kPi * kSolarAngularRadius * kSolarAngularRadius * norm);
}

}  // namespace skylight
