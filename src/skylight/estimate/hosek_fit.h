// Turbidity and ground albedo of the Hosek-Wilkie sky (Hosek & Wilkie 2012) fitted to a photo's
// luminance samples, with a free luminance scale (docs/ESTIMATE.md): the same residuals as the
// Preetham fit (turbidity.h), r_i = ln Y_i - ln s - ln Y_HW(v_i; T, albedo).
#pragma once

#include <span>
#include <string>

#include "skylight/core/frame.h"
#include "skylight/estimate/turbidity.h"

namespace skylight::estimate {

struct HosekFit {
  double turbidity = 0.0;        // [1, 10] (the dataset's knots)
  double albedo = 0.0;           // [0, 1]
  double turbidity_sigma = 0.0;  // bootstrap over the inliers, as TurbidityEstimate
  double albedo_sigma = 0.0;
  double log_scale = 0.0;  // ln s: the photo's Y over the model's Y [cd/m^2]
  double residual = 0.0;   // RMS of r_i over the inliers
  int samples = 0, inliers = 0;
  double inlier_fraction = 1.0;
};

// 1. ln Y_HW on a grid of (T, albedo) (T = 1, 1.5, ..., 10; albedo 0, 0.5, 1) for every sample;
// 2. RANSAC (when settings.ransac): minimal sets of settings.ransac_minimal_set samples fitted on
//    that grid (ln s in closed form), the consensus |r_i| < settings.inlier_threshold;
// 3. Levenberg-Marquardt (Eigen) on (T, albedo, ln s) over the inliers from the best grid point,
//    central differences in T and albedo, the box [1, 10] x [0, 1] enforced by clamping;
// 4. settings.bootstrap resamples of the inliers refitted by LM for the sigmas.
HosekFit fit_hosek(std::span<const LuminanceSample> samples, const SunPosition& sun,
                   const EstimateSettings& settings);

}  // namespace skylight::estimate
