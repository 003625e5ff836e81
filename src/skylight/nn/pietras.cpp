#include "skylight/nn/pietras.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "skylight/core/detail/json_reader.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/nn/detail/mlp_kernel.h"
#include "skylight/nn/random.h"
#include "skylight/nn/train.h"

namespace skylight::nn {

std::string_view to_string(PietrasKind k) {
  return k == PietrasKind::pietras ? "pietras" : "log3";
}

std::optional<PietrasKind> parse_pietras_kind(std::string_view name) {
  if (name == "pietras") return PietrasKind::pietras;
  if (name == "log3") return PietrasKind::log3;
  return std::nullopt;
}

std::vector<MlpLayout> pietras_layouts(PietrasKind k) {
  if (k == PietrasKind::pietras) {
    // §III: four independent 4-8-4-1 perceptrons, f(x) = 1/(1 + 2^{2x}) on every neuron.
    const MlpLayout l = MlpLayout::make(4, {8, 4}, 1, Activation::pietras, Activation::pietras);
    return {l, l, l, l};
  }
  const MlpLayout l = MlpLayout::make(4, {16, 16}, 1, Activation::pietras, Activation::identity);
  return {l, l, l};
}

PietrasNetwork initial_pietras_network(PietrasKind k, std::uint64_t seed) {
  PietrasNetwork net;
  net.kind = k;
  Rng rng(seed);
  for (const MlpLayout& l : pietras_layouts(k)) net.subnets.push_back(initial_network(l, rng));
  return net;
}

std::size_t PietrasNetwork::parameter_count() const {
  std::size_t n = 0;
  for (const Mlp& m : subnets) n += m.layout().parameter_count();
  return n;
}

double PietrasNetwork::density(double altitude_m) const {
  return std::exp(-std::clamp(altitude_m, 0.0, top_altitude_m) / scale_height_m);
}

// A point at radius r <= r_t is lit only if its sun zenith is below pi/2 + acos(R0 / r) (else the
// planet's shadow covers it). The atmosphere visible from radius r_o lies within an angle
// acos(R0 / r_o) + acos(R0 / r_t) of the observer's zenith (rays grazing the ground), and the sun
// zenith there is at least theta0 minus that angle. So theta0 >= pi/2 + 2 acos(R0 / r_t) +
// acos(R0 / r_o) leaves every visible point in shadow.
double PietrasNetwork::night_cos_sun_zenith(double altitude_m) const {
  const double r0 = ground_radius_m, rt = r0 + top_altitude_m;
  const double ro = r0 + std::clamp(altitude_m, 0.0, top_altitude_m);
  const double theta = kPi / 2 + 2.0 * std::acos(r0 / rt) + std::acos(r0 / ro);
  return theta >= kPi ? -2.0 : std::cos(theta);
}

bool view_ray_lit(double ground_radius_m, double top_altitude_m, double altitude_m,
                  double cos_view_zenith, double cos_view_sun, double cos_sun_zenith) {
  const double r0 = ground_radius_m, rt = r0 + top_altitude_m;
  const double r = r0 + std::max(altitude_m, 0.0);
  // The ray x(t) = P + t view, |P| = r: |x|^2 = r^2 + 2 t r cos_view_zenith + t^2,
  // x.sun = r cos_sun_zenith + t cos_view_sun. Its part in the atmosphere: t in [t0, t1].
  const double b = r * cos_view_zenith;
  const double top = b * b - (r * r - rt * rt);
  if (top <= 0.0) return false;  // misses the atmosphere (or grazes it)
  double t1 = -b + std::sqrt(top);
  if (t1 <= 0.0) return false;  // above the top, looking away from it
  const double t0 = std::max(0.0, -b - std::sqrt(top));
  bool ground = false;
  const double g = b * b - (r * r - r0 * r0);
  if (g > 0.0 && -b - std::sqrt(g) >= 0.0) {
    t1 = std::min(t1, -b - std::sqrt(g));
    ground = true;
  }
  auto shadowed = [&](double t, bool on_ground) {
    const double d = r * cos_sun_zenith + t * cos_view_sun;
    if (!(d < 0.0)) return false;
    if (on_ground) return true;  // |x| = R0 and x.sun < 0
    return r * r + 2.0 * t * b + t * t - d * d < r0 * r0;
  };
  return !(shadowed(t0, false) && shadowed(t1, ground));
}

bool PietrasNetwork::lit(double altitude_m, double cos_view_zenith, double cos_view_sun,
                         double cos_sun_zenith) const {
  return view_ray_lit(ground_radius_m, top_altitude_m, altitude_m, cos_view_zenith, cos_view_sun,
                      cos_sun_zenith);
}

std::vector<double> PietrasNetwork::outputs(const PietrasInput& in) const {
  const double v[4] = {in.cos_view_zenith, in.cos_view_sun, in.cos_sun_zenith, in.density};
  std::vector<double> out(subnets.size());
  for (std::size_t i = 0; i < subnets.size(); ++i) subnets[i].forward(v, {&out[i], 1});
  return out;
}

Rgb decode_pietras(PietrasKind k, double max_value, const double* o) {
  if (k == PietrasKind::pietras) {
    if (!(o[3] > kPietrasMOffset)) return {};  // night (§III: M = 0)
    const double n = max_value * (o[3] - kPietrasMOffset) / kPietrasMScale;
    return {n * std::max(o[0], 0.0), n * std::max(o[1], 0.0), n * std::max(o[2], 0.0)};
  }
  const double y = max_value * std::max(0.0, std::exp(std::min(o[0], 50.0)) - kLog3Epsilon);
  if (!(y > 0.0)) return {};
  const double r = o[1], b = o[2], g = 1.0 - r - b;
  // Y of linear sRGB (core/colorimetry.h) per unit S = R + G + B; sky colours keep it near 0.2-0.4.
  const double d = std::max(0.2126 * r + 0.7152 * g + 0.0722 * b, 1e-3);
  const double s = y / d;
  return {s * r, s * g, s * b};
}

Rgb PietrasNetwork::rgb(const PietrasInput& in) const {
  const auto o = outputs(in);
  return decode_pietras(kind, max_value, o.data());
}

Rgb PietrasNetwork::rgb_at(double altitude_m, double cos_view_zenith, double cos_view_sun,
                           double cos_sun_zenith) const {
  if (!lit(altitude_m, cos_view_zenith, cos_view_sun, cos_sun_zenith)) return {};
  return rgb({cos_view_zenith, cos_view_sun, cos_sun_zenith, density(altitude_m)});
}

// ---- weights file -------------------------------------------------------------------------------

namespace {

// The strict reader of core/json_reader.h.
using namespace skylight::detail::json;  // NOLINT(google-build-using-namespace)

// Bounds of the weights file's integers (a corrupt file stops at the loader).
constexpr long long kMaxVersion = 1000000, kMaxSamples = 1LL << 53, kMaxIterations = 1LL << 31;

constexpr const char* kInputs[] = {"cos_view_zenith", "cos_view_sun", "cos_sun_zenith", "density"};

}  // namespace

std::string to_json(const PietrasNetwork& net) {
  nlohmann::json j;
  j["format"] = kPietrasFormat;
  j["version"] = kPietrasVersion;
  j["network"] = to_string(net.kind);
  j["inputs"] = std::vector<std::string>(std::begin(kInputs), std::end(kInputs));
  j["outputs"] = net.kind == PietrasKind::pietras
                     ? std::vector<std::string>{"R/N", "G/N", "B/N", "0.9 N/max_value + 0.05"}
                     : std::vector<std::string>{"ln(Y/max_value + 1e-6)", "R/(R+G+B)", "B/(R+G+B)"};
  j["scale_height_m"] = net.scale_height_m;
  j["top_altitude_m"] = net.top_altitude_m;
  j["ground_radius_m"] = net.ground_radius_m;
  j["max_value"] = net.max_value;
  nlohmann::json subs = nlohmann::json::array();
  for (const Mlp& m : net.subnets) {
    nlohmann::json s;
    s["widths"] = m.layout().widths;
    std::vector<std::string> acts;
    for (Activation a : m.layout().activations) acts.emplace_back(to_string(a));
    s["activations"] = acts;
    const auto p = m.parameters();
    s["parameters"] = std::vector<double>(p.begin(), p.end());
    subs.push_back(s);
  }
  j["subnets"] = subs;
  const PietrasProvenance& pv = net.provenance;
  nlohmann::json prov;
  prov["source"] = pv.source;
  prov["colour"] = pv.colour;
  prov["geometry"] = pv.geometry;
  prov["region"] = pv.region;
  nlohmann::json sp = nlohmann::json::object();
  for (const auto& [k, v] : pv.source_parameters) sp[k] = v;
  prov["source_parameters"] = sp;
  prov["samples"] = pv.samples;
  prov["seed"] = pv.seed;
  prov["trainer"] = pv.trainer;
  prov["iterations"] = pv.iterations;
  prov["training_seconds"] = pv.training_seconds;
  prov["date"] = pv.date;
  prov["software"] = pv.software;
  j["provenance"] = prov;
  return j.dump(1) + "\n";
}

bool is_pietras_json(std::string_view text) {
  const auto j = nlohmann::json::parse(text, nullptr, false);
  return j.is_object() && j.contains("format") && j["format"].is_string() &&
         j["format"].get<std::string>() == kPietrasFormat;
}

PietrasNetwork pietras_from_json(std::string_view s, const std::string& where) {
  const nlohmann::json j = skylight::detail::json::parse_object(s, where);
  if (text(field(j, where, "format"), where, "format") != kPietrasFormat)
    bad(where, "format", "is not \"" + std::string(kPietrasFormat) + "\"");
  if (integer(field(j, where, "version"), where, "version", 0, kMaxVersion) != kPietrasVersion)
    bad(where, "version", "is not " + std::to_string(kPietrasVersion));
  PietrasNetwork net;
  const std::string kind = text(field(j, where, "network"), where, "network");
  const auto k = parse_pietras_kind(kind);
  if (!k) bad(where, "network", "is not pietras or log3");
  net.kind = *k;
  const auto& ins = array(field(j, where, "inputs"), where, "inputs");
  if (ins.size() != 4) bad(where, "inputs", "does not hold the 4 inputs");
  for (std::size_t i = 0; i < 4; ++i)
    if (text(ins[i], where, "inputs") != kInputs[i])
      bad(where, "inputs", std::string("entry ") + std::to_string(i) + " is not " + kInputs[i]);
  net.scale_height_m = positive(field(j, where, "scale_height_m"), where, "scale_height_m");
  net.top_altitude_m = positive(field(j, where, "top_altitude_m"), where, "top_altitude_m");
  net.ground_radius_m = positive(field(j, where, "ground_radius_m"), where, "ground_radius_m");
  net.max_value = positive(field(j, where, "max_value"), where, "max_value");
  const auto layouts = pietras_layouts(net.kind);
  const auto& subs = array(field(j, where, "subnets"), where, "subnets");
  if (subs.size() != layouts.size())
    bad(where, "subnets", "does not hold " + std::to_string(layouts.size()) + " sub-networks");
  for (std::size_t i = 0; i < subs.size(); ++i) {
    const std::string name = "subnets[" + std::to_string(i) + "]";
    std::vector<int> widths;
    for (const auto& w : array(field(subs[i], where, "widths"), where, name + ".widths"))
      widths.push_back(
          static_cast<int>(integer(w, where, name + ".widths", 1, detail::kMaxBatchWidth)));
    std::vector<Activation> acts;
    for (const auto& a :
         array(field(subs[i], where, "activations"), where, name + ".activations")) {
      const auto act = parse_activation(text(a, where, name + ".activations"));
      if (!act) bad(where, name + ".activations", "holds an unknown activation");
      acts.push_back(*act);
    }
    if (widths != layouts[i].widths || acts != layouts[i].activations)
      bad(where, name, "is not the " + layouts[i].describe() + " sub-network of " + kind);
    auto params = numbers(field(subs[i], where, "parameters"), where, name + ".parameters");
    check_weight_magnitudes(params, where, name + ".parameters");
    if (params.size() != layouts[i].parameter_count())
      bad(where, name + ".parameters",
          "holds " + std::to_string(params.size()) + " numbers, not " +
              std::to_string(layouts[i].parameter_count()));
    net.subnets.emplace_back(layouts[i], std::move(params));
  }
  const auto& pj = field(j, where, "provenance");
  PietrasProvenance& pv = net.provenance;
  pv.source = text(field(pj, where, "source"), where, "provenance.source");
  pv.colour = text(field(pj, where, "colour"), where, "provenance.colour");
  pv.geometry = text(field(pj, where, "geometry"), where, "provenance.geometry");
  if (pj.contains("region")) pv.region = text(pj.at("region"), where, "provenance.region");
  const auto& sp = field(pj, where, "source_parameters");
  if (!sp.is_object()) bad(where, "provenance.source_parameters", "is not an object");
  for (const auto& [key, v] : sp.items())
    pv.source_parameters.emplace_back(key, number(v, where, "provenance.source_parameters." + key));
  pv.samples = static_cast<std::size_t>(
      integer(field(pj, where, "samples"), where, "provenance.samples", 0, kMaxSamples));
  pv.seed = static_cast<std::uint64_t>(integer(field(pj, where, "seed"), where, "provenance.seed",
                                               0, std::numeric_limits<long long>::max()));
  pv.trainer = text(field(pj, where, "trainer"), where, "provenance.trainer");
  for (const auto& it : array(field(pj, where, "iterations"), where, "provenance.iterations"))
    pv.iterations.push_back(
        static_cast<int>(integer(it, where, "provenance.iterations", 0, kMaxIterations)));
  pv.training_seconds =
      number(field(pj, where, "training_seconds"), where, "provenance.training_seconds");
  pv.date = text(field(pj, where, "date"), where, "provenance.date");
  pv.software = text(field(pj, where, "software"), where, "provenance.software");
  return net;
}

// ---- batch path ---------------------------------------------------------------------------------

PietrasBatch::PietrasBatch(const PietrasNetwork& net, double altitude_m, double cos_sun_zenith)
    : kind_(net.kind),
      max_value_(net.max_value),
      night_(cos_sun_zenith <= net.night_cos_sun_zenith(altitude_m)),
      observer_lit_(altitude_m >= 0.0 && altitude_m <= net.top_altitude_m && cos_sun_zenith > 0.0),
      ground_radius_m_(net.ground_radius_m),
      top_altitude_m_(net.top_altitude_m),
      altitude_m_(altitude_m),
      cos_sun_zenith_(static_cast<float>(cos_sun_zenith)),
      density_(static_cast<float>(net.density(altitude_m))) {
  for (const Mlp& m : net.subnets) subnets_.emplace_back(m);
}

void PietrasBatch::rgb(const float* cos_view_zenith, const float* cos_view_sun, float* r, float* g,
                       float* b, std::size_t n) const {
  if (night_) {
    std::fill(r, r + n, 0.0f);
    std::fill(g, g + n, 0.0f);
    std::fill(b, b + n, 0.0f);
    return;
  }
  const std::size_t k = subnets_.size();
  std::vector<float> sun(n, cos_sun_zenith_), rho(n, density_), out(k * n);
  const float* in[4] = {cos_view_zenith, cos_view_sun, sun.data(), rho.data()};
  for (std::size_t s = 0; s < k; ++s) {
    float* o[1] = {out.data() + s * n};
    subnets_[s].forward(in, o, n);
  }
  std::array<double, 4> o{};
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t s = 0; s < k; ++s) o[s] = out[s * n + i];
    const Rgb c =
        observer_lit_ || view_ray_lit(ground_radius_m_, top_altitude_m_, altitude_m_,
                                      cos_view_zenith[i], cos_view_sun[i], cos_sun_zenith_)
            ? decode_pietras(kind_, max_value_, o.data())
            : Rgb{};
    r[i] = static_cast<float>(c.r);
    g[i] = static_cast<float>(c.g);
    b[i] = static_cast<float>(c.b);
  }
}

}  // namespace skylight::nn
