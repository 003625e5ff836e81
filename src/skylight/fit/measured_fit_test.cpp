#include "skylight/fit/measured_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/math.h"
#include "skylight/core/random.h"
#include "skylight/models/sky_model.h"

namespace skylight::fit {
namespace {

MeasuredSettings preetham_settings() {
  MeasuredSettings s;
  s.model = "preetham";
  return s;
}

// A capture of the shipped subset's geometry whose "measurement" is a Preetham sky of turbidity
// `t` times `scale` (luminance and spectra), each sample's luminance times (1 + noise u), u uniform
// in [-1, 1) from SplitMix64(seed).
io::KiderCapture synthetic_capture(const analysis::CaptureSun& sun, double t, double scale,
                                   double noise, std::uint64_t seed) {
  io::KiderCapture c = io::shipped_kider_subset()[4];
  SkyParameters p;
  p.sun = sun.sun;
  p.values.set("turbidity", t);
  const auto sky = make_sky_model("preetham", p);
  SplitMix64 rng(seed);
  for (io::KiderSample& s : c.samples) {
    const Vec3 v = direction_from_angles(s.zenith, s.azimuth);
    s.luminance = scale * sky->tristimulus(v).Y * (1.0 + noise * rng.symmetric());
    for (std::size_t k = 0; k < c.wavelengths_nm.size(); ++k)
      s.radiance[k] = scale * sky->spectral_radiance(v, c.wavelengths_nm[k]).value_or(0.0);
  }
  return c;
}

// The variance of ln(m / M) over the used samples: the fit's cost with the best scale.
double log_cost(const MeasuredCaptureResult& r, const io::KiderCapture& c, double t) {
  SkyParameters p;
  p.sun = r.sun.sun;
  p.values.set("turbidity", t);
  const auto sky = make_sky_model("preetham", p);
  std::vector<double> d;
  for (std::size_t i = 0; i < c.samples.size(); ++i)
    if (r.samples[i].used)
      d.push_back(std::log(
          c.samples[i].luminance /
          sky->tristimulus(direction_from_angles(c.samples[i].zenith, c.samples[i].azimuth)).Y));
  double mean = 0.0, var = 0.0;
  for (double x : d) mean += x / static_cast<double>(d.size());
  for (double x : d) var += (x - mean) * (x - mean);
  return var;
}

// A sky that is a Preetham sky (times 0.5): its turbidity and scale come back, the shape error is
// nil, the absolute one is the factor's.
TEST(MeasuredFit, RecoversTheTurbidityAndScaleOfAModelSky) {
  constexpr double kTurbidityTolerance = 1e-3;  // the LM's stopping tolerance on a clean sky
  const io::KiderCapture geometry = io::shipped_kider_subset()[4];
  const analysis::CaptureSun sun = analysis::capture_sun(geometry, {}, false);
  const io::KiderCapture c = synthetic_capture(sun, 3.4, 0.5, 0.0, 1);
  const MeasuredCaptureResult r = compare_capture(c, sun, preetham_settings());
  ASSERT_EQ(r.fit.parameters.size(), 1u);
  EXPECT_NEAR(r.fit.parameters[0].value, 3.4, kTurbidityTolerance);
  EXPECT_NEAR(r.scale, 0.5, 1e-4);
  EXPECT_LT(r.luminance_rms_shape, 1e-4);
  EXPECT_NEAR(r.luminance_rms_abs, 1.0, 1e-3);  // the model is twice the "measurement"
  ASSERT_TRUE(r.spectral_rms);
  EXPECT_LT(*r.spectral_rms, 1e-3);
  // The model's tristimulus comes from its Perez xyY, the "measured" colour from its spectrum
  // (CIE daylight basis, Preetham's appendix): the two chromaticities differ by a few 1e-3.
  EXPECT_LT(r.mean_delta_uv, 0.01);
  EXPECT_EQ(r.samples_used, 80);  // one sample within 10 deg of this capture's sun
  EXPECT_FALSE(r.global_horizontal_model_w_m2);
}

// 5 % multiplicative noise per sample, over seeds: the turbidity within 0.15 and the scale within
// 2 % (81 samples: the noise averages out in the ln fit).
TEST(MeasuredFit, NoisySkiesOverSeedsStayNearTheTruth) {
  const io::KiderCapture geometry = io::shipped_kider_subset()[4];
  const analysis::CaptureSun sun = analysis::capture_sun(geometry, {}, false);
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    const io::KiderCapture c = synthetic_capture(sun, 4.0, 0.5, 0.05, seed);
    const MeasuredCaptureResult r = compare_capture(c, sun, preetham_settings());
    EXPECT_NEAR(r.fit.parameters[0].value, 4.0, 0.15) << seed;
    EXPECT_NEAR(r.scale, 0.5, 0.01) << seed;
    EXPECT_LT(r.luminance_rms_shape, 0.04) << seed;
  }
}

// On the measured captures the fit is never worse than a brute-force grid over the same range
// (0.01 steps), and it is reproducible to the last digit.
TEST(MeasuredFit, NeverWorseThanABruteForceGridAndReproducible) {
  const auto captures = io::shipped_kider_subset();
  const EstimationPolicy& policy = estimation_policy("preetham");
  for (std::size_t k : {0u, 7u, 14u}) {
    const io::KiderCapture& c = captures[k];
    const analysis::CaptureSun sun = analysis::capture_sun(c, {}, true);
    const MeasuredCaptureResult r = compare_capture(c, sun, preetham_settings());
    const double fitted = log_cost(r, c, r.fit.parameters[0].value);
    double best = fitted * 10.0;
    for (double t = policy.axes[0].min; t <= policy.axes[0].max; t += 0.01)
      best = std::min(best, log_cost(r, c, t));
    EXPECT_LE(fitted, best * (1.0 + 1e-9)) << c.name;
    const MeasuredCaptureResult again = compare_capture(c, sun, preetham_settings());
    EXPECT_EQ(again.fit.parameters[0].value, r.fit.parameters[0].value);
    EXPECT_EQ(again.scale, r.scale);
  }
}

// The physical atmosphere with its aerosols fitted (docs/MEASURED.md): on the shipped subset
// nishita's shape is 3.6-7.7 % off (median 5.0 %), better than every analytic model; its single
// scattering leaves the sky darker than the scans (scale > 1). On one capture its fit is never
// worse than a brute-force grid over the three parameters.
TEST(MeasuredFit, ThePhysicalAtmosphereWithItsAerosolsFitted) {
  MeasuredSettings settings;
  settings.model = "nishita";
  const auto captures = io::shipped_kider_subset();
  const auto out = compare_to_measured(captures, settings);
  for (const auto& r : out) {
    EXPECT_LT(r.luminance_rms_shape, 0.09) << r.name;
    EXPECT_GT(r.scale, 1.0) << r.name;
  }
  const MeasuredCaptureResult& r = out[4];
  std::vector<Vec3> views;
  std::vector<double> log_m;
  for (const MeasuredSampleResult& m : r.samples)
    if (m.used) {
      views.push_back(direction_from_angles(deg_to_rad(m.zenith_deg), deg_to_rad(m.azimuth_deg)));
      log_m.push_back(std::log(m.measured_luminance));
    }
  const auto cost = [&](double tau, double alpha, double g) {
    SkyParameters p;
    p.sun = r.sun.sun;
    p.values.set("aerosol-optical-depth", tau);
    p.values.set("angstrom-exponent", alpha);
    p.values.set("mie-g", g);
    const auto sky = make_sky_model("nishita", p);
    std::vector<double> d;
    for (std::size_t i = 0; i < views.size(); ++i)
      d.push_back(log_m[i] - std::log(sky->tristimulus(views[i]).Y));
    double mean = 0.0, var = 0.0;
    for (double x : d) mean += x / static_cast<double>(d.size());
    for (double x : d) var += (x - mean) * (x - mean);
    return var;
  };
  const double fitted =
      cost(r.fit.parameters[0].value, r.fit.parameters[1].value, r.fit.parameters[2].value);
  double best = fitted * 10.0;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 5; ++j)
      for (int k = 0; k <= 3; ++k) best = std::min(best, cost(0.1 * i, 0.5 * j, 0.5 + 0.15 * k));
  EXPECT_LE(fitted, best * (1.0 + 1e-9));
}

TEST(MeasuredFit, EveryCaptureOfTheShippedSubset) {
  const auto captures = io::shipped_kider_subset();
  int steps = 0;
  const auto out = compare_to_measured(captures, preetham_settings(),
                                       [&](int, int, std::string_view) { ++steps; });
  ASSERT_EQ(out.size(), 15u);
  EXPECT_EQ(steps, 16);
  for (const auto& r : out) {
    // Measured on the shipped subset (docs/MEASURED.md): Preetham's shape is 11-14 % off, and
    // the model about twice as bright as the scans.
    EXPECT_GT(r.luminance_rms_shape, 0.05) << r.name;
    EXPECT_LT(r.luminance_rms_shape, 0.2) << r.name;
    EXPECT_GT(r.scale, 0.3) << r.name;
    EXPECT_LT(r.scale, 0.7) << r.name;
  }
  MeasuredSettings bad = preetham_settings();
  bad.model = "perez";
  EXPECT_THROW(compare_to_measured(captures, bad), InvalidArgument);
}

}  // namespace
}  // namespace skylight::fit
