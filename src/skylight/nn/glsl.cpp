#include "skylight/nn/glsl.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <set>

#include "skylight/core/error.h"
#include "skylight/nn/detail/mlp_kernel.h"

namespace skylight::nn {

namespace {

// A float literal that GLSL parses back to exactly static_cast<float>(v) (9 significant digits
// round-trip any float; the exponent form always reads as float).
std::string literal(double v) {
  return fmt::format("{:.8e}", static_cast<float>(v));
}

// User text (a weights file's provenance) inside a // comment: one line, printable ASCII.
std::string comment_text(std::string_view s) {
  if (s.empty()) return "?";
  std::string out(s.substr(0, 200));
  for (char& c : out)
    if (c < 0x20 || c > 0x7e) c = ' ';
  return out;
}

bool is_identifier(std::string_view s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s.front()))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

}  // namespace

std::string glsl_activation_name(Activation a) {
  return "skylight_act_" + std::string(to_string(a));
}

std::string glsl_activation_function(Activation a) {
  switch (a) {
    case Activation::identity:
      return "return x;";
    case Activation::satilmis:
      return "return 1.0 / (1.0 + x * x);";
    case Activation::pietras:
      // 1 / (1 + 2^(2x)) = sigmoid(-2 ln2 x), through 2^(-2|x|) <= 1.
      return "float e = exp2(-2.0 * abs(x));\n  return x > 0.0 ? e / (1.0 + e) : 1.0 / (1.0 + e);";
    case Activation::tanh:
      // Not the builtin tanh: some drivers evaluate it as (e^2x - 1) / (e^2x + 1), NaN for large x.
      return "float e = exp(-2.0 * abs(x));\n  return sign(x) * (1.0 - e) / (1.0 + e);";
    case Activation::sigmoid:
      return "float e = exp(-abs(x));\n  return x >= 0.0 ? 1.0 / (1.0 + e) : e / (1.0 + e);";
    case Activation::relu:
      return "return max(x, 0.0);";
    case Activation::softplus:
      return "return max(x, 0.0) + log(1.0 + exp(-abs(x)));";
  }
  return "return x;";
}

namespace {

std::string activation_helpers(const std::set<Activation>& used) {
  std::string s;
  for (Activation a : used)
    s += fmt::format("float {}(float x) {{\n  {}\n}}\n\n", glsl_activation_name(a),
                     glsl_activation_function(a));
  return s;
}

// glsl_mlp without the activation helpers.
std::string mlp_function(const Mlp& net, std::string_view name) {
  const MlpLayout& l = net.layout();
  std::string s;
  s += fmt::format("// {} ({} parameters), weights baked in (single precision).\n", l.describe(),
                   l.parameter_count());
  s += fmt::format("void {}(in float x[{}], out float y[{}]) {{\n", name, l.inputs(), l.outputs());
  const auto p = net.parameters();
  for (int k = 1; k <= l.layers(); ++k) {
    const int n_in = l.widths[static_cast<std::size_t>(k - 1)];
    const int n_out = l.widths[static_cast<std::size_t>(k)];
    const std::size_t w = l.weight_offset(k), b = l.bias_offset(k);
    const std::string f = glsl_activation_name(l.activations[static_cast<std::size_t>(k - 1)]);
    const bool last = k == l.layers();
    for (int j = 0; j < n_out; ++j) {
      std::string sum = literal(p[b + static_cast<std::size_t>(j)]);
      for (int i = 0; i < n_in; ++i) {
        const std::string in = k == 1 ? fmt::format("x[{}]", i) : fmt::format("o{}_{}", k - 1, i);
        sum +=
            fmt::format(" + {} * {}", literal(p[w + static_cast<std::size_t>(j) * n_in + i]), in);
      }
      if (last)
        s += fmt::format("  y[{}] = {}({});\n", j, f, sum);
      else
        s += fmt::format("  float o{}_{} = {}({});\n", k, j, f, sum);
    }
  }
  s += "}\n";
  return s;
}

}  // namespace

std::string glsl_mlp(const Mlp& net, std::string_view name) {
  const MlpLayout& l = net.layout();
  l.validate();
  if (!is_identifier(name))
    throw InvalidArgument(fmt::format("GLSL function name '{}' is not an identifier", name));
  return activation_helpers(std::set<Activation>(l.activations.begin(), l.activations.end())) +
         mlp_function(net, name);
}

