// The neural sky model of Satilmis et al. 2016 as a SkyModel (`nn`): a trained network
// (nn/sky_network.h) loaded from a weights file (docs/NN.md), evaluated for one sky state (sun,
// turbidity). rgb() is the network's output, in the units of the source model's rgb() (the
// network learns rgb / target_scale and multiplies back); tristimulus() is that rgb converted to
// XYZ (linear sRGB, D65). See docs/MODELS.md and docs/NN.md.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "skylight/models/sky_model.h"
#include "skylight/nn/sky_network.h"

namespace skylight {

// Turbidity accepted by `nn` (the network extrapolates outside its training range, which
// domain() then reports; the inputs stay finite and the outputs bounded for any value here).
inline constexpr double kNeuralTurbidityMin = 1.0;
inline constexpr double kNeuralTurbidityMax = 64.0;
// The network bundled with skylight (data/nn/, embedded): the paper's 6-12-3 network trained on
// `preetham` with the default trainer (docs/NN.md).
inline constexpr const char* kEmbeddedSkyNetwork = "nn/preetham_6-12-3.json";

struct NeuralSkyParameters {
  SunPosition sun;
  std::string weights;     // --weights FILE; empty: the embedded network (kEmbeddedSkyNetwork)
  double turbidity = 3.0;  // --turbidity T [1], the network's sqrt(T) input

  static const ParameterSchema<NeuralSkyParameters>& schema();
};

// Reads and checks a weights file: IoError when it cannot be read, InvalidArgument (naming the
// file and the field) when its content is malformed or inconsistent (nn::sky_network_from_json),
// or when it is a Pietras network (models/pietras.h reads those).
nn::SkyNetwork load_sky_network_file(const std::filesystem::path& path);
// The embedded network (parsed once).
const nn::SkyNetwork& embedded_sky_network();

// The `nn` model. A network trained on a source without turbidity (provenance turbidities {0})
// gets the input 0 whatever --turbidity says. Views below the horizon and a sun below the horizon
// return 0 (the network was trained for suns in [0, pi/2]: below, domain() says undefined). Batch
// path: SkyNetworkBatch (float SIMD; error against the scalar double path:
// kNeuralBatchRelativeTolerance in the tests).
class NeuralSkyModel final : public SkyModel {
 public:
  explicit NeuralSkyModel(const NeuralSkyParameters& p);
  // A sky network given in code, e.g. one just trained (p.weights only describes it).
  NeuralSkyModel(const NeuralSkyParameters& p, nn::SkyNetwork network);

  static constexpr std::string_view kName = "nn";
  // The registry entry: documentation, schema, factory and policy (models/sky_model.h).
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  ParameterValues parameter_values() const override;
  Xyz tristimulus(Vec3 view) const override;
  Rgb rgb(Vec3 view) const override;
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  Domain domain() const override;
  std::optional<GpuSky> gpu_sky() const override;

  const nn::SkyNetwork& network() const { return network_; }
  const nn::SkyState& state() const { return state_; }

 private:
  void init_sky();
  NeuralSkyParameters params_;
  nn::SkyNetwork network_;
  nn::SkyState state_;
  bool sun_up_ = true;
  bool turbidity_unused_ = false;  // trained on a source without turbidity: the input is 0
  std::unique_ptr<nn::SkyNetworkBatch> batch_;
};

}  // namespace skylight
