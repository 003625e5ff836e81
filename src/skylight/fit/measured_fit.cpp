// Sky models against measured skies (measured_fit.h).
#include "skylight/fit/measured_fit.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/colorimetry.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/models/sky_model.h"
#include "skylight/sun/time.h"

namespace skylight::fit {
namespace {

// The measured value at `nm`, linear between the capture's wavelengths (nullopt outside them).
std::optional<double> measured_at(const std::vector<double>& grid, const std::vector<double>& v,
                                  double nm) {
  if (grid.empty() || nm < grid.front() || nm > grid.back()) return std::nullopt;
  const auto it = std::lower_bound(grid.begin(), grid.end(), nm);
  const std::size_t hi = static_cast<std::size_t>(it - grid.begin());
  if (grid[hi] == nm) return v[hi];
  const std::size_t lo = hi - 1;
  const double t = (nm - grid[lo]) / (grid[hi] - grid[lo]);
  return (1.0 - t) * v[lo] + t * v[hi];
}

// CIE 1976 u', v'.
std::array<double, 2> uv_prime(const Xyz& c) {
  const double d = c.X + 15.0 * c.Y + 3.0 * c.Z;
  if (!(d > 0.0)) return {0.0, 0.0};
  return {4.0 * c.X / d, 9.0 * c.Y / d};
}

// Spectral and colour errors of the fitted model over the used samples.
void colour_errors(const io::KiderCapture& c, const SkyModel& model, MeasuredCaptureResult& r) {
  double diff2 = 0.0, ref2 = 0.0, duv = 0.0;
  bool spectral = false;
  for (std::size_t k = 0; k < c.samples.size(); ++k) {
    if (!r.samples[k].used) continue;
    const io::KiderSample& s = c.samples[k];
    const Vec3 v = direction_from_angles(s.zenith, s.azimuth);
    const auto m = uv_prime(measured_sample_xyz(c, s)), p = uv_prime(model.tristimulus(v));
    duv += std::hypot(m[0] - p[0], m[1] - p[1]);
    for (double nm = kSpectralFirstNm; nm <= kSpectralLastNm + 1e-9; nm += kSpectralStepNm) {
      const auto mv = measured_at(c.wavelengths_nm, s.radiance, nm);
      const auto pv = model.spectral_radiance(v, nm);
      if (!mv || !pv) continue;
      spectral = true;
      diff2 += (r.scale * *pv - *mv) * (r.scale * *pv - *mv);
      ref2 += *mv * *mv;
    }
  }
  r.mean_delta_uv = duv / r.samples_used;
  if (spectral && ref2 > 0.0) r.spectral_rms = std::sqrt(diff2 / ref2);
}

}  // namespace

const ParameterSchema<MeasuredSettings>& MeasuredSettings::schema() {
  static const ParameterSchema<MeasuredSettings> s = [] {
    using S = MeasuredSettings;
    const S d;
    ParameterSchema<S> s;
    std::string models;
    for (const std::string& m : measured_models()) models += (models.empty() ? "" : "|") + m;
    s.text(&S::model, {.name = "model",
                       .unit = "",
                       .default_value = Required{},
                       .description = fmt::format("the model fitted to each capture: {} (its "
                                                  "estimation policy's parameters, `skylight "
                                                  "estimate`)",
                                                  models),
                       .choices = measured_models()})
        .number(&S::exclude_sun_deg,
                {.name = "exclude-sun-deg",
                 .unit = "deg",
                 .min = 0.0,
                 .max = 90.0,
                 .default_value = ParameterValue(d.exclude_sun_deg),
                 .description = "samples within this angle of the sun are not used"})
        .choice(&S::sun_azimuth,
                {.name = "sun-azimuth-from",
                 .unit = "",
                 .default_value = ParameterValue(std::string("symmetry")),
                 .description = "the sun's azimuth: the SPA's at the capture's time (spa), or the "
                                "measured sky's axis of symmetry within 30 deg of it (symmetry; "
                                "the scans' azimuths drift from the SPA's by 6-17 deg)"},
                {{"spa", SunAzimuthSource::spa}, {"symmetry", SunAzimuthSource::symmetry}})
        .number(&S::site_lat_deg,
                {.name = "site-lat",
                 .unit = "deg",
                 .min = -90.0,
                 .max = 90.0,
                 .default_value = ParameterValue(d.site_lat_deg),
                 .description = "the captures' latitude, north positive (Kider et al.'s roof)"})
        .number(&S::site_lon_deg,
                {.name = "site-lon",
                 .unit = "deg",
                 .min = -180.0,
                 .max = 180.0,
                 .default_value = ParameterValue(d.site_lon_deg),
                 .description = "the captures' longitude, east positive (Kider et al.'s roof)"})
        .text(
            &S::utc_offset,
            {.name = "utc-offset",
             .unit = "",
             .default_value = ParameterValue(d.utc_offset),
             .description = "the captures' local time minus UTC, +hh:mm or -hh:mm (EDT: -04:00)"});
    return s;
  }();
  return s;
}

Xyz measured_sample_xyz(const io::KiderCapture& c, const io::KiderSample& s) {
  std::vector<double> nm, v;
  for (std::size_t i = 0; i < c.wavelengths_nm.size(); ++i)
    if (c.wavelengths_nm[i] >= kSpectralFirstNm && c.wavelengths_nm[i] <= kSpectralLastNm) {
      nm.push_back(c.wavelengths_nm[i]);
      v.push_back(s.radiance[i]);
    }
  return spectral_radiance_to_xyz(nm, v);
}

std::unique_ptr<SkyModel> fitted_model(const LuminanceFit& fit, const SunPosition& sun) {
  SkyParameters p;
  p.sun = sun;
  for (const FittedParameter& q : fit.parameters) p.values.set(q.name, q.value);
  return make_sky_model(fit.model, p);
}

std::vector<std::string> measured_models() {
  return estimated_models();
}

analysis::KiderSite MeasuredSettings::site() const {
  analysis::KiderSite s;
  s.latitude_deg = site_lat_deg;
  s.longitude_deg = site_lon_deg;
  s.utc_offset = utc_offset;
  // The offset is checked by the ISO 8601 parser, on a time of the right form.
  try {
    (void)sun::parse_iso8601("2000-01-01T12:00:00" + utc_offset);
  } catch (const InvalidArgument&) {
    throw InvalidArgument(fmt::format("{} '{}' is not a UTC offset +hh:mm or -hh:mm",
                                      spelled("utc-offset"), excerpt(utc_offset)));
  }
  return s;
}

MeasuredCaptureResult compare_capture(const io::KiderCapture& c, const analysis::CaptureSun& sun,
                                      const MeasuredSettings& settings) {
  MeasuredCaptureResult r;
  r.name = c.name;
  r.local_time = c.local_time;
  r.sun = sun;
  r.global_horizontal_measured_w_m2 = c.global_horizontal_w_m2();
  const Vec3 sun_dir = sun.sun.direction();
  std::vector<LuminanceSample> used;
  for (const io::KiderSample& s : c.samples) {
    MeasuredSampleResult m;
    m.index = s.index;
    m.zenith_deg = rad_to_deg(s.zenith);
    m.azimuth_deg = rad_to_deg(s.azimuth);
    m.measured_luminance = s.luminance;
    const Vec3 v = direction_from_angles(s.zenith, s.azimuth);
    m.used = angle_between(v, sun_dir) >= deg_to_rad(settings.exclude_sun_deg) && s.luminance > 0.0;
    if (m.used) used.push_back({v, s.luminance});
    r.samples.push_back(m);
  }
  const EstimationPolicy& policy = estimation_policy(settings.model);
  if (used.size() < policy.axes.size() + 2)
    throw InvalidArgument(
        fmt::format("capture {}: {} samples outside {} deg of the sun, too few to fit '{}'", c.name,
                    used.size(), settings.exclude_sun_deg, settings.model));
  EstimateSettings es;
  es.ransac = false;  // clear skies: every sample counts
  r.fit = fit_luminance(settings.model, used, sun.sun, es);
  r.samples_used = static_cast<int>(used.size());
  // The fitted model's own (absolute) luminance in every direction: a policy's luminance may be
  // relative (its scale is free), so the scale is found again here, by the fit's measure: the
  // factor s minimising sum (ln m - ln s M)^2, s = exp(mean ln(m / M)).
  const auto model = fitted_model(r.fit, sun.sun);
  double log_ratio = 0.0;
  for (std::size_t i = 0; i < c.samples.size(); ++i) {
    const io::KiderSample& s = c.samples[i];
    MeasuredSampleResult& m = r.samples[i];
    m.model_luminance = model->tristimulus(direction_from_angles(s.zenith, s.azimuth)).Y;
    if (!m.used) continue;
    if (!(m.model_luminance > 0.0))
      throw InvalidArgument(
          fmt::format("capture {}: the fitted '{}' gives no light at sample {} (zenith {:.1f} deg)",
                      c.name, settings.model, s.index, m.zenith_deg));
    log_ratio += std::log(m.measured_luminance / m.model_luminance);
  }
  r.scale = std::exp(log_ratio / r.samples_used);
  double shape2 = 0.0, abs2 = 0.0;
  for (const MeasuredSampleResult& m : r.samples) {
    if (!m.used) continue;
    const double ratio = m.model_luminance / m.measured_luminance;
    shape2 += (r.scale * ratio - 1.0) * (r.scale * ratio - 1.0);
    abs2 += (ratio - 1.0) * (ratio - 1.0);
  }
  r.luminance_rms_shape = std::sqrt(shape2 / r.samples_used);
  r.luminance_rms_abs = std::sqrt(abs2 / r.samples_used);
  colour_errors(c, *model, r);
  return r;
}

std::vector<MeasuredCaptureResult> compare_to_measured(
    const std::vector<io::KiderCapture>& captures, const MeasuredSettings& settings,
    const ProgressSink& progress) {
  (void)estimation_policy(settings.model);
  const analysis::KiderSite site = settings.site();
  std::vector<MeasuredCaptureResult> out;
  const int total = static_cast<int>(captures.size());
  for (int i = 0; i < total; ++i) {
    const io::KiderCapture& c = captures[static_cast<std::size_t>(i)];
    if (progress) progress(i, total, c.name);
    const analysis::CaptureSun sun =
        analysis::capture_sun(c, site, settings.sun_azimuth == SunAzimuthSource::symmetry);
    out.push_back(compare_capture(c, sun, settings));
  }
  if (progress) progress(total, total, "done");
  return out;
}

}  // namespace skylight::fit
