#include "skylight/sh/irradiance.h"

#include <cmath>

#include "skylight/core/math.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/rotation.h"

namespace skylight::sh {

double clamped_cosine_factor(int l) {
  if (l == 0) return kPi;
  if (l == 1) return 2.0 * kPi / 3.0;
  if (l % 2 == 1) return 0.0;
  // l! / (2^l ((l/2)!)^2) = C(l, l/2) / 2^l, built as a product to stay exact in double.
  double ratio = 1.0;
  for (int k = 1; k <= l / 2; ++k) ratio *= static_cast<double>(l / 2 + k) / (4.0 * k);
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * kPi * sign / ((l + 2.0) * (l - 1.0)) * ratio;
}

Coefficients irradiance_coefficients(const Coefficients& radiance) {
  Coefficients e = radiance;
  for (std::size_t i = 0; i < e.c.size(); ++i) {
    const double a = clamped_cosine_factor(degree_order(static_cast<int>(i)).l);
    for (double& v : e.c[i]) v *= a;
  }
  return e;
}

Triple irradiance(const Coefficients& radiance, Vec3 normal) {
  return reconstruct(irradiance_coefficients(radiance), normal);
}

}  // namespace skylight::sh
