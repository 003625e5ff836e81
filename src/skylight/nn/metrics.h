// Error measures of a neural sky model against its source on a Dataset (validation set).
//
// Definitions (L = normalised source radiance rgb / target_scale, L_net = the network's; per
// example i and channel c in {r, g, b}):
//  * rmse: the paper's normalised RMSE (Satilmis et al. 2016 §IV-A, Table 1), pooled:
//      sqrt( mean_{i,c} ( L_s^-1(L_net) - L_s^-1(max(L, 0)) )^2 ),  L_s^-1(L) = 1 / (1 + 2L).
//    For a satilmis-encoded network L_s^-1(L_net) is exactly its output Psi in [0, 1], so this is
//    the RMSE of the network's outputs against its targets; for other encodings the network's
//    radiance is mapped the same way, which keeps the numbers comparable.
//  * relative error per example and channel: |L_net - L| / L, over the examples with
//    L >= kRelativeErrorFloor (the others are counted in relative_excluded); median, 95th
//    percentile (nearest rank), mean and max.
//  * irradiance (eq. 11): I = int_hemisphere L(omega) cos theta d omega per sky state and
//    channel, midpoint rule on an n_theta x n_phi grid (theta in [0, pi/2]), for the source and
//    the network on the same grid; reported as means over states and channels of I_ref, I_net,
//    |I_net - I_ref| and |I_net - I_ref| / I_ref, and the max of the latter.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "skylight/nn/dataset.h"
#include "skylight/nn/sky_network.h"

namespace skylight::nn {

// Normalised radiance below which the relative error is not taken (the paper sets' smallest
// value is ~0.03; Preetham's out-of-gamut channels are <= 0).
inline constexpr double kRelativeErrorFloor = 1e-3;

struct ErrorStats {
  double rmse = 0.0;
  std::size_t samples = 0;  // examples x channels
  double relative_median = 0.0;
  double relative_p95 = 0.0;
  double relative_mean = 0.0;
  double relative_max = 0.0;
  std::size_t relative_count = 0;
  std::size_t relative_excluded = 0;
};

struct IrradianceStats {
  double reference_mean = 0.0;
  double network_mean = 0.0;
  double abs_difference_mean = 0.0;
  double rel_difference_mean = 0.0;
  double rel_difference_max = 0.0;
  // Per state: I_ref and I_net (r, g, b), normalised units.
  std::vector<std::array<double, 3>> reference, network;
};

// Over all examples of ds (network evaluated in double precision, parallel).
ErrorStats evaluate_errors(const SkyNetwork& sky, const Dataset& ds);
// Eq. 11 per state of ds.
// source: the sky the dataset was built from (build_dataset).
IrradianceStats evaluate_irradiance(const SkyNetwork& sky, const Dataset& ds,
                                    const SkySource& source, int n_theta = 32, int n_phi = 64);

}  // namespace skylight::nn
