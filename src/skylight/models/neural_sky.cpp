#include "skylight/models/neural_sky.h"

#include <fmt/format.h>
#include <algorithm>
#include <array>
#include <cmath>

#include "skylight/core/data.h"
#include "skylight/core/math.h"
#include "skylight/io/file.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/preetham.h"
#include "skylight/nn/glsl.h"
#include "skylight/nn/pietras.h"

namespace skylight {

const ParameterSchema<NeuralSkyParameters>& NeuralSkyParameters::schema() {
  static const auto s = [] {
    ParameterSchema<NeuralSkyParameters> s;
    const NeuralSkyParameters defaults;
    s.text(&NeuralSkyParameters::weights,
           {.name = "weights",
            .kind = ParameterKind::text,
            .default_value = Absent{"the embedded 6-12-3 network trained on preetham (data/nn/)"},
            .description = "weights file of a trained neural sky (skylight nn train; docs/NN.md)"});
    s.number(
        &NeuralSkyParameters::turbidity,
        {.name = "turbidity",
         .unit = "1",
         .min = kNeuralTurbidityMin,
         .max = kNeuralTurbidityMax,
         .default_value = ParameterValue(defaults.turbidity),
         .description =
             "atmospheric turbidity T, the network's sqrt(T) input (trained range: the weights "
             "file's provenance)"});
    return s;
  }();
  return s;
}

nn::SkyNetwork load_sky_network_file(const std::filesystem::path& path) {
  const std::string text = io::read_text_file(path);
  if (nn::is_pietras_json(text))
    throw InvalidArgument(fmt::format(
        "{}: a Pietras network ({}), not a sky network ({}): the model pietras reads it "
        "(models/pietras.h)",
        path.string(), nn::kPietrasFormat, nn::kSkyNetworkFormat));
  return nn::sky_network_from_json(text, path.string());
}

const nn::SkyNetwork& embedded_sky_network() {
  static const nn::SkyNetwork net = nn::sky_network_from_json(
      data::embedded_file(kEmbeddedSkyNetwork), std::string("data/") + kEmbeddedSkyNetwork);
  return net;
}

NeuralSkyModel::NeuralSkyModel(const NeuralSkyParameters& p) : SkyModel(p.sun), params_(p) {
  NeuralSkyParameters::schema().validate(p, model_context(kName));
  if (!p.weights.empty()) {
    network_ = load_sky_network_file(p.weights);
  } else {
    network_ = embedded_sky_network();
  }
  init_sky();
}

NeuralSkyModel::NeuralSkyModel(const NeuralSkyParameters& p, nn::SkyNetwork network)
    : SkyModel(p.sun), params_(p), network_(std::move(network)) {
  NeuralSkyParameters::schema().validate(p, model_context(kName));
  init_sky();
}

void NeuralSkyModel::init_sky() {
  const NeuralSkyParameters& p = params_;
  if (network_.net.layout().outputs() != 3 ||
      network_.net.layout().inputs() != static_cast<int>(network_.inputs.size())) {
    throw InvalidArgument("model 'nn': the network needs one input per input name and 3 outputs");
  }
  // A network trained on a source without turbidity saw the input 0 (Satilmis et al. 2016: unused
  // inputs are zero); --turbidity then does not apply.
  const auto& t = network_.provenance.turbidities;
  turbidity_unused_ = t.size() == 1 && t.front() == 0.0;
  state_.turbidity = turbidity_unused_ ? 0.0 : p.turbidity;
  state_.sun_zenith = p.sun.zenith;
  state_.sun_azimuth = p.sun.azimuth;
  state_.ground_albedo = network_.provenance.ground_albedo;
  sun_up_ = p.sun.zenith <= kPi / 2;
  batch_ = std::make_unique<nn::SkyNetworkBatch>(network_, state_);
}

ParameterValues NeuralSkyModel::parameter_values() const {
  ParameterValues v = NeuralSkyParameters::schema().values_of(params_);
  if (turbidity_unused_) v.erase("turbidity");  // the network has no turbidity input
  return v;
}

Rgb NeuralSkyModel::rgb(Vec3 view) const {
  if (!sun_up_) return {};
  return network_.rgb(state_, view);
}

Xyz NeuralSkyModel::tristimulus(Vec3 view) const {
  return linear_srgb_to_xyz(rgb(view));
}

void NeuralSkyModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  if (!sun_up_) {
    std::fill(out.X.begin(), out.X.end(), 0.0f);
    std::fill(out.Y.begin(), out.Y.end(), 0.0f);
    std::fill(out.Z.begin(), out.Z.end(), 0.0f);
    return;
  }
  // rgb into the output spans, then the 3x3 matrix in place.
  batch_->rgb(dirs.x.data(), dirs.y.data(), dirs.z.data(), out.X.data(), out.Y.data(), out.Z.data(),
              dirs.size());
  linear_srgb_to_xyz_in_place(out);
}

