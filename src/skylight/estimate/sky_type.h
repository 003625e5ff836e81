// The CIE standard sky type that best fits a photo's luminance samples (CIE S 011/E:2003,
// ISO 15469:2004; docs/ESTIMATE.md): each of the 15 types' relative luminance distribution against
// the samples, with a free luminance scale and robust to clouds.
#pragma once

#include <span>
#include <vector>

#include "skylight/core/frame.h"
#include "skylight/estimate/turbidity.h"

namespace skylight::estimate {

struct CieTypeFit {
  int type = 0;            // 1..15
  double log_scale = 0.0;  // ln of the photo's Y over L/Lz of the type
  double residual = 0.0;   // RMS of ln-luminance residuals over the inliers
  int inliers = 0;
  double inlier_fraction = 0.0;
};

// For each type: r_i = ln Y_i - ln s - ln(L/Lz)_i (CIE S 011 eq. 1); ln s starts as the median of
// ln Y_i - ln(L/Lz)_i (clouds on less than half the samples do not move it), the inliers are the
// samples with |r_i| < inlier_threshold, ln s is refitted as their mean (and the inliers found
// again once). The ranking is by inlier count, then by residual; best first.
std::vector<CieTypeFit> rank_cie_types(std::span<const LuminanceSample> samples,
                                       const SunPosition& sun, double inlier_threshold);

}  // namespace skylight::estimate
