// A closed-form sky for the tests of skylight::nn (which knows no sky model): smooth in the view,
// the sun and the turbidity, brightest towards the sun, like the analytic models it stands for.
#pragma once

#include <cmath>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/nn/dataset.h"

namespace skylight::testing_support {

// rgb(v) = scale * (0.3 + 0.1 t) * (0.5 + v_z) * (1 + 2 exp(-3 d)) * (1, 0.9, 0.8),
// d = |omega_sun - omega_view| (Satilmis et al. 2016's chord input); 0 below the horizon.
inline Rgb analytic_sky(const nn::SkyState& s, Vec3 v, double scale) {
  if (v.z < 0.0) return {};
  const Vec3 sun = direction_from_angles(s.sun_zenith, s.sun_azimuth);
  const double d = length(sun - v);
  const double L =
      scale * (0.3 + 0.1 * s.turbidity) * (0.5 + v.z) * (1.0 + 2.0 * std::exp(-3.0 * d));
  return {L, 0.9 * L, 0.8 * L};
}

inline nn::SkySource analytic_sky_source(double scale) {
  return [scale](const nn::SkyState& s) -> nn::SkyFunction {
    return [s, scale](Vec3 v) { return analytic_sky(s, v, scale); };
  };
}

}  // namespace skylight::testing_support
