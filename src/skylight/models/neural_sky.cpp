#include "skylight/models/neural_sky.h"

#include <fmt/format.h>
#include <algorithm>
#include <array>
#include <cmath>

#include "skylight/core/data.h"
#include "skylight/core/math.h"
#include "skylight/io/file.h"
#include "skylight/models/nishita.h"

namespace skylight {

const ParameterSchema<NeuralSkyParameters>& NeuralSkyParameters::schema() {
  static const auto s = [] {
    ParameterSchema<NeuralSkyParameters> s;
    const NeuralSkyParameters defaults;
    s.text(&NeuralSkyParameters::weights,
           {"weights", "", ParameterKind::text, 0, 0, 1,
            Absent{"the embedded 6-12-3 network trained on preetham (data/nn/)"},
            "weights file of a trained neural sky (skylight nn train; docs/NN.md)"});
    s.number(&NeuralSkyParameters::turbidity,
             {"turbidity", "1", ParameterKind::number, kNeuralTurbidityMin, kNeuralTurbidityMax, 1,
              ParameterValue(defaults.turbidity),
              "atmospheric turbidity T, the network's sqrt(T) input (trained range: the weights "
              "file's provenance)"});
    s.number(&NeuralSkyParameters::observer_altitude_m,
             {"observer-altitude", "m", ParameterKind::number, 0.0, kNishitaMaxAltitude, 1,
              ParameterValue(defaults.observer_altitude_m),
              "observer above the ground (Pietras networks: the density input; others ignore it)"});
    return s;
  }();
  return s;
}

nn::SkyNetwork load_sky_network_file(const std::filesystem::path& path) {
  const std::string text = io::read_text_file(path);
  if (nn::is_pietras_json(text))
    throw InvalidArgument(fmt::format(
        "{}: a Pietras network ({}), not a sky network ({}): this loader reads sky networks "
        "only (the model nn, eval, render and the nn commands take both)",
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
    const std::string text = io::read_text_file(p.weights);
    if (nn::is_pietras_json(text)) {
      pietras_ = std::make_unique<nn::PietrasNetwork>(nn::pietras_from_json(text, p.weights));
      pietras_batch_ = std::make_unique<nn::PietrasBatch>(*pietras_, p.observer_altitude_m,
                                                          std::cos(p.sun.zenith));
      return;
    }
    network_ = nn::sky_network_from_json(text, p.weights);
  } else {
    network_ = embedded_sky_network();
  }
  init_sky();
}

NeuralSkyModel::NeuralSkyModel(const NeuralSkyParameters& p, nn::PietrasNetwork network)
    : SkyModel(p.sun), params_(p) {
  NeuralSkyParameters::schema().validate(p, model_context(kName));
  pietras_ = std::make_unique<nn::PietrasNetwork>(std::move(network));
  pietras_batch_ =
      std::make_unique<nn::PietrasBatch>(*pietras_, p.observer_altitude_m, std::cos(p.sun.zenith));
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
  return NeuralSkyParameters::schema().values_of(params_);
}

Rgb NeuralSkyModel::rgb(Vec3 view) const {
  if (pietras_) {
    const Vec3 v = normalize(view);
    return pietras_->rgb_at(params_.observer_altitude_m, v.z, dot(v, sun().direction()),
                            std::cos(sun().zenith));
  }
  if (!sun_up_) return {};
  return network_.rgb(state_, view);
}

Xyz NeuralSkyModel::tristimulus(Vec3 view) const {
  return linear_srgb_to_xyz(rgb(view));
}

void NeuralSkyModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  const std::size_t n = dirs.size();
  if (pietras_) {
    // cos alpha0 = z, cos beta0 = view . sun; then rgb into the output spans.
    const Vec3 s = sun().direction();
    std::vector<float> cb(n);
    for (std::size_t i = 0; i < n; ++i)
      cb[i] = static_cast<float>(s.x * dirs.x[i] + s.y * dirs.y[i] + s.z * dirs.z[i]);
    pietras_batch_->rgb(dirs.z.data(), cb.data(), out.X.data(), out.Y.data(), out.Z.data(), n);
  } else if (!sun_up_) {
    std::fill(out.X.begin(), out.X.end(), 0.0f);
    std::fill(out.Y.begin(), out.Y.end(), 0.0f);
    std::fill(out.Z.begin(), out.Z.end(), 0.0f);
    return;
  } else {
    // rgb into the output spans, then the 3x3 matrix in place.
    batch_->rgb(dirs.x.data(), dirs.y.data(), dirs.z.data(), out.X.data(), out.Y.data(),
                out.Z.data(), n);
  }
  const Matrix3& m = srgb_to_xyz_matrix();
  std::array<float, 9> f{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) f[3 * r + c] = static_cast<float>(m[r][c]);
  for (std::size_t i = 0; i < n; ++i) {
    const float R = out.X[i], G = out.Y[i], B = out.Z[i];
    out.X[i] = f[0] * R + f[1] * G + f[2] * B;
    out.Y[i] = f[3] * R + f[4] * G + f[5] * B;
    out.Z[i] = f[6] * R + f[7] * G + f[8] * B;
  }
}

Domain NeuralSkyModel::domain() const {
  Domain d;
  if (pietras_) return d;
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
  };
}

}  // namespace skylight
