// `skylight nn`: neural sky models (Satilmis et al. 2016; docs/NN.md) and the Pietras per-vertex
// networks (docs/PIETRAS.md): the family's subcommands, one file each.
#include "nn.h"

namespace skylight::cli {

void add_nn_command(CLI::App& app, Commands& commands) {
  auto* nn = app.add_subcommand(
      "nn",
      "neural sky models: train, validate, export, animate, study, planet\n"
      "Neural sky models (Satilmis et al. 2016; docs/NN.md) and the per-vertex network of the "
      "atmosphere (Pietras; docs/PIETRAS.md): train on a sky model or HDR photos, validate, export "
      "as GLSL, animate, the hidden-layer study, a planet in a vertex shader.");
  nn->require_subcommand(1);
  add_nn_train_command(*nn, commands);
  add_nn_validate_command(*nn, commands);
  add_nn_animate_command(*nn, commands);
  add_nn_study_command(*nn, commands);
  add_nn_planet_command(*nn, commands);
}

}  // namespace skylight::cli