std::string glsl_pietras_network(const PietrasNetwork& net) {
  std::set<Activation> used;
  for (const Mlp& m : net.subnets) {
    m.layout().validate();
    if (m.layout().inputs() != 4 || m.layout().outputs() != 1)
      throw InvalidArgument("glsl_pietras_network: a sub-network is not 4 -> 1");
    used.insert(m.layout().activations.begin(), m.layout().activations.end());
  }
  const std::size_t k = net.kind == PietrasKind::pietras ? 4 : 3;
  if (net.subnets.size() != k)
    throw InvalidArgument(fmt::format("glsl_pietras_network: {} sub-networks for {}, not {}",
                                      net.subnets.size(), to_string(net.kind), k));
  std::string s = activation_helpers(used);
  for (std::size_t i = 0; i < k; ++i)
    s += mlp_function(net.subnets[i], fmt::format("skylight_pietras_{}", i)) + "\n";
  s += fmt::format("// PietrasNetwork::rgb (nn/pietras.h, decode_pietras): {} network.\n",
                   to_string(net.kind));
  s += "vec3 skylight_pietras(vec4 v) {\n  float x[4] = float[4](v.x, v.y, v.z, v.w);\n";
  for (std::size_t i = 0; i < k; ++i)
    s += fmt::format("  float y{0}[1];\n  skylight_pietras_{0}(x, y{0});\n", i);
  if (net.kind == PietrasKind::pietras) {
    s += fmt::format("  if (!(y3[0] > {})) return vec3(0.0);  // night: M = 0\n",
                     literal(kPietrasMOffset));
    s += fmt::format("  float n = {} * (y3[0] - {}) / {};\n", literal(net.max_value),
                     literal(kPietrasMOffset), literal(kPietrasMScale));
    s += "  return n * max(vec3(y0[0], y1[0], y2[0]), vec3(0.0));\n}\n";
  } else {
    s += fmt::format("  float Y = {} * max(0.0, exp(min(y0[0], 50.0)) - {});\n",
                     literal(net.max_value), literal(kLog3Epsilon));
    s += "  if (!(Y > 0.0)) return vec3(0.0);\n";
    s += "  float r = y1[0], b = y2[0], g = 1.0 - r - b;\n";
    s += "  float d = max(0.2126 * r + 0.7152 * g + 0.0722 * b, 1e-3);\n";
    s += "  return (Y / d) * vec3(r, g, b);\n}\n";
  }
  return s;
}

std::string glsl_pietras_sky(const PietrasNetwork& net) {
  std::string s = glsl_pietras_network(net);
  const std::string r0 = literal(net.ground_radius_m), top = literal(net.top_altitude_m);
  s += fmt::format(
      "// PietrasNetwork::lit (nn/pietras.h, view_ray_lit) in altitudes: R0 = {0} m, the top {1} "
      "m\n"
      "// above it.\n"
      "bool skylight_pietras_shadowed(float h, float b, float cs, float cb, float t, bool ground) "
      "{{\n"
      "  float d = ({0} + h) * cs + t * cb;  // x . sun\n"
      "  if (!(d < 0.0)) return false;\n"
      "  if (ground) return true;\n"
      "  return h * (2.0 * {0} + h) + 2.0 * t * b + t * t - d * d < 0.0;  // |x|^2 - d^2 < R0^2\n"
      "}}\n"
      "bool skylight_pietras_lit(float altitude, float cos_view_zenith, float cos_view_sun,\n"
      "                          float cos_sun_zenith) {{\n"
      "  float h = max(altitude, 0.0);\n"
      "  float b = ({0} + h) * cos_view_zenith;\n"
      "  float top = b * b - (h - {1}) * (2.0 * {0} + h + {1});\n"
      "  if (top <= 0.0) return false;\n"
      "  float t1 = -b + sqrt(top);\n"
      "  if (t1 <= 0.0) return false;\n"
      "  float t0 = max(0.0, -b - sqrt(top));\n"
      "  bool ground = false;\n"
      "  float g = b * b - h * (2.0 * {0} + h);\n"
      "  if (g > 0.0 && -b - sqrt(g) >= 0.0) {{\n"
      "    t1 = min(t1, -b - sqrt(g));\n"
      "    ground = true;\n"
      "  }}\n"
      "  return !(skylight_pietras_shadowed(h, b, cos_sun_zenith, cos_view_sun, t0, false) &&\n"
      "           skylight_pietras_shadowed(h, b, cos_sun_zenith, cos_view_sun, t1, ground));\n"
      "}}\n",
      r0, top);
  s += fmt::format(
      "// PietrasNetwork::rgb_at: 0 where the view ray is not lit, else the network at\n"
      "// rho0 = exp(-h / H0), h clamped to [0, top], H0 = {1} m.\n"
      "vec3 skylight_pietras_at(float altitude, vec3 view, vec3 sun) {{\n"
      "  float cv = view.z, cb = dot(view, sun), cs = sun.z;\n"
      "  if (!skylight_pietras_lit(altitude, cv, cb, cs)) return vec3(0.0);\n"
      "  float rho = exp(-clamp(altitude, 0.0, {0}) / {1});\n"
      "  return skylight_pietras(vec4(cv, cb, cs, rho));\n"
      "}}\n",
      top, literal(net.scale_height_m));
  return s;
}

