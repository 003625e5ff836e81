#include "skylight/nn/image_dataset.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/parameters.h"
#include "skylight/core/statistics.h"

namespace skylight::nn {

double image_target_scale(const std::vector<ImageSamples>& images) {
  std::vector<double> values;
  for (const ImageSamples& im : images)
    for (const Rgb& c : im.rgb) {
      values.push_back(c.r);
      values.push_back(c.g);
      values.push_back(c.b);
    }
  if (values.empty()) throw InvalidArgument("images: no sky samples");
  const double median = nearest_rank_percentile(values, 0.5);
  if (!(median > 0.0) || !std::isfinite(median))
    throw InvalidArgument(
        fmt::format("images: the median sky pixel value is {}, not positive", median));
  return median / kImageTargetMedian;
}

Dataset image_dataset(const std::vector<ImageSamples>& images, const InputSpec& inputs,
                      double target_scale) {
  if (!(target_scale > 0.0) || !std::isfinite(target_scale))
    throw InvalidArgument(fmt::format("images: target scale {} is not positive", target_scale));
  Dataset ds;
  ds.spec.source = "images";
  ds.spec.target_scale = target_scale;
  ds.spec.sun_count = static_cast<int>(images.size());
  ds.spec.turbidities = {0.0};
  ds.spec.view_zeniths = 0;
  ds.spec.view_azimuths = 0;
  ds.input_spec = inputs;
  std::vector<double> x(inputs.size());
  for (std::size_t s = 0; s < images.size(); ++s) {
    const ImageSamples& im = images[s];
    SKYLIGHT_CHECK(im.views.size() == im.rgb.size(), "image_dataset: views and rgb sizes differ");
    ds.states.push_back(im.state);
    for (std::size_t i = 0; i < im.views.size(); ++i) {
      ds.state_index.push_back(static_cast<int>(s));
      ds.views.push_back(im.views[i]);
      compute_inputs(inputs, im.state, im.views[i], x);
      ds.inputs.insert(ds.inputs.end(), x.begin(), x.end());
      ds.radiance.push_back(im.rgb[i].r / target_scale);
      ds.radiance.push_back(im.rgb[i].g / target_scale);
      ds.radiance.push_back(im.rgb[i].b / target_scale);
    }
  }
  return ds;
}

namespace {

// The examples i with keep_state[state] && keep_example(i); kept states renumbered in order.
template <class KeepExample>
Dataset subset(const Dataset& ds, const std::vector<bool>& keep_state, KeepExample keep_example) {
  Dataset out;
  out.spec = ds.spec;
  out.input_spec = ds.input_spec;
  std::vector<int> index(ds.states.size(), -1);
  for (std::size_t s = 0; s < ds.states.size(); ++s)
    if (keep_state[s]) {
      index[s] = static_cast<int>(out.states.size());
      out.states.push_back(ds.states[s]);
    }
  const std::size_t n_in = ds.input_spec.size();
  for (std::size_t i = 0; i < ds.size(); ++i) {
    const int s = index[static_cast<std::size_t>(ds.state_index[i])];
    if (s < 0 || !keep_example(i)) continue;
    out.state_index.push_back(s);
    out.views.push_back(ds.views[i]);
    out.inputs.insert(out.inputs.end(), ds.inputs.begin() + static_cast<std::ptrdiff_t>(i * n_in),
                      ds.inputs.begin() + static_cast<std::ptrdiff_t>((i + 1) * n_in));
    out.radiance.insert(out.radiance.end(),
                        ds.radiance.begin() + static_cast<std::ptrdiff_t>(3 * i),
                        ds.radiance.begin() + static_cast<std::ptrdiff_t>(3 * i + 3));
  }
  return out;
}

}  // namespace

Dataset subset_by_state(const Dataset& ds, const std::vector<bool>& keep) {
  SKYLIGHT_CHECK(keep.size() == ds.states.size(), "subset_by_state: one flag per state");
  return subset(ds, keep, [](std::size_t) { return true; });
}

Dataset every_nth_example(const Dataset& ds, std::size_t every, std::size_t first) {
  SKYLIGHT_CHECK(every > 0 && first < every, "every_nth_example: 0 <= first < every");
  return subset(ds, std::vector<bool>(ds.states.size(), true),
                [&](std::size_t i) { return i % every == first; });
}

TrainedSkyNetwork train_sky_network(const Dataset& ds, const NetworkSetup& setup) {
  if (ds.size() == 0) throw InvalidArgument("training set: no examples");
  const std::vector<double> targets = ds.targets(setup.encoding);
  const Examples ex{ds.inputs, targets, ds.size()};
  const Activation out_f =
      setup.encoding == OutputEncoding::satilmis ? Activation::satilmis : Activation::identity;
  const MlpLayout layout =
      MlpLayout::make(ds.n_inputs(), setup.hidden, 3, Activation::satilmis, out_f);
  TrainedSkyNetwork r;
  r.train = train(layout, ex, setup.options);
  SkyNetwork& sky = r.network;
  sky.net = r.train.net;
  sky.inputs = ds.input_spec;
  sky.encoding = setup.encoding;
  sky.target_scale = ds.spec.target_scale;
  if (const double m = ds.max_radiance(); m > 0.0) sky.max_radiance = kMaxRadianceMargin * m;
  SkyNetworkProvenance& pv = sky.provenance;
  pv.source = ds.spec.source;
  for (const SkyState& s : ds.states)
    if (std::find(pv.turbidities.begin(), pv.turbidities.end(), s.turbidity) ==
        pv.turbidities.end())
      pv.turbidities.push_back(s.turbidity);
  pv.ground_albedo = ds.spec.ground_albedo;
  pv.sun_count = ds.spec.sun_count;
  pv.view_zeniths = ds.spec.view_zeniths;
  pv.view_azimuths = ds.spec.view_azimuths;
  pv.seed = setup.options.seed;
  pv.trainer = std::string(to_string(setup.options.trainer));
  pv.iterations = r.train.iterations;
  pv.stop = r.train.stop;
  pv.training_seconds = r.train.seconds;
  pv.training_mse = r.train.mse;
  return r;
}

CrossValidation cross_validate(const Dataset& ds, int folds, const NetworkSetup& setup,
                               const std::function<void(int, int)>& on_fold) {
  const int n = static_cast<int>(ds.states.size());
  if (folds < 2 || folds > n)
    throw InvalidArgument(fmt::format("{} {}: needs 2 to {} folds (the number of images)",
                                      spelled("kfold"), folds, n));
  CrossValidation cv;
  for (int k = 0; k < folds; ++k) {
    if (on_fold) on_fold(k, folds);
    std::vector<bool> train_keep(static_cast<std::size_t>(n)),
        test_keep(static_cast<std::size_t>(n));
    FoldResult f;
    for (int s = 0; s < n; ++s) {
      const bool held = s % folds == k;
      test_keep[static_cast<std::size_t>(s)] = held;
      train_keep[static_cast<std::size_t>(s)] = !held;
      if (held) f.held_out.push_back(s);
    }
    const Dataset train_set = subset_by_state(ds, train_keep);
    const Dataset test_set = subset_by_state(ds, test_keep);
    const TrainedSkyNetwork t = train_sky_network(train_set, setup);
    f.training_examples = train_set.size();
    f.test_examples = test_set.size();
    f.training_rmse = std::sqrt(t.train.mse);
    f.errors = evaluate_errors(t.network, test_set);
    cv.mean_rmse += f.errors.rmse / folds;
    cv.mean_relative_median += f.errors.relative_median / folds;
    cv.mean_relative_p95 += f.errors.relative_p95 / folds;
    cv.folds.push_back(std::move(f));
  }
  return cv;
}

}  // namespace skylight::nn
