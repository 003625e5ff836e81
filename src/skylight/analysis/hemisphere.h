// Quadrature over the sky hemisphere: a midpoint grid with exact cell solid angles, and the sky
// luminance of a model on it (scalar double path, all threads).
#pragma once

#include <vector>

#include "skylight/core/frame.h"
#include "skylight/models/sky_model.h"

namespace skylight::analysis {

// Midpoint grid over the upper hemisphere: n_theta rings of equal zenith-angle width, n_phi
// azimuth sectors; each cell's exact solid angle (cos theta0 - cos theta1) dphi [sr].
struct HemisphereGrid {
  std::vector<Vec3> directions;
  std::vector<double> solid_angle;  // [sr], sums to 2 pi
};
HemisphereGrid hemisphere_grid(int n_theta, int n_phi);
// Scalar (double) sky luminance Y [cd/m^2] of `model` at each direction, on all threads.
std::vector<double> sky_luminance(const SkyModel& model, const std::vector<Vec3>& directions);

}  // namespace skylight::analysis
