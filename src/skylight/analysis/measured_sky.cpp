// The sun of a measured capture (measured_sky.h).
#include "skylight/analysis/measured_sky.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "skylight/core/math.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"

namespace skylight::analysis {
namespace {

// A ring of samples at one elevation: azimuths ascending [rad] and log luminances.
struct Ring {
  std::vector<double> azimuth, log_luminance;
  // Periodic linear interpolation at `phi`.
  double at(double phi) const {
    phi = wrap_azimuth(phi);
    const std::size_t n = azimuth.size();
    const auto it = std::upper_bound(azimuth.begin(), azimuth.end(), phi);
    const std::size_t hi = static_cast<std::size_t>(it - azimuth.begin()) % n;
    const std::size_t lo = (hi + n - 1) % n;
    double span = azimuth[hi] - azimuth[lo], offset = phi - azimuth[lo];
    if (span <= 0.0) span += 2 * kPi;
    if (offset < 0.0) offset += 2 * kPi;
    const double t = offset / span;
    return (1.0 - t) * log_luminance[lo] + t * log_luminance[hi];
  }
};

constexpr std::size_t kMinRingSamples = 8;

std::vector<Ring> rings_of(const io::KiderCapture& c) {
  std::map<double, std::vector<std::pair<double, double>>> by_elevation;
  for (const auto& s : c.samples)
    if (s.luminance > 0.0)
      by_elevation[s.elevation_deg].push_back({s.azimuth, std::log(s.luminance)});
  std::vector<Ring> rings;
  for (auto& [elevation, samples] : by_elevation) {
    if (samples.size() < kMinRingSamples) continue;
    std::sort(samples.begin(), samples.end());
    Ring r;
    for (const auto& [a, l] : samples) {
      r.azimuth.push_back(a);
      r.log_luminance.push_back(l);
    }
    rings.push_back(std::move(r));
  }
  return rings;
}

}  // namespace

double symmetry_axis_azimuth(const io::KiderCapture& capture, double initial_azimuth) {
  const std::vector<Ring> rings = rings_of(capture);
  double best = initial_azimuth, best_error = -1.0;
  const int steps = static_cast<int>(std::lround(kSymmetrySearchDeg / kSymmetryStepDeg));
  for (int k = -steps; k <= steps; ++k) {
    const double axis = initial_azimuth + deg_to_rad(k * kSymmetryStepDeg);
    double error = 0.0;
    for (const Ring& r : rings)
      for (std::size_t i = 0; i < r.azimuth.size(); ++i)
        error += std::abs(r.log_luminance[i] - r.at(2.0 * axis - r.azimuth[i]));
    if (best_error < 0.0 || error < best_error) {
      best_error = error;
      best = axis;
    }
  }
  return wrap_azimuth(best);
}

CaptureSun capture_sun(const io::KiderCapture& capture, const KiderSite& site,
                       bool azimuth_from_symmetry) {
  sun::SpaInput in;
  in.time = sun::parse_iso8601(capture.local_time + site.utc_offset);
  in.latitude = deg_to_rad(site.latitude_deg);
  in.longitude = deg_to_rad(site.longitude_deg);
  in.elevation = site.elevation_m;
  sun::validate(in);
  const sun::SpaResult spa = sun::solar_position(in);
  CaptureSun out;
  out.spa_zenith = spa.zenith;
  out.spa_azimuth = spa.azimuth;
  out.sun = {spa.zenith, spa.azimuth};
  if (azimuth_from_symmetry) {
    out.symmetry_azimuth = symmetry_axis_azimuth(capture, spa.azimuth);
    out.sun.azimuth = *out.symmetry_azimuth;
  }
  return out;
}

}  // namespace skylight::analysis
