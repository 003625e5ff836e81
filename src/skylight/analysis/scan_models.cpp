// Sky-luminance scans against sky models: the synthetic example scan and the error statistics of a
// model against a scan (scan.h).
#include "skylight/analysis/scan.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>

#include "skylight/core/error.h"
#include "skylight/core/random.h"
#include "skylight/models/cie_sky.h"

namespace skylight::analysis {

std::vector<std::string> synthetic_scan_comments(const SyntheticScanSettings& s) {
  return {
      "Synthetic sky-luminance scan (NOT a measurement), written by",
      "`skylight report --write-synthetic-measurements FILE` (render/measurements.h).",
      fmt::format("CIE S 011 type {} sky with the Kittler-Darula typical zenith luminance at the",
                  s.cie_type),
      fmt::format("145 Tregenza (1987) patch centres, times (1 + {} u), u uniform in [-1, 1)",
                  s.noise),
      fmt::format("from SplitMix64 with seed {}.", s.seed),
  };
}

SkyScan synthetic_tregenza_scan(const SyntheticScanSettings& s) {
  require_in_range("noise", s.noise, 0.0, 0.999);
  SkyParameters p;
  p.values.set("cie-type", s.cie_type);
  p.sun = {kPi / 2 - s.sun_elevation, wrap_azimuth(s.sun_azimuth)};
  const auto sky = make_sky_model(CieSkyModel::kName, p);
  SplitMix64 rng(s.seed);
  SkyScan scan;
  scan.source = "synthetic";
  scan.sun_azimuth = p.sun.azimuth;
  scan.sun_elevation = s.sun_elevation;
  std::size_t line = 0;
  for (const auto& c : tregenza_patch_centres()) {
    const Vec3 v = direction_from_angles(kPi / 2 - c.elevation, c.azimuth);
    const double L = sky->tristimulus(v).Y * (1.0 + s.noise * rng.symmetric());
    scan.samples.push_back({c.azimuth, c.elevation, L, ++line});
  }
  return scan;
}

ScanErrors compare_to_scan(const SkyModel& model, const SkyScan& scan, double sun_exclusion) {
  const Vec3 sun = model.sun().direction();
  std::vector<double> d;
  const LuminanceSample* top = nullptr;
  double top_ratio = 0.0;
  for (const auto& s : scan.samples) {
    const Vec3 v = direction_from_angles(kPi / 2 - s.elevation, s.azimuth);
    if (angle_between(v, sun) < sun_exclusion) continue;
    const double m = model.tristimulus(v).Y;
    if (!(m > 0.0) || !(s.luminance > 0.0)) continue;
    d.push_back(std::log10(m / s.luminance));
    if (top == nullptr || s.elevation > top->elevation) {
      top = &s;
      top_ratio = d.back();
    }
  }
  if (d.empty())
    throw InvalidArgument(
        fmt::format("{}: no sample usable for comparing model '{}'", scan.source, model.name()));
  ScanErrors e;
  e.samples_used = d.size();
  double s1 = 0, s2 = 0, r1 = 0, r2 = 0;
  for (double x : d) {
    s1 += x;
    s2 += x * x;
    const double r = x - top_ratio;  // both normalised at the highest sample
    r1 += r;
    r2 += r * r;
  }
  const double n = static_cast<double>(d.size());
  e.bias_log10_absolute = s1 / n;
  e.rms_log10_absolute = std::sqrt(s2 / n);
  e.bias_log10_relative = r1 / n;
  e.rms_log10_relative = std::sqrt(r2 / n);
  return e;
}

}  // namespace skylight::analysis
