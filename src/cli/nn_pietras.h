// `skylight nn train --network pietras|log3` and `nn validate` of a Pietras weights file
// (docs/PIETRAS.md), called from nn_cmd.cpp.
#pragma once

#include <CLI/CLI.hpp>

#include <map>
#include <optional>
#include <string>

namespace skylight::cli {

struct PietrasTrainArgs {
  std::string network;  // pietras, log3
  std::string source;   // must be nishita
  std::string trainer;  // train.h's names
  int samples = 800000;
  int seed = 1;
  int iterations = 4000;        // per sub-network
  double time_limit_s = 600.0;  // per sub-network
  std::string output;
  // The nishita planet and atmosphere (add_planet_flags): given values over Earth's defaults.
  std::map<std::string, std::optional<double>> planet;
  std::string init;  // --init: a weights file to continue from (its planet); empty: none
};
// The nishita schema's planet and atmosphere parameters (ground-radius, top-radius, scale
// heights, mie-g, ozone, solar-irradiance) as flags of `nn train`, into `values` by name.
void add_planet_flags(CLI::App& train, std::map<std::string, std::optional<double>>& values);
// True when any of them was given.
bool planet_given(const std::map<std::string, std::optional<double>>& values);
int run_pietras_train(const PietrasTrainArgs& a, const std::string& date,
                      const std::string& software);
// Validation sets of `samples` each (day, twilight, night), seed fixed.
int run_pietras_validate(const std::string& weights, const std::string& text, bool json,
                         int samples);

}  // namespace skylight::cli
