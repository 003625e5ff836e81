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
};

struct NeuralValidation {
  nn::Dataset dataset;  // the validation set (states, views, source radiance)
  nn::ErrorStats errors;
  nn::IrradianceStats irradiance;  // eq. 11 per sky state, normalised units (x target_scale: rgb)
};

struct NeuralTrainingResult {
  nn::SkyNetwork network;  // provenance filled in (date and software left to the caller)
  nn::TrainResult train;
  std::optional<NeuralValidation> validation;
};

// Builds the training set, trains, and (with `validate`) measures the validation set; the metrics
// go into the network's provenance.
NeuralTrainingResult train_neural_sky(const NeuralTraining& t);

// The metrics of a network on the paper's validation set of its provenance source (its source
// model must be registered). sun_count / view counts: overrides of the protocol's (0 = its own).
NeuralValidation validate_neural_sky(const nn::SkyNetwork& sky, int sun_count = 0,
                                     int view_zeniths = 0, int view_azimuths = 0);

}  // namespace skylight::fit
