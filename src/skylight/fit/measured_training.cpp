// Sky networks trained on measured skies (fit/measured_training.h, docs/MEASURED.md).
#include "skylight/fit/measured_training.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "skylight/core/colorimetry.h"
#include "skylight/core/error.h"
#include "skylight/core/statistics.h"
#include "skylight/fit/network_training.h"
#include "skylight/nn/metrics.h"

namespace skylight::fit {
namespace {

// The luminance of linear sRGB (ITU-R BT.709 primaries, D65: the Y row of the sRGB matrix).
double rgb_luminance(const Rgb& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// A capture's training samples: the used directions and their measured linear sRGB (negative
// channels of out-of-gamut colours clamped to 0).
nn::ImageSamples capture_samples(const io::KiderCapture& c, const MeasuredCaptureResult& r,
                                 double turbidity) {
  nn::ImageSamples s;
  s.state.turbidity = turbidity;
  s.state.sun_zenith = r.sun.sun.zenith;
  s.state.sun_azimuth = r.sun.sun.azimuth;
  for (std::size_t i = 0; i < c.samples.size(); ++i) {
    if (!r.samples[i].used) continue;
    s.views.push_back(direction_from_angles(c.samples[i].zenith, c.samples[i].azimuth));
    const Rgb rgb = xyz_to_linear_srgb(measured_sample_xyz(c, c.samples[i]));
    s.rgb.push_back({std::max(rgb.r, 0.0), std::max(rgb.g, 0.0), std::max(rgb.b, 0.0)});
  }
  return s;
}

// The shape and absolute errors of luminances `model` against `measured` (as compare_capture:
// scale = exp(mean ln(m / M))); infinite when the model gives no light somewhere.
std::pair<double, double> luminance_errors(const std::vector<double>& model,
                                           const std::vector<double>& measured) {
  double log_ratio = 0.0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (!(model[i] > 0.0))
      return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    log_ratio += std::log(measured[i] / model[i]);
  }
  const double scale = std::exp(log_ratio / static_cast<double>(model.size()));
  double shape = 0.0, abs = 0.0;
  for (std::size_t i = 0; i < model.size(); ++i) {
    const double q = model[i] / measured[i];
    shape += (scale * q - 1.0) * (scale * q - 1.0);
    abs += (q - 1.0) * (q - 1.0);
  }
  const auto n = static_cast<double>(model.size());
  return {std::sqrt(shape / n), std::sqrt(abs / n)};
}

}  // namespace

const ParameterSchema<MeasuredTrainingOptions>& MeasuredTrainingOptions::schema() {
  static const ParameterSchema<MeasuredTrainingOptions> s = [] {
    ParameterSchema<MeasuredTrainingOptions> s;
    s.text(&MeasuredTrainingOptions::kider,
           {.name = "measured",
            .kind = ParameterKind::text,
            .default_value = Absent{"--source"},
            .description = "train on measured clear skies instead of --source: a folder of Kider "
                           "et al. 2014's captures (the data set, a date, one capture, or the "
                           "shipped subset data/measured/kider2014; docs/MEASURED.md)"});
    return s;
  }();
  return s;
}

MeasuredTrainingResult train_on_measured(
    const std::vector<io::KiderCapture>& captures, const NeuralTraining& t,
    const MeasuredSettings& settings,
    const std::function<void(int, int, const std::string&)>& progress) {
  if (captures.size() < 3)
    throw InvalidArgument(fmt::format(
        "nn train --measured: {} captures; at least 3 are needed (one is left out in turn)",
        captures.size()));
  MeasuredSettings preetham = settings;
  preetham.model = std::string(PreethamModel::kName);
  const analysis::KiderSite site = settings.site();
  const int steps = static_cast<int>(captures.size()) + 1;
  const auto report = [&](int done, const std::string& step) {
    if (progress) progress(done, steps, step);
  };
  MeasuredTrainingResult out;
  std::vector<nn::ImageSamples> samples;
  std::vector<std::vector<double>> measured_y, turbidity_model_y;
  for (const io::KiderCapture& c : captures) {
    const analysis::CaptureSun sun =
        analysis::capture_sun(c, site, settings.sun_azimuth == SunAzimuthSource::symmetry);
    const MeasuredCaptureResult r = compare_capture(c, sun, preetham);
    const double turbidity = r.fit.parameters.front().value;
    out.captures.push_back(c.name);
    out.turbidities.push_back(turbidity);
    samples.push_back(capture_samples(c, r, turbidity));
    std::vector<double> m, p;
    for (const MeasuredSampleResult& x : r.samples)
      if (x.used) {
        m.push_back(x.measured_luminance);
        p.push_back(x.model_luminance);
      }
    measured_y.push_back(std::move(m));
    turbidity_model_y.push_back(std::move(p));
  }
  out.target_scale = t.target_scale ? *t.target_scale : nn::image_target_scale(samples);
  nn::Dataset ds = nn::image_dataset(samples, t.inputs, out.target_scale);
  ds.spec.source = "measured";
  out.examples = ds.size();
  nn::NetworkSetup setup = data_network_setup(t);
  setup.options.restarts = t.starts;
  setup.options.restart_iterations = t.start_iterations;
  std::vector<double> shapes, turbidity_shapes;
  for (std::size_t k = 0; k < captures.size(); ++k) {
    report(static_cast<int>(k), "without " + captures[k].name);
    std::vector<bool> keep(captures.size(), true);
    keep[k] = false;
    const nn::TrainedSkyNetwork fold = nn::train_sky_network(nn::subset_by_state(ds, keep), setup);
    std::vector<double> y;
    for (const Vec3& v : samples[k].views)
      y.push_back(rgb_luminance(fold.network.rgb(samples[k].state, v)));
    MeasuredFold f;
    f.capture = captures[k].name;
    std::tie(f.luminance_rms_shape, f.luminance_rms_abs) = luminance_errors(y, measured_y[k]);
    f.turbidity_model_rms_shape = luminance_errors(turbidity_model_y[k], measured_y[k]).first;
    shapes.push_back(f.luminance_rms_shape);
    turbidity_shapes.push_back(f.turbidity_model_rms_shape);
    out.folds.push_back(f);
  }
  out.median_shape = median(shapes);
  out.median_turbidity_model_shape = median(turbidity_shapes);
  if (t.max_relative_p95) out.max_shape = *t.max_relative_p95;
  if (!(out.median_shape <= out.max_shape))
    throw FitFailed(fmt::format(
        "nn train --measured: the network misses the captures it did not see by {:.1f} % "
        "(median luminance shape RMS, one capture left out in turn; bound {:.3g} %); nothing "
        "written",
        100.0 * out.median_shape, 100.0 * out.max_shape));
  report(static_cast<int>(captures.size()), "final network on every capture");
  out.trained = nn::train_sky_network(ds, setup);
  out.errors = nn::evaluate_errors(out.trained.network, ds);
  report(steps, "done");
  return out;
}

}  // namespace skylight::fit