std::string glsl_pietras_network_file(const PietrasNetwork& net) {
  const PietrasProvenance& pv = net.provenance;
  std::string s = "#version 330 core\n";
  s += "// A Pietras network exported by skylight (`skylight nn export --glsl`, docs/GPU.md).\n";
  s += fmt::format("// Network: {} ({} weights, {} sub-networks); max value {}.\n",
                   to_string(net.kind), net.parameter_count(), net.subnets.size(),
                   literal(net.max_value));
  s += fmt::format("// Trained on: {} ({}), {} samples, trainer {}, {}, {}.\n",
                   comment_text(pv.source), comment_text(pv.colour), pv.samples,
                   comment_text(pv.trainer), comment_text(pv.date), comment_text(pv.software));
  s += "// Entry points: vec3 skylight_pietras_at(float altitude, vec3 view, vec3 sun): linear\n"
       "// sRGB in the source's units, altitude in m, view and sun unit vectors (z up); and\n"
       "// vec3 skylight_pietras(vec4 x), x = (cos alpha0, cos beta0, cos theta0, rho0), without\n"
       "// the shadow test (docs/PIETRAS.md).\n\n";
  s += glsl_pietras_sky(net);
  return s;
}

namespace {

std::string input_expression(Input in) {
  switch (in) {
    case Input::sqrt_turbidity:
      return "sqrt(turbidity)";
    case Input::sun_zenith:
      return "sun_zenith";
    case Input::view_x:
      return "v.x";
    case Input::view_y:
      return "v.y";
    case Input::view_z:
      return "v.z";
    case Input::chord:
      return "d";
    case Input::log_chord:
      return fmt::format("log(d + {})", literal(detail::kLogChordOffset));
    case Input::sqrt_view_z:
      return "sqrt(max(v.z, 0.0))";
    case Input::aureole:
      return fmt::format("1.0 / (d * d + {})", literal(detail::kAureoleOffset));
    case Input::cos_sun_zenith:
      return "cos(sun_zenith)";
    case Input::sun_elevation_cbrt:
      // cbrt of a value in [0, 1]; GLSL's pow(x, y) is undefined only for x < 0 (and x = 0,
      // y <= 0).
      return fmt::format("pow(max(0.0, 1.0 - sun_zenith / {}), 1.0 / 3.0)", literal(kPi / 2));
    case Input::turbidity:
      return "turbidity";
  }
  return "0.0";
}

std::string decode_expression(OutputEncoding e, const std::string& y) {
  switch (e) {
    case OutputEncoding::satilmis:
      return fmt::format("0.5 * (1.0 / {} - 1.0)", y);  // eq. 7
    case OutputEncoding::log:
      return fmt::format("exp({})", y);
    case OutputEncoding::root4:
      return fmt::format("({0} * {0}) * ({0} * {0})", y);
    case OutputEncoding::root8:
      return fmt::format("(({0} * {0}) * ({0} * {0})) * (({0} * {0}) * ({0} * {0}))", y);
  }
  return y;
}

}  // namespace

