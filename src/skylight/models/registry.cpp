// The model registry: every model's entry, declared in its own source file
// (`<Model>::registry_entry()`: documentation, schema, factory and per-model policy).
#include "skylight/models/bruneton.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/hillaire.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/nishita.h"
#include "skylight/models/perez.h"
#include "skylight/models/pietras.h"
#include "skylight/models/preetham.h"
#include "skylight/models/sh.h"
#include "skylight/models/sky_model.h"

namespace skylight {

const std::vector<ModelInfo>& model_registry() {
  static const std::vector<ModelInfo> registry{
      PerezModel::registry_entry(),      PreethamModel::registry_entry(),
      CieSkyModel::registry_entry(),     HosekWilkieModel::registry_entry(),
      NishitaModel::registry_entry(),    HillaireModel::registry_entry(),
      BrunetonModel::registry_entry(),   NeuralSkyModel::registry_entry(),
      PietrasSkyModel::registry_entry(), ShSkyModel::registry_entry(),
  };
  return registry;
}

}  // namespace skylight
