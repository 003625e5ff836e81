// `skylight nn train|validate|study` as a user asks for them (docs/NN.md, docs/PIETRAS.md): every
// option declared once with its schema, the trainers' defaults, and what turns the options into
// the library's training: a sky network on a registered model (fit/neural_training.h) or on a
// sequence of sky images, or a Pietras network on nishita (fit/pietras_training.h).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/parameters.h"
#include "skylight/estimate/photo.h"
#include "skylight/estimate/sky_sequence.h"
#include "skylight/fit/neural_training.h"
#include "skylight/fit/pietras_training.h"
#include "skylight/nn/image_dataset.h"

namespace skylight::fit {

// Trainer defaults of the sky networks (docs/NN.md): LM, 500 iterations, 60 s.
inline constexpr nn::Trainer kSkyTrainer = nn::Trainer::levenberg_marquardt;
inline constexpr int kSkyIterations = 500;
inline constexpr double kSkyTimeLimitS = 60.0;
// Starts of a sky network, each start_iterations long, judged on held-out data
// (fit/neural_training.h; docs/NN.md, "Every seed").
inline constexpr int kSkyStarts = 4;
inline constexpr int kSkyStartIterations = 60;
// Sky pixels sampled per image of an image sequence (docs/NN.md: 2000 per image keep a 12-image
// sequence at 24 000 examples), and 200 000 samples of nishita for a Pietras network (§VI uses
// 800 000; with kPietrasTimeLimitS a default training is <= 300 s of CPU: docs/PIETRAS.md).
inline constexpr int kImageSamples = 2000;
// The bound on the held-out captures' relative error p95 of a sequence (docs/NN.md, "Sparse
// sequences"): beyond it the captures are too far apart for the network to interpolate them.
inline constexpr double kImageMaxRelativeP95 = 0.20;
inline constexpr int kPietrasSamples = 200000;

struct NetworkTrainingRequest {
  std::string source;  // empty: the embedded network's source (the paper's Preetham)
  int seed = 1;
  int hidden = 12;
  std::optional<nn::Trainer> trainer;  // absent: kSkyTrainer, with --network kPietrasTrainer
  nn::InputSpec inputs = nn::satilmis_inputs();
  nn::OutputEncoding encoding = nn::OutputEncoding::satilmis;
  std::optional<double> time_limit_s;  // absent: kSkyTimeLimitS, with --network per sub-network
  std::optional<int> iterations;       // absent: kSkyIterations, with --network per sub-network
  int starts = kSkyStarts, start_iterations = kSkyStartIterations;
  std::optional<double> max_error_percent;            // absent: the source's NeuralPolicy bound
  std::optional<double> target_scale;                 // absent: the source's NeuralPolicy
  int suns = 0, view_zeniths = 0, view_azimuths = 0;  // 0: the protocol's
  std::optional<nn::PietrasKind> network;             // a Pietras network instead
  std::optional<int> samples;  // absent: kPietrasSamples (--network), kImageSamples (images)
  std::string init;            // --network: a weights file to continue from
  PietrasRegion region = PietrasRegion::full;  // --network: what the samples cover
  ParameterValues planet;  // --network: nishita's planet and atmosphere as given

