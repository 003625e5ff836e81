// Morales et al. 2017 eq. 11; docs/HAZE.md.
#include "skylight/haze/attenuation.h"

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"

namespace skylight::haze {

SpectralWeights::SpectralWeights(const CameraSensitivity& camera) {
  for (std::size_t c = 0; c < 3; ++c) {
    double total = 0.0;
    for (std::size_t i = 0; i < kGridSamples; ++i) {
      const double trapezoid = (i == 0 || i + 1 == kGridSamples) ? 0.5 * kGridStepNm : kGridStepNm;
      raw_[c][i] = trapezoid * camera.channel[c](nm(i));
      total += raw_[c][i];
    }
    SKYLIGHT_CHECK(total > 0.0, "camera channel without sensitivity in 380 .. 780 nm");
    for (std::size_t i = 0; i < kGridSamples; ++i) w_[c][i] = raw_[c][i] / total;
  }
}

Attenuation::Attenuation(const Atmosphere& atmosphere, const CameraSensitivity& camera)
    : weights_(camera) {
  validate(atmosphere);
  for (std::size_t i = 0; i < kGridSamples; ++i)
    beta_[i] = total_per_m(SpectralWeights::nm(i), atmosphere);
}

Rgb3 Attenuation::gamma(double s_m) const {
  std::array<double, kGridSamples> e{};
  for (std::size_t i = 0; i < kGridSamples; ++i) e[i] = std::exp(-beta_[i] * s_m);
  Rgb3 g{};
  for (std::size_t c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (std::size_t i = 0; i < kGridSamples; ++i) sum += weights_.normalised()[c][i] * e[i];
    g[c] = sum;
  }
  return g;
}

double Attenuation::max_curvature_per_m2() const {
  double worst = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (std::size_t i = 0; i < kGridSamples; ++i)
      sum += weights_.normalised()[c][i] * beta_[i] * beta_[i];
    worst = std::max(worst, sum);
  }
  return worst;
}

AttenuationTable make_attenuation_table(const Attenuation& attenuation, double max_distance_m,
                                        double max_error, double curvature_floor_per_m2) {
  SKYLIGHT_CHECK(max_distance_m >= 0.0 && std::isfinite(max_distance_m), "bad table distance");
  SKYLIGHT_CHECK(max_error > 0.0, "bad table error");
  constexpr std::size_t kMaxEntries = std::size_t{1} << 20;
  const double curvature = attenuation.max_curvature_per_m2();
  const double span = std::max(max_distance_m, 1.0);
  // h^2 / 8 x curvature <= max_error.
  const double grid_curvature = std::max(curvature, curvature_floor_per_m2);
  const double h_max = grid_curvature > 0.0 ? std::sqrt(8.0 * max_error / grid_curvature) : span;
  const auto intervals = static_cast<std::size_t>(
      std::clamp(std::ceil(span / h_max), 1.0, static_cast<double>(kMaxEntries - 1)));
  AttenuationTable t;
  t.step_m = span / static_cast<double>(intervals);
  t.error_bound = t.step_m * t.step_m / 8.0 * curvature;
  t.gamma.resize(3 * (intervals + 1));
  for (std::size_t i = 0; i <= intervals; ++i) {
    const Rgb3 g = attenuation.gamma(static_cast<double>(i) * t.step_m);
    for (std::size_t c = 0; c < 3; ++c) t.gamma[3 * i + c] = static_cast<float>(g[c]);
  }
  return t;
}

}  // namespace skylight::haze
