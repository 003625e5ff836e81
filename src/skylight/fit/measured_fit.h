// Sky models judged against measured skies (`skylight measured`; docs/MEASURED.md): per capture of
// Kider et al. 2014 (io/kider.h), the model's free parameters fitted to the measured luminance with
// the fit floor every estimate uses (fit_luminance: its registry entry's EstimationPolicy, a grid
// then Levenberg-Marquardt in the box, ln-luminance residuals with a free scale; no RANSAC: the
// skies are clear), then the errors in shape, in absolute level, in spectrum and in colour, over
// the samples further than --exclude-sun-deg from the sun.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "skylight/analysis/measured_sky.h"
#include "skylight/core/parameters.h"
#include "skylight/core/progress.h"
#include "skylight/fit/luminance_fit.h"
#include "skylight/io/kider.h"

namespace skylight::fit {

enum class SunAzimuthSource { spa, symmetry };

struct MeasuredSettings {
  std::string model;
  double exclude_sun_deg = 10.0;  // samples within this angle of the sun are not used [deg]
  // The sun's azimuth: the SPA's at the capture's time, or the measured sky's axis of symmetry
  // searched around it (analysis::symmetry_axis_azimuth; Bruneton 2017's harness does the same).
  SunAzimuthSource sun_azimuth = SunAzimuthSource::symmetry;
  // Where and when (analysis::KiderSite's defaults: Kider et al.'s roof, EDT).
  double site_lat_deg = analysis::KiderSite{}.latitude_deg;
  double site_lon_deg = analysis::KiderSite{}.longitude_deg;
  std::string utc_offset = analysis::KiderSite{}.utc_offset;

  analysis::KiderSite site() const;

  static const ParameterSchema<MeasuredSettings>& schema();
};

// The spectral comparison's wavelengths: 380, 385, ..., 780 nm (those the model gives).
inline constexpr double kSpectralFirstNm = 380.0, kSpectralLastNm = 780.0, kSpectralStepNm = 5.0;

struct MeasuredSampleResult {
  int index = 0;
  double zenith_deg = 0.0, azimuth_deg = 0.0;  // skylight's convention
  double measured_luminance = 0.0;             // [cd/m^2]
  double model_luminance = 0.0;                // [cd/m^2] the fitted model, without the scale
  bool used = true;                            // outside the sun's exclusion
};

struct MeasuredCaptureResult {
  std::string name, local_time;
  analysis::CaptureSun sun;
  LuminanceFit fit;  // the fitted parameters and method (its ln scale is the policy's units)
  // The best single factor, measured ~ scale x model (the model's own absolute luminance), by the
  // fit's measure: exp(mean ln(m / M)) over the used samples.
  double scale = 1.0;
  double luminance_rms_shape = 0.0;  // sqrt(mean((scale M / m - 1)^2)) over the used samples
  double luminance_rms_abs = 0.0;    // sqrt(mean((M / m - 1)^2))
  // sqrt(sum (scale M(l) - m(l))^2 / sum m(l)^2) over the used samples and the spectral
  // comparison's wavelengths the model gives; nullopt for a model without spectra.
  std::optional<double> spectral_rms;
  // Mean over the used samples of the CIE 1976 u'v' distance between the model's and the
  // measured spectrum's chromaticity (380-780 nm).
  double mean_delta_uv = 0.0;
  // The model's global horizontal irradiance needs its broadband spectrum (the pyranometer sees
  // about 300-2800 nm): nullopt for models without it (today every model; docs/MEASURED.md).
  std::optional<double> global_horizontal_model_w_m2;
  std::optional<double> global_horizontal_measured_w_m2;  // the pyranometer's mean
  int samples_used = 0;
  std::vector<MeasuredSampleResult> samples;
};

// The measured colour of a sample: XYZ of its spectrum over 380-780 nm (Y = luminance [cd/m^2]).
Xyz measured_sample_xyz(const io::KiderCapture& capture, const io::KiderSample& sample);

// The fitted model of a fit at the capture's sun (its parameters set, the others at their
// defaults): its own absolute luminance (without the fit's scale).
std::unique_ptr<SkyModel> fitted_model(const LuminanceFit& fit, const SunPosition& sun);

// The models `measured` fits: those with an estimation policy (registry order).
std::vector<std::string> measured_models();

// Every capture compared (progress: one step per capture). Throws InvalidArgument for a model
// that is not fitted (the message lists those that are).
std::vector<MeasuredCaptureResult> compare_to_measured(
    const std::vector<io::KiderCapture>& captures, const MeasuredSettings& settings,
    const ProgressSink& progress = {});

// One capture (the sun already placed).
MeasuredCaptureResult compare_capture(const io::KiderCapture& capture,
                                      const analysis::CaptureSun& sun,
                                      const MeasuredSettings& settings);

}  // namespace skylight::fit