Domain NeuralSkyModel::domain() const {
  Domain d;
  if (!sun_up_) {
    d.issues.push_back({"sun_zenith", Validity::undefined,
                        "the sun is below the horizon: the network was trained for suns in "
                        "0-90 deg zenith; sky returned as 0"});
  }
  const auto& t = network_.provenance.turbidities;
  if (!t.empty() && !turbidity_unused_) {
    const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
    if (params_.turbidity < *lo || params_.turbidity > *hi) {
      d.issues.push_back({"turbidity", Validity::extrapolated,
                          fmt::format("turbidity {} is outside the network's training range "
                                      "{}-{} ({}): extrapolated",
                                      params_.turbidity, *lo, *hi, network_.provenance.source)});
    }
  }
  return d;
}

// The turbidities the embedded 6-12-3 network was trained on (data/nn/PROVENANCE.md).
constexpr std::array<double, 2> kEmbeddedNetworkTurbidity{2.0, 6.0};

ModelInfo NeuralSkyModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "Neural sky model (Satilmis et al. 2016): a small MLP trained on another sky model "
          "(skylight nn train), e.g. the paper's 6-12-3 network; fixed cost per direction",
      .output =
          "rgb = the network's linear sRGB in the units of its source model's rgb() (the weights "
          "file's target_scale); XYZ = rgb converted (D65)",
      .parameters = NeuralSkyParameters::schema().specs(),
      .domain =
          "the source model's validity within the network's training range (weights file "
          "provenance: turbidities, suns 0-90 deg); outside it extrapolated (flagged); sun below "
          "the horizon: 0 (undefined); no spectral output, no solar disc",
      .make = model_factory<NeuralSkyModel, NeuralSkyParameters>(),
      // T = 1..10 of the turbidity input
      .neural = NeuralPolicy::over_turbidity(1.0, 10.0),
      // The embedded network's turbidity input over the range it was trained on.
      .estimation = registry_estimation(
          std::string(kName),
          {{.parameter = "turbidity",
            .label = "turbidity",
            .min = kEmbeddedNetworkTurbidity[0],
            .max = kEmbeddedNetworkTurbidity[1],
            .grid_points = 9}},
          "the turbidity input of the network (the embedded one: trained on preetham at T "
          "2-6), free luminance scale"),
      .sh_fit = ShFitPolicy{.parameter = "turbidity"},
      // Satilmis et al. 2016 compare the network with the Hosek-Wilkie model it replaces.
      .bench = BenchPolicy{.by_default = true,
                           .baseline = std::string(HosekWilkieModel::kName),
                           .label = "nn (6-12-3)"},
      // The embedded 6-12-3 network: trained on preetham at T 2-6 (data/nn/PROVENANCE.md; its
      // weights file's provenance.turbidities, checked by ReportPolicyMatchesTheEmbeddedData).
      .report = ReportPolicy{.title = "nn 6-12-3",
                             .axis = "turbidity",
                             .axis_label = "T = ",
                             .colour = "#e377c2",
                             .axis_range = kEmbeddedNetworkTurbidity,
                             .source = std::string(PreethamModel::kName)},
  };
}

std::optional<GpuSky> NeuralSkyModel::gpu_sky() const {
  // rgb(): the network (nn/glsl.h) with this model's sky state; 0 for a sun below the horizon.
  GpuSky g;
  g.glsl = nn::glsl_sky_network(network_) +
           "uniform float skylight_sun_zenith, skylight_sun_azimuth, skylight_turbidity;\n"
           "uniform int skylight_sun_up;\n";
  g.expression =
      "(skylight_sun_up != 0 ? skylight_sky_state(dir, skylight_sun_zenith, skylight_sun_azimuth, "
      "skylight_turbidity) : vec3(0.0))";
  g.output = GpuSky::Output::rgb;
  g.uniforms = {gpu_uniform("skylight_sun_zenith", {state_.sun_zenith}),
                gpu_uniform("skylight_sun_azimuth", {state_.sun_azimuth}),
                gpu_uniform("skylight_turbidity", {state_.turbidity}),
                gpu_int_uniform("skylight_sun_up", state_.sun_zenith <= kPi / 2 ? 1 : 0)};
  g.comment = "nn: a network learned from " + network_.provenance.source;
  return g;
}

}  // namespace skylight
