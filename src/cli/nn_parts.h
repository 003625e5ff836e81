// The parts of the `skylight nn` family (nn_cmd.cpp) that live in their own files: training on
// sky-image sequences with K-fold cross-validation (nn_images_cmd.cpp), `nn animate`
// (nn_animate_cmd.cpp), the hidden-layer study `nn study` (nn_study_cmd.cpp) and `nn planet`
// (nn_planet_cmd.cpp). docs/NN.md, docs/PIETRAS.md.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

#include "common.h"
#include "skylight/fit/neural_training.h"

namespace skylight::cli {

struct ImageTrainFlags;
// Adds --images and its flags (projection, mask, sun, sampling, --kfold) to `nn train`.
std::shared_ptr<ImageTrainFlags> add_image_train_flags(CLI::App& train);
bool images_given(const ImageTrainFlags& f);
// `nn train --images LIST`: the network of `t` (hidden, inputs, encoding, target scale, trainer
// options) trained on the list's images; writes `output` and the training log `log` (when not
// empty); `samples_per_image` sky pixels are drawn from each image (all when it has fewer).
int run_train_images(const ImageTrainFlags& f, const fit::NeuralTraining& t,
                     const std::string& output, const std::string& log, int samples_per_image);

void add_nn_animate_command(CLI::App& nn, Commands& commands);
void add_nn_study_command(CLI::App& nn, Commands& commands);
// `nn planet` (nn_planet_cmd.cpp): the Pietras vertex shader's planet (gpu/planet.h).
void add_nn_planet_command(CLI::App& nn, Commands& commands);

// ISO 8601 UTC of now, for provenance.date.
std::string utc_now_iso8601();
// A fraction as a percentage with two decimals ("1.69 %"), as the nn commands print errors.
std::string percent(double fraction);

}  // namespace skylight::cli
