// Training and validating neural sky models (Satilmis et al. 2016 §III-D, §IV) on any registered
// SkyModel: the source (its rgb() per sky state), the paper's sampling protocol over the model's
// turbidities (its registry entry's NeuralPolicy), training through nn::train and the metrics of
// nn/metrics.h on the paper's validation sets. docs/NN.md.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/models/preetham.h"
#include "skylight/nn/dataset.h"
#include "skylight/nn/metrics.h"
#include "skylight/nn/sky_network.h"
#include "skylight/nn/train.h"

namespace skylight::fit {

// Normalisation of a source's rgb() (the network learns rgb / target_scale): its registry entry's
// NeuralPolicy::target_scale. InvalidArgument for an unknown model.
double default_target_scale(std::string_view source);

// A training source from a registered model: per sky state, the model built with the state's
// sun and, where the model's schema declares them, `turbidity` and `albedo`. InvalidArgument for
// an unknown model or one that needs parameters the state does not give.
nn::SkySource sky_model_source(std::string_view model);

// The paper protocol (§III-D, §IV-A; nn::paper_training_spec) over the source's NeuralPolicy
// turbidities (a source without turbidity: a single state per sun with T = 0, the input unused,
// as for image-trained networks); 20 training suns at azimuth pi, 7 validation suns at random
// azimuths; 10 x 20 stratified views; albedo 0.5.
nn::SamplingSpec neural_training_spec(std::string_view source);
nn::SamplingSpec neural_validation_spec(std::string_view source);
// Held-out sets on the policy's dense turbidity grid (NeuralPolicy::held_out_turbidities), at
// random sun azimuths, disjoint in their random draws from the training and validation sets:
// the selection set that picks among the starts (5 suns, 6 x 12 views, seed 3) and the check set
// every trained network must pass (7 suns, 10 x 20 views, seed 4).
nn::SamplingSpec neural_selection_spec(std::string_view source);
nn::SamplingSpec neural_check_spec(std::string_view source);

struct NeuralTraining {
  std::string source = std::string(PreethamModel::kName);
  std::vector<int> hidden{12};  // hidden layer widths (the paper: one layer of 12)
  nn::InputSpec inputs = nn::satilmis_inputs();
  nn::OutputEncoding encoding = nn::OutputEncoding::satilmis;
  std::optional<double> target_scale;  // default_target_scale(source) when absent
  // Overrides of the protocol's sampling (tests use smaller sets); 0 = the protocol's.
  int sun_count = 0;
  int view_zeniths = 0;
  int view_azimuths = 0;
  nn::TrainOptions options;  // trainer, seed, stops, progress callback
  bool validate = true;      // measure the paper's validation set afterwards
  // Starts: independent initialisations trained for start_iterations each, judged on the held-out
  // selection set; the best continues (nn::TrainOptions::restarts).
  int starts = 1;
  int start_iterations = 60;
  // The held-out check (neural_check_spec): its p95 bound; absent: the source's
  // NeuralPolicy::max_relative_p95. check = false skips it (tests of the trainer alone).
  std::optional<double> max_relative_p95;
  bool check = true;
};

struct NeuralValidation {
  nn::Dataset dataset;  // the validation set (states, views, source radiance)
  nn::ErrorStats errors;
  nn::IrradianceStats irradiance;  // eq. 11 per sky state, normalised units (x target_scale: rgb)
};

// The held-out check of a trained network: its errors on neural_check_spec's set and the bound.
struct HeldOutCheck {
  nn::ErrorStats errors;
  double max_relative_p95 = 0.0;
  double t_min = 0.0, t_max = 0.0;  // the grid's turbidities
  std::size_t turbidities = 0;
  bool passed() const { return errors.relative_p95 <= max_relative_p95; }
  // "held-out check: relative error median 2.10 %, p95 8.30 % (bound 12 %) over T 2-6 (41
  // values)"
  std::string summary() const;
};

struct NeuralTrainingResult {
  nn::SkyNetwork network;  // provenance filled in (date and software left to the caller)
  nn::TrainResult train;
  std::optional<NeuralValidation> validation;
  std::optional<HeldOutCheck> check;
};

// Builds the training set, trains (the starts judged on the held-out selection set), and (with
// `validate`) measures the paper's validation set, the metrics going into the network's
// provenance; then (with `check`) the held-out check: a FitFailed error, with the check's summary,
// when its p95 exceeds the bound. A network that fails is never returned.
NeuralTrainingResult train_neural_sky(const NeuralTraining& t);

// The held-out check of a network of a registered source (neural_check_spec); the bound: the
// source's NeuralPolicy::max_relative_p95 unless given.
HeldOutCheck check_neural_sky(const nn::SkyNetwork& sky,
                              std::optional<double> max_relative_p95 = std::nullopt);

// The metrics of a network on the paper's validation set of its provenance source (its source
// model must be registered). sun_count / view counts: overrides of the protocol's (0 = its own).
NeuralValidation validate_neural_sky(const nn::SkyNetwork& sky, int sun_count = 0,
                                     int view_zeniths = 0, int view_azimuths = 0);

}  // namespace skylight::fit
