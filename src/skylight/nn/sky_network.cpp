#include "skylight/nn/sky_network.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "skylight/core/detail/json_reader.h"
#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/nn/detail/mlp_kernel.h"

namespace skylight::nn {

std::vector<double> SkyNetwork::output(const SkyState& state, Vec3 view) const {
  std::vector<double> in(inputs.size());
  compute_inputs(inputs, state, view, in);
  return net(in);
}

Rgb SkyNetwork::rgb(const SkyState& state, Vec3 view) const {
  if (view.z < 0.0) return {};
  const auto y = output(state, view);
  return {target_scale * radiance(y[0]), target_scale * radiance(y[1]),
          target_scale * radiance(y[2])};
}

// ---- weights file
// --------------------------------------------------------------------------------

namespace {

// The strict reader of core/json_reader.h.
using namespace skylight::detail::json;  // NOLINT(google-build-using-namespace)

// The widest layer a weights file may describe: what the batch kernels accept (this also guards
// the allocation of a corrupt file).
constexpr long long kMaxFileWidth = detail::kMaxBatchWidth;
constexpr long long kMaxFileLayers = 16;

constexpr const char* kInputTransform =
    "views rotated about the zenith by phi_sun - pi (Satilmis et al. 2016 eq. 10) before v_x, "
    "v_y; chord d = |omega_sun - omega_view|; angles in radians";
constexpr const char* kParameterOrder =
    "for each layer k = 1..L: weights W^k row-major (n_k rows of n_(k-1)), then biases (n_k)";

}  // namespace

std::string to_json(const SkyNetwork& sky) {
  const MlpLayout& l = sky.net.layout();
  nlohmann::json j;
  j["format"] = kSkyNetworkFormat;
  j["version"] = kSkyNetworkVersion;
  nlohmann::json arch;
  arch["widths"] = l.widths;
  std::vector<std::string> acts;
  for (Activation a : l.activations) acts.emplace_back(to_string(a));
  arch["activations"] = acts;
  arch["parameter_order"] = kParameterOrder;
  j["architecture"] = arch;
  std::vector<std::string> ins;
  for (Input in : sky.inputs) ins.emplace_back(to_string(in));
  j["inputs"] = ins;
  j["input_transform"] = kInputTransform;
  j["output_encoding"] = to_string(sky.encoding);
  j["target_scale"] = sky.target_scale;
  if (sky.max_radiance) j["max_radiance"] = *sky.max_radiance;
  const auto p = sky.net.parameters();
  j["parameters"] = std::vector<double>(p.begin(), p.end());
  const SkyNetworkProvenance& pv = sky.provenance;
  nlohmann::json prov;
  prov["source"] = pv.source;
  prov["turbidities"] = pv.turbidities;
  prov["ground_albedo"] = pv.ground_albedo;
  prov["sun_count"] = pv.sun_count;
  prov["view_zeniths"] = pv.view_zeniths;
  prov["view_azimuths"] = pv.view_azimuths;
  prov["seed"] = pv.seed;
  prov["trainer"] = pv.trainer;
  prov["iterations"] = pv.iterations;
  prov["stop"] = pv.stop;
  prov["training_seconds"] = pv.training_seconds;
  prov["training_mse"] = pv.training_mse;
  nlohmann::json metrics = nlohmann::json::object();
  if (pv.validation_rmse) metrics["rmse"] = *pv.validation_rmse;
  if (pv.validation_relative_median) metrics["relative_median"] = *pv.validation_relative_median;
  if (pv.validation_relative_p95) metrics["relative_p95"] = *pv.validation_relative_p95;
  prov["validation"] = metrics;
  prov["date"] = pv.date;
  prov["software"] = pv.software;
  j["provenance"] = prov;
  return j.dump(1) + "\n";
}

namespace {

// The "architecture" object of a sky-network file.
MlpLayout read_architecture(const nlohmann::json& j, const std::string& where) {
  const auto& arch = field(j, where, "architecture");
  if (!arch.is_object()) bad(where, "architecture", "is not an object");
  MlpLayout layout;
  for (const auto& w :
       array(field(arch, where, "widths", "architecture."), where, "architecture.widths"))
    layout.widths.push_back(
        static_cast<int>(integer(w, where, "architecture.widths", 1, kMaxFileWidth)));
  if (layout.widths.size() < 2 || static_cast<long long>(layout.widths.size()) > kMaxFileLayers + 1)
    bad(where, "architecture.widths",
        "needs 2 to " + std::to_string(kMaxFileLayers + 1) + " layers");
  if (layout.widths.back() != 3)
    bad(where, "architecture.widths", "must end in 3 outputs (r, g, b)");
  for (const auto& a : array(field(arch, where, "activations", "architecture."), where,
                             "architecture.activations")) {
    const std::string name = text(a, where, "architecture.activations");
    const auto act = parse_activation(name);
    if (!act)
      bad(where, "architecture.activations", "has an unknown activation '" + excerpt(name) + "'");
    layout.activations.push_back(*act);
  }
  if (static_cast<int>(layout.activations.size()) != layout.layers())
    bad(where, "architecture.activations", "needs one activation per layer");
  return layout;
}

// The "provenance" object of a sky-network file.
SkyNetworkProvenance read_provenance(const nlohmann::json& j, const std::string& where) {
  const auto& pj = field(j, where, "provenance");
  if (!pj.is_object()) bad(where, "provenance", "is not an object");
  SkyNetworkProvenance pv;
  pv.source = text(field(pj, where, "source", "provenance."), where, "provenance.source");
  pv.turbidities =
      numbers(field(pj, where, "turbidities", "provenance."), where, "provenance.turbidities");
  pv.ground_albedo =
      number(field(pj, where, "ground_albedo", "provenance."), where, "provenance.ground_albedo");
  pv.sun_count = static_cast<int>(integer(field(pj, where, "sun_count", "provenance."), where,
                                          "provenance.sun_count", 0, 1 << 30));
  pv.view_zeniths = static_cast<int>(integer(field(pj, where, "view_zeniths", "provenance."), where,
                                             "provenance.view_zeniths", 0, 1 << 30));
  pv.view_azimuths = static_cast<int>(integer(field(pj, where, "view_azimuths", "provenance."),
                                              where, "provenance.view_azimuths", 0, 1 << 30));
  const auto& seed = field(pj, where, "seed", "provenance.");
  if (!seed.is_number_unsigned()) bad(where, "provenance.seed", "is not an unsigned integer");
  pv.seed = seed.get<std::uint64_t>();
  pv.trainer = text(field(pj, where, "trainer", "provenance."), where, "provenance.trainer");
  pv.iterations = static_cast<int>(integer(field(pj, where, "iterations", "provenance."), where,
                                           "provenance.iterations", 0, 1 << 30));
  pv.stop = text(field(pj, where, "stop", "provenance."), where, "provenance.stop");
  pv.training_seconds = number(field(pj, where, "training_seconds", "provenance."), where,
                               "provenance.training_seconds");
  pv.training_mse =
      number(field(pj, where, "training_mse", "provenance."), where, "provenance.training_mse");
  const auto& vj = field(pj, where, "validation", "provenance.");
  if (!vj.is_object()) bad(where, "provenance.validation", "is not an object");
  auto optional_number = [&](const char* name, std::optional<double>& out) {
    if (vj.contains(name))
      out = number(vj.at(name), where, std::string("provenance.validation.") + name);
  };
  optional_number("rmse", pv.validation_rmse);
  optional_number("relative_median", pv.validation_relative_median);
  optional_number("relative_p95", pv.validation_relative_p95);
  pv.date = text(field(pj, where, "date", "provenance."), where, "provenance.date");
  pv.software = text(field(pj, where, "software", "provenance."), where, "provenance.software");
  return pv;
}

}  // namespace

SkyNetwork sky_network_from_json(std::string_view s, const std::string& where) {
  const nlohmann::json j = skylight::detail::json::parse_object(s, where);
  if (text(field(j, where, "format"), where, "format") != kSkyNetworkFormat)
    bad(where, "format", "is not '" + std::string(kSkyNetworkFormat) + "'");
  if (integer(field(j, where, "version"), where, "version", 0, 1000000) != kSkyNetworkVersion)
    bad(where, "version", "is not " + std::to_string(kSkyNetworkVersion));

  MlpLayout layout = read_architecture(j, where);
  SkyNetwork sky;
  sky.inputs.clear();
  for (const auto& in : array(field(j, where, "inputs"), where, "inputs")) {
    const std::string name = text(in, where, "inputs");
    const auto parsed = parse_input(name);
    if (!parsed) bad(where, "inputs", "has an unknown input '" + excerpt(name) + "'");
    sky.inputs.push_back(*parsed);
  }
  if (static_cast<int>(sky.inputs.size()) != layout.inputs())
    bad(where, "inputs",
        "has " + std::to_string(sky.inputs.size()) + " entries but the first layer has " +
            std::to_string(layout.inputs()));
  text(field(j, where, "input_transform"), where, "input_transform");
  const std::string enc = text(field(j, where, "output_encoding"), where, "output_encoding");
  const auto encoding = parse_output_encoding(enc);
  if (!encoding) bad(where, "output_encoding", "is not a known encoding: '" + excerpt(enc) + "'");
  sky.encoding = *encoding;
  sky.target_scale = number(field(j, where, "target_scale"), where, "target_scale");
  if (!(sky.target_scale > 0.0)) bad(where, "target_scale", "is not positive");
  if (j.contains("max_radiance")) {
    sky.max_radiance = number(j.at("max_radiance"), where, "max_radiance");
    if (!(*sky.max_radiance > 0.0)) bad(where, "max_radiance", "is not positive");
  }
  std::vector<double> params = numbers(field(j, where, "parameters"), where, "parameters");
  check_weight_magnitudes(params, where, "parameters");
  if (params.size() != layout.parameter_count())
    bad(where, "parameters",
        "has " + std::to_string(params.size()) + " values, the architecture " +
            std::to_string(layout.parameter_count()));

  sky.provenance = read_provenance(j, where);
  sky.net = Mlp(std::move(layout), std::move(params));
  return sky;
}

// ---- batch
// ---------------------------------------------------------------------------------------

// The kernel's parameters: p points into the vectors (a move of the Kernel's owner keeps them).
struct SkyNetworkBatch::Kernel {
  std::vector<float> params;
  std::vector<detail::BatchLayer> layers;
  std::vector<detail::DirectionInput> inputs;
  detail::SkyBatchParams p;
};

SkyNetworkBatch::~SkyNetworkBatch() = default;
SkyNetworkBatch::SkyNetworkBatch(SkyNetworkBatch&&) noexcept = default;
SkyNetworkBatch& SkyNetworkBatch::operator=(SkyNetworkBatch&&) noexcept = default;

namespace {

// Kernel inputs: the view's linear inputs in the world frame (x and y when v_x is used, the
// rotated v_y alone when only v_y is: one input instead of two), z, then the non-linear direction
// inputs in spec order. The columns of each in the kernel's input list (-1: not used).
struct KernelColumns {
  int x = -1, y = -1, ry = -1, z = -1;
  std::vector<int> column;  // per spec input: the kernel input a non-linear one feeds
  double c = 1.0, s = 0.0;  // cos and sin of the frame's rotation, eq. 10
};
KernelColumns kernel_inputs(const SkyNetwork& sky, const SkyState& state,
                            std::vector<detail::DirectionInput>& inputs,
                            detail::SkyBatchParams& kp) {
  using detail::DirectionInput;
  KernelColumns k;
  const double r = state.sun_azimuth - kPi;  // eq. 10
  k.c = std::cos(r);
  k.s = std::sin(r);
  auto has = [&](Input in) {
    return std::find(sky.inputs.begin(), sky.inputs.end(), in) != sky.inputs.end();
  };
  auto add = [&](DirectionInput in) {
    inputs.push_back(in);
    return static_cast<int>(inputs.size()) - 1;
  };
  if (has(Input::view_x)) {
    k.x = add(DirectionInput::x);
    k.y = add(DirectionInput::y);
  } else if (has(Input::view_y)) {
    k.ry = add(DirectionInput::reference_y);
    kp.ry_x = static_cast<float>(k.s);  // v_y = y' c + x' s
    kp.ry_y = static_cast<float>(k.c);
  }
  if (has(Input::view_z)) k.z = add(DirectionInput::z);
  k.column.assign(sky.inputs.size(), -1);
  for (std::size_t i = 0; i < sky.inputs.size(); ++i) {
    switch (sky.inputs[i]) {
      case Input::chord:
        k.column[i] = add(DirectionInput::chord);
        break;
      case Input::log_chord:
        k.column[i] = add(DirectionInput::log_chord);
        break;
      case Input::sqrt_view_z:
        k.column[i] = add(DirectionInput::sqrt_z);
        break;
      case Input::aureole:
        k.column[i] = add(DirectionInput::aureole);
        break;
      default:
        break;
    }
  }
  return k;
}

// Layer 1 folded onto the kernel inputs (double, then rounded): W'(n1 x nk), b'. State inputs do
// not depend on the view: their weights go into the bias.
void fold_first_layer(const SkyNetwork& sky, const SkyState& state, const KernelColumns& k, int nk,
                      std::vector<double>& W1, std::vector<double>& b1) {
  const MlpLayout& l = sky.net.layout();
  const auto p = sky.net.parameters();
  const int n0 = l.inputs(), n1 = l.widths[1];
  W1.assign(static_cast<std::size_t>(n1) * nk, 0.0);
  b1.assign(n1, 0.0);
  const double* W = p.data() + l.weight_offset(1);
  const double* b = p.data() + l.bias_offset(1);
  std::vector<double> state_value(n0);
  compute_inputs(sky.inputs, state, Vec3{0.0, 0.0, 1.0}, state_value);
  for (int j = 0; j < n1; ++j) {
    b1[j] = b[j];
    double* w = W1.data() + static_cast<std::size_t>(j) * nk;
    for (int i = 0; i < n0; ++i) {
      const double wi = W[static_cast<std::size_t>(j) * n0 + i];
      switch (sky.inputs[i]) {
        case Input::view_x:  // v_x = x' c - y' s
          w[k.x] += wi * k.c;
          w[k.y] -= wi * k.s;
          break;
        case Input::view_y:  // v_y = y' c + x' s
          if (k.ry >= 0) {
            w[k.ry] += wi;
          } else {
            w[k.y] += wi * k.c;
            w[k.x] += wi * k.s;
          }
          break;
        case Input::view_z:
          w[k.z] += wi;
          break;
        default:
          if (k.column[i] >= 0) {
            w[k.column[i]] += wi;
          } else {
            SKYLIGHT_CHECK(is_state_input(sky.inputs[i]), "SkyNetworkBatch: unhandled input");
            b1[j] += wi * state_value[i];
          }
      }
    }
  }
}

// Output mapping; returns the gain folded into the last layer. satilmis encoding + satilmis output
// activation: rgb = (sqrt(scale/2) o)^2; root4 / root8 with an identity output:
// rgb = (scale^(1/4) o)^4 / (scale^(1/8) o)^8.
double output_mapping(const SkyNetwork& sky, detail::SkyBatchParams& kp) {
  const Activation f_out = sky.net.layout().activations.back();
  const bool identity = f_out == Activation::identity;
  kp.scale = static_cast<float>(sky.target_scale);
  if (sky.max_radiance)
    kp.max_value = static_cast<float>(std::min(sky.target_scale * *sky.max_radiance, 3e38));
  switch (sky.encoding) {
    case OutputEncoding::satilmis:
      if (f_out == Activation::satilmis) {
        kp.output = detail::SkyBatchOutput::squared;
        return std::sqrt(0.5 * sky.target_scale);
      }
      kp.output = detail::SkyBatchOutput::inverse_ls;
      return 1.0;
    case OutputEncoding::root4:
      kp.output = detail::SkyBatchOutput::power4;
      if (identity) return std::pow(sky.target_scale, 0.25);
      break;
    case OutputEncoding::root8:
      kp.output = detail::SkyBatchOutput::power8;
      if (identity) return std::pow(sky.target_scale, 0.125);
      break;
    case OutputEncoding::log:
      kp.output = detail::SkyBatchOutput::exp;
      if (identity) return 1.0;
      break;
  }
  throw InvalidArgument("SkyNetworkBatch: the " + std::string(to_string(sky.encoding)) +
                        " encoding needs an identity output activation");
}

}  // namespace

SkyNetworkBatch::SkyNetworkBatch(const SkyNetwork& sky, const SkyState& state, bool allow_unrolled)
    : kernel_(std::make_unique<Kernel>()) {
  Kernel& kern = *kernel_;
  const MlpLayout& l = sky.net.layout();
  SKYLIGHT_CHECK(l.outputs() == 3, "SkyNetworkBatch: the network needs 3 outputs");
  const auto p = sky.net.parameters();
  const int L = l.layers();
  const KernelColumns cols = kernel_inputs(sky, state, kern.inputs, kern.p);
  const int nk = static_cast<int>(kern.inputs.size());
  std::vector<double> W1, b1;
  fold_first_layer(sky, state, cols, nk, W1, b1);
  const double out_gain = output_mapping(sky, kern.p);
  const bool fold_square = kern.p.output == detail::SkyBatchOutput::squared;

  // Float parameters: layer 1 folded, layers 2..L as trained (the last one scaled).
  std::vector<std::size_t> w_off(L + 1), b_off(L + 1);
  for (int k = 1; k <= L; ++k) {
    const int n_in = k == 1 ? nk : l.widths[k - 1], n_out = l.widths[k];
    w_off[k] = kern.params.size();
    const double gain = k == L ? out_gain : 1.0;
    for (int j = 0; j < n_out; ++j) {
      for (int i = 0; i < n_in; ++i) {
        const double v = k == 1 ? W1[static_cast<std::size_t>(j) * nk + i]
                                : p[l.weight_offset(k) + static_cast<std::size_t>(j) * n_in + i];
        kern.params.push_back(static_cast<float>(gain * v));
      }
    }
    b_off[k] = kern.params.size();
    for (int j = 0; j < n_out; ++j) {
      kern.params.push_back(static_cast<float>(gain * (k == 1 ? b1[j] : p[l.bias_offset(k) + j])));
    }
  }
  kern.layers.resize(L);
  for (int k = 1; k <= L; ++k) {
    Activation f = l.activations[k - 1];
    if (k == L && fold_square) f = Activation::identity;
    kern.layers[k - 1] = {k == 1 ? nk : l.widths[k - 1], l.widths[k], f,
                          kern.params.data() + w_off[k], kern.params.data() + b_off[k]};
  }
  kern.p.layers = kern.layers.data();
  kern.p.n_layers = L;
  kern.p.inputs = kern.inputs.data();
  kern.p.n_inputs = nk;
  kern.p.allow_unrolled = allow_unrolled;
  const Vec3 sun = direction_from_angles(state.sun_zenith, state.sun_azimuth);
  kern.p.sx = static_cast<float>(sun.x);
  kern.p.sy = static_cast<float>(sun.y);
  kern.p.sz = static_cast<float>(sun.z);
}

void SkyNetworkBatch::rgb(const float* x, const float* y, const float* z, float* r, float* g,
                          float* b, std::size_t n) const {
  detail::sky_batch(kernel_->p, x, y, z, r, g, b, n);
}

}  // namespace skylight::nn
