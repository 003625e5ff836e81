// Error measures of a reconstructed set of SH coefficients (Habel, Mustata & Wimmer 2008 §3.2).
#pragma once

#include "skylight/sh/projection.h"

namespace skylight::sh {

// Per channel, over the first N bands (l < N):
//   E_max^u  = (1 / L_min) sum_lm |c^rec_lm - c_lm|          (eq. 2)
//   E_mean^u = (1 / L_min) sqrt(sum_lm (c^rec_lm - c_lm)^2)   (eq. 3)
// as fractions (0.01 = 1 %). L_min > 0 per channel: the minimum of the original model over the
// upper hemisphere (minimum_over_sky).
struct ErrorMeasures {
  Triple e_max{};
  Triple e_mean{};
};
ErrorMeasures error_measures(const Coefficients& reference, const Coefficients& reconstructed,
                             int bands, const Triple& l_min);

// L_min of eq. 2-3: the minimum of the model over the upper hemisphere, per channel, on the
// midpoint grid of analysis::hemisphere_grid(n_theta, 4 n_theta) (cells of (90 / n_theta) deg).
// Throws InvalidArgument if a channel's minimum is not positive (the measures are then undefined).
Triple minimum_over_sky(const SkyModel& model, Channels channels, int n_theta = 90);

}  // namespace skylight::sh
