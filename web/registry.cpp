// The model registry of the page's WebAssembly build (web/CMakeLists.txt): in place of
// src/skylight/models/registry.cpp, the entries of the models whose sources the build compiles,
// each declared in its own source file as in the library: every model but sh, which has no GPU
// form (ModelInfo::no_gpu). The physical atmospheres compute their tables in the page (bruneton's
// take 20-40 s there, single-threaded: docs/VIEWER.md).
#include "skylight/models/bruneton.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/hillaire.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/nishita.h"
#include "skylight/models/perez.h"
#include "skylight/models/pietras.h"
#include "skylight/models/preetham.h"
#include "skylight/models/sky_model.h"

namespace skylight {

const std::vector<ModelInfo>& model_registry() {
  static const std::vector<ModelInfo> registry{
      PerezModel::registry_entry(),     PreethamModel::registry_entry(),
      CieSkyModel::registry_entry(),    HosekWilkieModel::registry_entry(),
      NeuralSkyModel::registry_entry(), PietrasSkyModel::registry_entry(),
      NishitaModel::registry_entry(),   HillaireModel::registry_entry(),
      BrunetonModel::registry_entry(),
  };
  return registry;
}

}  // namespace skylight
