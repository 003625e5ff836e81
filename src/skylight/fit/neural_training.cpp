#include "skylight/fit/neural_training.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/models/sky_model.h"

namespace skylight::fit {
namespace {

const ModelInfo& source_info(std::string_view source) {
  return require_model(source, "source");
}

void apply_overrides(nn::SamplingSpec& spec, const NeuralTraining& t) {
  if (t.sun_count > 0) spec.sun_count = t.sun_count;
  if (t.view_zeniths > 0) spec.view_zeniths = t.view_zeniths;
  if (t.view_azimuths > 0) spec.view_azimuths = t.view_azimuths;
}

}  // namespace

double default_target_scale(std::string_view source) {
  return source_info(source).neural.target_scale;
}

nn::SkySource sky_model_source(std::string_view model) {
  const ModelInfo& info = source_info(model);
  const bool has_turbidity = info.find_parameter("turbidity") != nullptr;
  const bool has_albedo = info.find_parameter("albedo") != nullptr;
  return [&info, has_turbidity, has_albedo](const nn::SkyState& s) -> nn::SkyFunction {
    SkyParameters p;
    p.sun = {s.sun_zenith, s.sun_azimuth};
    p.values = info.example;
    if (has_turbidity) p.values.set("turbidity", s.turbidity);
    if (has_albedo) p.values.set("albedo", s.ground_albedo);
    std::shared_ptr<const SkyModel> m = info.make(p);
    return [m](Vec3 view) { return m->rgb(view); };
  };
}

nn::SamplingSpec neural_training_spec(std::string_view source) {
  const NeuralPolicy& p = source_info(source).neural;
  return nn::paper_training_spec(source, p.training_turbidities, p.target_scale);
}

nn::SamplingSpec neural_validation_spec(std::string_view source) {
  const NeuralPolicy& p = source_info(source).neural;
  return nn::paper_validation_spec(source, p.validation_turbidities, p.target_scale);
}

nn::SamplingSpec neural_selection_spec(std::string_view source) {
  const NeuralPolicy& p = source_info(source).neural;
  nn::SamplingSpec s = nn::paper_validation_spec(source, p.held_out_turbidities, p.target_scale);
  s.sun_count = 5;
  s.view_zeniths = 6;
  s.view_azimuths = 12;
  s.seed = 3;
  return s;
}

nn::SamplingSpec neural_check_spec(std::string_view source) {
  const NeuralPolicy& p = source_info(source).neural;
  nn::SamplingSpec s = nn::paper_validation_spec(source, p.held_out_turbidities, p.target_scale);
  s.seed = 4;
  return s;
}

std::string HeldOutCheck::summary() const {
  const std::string over =
      turbidities > 1 ? fmt::format("over T {:g}-{:g} ({} values)", t_min, t_max, turbidities)
                      : std::string("over the source's skies (no turbidity)");
  return fmt::format(
      "held-out check: relative error median {:.2f} %, p95 {:.2f} % (bound {:.3g} %) {}",
      100.0 * errors.relative_median, 100.0 * errors.relative_p95, 100.0 * max_relative_p95, over);
}

NeuralTrainingResult train_neural_sky(const NeuralTraining& t) {
  nn::SamplingSpec spec = neural_training_spec(t.source);
  if (t.target_scale) spec.target_scale = *t.target_scale;
  apply_overrides(spec, t);
  if (!(spec.target_scale > 0.0)) throw InvalidArgument("target-scale must be positive");
  const nn::SkySource source = sky_model_source(t.source);
  const nn::Dataset data = nn::build_dataset(spec, t.inputs, source);
  const std::vector<double> targets = data.targets(t.encoding);
  const nn::Examples ex{data.inputs, targets, data.size()};

  const nn::Activation hidden_f = nn::Activation::satilmis;
  const nn::Activation out_f = t.encoding == nn::OutputEncoding::satilmis
                                   ? nn::Activation::satilmis
                                   : nn::Activation::identity;
  const nn::MlpLayout layout = nn::MlpLayout::make(data.n_inputs(), t.hidden, 3, hidden_f, out_f);

  // The starts are judged on a held-out selection set (never trained on).
  nn::TrainOptions options = t.options;
  nn::Dataset selection;
  std::vector<double> selection_targets;
  nn::Examples selection_ex;
  if (t.starts > 1) {
    nn::SamplingSpec ss = neural_selection_spec(t.source);
    ss.target_scale = spec.target_scale;
    ss.ground_albedo = spec.ground_albedo;
    selection = nn::build_dataset(ss, t.inputs, source);
    selection_targets = selection.targets(t.encoding);
    selection_ex = {selection.inputs, selection_targets, selection.size()};
    options.validation = &selection_ex;
    options.restarts = t.starts;
    options.restart_iterations = t.start_iterations;
  }
  NeuralTrainingResult r;
  r.train = nn::train(layout, ex, options);
  nn::SkyNetwork& sky = r.network;
  sky.net = r.train.net;
  sky.inputs = t.inputs;
  sky.encoding = t.encoding;
  sky.target_scale = spec.target_scale;
  if (const double m = data.max_radiance(); m > 0.0) sky.max_radiance = nn::kMaxRadianceMargin * m;
  nn::SkyNetworkProvenance& pv = sky.provenance;
  pv.source = t.source;
  pv.turbidities = spec.turbidities;
  pv.ground_albedo = spec.ground_albedo;
  pv.sun_count = spec.sun_count;
  pv.view_zeniths = spec.view_zeniths;
  pv.view_azimuths = spec.view_azimuths;
  pv.seed = t.options.seed;
  pv.trainer = std::string(nn::to_string(t.options.trainer));
  pv.iterations = r.train.iterations;
  pv.stop = r.train.stop;
  pv.training_seconds = r.train.seconds;
  pv.training_mse = r.train.mse;
  if (t.validate) {
    r.validation = validate_neural_sky(sky, t.sun_count, t.view_zeniths, t.view_azimuths);
    pv.validation_rmse = r.validation->errors.rmse;
    pv.validation_relative_median = r.validation->errors.relative_median;
    pv.validation_relative_p95 = r.validation->errors.relative_p95;
  }
  if (t.check) {
    r.check = check_neural_sky(sky, t.max_relative_p95);
    if (!r.check->passed())
      throw FitFailed(fmt::format(
          "nn train: the network fails its {} (seed {}); train with more --starts, another "
          "--seed, or accept it with --max-error",
          r.check->summary(), t.options.seed));
  }
  return r;
}

HeldOutCheck check_neural_sky(const nn::SkyNetwork& sky, std::optional<double> max_relative_p95) {
  nn::SamplingSpec spec = neural_check_spec(sky.provenance.source);
  spec.target_scale = sky.target_scale;
  spec.ground_albedo = sky.provenance.ground_albedo;
  HeldOutCheck c;
  c.errors = nn::evaluate_errors(
      sky, nn::build_dataset(spec, sky.inputs, sky_model_source(sky.provenance.source)));
  c.max_relative_p95 =
      max_relative_p95.value_or(source_info(sky.provenance.source).neural.max_relative_p95);
  c.t_min = *std::min_element(spec.turbidities.begin(), spec.turbidities.end());
  c.t_max = *std::max_element(spec.turbidities.begin(), spec.turbidities.end());
  c.turbidities = spec.turbidities.size();
  return c;
}

NeuralValidation validate_neural_sky(const nn::SkyNetwork& sky, int sun_count, int view_zeniths,
                                     int view_azimuths) {
  nn::SamplingSpec spec = neural_validation_spec(sky.provenance.source);
  spec.target_scale = sky.target_scale;
  spec.ground_albedo = sky.provenance.ground_albedo;
  if (sun_count > 0) spec.sun_count = sun_count;
  if (view_zeniths > 0) spec.view_zeniths = view_zeniths;
  if (view_azimuths > 0) spec.view_azimuths = view_azimuths;
  const nn::SkySource source = sky_model_source(sky.provenance.source);
  NeuralValidation v;
  v.dataset = nn::build_dataset(spec, sky.inputs, source);
  v.errors = nn::evaluate_errors(sky, v.dataset);
  v.irradiance = nn::evaluate_irradiance(sky, v.dataset, source);
  return v;
}

}  // namespace skylight::fit