std::string glsl_sky_network(const SkyNetwork& sky) {
  const MlpLayout& l = sky.net.layout();
  if (l.outputs() != 3 || static_cast<int>(sky.inputs.size()) != l.inputs())
    throw InvalidArgument(fmt::format("sky network {}: needs {} inputs and 3 outputs", l.describe(),
                                      sky.inputs.size()));
  std::string s = glsl_mlp(sky.net, "skylight_sky_network");
  s += "\n// SkyNetwork::rgb (nn/sky_network.h): linear sRGB on the source model's scale.\n";
  s += "vec3 skylight_sky_state(vec3 view, float sun_zenith, float sun_azimuth, float turbidity) "
       "{\n";
  s += "  if (view.z < 0.0) return vec3(0.0);\n";
  s += "  // Satilmis et al. 2016 eq. 10: the view rotated by phi_sun - pi about the zenith.\n";
  s += fmt::format("  float r = sun_azimuth - {};\n", literal(kPi));
  s += "  float cr = cos(r), sr = sin(r);\n";
  s += "  vec3 v = vec3(view.x * cr - view.y * sr, view.y * cr + view.x * sr, view.z);\n";
  s += "  float st = sin(sun_zenith);\n";
  s += "  vec3 sun = vec3(st * sin(sun_azimuth), st * cos(sun_azimuth), cos(sun_zenith));\n";
  s += "  float d = length(sun - view);  // the chord |omega_sun - omega_view|\n";
  s += fmt::format("  float x[{}];\n", l.inputs());
  for (std::size_t k = 0; k < sky.inputs.size(); ++k)
    s += fmt::format("  x[{}] = {};  // {}\n", k, input_expression(sky.inputs[k]),
                     to_string(sky.inputs[k]));
  s += "  float y[3];\n  skylight_sky_network(x, y);\n";
  const std::string decoded =
      fmt::format("vec3({}, {}, {})", decode_expression(sky.encoding, "y[0]"),
                  decode_expression(sky.encoding, "y[1]"), decode_expression(sky.encoding, "y[2]"));
  if (sky.max_radiance)  // SkyNetwork::max_radiance: the decoded radiance's bound
    s += fmt::format("  return {} * min({}, vec3({}));\n", literal(sky.target_scale), decoded,
                     literal(*sky.max_radiance));
  else
    s += fmt::format("  return {} * {};\n", literal(sky.target_scale), decoded);
  s += "}\n\n";
  s += "// The same with the sun as a unit vector (ENU).\n";
  s += "vec3 skylight_sky(vec3 view, vec3 sun, float turbidity) {\n";
  s += "  float sun_zenith = atan(length(sun.xy), sun.z);  // not acos: accurate near the zenith\n";
  s += fmt::format(
      "  float sun_azimuth = (sun.x == 0.0 && sun.y == 0.0) ? {} : atan(sun.x, sun.y);\n",
      literal(kPi));
  s += "  return skylight_sky_state(view, sun_zenith, sun_azimuth, turbidity);\n}\n";
  return s;
}

std::string glsl_sky_network_file(const SkyNetwork& sky) {
  const SkyNetworkProvenance& pv = sky.provenance;
  std::string s;
  s += "#version 330 core\n";
  s += "// A neural sky network exported by skylight (`skylight nn export --glsl`, docs/GPU.md).\n";
  s += fmt::format("// Architecture: {}; inputs: {}; output encoding: {}; target scale: {}.\n",
                   sky.net.layout().describe(), to_string(sky.inputs), to_string(sky.encoding),
                   sky.target_scale);
  s += fmt::format("// Trained on: {} ({}, {}), {}.\n", comment_text(pv.source),
                   comment_text(pv.trainer), comment_text(pv.date), comment_text(pv.software));
  s += "// Entry points: vec3 skylight_sky_state(vec3 view, float sun_zenith, float sun_azimuth,\n"
       "// float turbidity) and vec3 skylight_sky(vec3 view, vec3 sun, float turbidity): linear\n"
       "// sRGB, view and sun unit vectors (x east, y north, z up), angles in radians.\n\n";
  s += glsl_sky_network(sky);
  return s;
}

}  // namespace skylight::nn
