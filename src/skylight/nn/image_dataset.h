// Neural sky models from sky images (Satilmis et al. 2016 §III-D): the sky pixels of an image
// sequence as a Dataset (one sky state per image, the image's sun, turbidity input 0), training a
// SkyNetwork on any Dataset, and K-fold cross-validation over sky states (§IV-A: leave one sun
// position, or one image, out). nn/ reads no images: estimate/sky_sequence.h turns photographs
// into ImageSamples. docs/NN.md.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/nn/dataset.h"
#include "skylight/nn/metrics.h"
#include "skylight/nn/sky_network.h"
#include "skylight/nn/train.h"

namespace skylight::nn {

// The sampled sky pixels of one image.
struct ImageSamples {
  SkyState state;           // the image's sun; turbidity 0 (the input unused, §III-D)
  std::vector<Vec3> views;  // unit vectors, world frame
  std::vector<Rgb> rgb;     // the pixels' linear RGB, in the image's unit
};

// The target scale of an image-trained network: the median over all samples and channels of the
// pixel values, divided by kImageTargetMedian, so that the normalised radiance L = value /
// target_scale has its median where the paper's analytic sets have theirs (~0.04-0.05 at target
// scales 1000 and 683; docs/NN.md). InvalidArgument when the median is not positive.
inline constexpr double kImageTargetMedian = 0.05;
double image_target_scale(const std::vector<ImageSamples>& images);

// The examples of every image, in image order: state s = image s, radiance = rgb / target_scale.
// spec.source = "images", spec.target_scale, spec.sun_count = number of images.
Dataset image_dataset(const std::vector<ImageSamples>& images, const InputSpec& inputs,
                      double target_scale);

// The examples whose state is kept (keep.size() == ds.states.size()); states renumbered in order.
Dataset subset_by_state(const Dataset& ds, const std::vector<bool>& keep);
// Every `every`-th example from example `first` on (states unchanged): disjoint parts of a set.
Dataset every_nth_example(const Dataset& ds, std::size_t every, std::size_t first);

// A network and how to train it.
struct NetworkSetup {
  std::vector<int> hidden{12};
  OutputEncoding encoding = OutputEncoding::satilmis;
  TrainOptions options;
};

struct TrainedSkyNetwork {
  SkyNetwork network;  // provenance: source, sampling counts, trainer, seed, stop, seconds, mse
  TrainResult train;
};

// Trains the network of `setup` on all examples of ds (hidden layers satilmis; output satilmis
// for the satilmis encoding, identity otherwise). provenance.source = ds.spec.source,
// provenance.turbidities = the states' distinct turbidities.
TrainedSkyNetwork train_sky_network(const Dataset& ds, const NetworkSetup& setup);

// K-fold cross-validation over sky states: fold k holds out the states s with s mod K == k (K =
// the number of states: leave one image out; K smaller: every K-th image, so each fold's held-out
// images are spread over the sequence and are interpolated, not extrapolated), trains on the rest
// and measures the held-out examples (metrics.h).
struct FoldResult {
  std::vector<int> held_out;  // state indices
  std::size_t training_examples = 0, test_examples = 0;
  double training_rmse = 0.0;  // sqrt(training MSE), encoded outputs
  ErrorStats errors;           // on the held-out examples
};
struct CrossValidation {
  std::vector<FoldResult> folds;
  double mean_rmse = 0.0;  // mean over folds of errors.rmse
  double mean_relative_median = 0.0;
  double mean_relative_p95 = 0.0;
};
// InvalidArgument unless 2 <= folds <= ds.states.size(). on_fold(k, folds) before each fold.
CrossValidation cross_validate(const Dataset& ds, int folds, const NetworkSetup& setup,
                               const std::function<void(int, int)>& on_fold = {});

}  // namespace skylight::nn
