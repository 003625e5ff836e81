// Sky networks trained on measured skies (`nn train --measured DIR`; docs/MEASURED.md, "Learning
// from measurement"): Satilmis et al. 2016's network learns the captures of Kider et al. 2014,
// each with its sun (the sky's symmetry) and its fitted Preetham turbidity as the network's
// turbidity input (the paper trains on Preetham's turbidity), and is judged capture by capture on
// data it never saw (leave one capture out).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "skylight/fit/measured_fit.h"
#include "skylight/fit/neural_training.h"
#include "skylight/nn/image_dataset.h"

namespace skylight::fit {

// The bound on the median over captures of the leave-one-capture-out luminance shape error
// (relative RMS after the best scale, as `skylight measured` measures a model): beyond it the
// network does not generalise between the captures and nothing is written. Twice the analytic
// models' 11-14 % on the same captures.
inline constexpr double kMeasuredMaxShapeRms = 0.25;

struct MeasuredTrainingOptions {
  std::string kider;  // the captures' folder (io::read_kider); empty: the shipped subset
  static const ParameterSchema<MeasuredTrainingOptions>& schema();
};

// One capture left out: the network trained on the others, measured on it.
struct MeasuredFold {
  std::string capture;
  double luminance_rms_shape = 0.0, luminance_rms_abs = 0.0;  // as MeasuredCaptureResult's
  double turbidity_model_rms_shape = 0.0;  // the fitted Preetham sky's on the same samples
};

struct MeasuredTrainingResult {
  std::vector<std::string> captures;
  std::vector<double> turbidities;  // the input of each capture (fitted Preetham turbidity)
  double target_scale = 0.0;
  std::size_t examples = 0;
  std::vector<MeasuredFold> folds;  // leave one capture out, capture order
  double median_shape = 0.0, median_turbidity_model_shape = 0.0;  // over the folds
  double max_shape = kMeasuredMaxShapeRms;                        // the bound applied
  nn::TrainedSkyNetwork trained;                                  // on every capture
  nn::ErrorStats errors;  // of the final network on every capture
};

// Trains the network of `training` (its inputs, hidden layers, encoding, trainer options, starts)
// on the captures' samples more than settings.exclude_sun_deg from the sun (linear sRGB from each
// sample's 380-780 nm spectrum), each fold first, then the final network; FitFailed when the
// folds' median shape error exceeds the bound (training.max_relative_p95 when given, else
// kMeasuredMaxShapeRms). progress(done, total, step): one step per fold and the final network.
MeasuredTrainingResult train_on_measured(
    const std::vector<io::KiderCapture>& captures, const NeuralTraining& training,
    const MeasuredSettings& settings,
    const std::function<void(int, int, const std::string&)>& progress = {});

}  // namespace skylight::fit
