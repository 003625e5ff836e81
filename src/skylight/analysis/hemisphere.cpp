#include "skylight/analysis/hemisphere.h"

#include <fmt/format.h>

#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"

namespace skylight::analysis {

HemisphereGrid hemisphere_grid(int n_theta, int n_phi) {
  if (n_theta < 1 || n_phi < 1 || n_theta > 100000 || n_phi > 100000)
    throw InvalidArgument(
        fmt::format("hemisphere grid {} x {} must be 1-100000 in each direction", n_theta, n_phi));
  HemisphereGrid g;
  const double dt = (kPi / 2) / n_theta, dp = 2 * kPi / n_phi;
  for (int i = 0; i < n_theta; ++i) {
    const double t0 = i * dt, t1 = (i + 1) * dt, tm = (i + 0.5) * dt;
    const double omega = (std::cos(t0) - std::cos(t1)) * dp;
    for (int j = 0; j < n_phi; ++j) {
      g.directions.push_back(direction_from_angles(tm, (j + 0.5) * dp));
      g.solid_angle.push_back(omega);
    }
  }
  return g;
}

std::vector<double> sky_luminance(const SkyModel& model, const std::vector<Vec3>& directions) {
  std::vector<double> out(directions.size());
  parallel_for(directions.size(), 256, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) out[i] = model.tristimulus(directions[i]).Y;
  });
  return out;
}

}  // namespace skylight::analysis
