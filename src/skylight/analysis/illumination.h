// Horizontal illuminance and irradiance of a sky model: diffuse (sky hemisphere) and direct
// (solar disc), photometric and spectral.
#pragma once

#include <optional>

#include "skylight/analysis/hemisphere.h"
#include "skylight/models/sky_model.h"

namespace skylight::analysis {

struct IlluminationSettings {
  int n_theta = 90, n_phi = 180;                          // sky hemisphere grid (luminance)
  int n_theta_spectral = 24, n_phi_spectral = 48;         // coarser grid for spectral irradiance
  int sun_rings = 8, sun_sectors = 16;                    // polar grid over the solar disc
  double nm_min = 380.0, nm_max = 720.0, nm_step = 10.0;  // spectral range [nm], trapezoid rule
};
// Horizontal illuminance [lx] and irradiance [W/m^2] of one model:
//  * diffuse = the sky's luminance (radiance) integrated over the upper hemisphere with weight
//    cos theta (midpoint rule on hemisphere_grid);
//  * direct = the solar disc's luminance (radiance) integrated over the disc with weight
//    max(cos theta, 0) (polar grid), for models with a sun; 0 otherwise;
//  * irradiance: spectral radiance integrated over [nm_min, nm_max] as well; nullopt for models
//    without spectral output (and direct nullopt without a sun).
struct HorizontalIllumination {
  double sun_elevation = 0.0;  // [rad]
  double diffuse_lx = 0.0, direct_lx = 0.0;
  bool has_sun = false;
  std::optional<double> diffuse_w_m2, direct_w_m2;
  double global_lx() const { return diffuse_lx + direct_lx; }
};
double diffuse_horizontal_illuminance(const SkyModel& model, int n_theta, int n_phi);
double direct_horizontal_illuminance(const SkyModel& model, int rings, int sectors);
HorizontalIllumination horizontal_illumination(const SkyModel& model,
                                               const IlluminationSettings& settings, bool spectral);
}  // namespace skylight::analysis