  static const ParameterSchema<NetworkTrainingRequest>& schema();
  // What is trained: a sky network on a model, on images, or a Pietras network.
  enum class Kind { sky, images, measured, pietras };
  // The parameters among `given` that this kind of training does not read (front ends warn):
  // the starts and the held-out bound are the sky network's on a model, --samples the others'.
  static std::vector<std::string> unread(const ParameterValues& given, Kind kind);
  // The model trained on (source, or the default).
  std::string source_model() const;
  // A sky network's training (InvalidArgument for the Pietras-only options).
  NeuralTraining sky_training() const;
  // A Pietras network's training (InvalidArgument unless the source is nishita, for --init with
  // the planet options, or an --init file of another kind); `initial` keeps the --init network
  // that the training points to. `output`: refused when it names the --init file.
  PietrasTraining pietras_training(std::optional<nn::PietrasNetwork>& initial,
                                   const std::string& output) const;
};

// A sky network trained on a sequence of HDR sky images (`nn train --images LIST`): the list
// (file[,sun_zenith_deg,sun_azimuth_deg][,time][,mask]), its images' projection and lens, a
// common mask, --lat/--lon for rows with a time, the sky mask's rules, K-fold cross-validation.
struct ImageTrainingOptions {
  std::string list, mask;
  ImageOptions image;  // the images' layout (equirect by default)
  std::optional<double> lat_deg, lon_deg;
  int kfold = 0;
  estimate::MaskSettings mask_settings;
  static const ParameterSchema<ImageTrainingOptions>& schema();
};

struct LoadedImage {
  estimate::SequenceEntry entry;
  estimate::SampledImage sampled;
  std::string sun_source;  // "list", "time", "image"
};
// The held-out captures of a sequence: every other capture between the first and the last (list
// order) is left out of a check network, trained on the others; the starts are judged on half of
// the held-out captures' sampled pixels and the network is measured on the other half. With the
// held-out captures gone the others are twice as far apart as in the final network's training:
// the check is an upper estimate of the error between the captures of the final network.
struct CaptureCheck {
  std::vector<std::size_t> held_out;  // indices into ImageTrainingResult::images
  std::size_t training_captures = 0;
  nn::ErrorStats errors;
  double max_relative_p95 = 0.0;
  bool passed() const { return errors.relative_p95 <= max_relative_p95; }
  // "held-out captures (lines 3 5 7, the network trained on the other 4): relative error median
  // 1.10 %, p95 3.50 % (bound 20 %)"
  std::string summary(const std::vector<LoadedImage>& images) const;
};

struct ImageTrainingResult {
  std::vector<LoadedImage> images;
  double target_scale = 0.0;
  std::size_t examples = 0;
  std::optional<nn::CrossValidation> cross_validation;  // with kfold > 0
  std::optional<CaptureCheck> check;                    // with 3 or more images and training.check
  nn::TrainedSkyNetwork trained;
  nn::ErrorStats errors;  // of the final network on all images
};
// progress(done, total, step) while images are read and folds trained (may be empty). With three
// or more images (and training.check) the check network is trained first, with training.starts
// judged on the held-out captures; a FitFailed error ("too sparse") when its p95 exceeds
// training.max_relative_p95 (default kImageMaxRelativeP95), else the final network continues from
// it on all images. With two images there is nothing between them to hold out: the starts are
// judged on the training error and nothing is checked.
// The list's checks that read no image: its rows, each row's sun (a time needs --lat and --lon),
// and that every image and mask it names is a file. InvalidArgument "<list>:<line>: ...".
void check_image_list(const ImageTrainingOptions& options);

// The network of a training on data (images, measured skies): t's layers, encoding and trainer
// options, without its progress callback (the caller reports per step).
nn::NetworkSetup data_network_setup(const NeuralTraining& t);

ImageTrainingResult train_on_images(
    const ImageTrainingOptions& options, const NeuralTraining& training, int samples_per_image,
    const std::function<void(int, int, const std::string&)>& progress = {});

// `nn validate`: the protocol's validation sets (0: their own sizes), Pietras's samples per set.
struct ValidationOptions {
  int suns = 0, view_zeniths = 0, view_azimuths = 0;
  int samples = 20000;
  static const ParameterSchema<ValidationOptions>& schema();
};

// The hidden-layer study of Satilmis et al. 2016 §III-B (Fig. 5, eq. 8; `nn study`): per hidden
// width a network trained with the protocol, its validation error, its evaluation time on the
// 1024 x 512 equirect grid (batch path, one thread, best of `repeats`) and the efficiency
// eps = 1 / (Var T), Var = the validation MSE (RMSE^2).
struct HiddenLayerStudy {
  std::string source;  // empty: the paper's Hosek-Wilkie
  std::vector<double> hidden{4, 8, 12, 16, 24, 32};
  int seed = 1, iterations = kSkyIterations, repeats = 5;
  double time_limit_s = kSkyTimeLimitS;
  int suns = 0, view_zeniths = 0, view_azimuths = 0;
  static const ParameterSchema<HiddenLayerStudy>& schema();
  std::string source_model() const;
};
struct StudyRow {
  int hidden = 0;
  std::size_t weights = 0;
  double rmse = 0, median = 0, p95 = 0, train_s = 0, grid_s = 0, efficiency = 0;
  std::string stop;
};
std::vector<StudyRow> study_hidden_layers(const HiddenLayerStudy& study,
                                          const std::function<void(int, int, int)>& progress = {});

}  // namespace skylight::fit
