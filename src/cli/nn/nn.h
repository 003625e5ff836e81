// The `skylight nn` family (docs/NN.md, docs/PIETRAS.md): train, validate, export (nn.cpp),
// animate, study and planet, one file each; their options are the library's operations
// (operations/operations.h) and the work the library's (fit/network_training.h, ...).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "../common.h"

namespace skylight::cli {

void add_nn_train_command(CLI::App& nn, Commands& commands);
void add_nn_validate_command(CLI::App& nn, Commands& commands);
void add_nn_animate_command(CLI::App& nn, Commands& commands);
void add_nn_study_command(CLI::App& nn, Commands& commands);
void add_nn_planet_command(CLI::App& nn, Commands& commands);

// ISO 8601 UTC of now, for provenance.date.
std::string utc_now_iso8601();
// A fraction as a percentage with two decimals ("1.69 %"), as the nn commands print errors.
std::string percent(double fraction);

}  // namespace skylight::cli
