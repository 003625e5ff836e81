// Error measures of a reconstructed set of SH coefficients (Habel, Mustata & Wimmer 2008 §3.2).
#pragma once

#include "skylight/sh/projection.h"

namespace skylight::sh {

// Per channel, over the first N bands (l < N):
//   E_max^u  = (1 / L_min) sum_lm |c^rec_lm - c_lm|          (eq. 2)
//   E_mean^u = (1 / L_min) sqrt(sum_lm (c^rec_lm - c_lm)^2)   (eq. 3)
// as fractions (0.01 = 1 %). L_min > 0 per channel: the minimum of the original model over the
// upper hemisphere (fit::minimum_over_sky in fit/sh_fit.h).
struct ErrorMeasures {
  Triple e_max{};
  Triple e_mean{};
};
ErrorMeasures error_measures(const Coefficients& reference, const Coefficients& reconstructed,
                             int bands, const Triple& l_min);

}  // namespace skylight::sh
