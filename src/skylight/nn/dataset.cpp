#include "skylight/nn/dataset.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "skylight/core/error.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parallel.h"
#include "skylight/nn/detail/mlp_kernel.h"
#include "skylight/nn/random.h"

namespace skylight::nn {

// ---- inputs
// --------------------------------------------------------------------------------------

namespace {
struct InputName {
  Input in;
  std::string_view name;
};
constexpr InputName kInputNames[] = {
    {Input::sqrt_turbidity, "sqrt_turbidity"},
    {Input::sun_zenith, "sun_zenith"},
    {Input::view_x, "view_x"},
    {Input::view_y, "view_y"},
    {Input::view_z, "view_z"},
    {Input::chord, "chord"},
    {Input::log_chord, "log_chord"},
    {Input::sqrt_view_z, "sqrt_view_z"},
    {Input::cos_sun_zenith, "cos_sun_zenith"},
    {Input::sun_elevation_cbrt, "sun_elevation_cbrt"},
    {Input::turbidity, "turbidity"},
    {Input::aureole, "aureole"},
};
}  // namespace

std::string_view to_string(Input in) {
  for (const auto& n : kInputNames) {
    if (n.in == in) return n.name;
  }
  return "?";
}

std::optional<Input> parse_input(std::string_view name) {
  for (const auto& n : kInputNames) {
    if (n.name == name) return n.in;
  }
  return std::nullopt;
}

bool is_state_input(Input in) {
  return in == Input::sqrt_turbidity || in == Input::sun_zenith || in == Input::cos_sun_zenith ||
         in == Input::sun_elevation_cbrt || in == Input::turbidity;
}

InputSpec satilmis_inputs() {
  return {Input::sqrt_turbidity, Input::sun_zenith, Input::view_x,
          Input::view_y,         Input::view_z,     Input::chord};
}

std::string to_string(const InputSpec& spec) {
  std::string s;
  for (std::size_t i = 0; i < spec.size(); ++i) {
    if (i) s += ',';
    s += to_string(spec[i]);
  }
  return s;
}

InputSpec parse_inputs(std::string_view list) {
  InputSpec spec;
  std::size_t pos = 0;
  while (pos <= list.size()) {
    const std::size_t end = std::min(list.find(',', pos), list.size());
    const std::string_view item = list.substr(pos, end - pos);
    const auto in = parse_input(item);
    if (!in) throw InvalidArgument("inputs: unknown input '" + excerpt(item) + "'");
    spec.push_back(*in);
    pos = end + 1;
  }
  return spec;
}

Vec3 rotate_view_to_reference(Vec3 view, double sun_azimuth) {
  const double r = sun_azimuth - kPi;  // eq. 10: rotate = phi_sun - pi
  const double c = std::cos(r), s = std::sin(r);
  return {view.x * c - view.y * s, view.y * c + view.x * s, view.z};
}

void compute_inputs(const InputSpec& spec, const SkyState& state, Vec3 view,
                    std::span<double> out) {
  SKYLIGHT_CHECK(out.size() == spec.size(), "compute_inputs: output size");
  const Vec3 v = rotate_view_to_reference(view, state.sun_azimuth);
  const Vec3 sun = direction_from_angles(state.sun_zenith, state.sun_azimuth);
  const double d = length(sun - view);  // rotation-invariant: computed in the world frame
  for (std::size_t k = 0; k < spec.size(); ++k) {
    double x = 0.0;
    switch (spec[k]) {
      case Input::sqrt_turbidity:
        x = std::sqrt(state.turbidity);
        break;
      case Input::sun_zenith:
        x = state.sun_zenith;
        break;
      case Input::view_x:
        x = v.x;
        break;
      case Input::view_y:
        x = v.y;
        break;
      case Input::view_z:
        x = v.z;
        break;
      case Input::chord:
        x = d;
        break;
      case Input::log_chord:
        x = std::log(d + detail::kLogChordOffset);
        break;
      case Input::sqrt_view_z:
        x = std::sqrt(std::max(v.z, 0.0));
        break;
      case Input::aureole:
        x = 1.0 / (d * d + detail::kAureoleOffset);
        break;
      case Input::cos_sun_zenith:
        x = std::cos(state.sun_zenith);
        break;
      case Input::sun_elevation_cbrt:
        x = std::cbrt(std::max(0.0, 1.0 - state.sun_zenith / (kPi / 2)));
        break;
      case Input::turbidity:
        x = state.turbidity;
        break;
    }
    out[k] = x;
  }
}

// ---- output encodings
// ----------------------------------------------------------------------------

std::string_view to_string(OutputEncoding e) {
  switch (e) {
    case OutputEncoding::satilmis:
      return "satilmis";
    case OutputEncoding::log:
      return "log";
    case OutputEncoding::root4:
      return "root4";
    case OutputEncoding::root8:
      return "root8";
  }
  return "?";
}

std::optional<OutputEncoding> parse_output_encoding(std::string_view name) {
  if (name == "satilmis") return OutputEncoding::satilmis;
  if (name == "log") return OutputEncoding::log;
  if (name == "root4") return OutputEncoding::root4;
  if (name == "root8") return OutputEncoding::root8;
  return std::nullopt;
}

double encode_radiance(OutputEncoding e, double L) {
  switch (e) {
    case OutputEncoding::satilmis:
      return 1.0 / (1.0 + 2.0 * std::max(L, 0.0));
    case OutputEncoding::log:
      return std::log(std::max(L, kLogRadianceFloor));
    case OutputEncoding::root4:
      return std::sqrt(std::sqrt(std::max(L, 0.0)));
    case OutputEncoding::root8:
      return std::sqrt(std::sqrt(std::sqrt(std::max(L, 0.0))));
  }
  return L;
}

double decode_radiance(OutputEncoding e, double y) {
  switch (e) {
    case OutputEncoding::satilmis:
      return 0.5 * (1.0 / y - 1.0);  // eq. 7
    case OutputEncoding::log:
      return std::exp(y);
    case OutputEncoding::root4:
      return (y * y) * (y * y);
    case OutputEncoding::root8: {
      const double y4 = (y * y) * (y * y);
      return y4 * y4;
    }
  }
  return y;
}

// ---- sampling
// ------------------------------------------------------------------------------------

SamplingSpec paper_training_spec(std::string_view source, std::vector<double> turbidities,
                                 double target_scale) {
  SamplingSpec s;
  s.source = std::string(source);
  s.target_scale = target_scale;
  s.turbidities = std::move(turbidities);
  s.sun_count = 20;
  s.vary_sun_azimuth = false;
  s.seed = 1;
  return s;
}

SamplingSpec paper_validation_spec(std::string_view source, std::vector<double> turbidities,
                                   double target_scale) {
  SamplingSpec s = paper_training_spec(source, std::move(turbidities), target_scale);
  s.sun_count = 7;
  s.vary_sun_azimuth = true;
  s.seed = 2;
  return s;
}

double Dataset::max_radiance() const {
  double m = 0.0;
  for (double L : radiance)
    if (L > m) m = L;
  return m;
}

std::vector<double> Dataset::targets(OutputEncoding e) const {
  std::vector<double> t(radiance.size());
  std::transform(radiance.begin(), radiance.end(), t.begin(),
                 [e](double L) { return encode_radiance(e, L); });
  return t;
}

Dataset build_dataset(const SamplingSpec& spec, const InputSpec& inputs, const SkySource& source) {
  if (spec.turbidities.empty() || spec.sun_count < 1 || spec.view_zeniths < 1 ||
      spec.view_azimuths < 1) {
    throw InvalidArgument("sampling spec: empty turbidity list or a count below 1");
  }
  Dataset ds;
  ds.spec = spec;
  ds.input_spec = inputs;
  Rng rng(spec.seed);
  for (double t : spec.turbidities) {
    for (int k = 0; k < spec.sun_count; ++k) {
      SkyState s;
      s.turbidity = t;
      s.sun_zenith = (k + 0.5) / spec.sun_count * (kPi / 2);
      s.sun_azimuth = spec.vary_sun_azimuth ? rng.uniform(0.0, 2 * kPi) : kPi;
      s.ground_albedo = spec.ground_albedo;
      ds.states.push_back(s);
    }
  }
  const int views_per_state = spec.view_zeniths * spec.view_azimuths;
  const std::size_t n = ds.states.size() * views_per_state;
  ds.state_index.resize(n);
  ds.views.resize(n);
  ds.inputs.resize(n * inputs.size());
  ds.radiance.resize(n * 3);
  // Jitter drawn sequentially (deterministic), models evaluated in parallel.
  for (std::size_t si = 0; si < ds.states.size(); ++si) {
    for (int a = 0; a < spec.view_azimuths; ++a) {
      for (int z = 0; z < spec.view_zeniths; ++z) {
        const std::size_t i = si * views_per_state + a * spec.view_zeniths + z;
        const double theta = (z + rng.uniform()) / spec.view_zeniths * (kPi / 2);
        const double phi = (a + rng.uniform()) / spec.view_azimuths * (2 * kPi);
        ds.state_index[i] = static_cast<int>(si);
        ds.views[i] = direction_from_angles(theta, phi);
      }
    }
  }
  parallel_for(ds.states.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t si = begin; si < end; ++si) {
      const SkyState& s = ds.states[si];
      const SkyFunction sky = source(s);
      for (int v = 0; v < views_per_state; ++v) {
        const std::size_t i = si * views_per_state + v;
        const Rgb c = sky(ds.views[i]);
        ds.radiance[3 * i + 0] = c.r / spec.target_scale;
        ds.radiance[3 * i + 1] = c.g / spec.target_scale;
        ds.radiance[3 * i + 2] = c.b / spec.target_scale;
        compute_inputs(inputs, s, ds.views[i],
                       std::span<double>(ds.inputs).subspan(i * inputs.size(), inputs.size()));
      }
    }
  });
  return ds;
}

}  // namespace skylight::nn
