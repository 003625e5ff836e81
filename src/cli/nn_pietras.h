// `skylight nn train --network pietras|log3` and `nn validate` of a Pietras weights file
// (docs/PIETRAS.md), called from nn_cmd.cpp.
#pragma once

#include <string>

namespace skylight::cli {

struct PietrasTrainArgs {
  std::string network;  // pietras, log3
  std::string source;   // must be nishita
  std::string trainer;
  int samples = 800000;
  int seed = 1;
  int iterations = 500;
  double time_limit_s = 60.0;  // per sub-network
  std::string output;
};
int run_pietras_train(const PietrasTrainArgs& a, const std::string& date,
                      const std::string& software);
// Validation sets of `samples` each (day, twilight, night), seed fixed.
int run_pietras_validate(const std::string& weights, const std::string& text, bool json,
                         int samples);

}  // namespace skylight::cli
