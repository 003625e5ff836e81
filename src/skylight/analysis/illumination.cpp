#include "skylight/analysis/illumination.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "skylight/core/parallel.h"

namespace skylight::analysis {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

namespace {

// Directions and solid angles of a polar grid over the solar disc, centred on the sun.
struct DiscSamples {
  std::vector<Vec3> directions;
  std::vector<double> solid_angle;
};
DiscSamples disc_samples(const SkyModel& model, int rings, int sectors) {
  DiscSamples d;
  const double r = model.sun_angular_radius();
  const Vec3 s = model.sun().direction();
  // An orthonormal basis (u, w) perpendicular to s.
  const Vec3 helper = std::abs(s.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 u = normalize(cross(helper, s)), w = cross(s, u);
  for (int i = 0; i < rings; ++i) {
    const double r0 = r * i / rings, r1 = r * (i + 1) / rings, rm = 0.5 * (r0 + r1);
    const double omega = (std::cos(r0) - std::cos(r1)) * 2 * kPi / sectors;
    for (int j = 0; j < sectors; ++j) {
      const double a = 2 * kPi * (j + 0.5) / sectors;
      d.directions.push_back(
          normalize(std::cos(rm) * s + std::sin(rm) * (std::cos(a) * u + std::sin(a) * w)));
      d.solid_angle.push_back(omega);
    }
  }
  return d;
}

// Trapezoid weights [nm] over [nm_min, nm_max] with step nm_step.
std::vector<std::array<double, 2>> wavelength_weights(double nm_min, double nm_max, double step) {
  std::vector<std::array<double, 2>> out;
  const int n = std::max(1, static_cast<int>(std::lround((nm_max - nm_min) / step)));
  const double h = (nm_max - nm_min) / n;
  for (int k = 0; k <= n; ++k) out.push_back({nm_min + k * h, (k == 0 || k == n) ? 0.5 * h : h});
  return out;
}

}  // namespace

double diffuse_horizontal_illuminance(const SkyModel& model, int n_theta, int n_phi) {
  const HemisphereGrid g = hemisphere_grid(n_theta, n_phi);
  const std::vector<double> L = sky_luminance(model, g.directions);
  double e = 0.0;
  for (std::size_t i = 0; i < L.size(); ++i) e += L[i] * g.directions[i].z * g.solid_angle[i];
  return e;
}

double direct_horizontal_illuminance(const SkyModel& model, int rings, int sectors) {
  if (!model.has_sun()) return 0.0;
  const DiscSamples d = disc_samples(model, rings, sectors);
  double e = 0.0;
  for (std::size_t i = 0; i < d.directions.size(); ++i)
    e += model.sun_tristimulus(d.directions[i]).Y * std::max(d.directions[i].z, 0.0) *
         d.solid_angle[i];
  return e;
}

HorizontalIllumination horizontal_illumination(const SkyModel& model, const IlluminationSettings& s,
                                               bool spectral) {
  HorizontalIllumination h;
  h.sun_elevation = model.sun().elevation();
  h.has_sun = model.has_sun();
  h.diffuse_lx = diffuse_horizontal_illuminance(model, s.n_theta, s.n_phi);
  h.direct_lx = direct_horizontal_illuminance(model, s.sun_rings, s.sun_sectors);
  if (!spectral) return h;
  const auto nm = wavelength_weights(s.nm_min, s.nm_max, s.nm_step);
  const HemisphereGrid g = hemisphere_grid(s.n_theta_spectral, s.n_phi_spectral);
  // Per direction: the cosine-weighted, wavelength-integrated radiance; NaN flags a wavelength
  // outside the model's range.
  std::vector<double> per_dir(g.directions.size(), 0.0);
  parallel_for(g.directions.size(), 16, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      double sum = 0.0;
      for (const auto& [lambda, w] : nm) {
        const auto L = model.spectral_radiance(g.directions[i], lambda);
        sum += L ? *L * w : kNaN;
      }
      per_dir[i] = sum * g.directions[i].z * g.solid_angle[i];
    }
  });
  const double diffuse = std::accumulate(per_dir.begin(), per_dir.end(), 0.0);
  if (std::isfinite(diffuse)) h.diffuse_w_m2 = diffuse;
  if (h.has_sun) {
    const DiscSamples d = disc_samples(model, s.sun_rings, s.sun_sectors);
    double direct = 0.0;
    for (std::size_t i = 0; i < d.directions.size(); ++i) {
      double sum = 0.0;
      for (const auto& [lambda, w] : nm) {
        const auto L = model.sun_spectral_radiance(d.directions[i], lambda);
        sum += L ? *L * w : kNaN;
      }
      direct += sum * std::max(d.directions[i].z, 0.0) * d.solid_angle[i];
    }
    if (std::isfinite(direct)) h.direct_w_m2 = direct;
  }
  return h;
}
}  // namespace skylight::analysis
