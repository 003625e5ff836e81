// The per-vertex network of the physical atmosphere (Pietras, "GPU-based multi-layer perceptron as
// efficient method for approximation complex light models in per-vertex lighting", §III) and a
// larger variant, as nn::Mlp sub-networks (so any Mlp back end, e.g. a GLSL emitter, covers them).
//
// Inputs (§III), one vector for every sub-network: (cos alpha0, cos beta0, cos theta0, rho0) =
// view zenith, view-sun angle, sun zenith, relative density rho0 = exp(-h / H0) at the observer.
// Networks (docs/PIETRAS.md):
//  * pietras (the paper's): four sub-networks 4-8-4-1, activation f(x) = 1/(1 + 2^{2x}) on every
//    layer, 324 weights. Outputs R = I_r/N, G = I_g/N, B = I_b/N with N = max(I_r, I_g, I_b) and
//    M = 0.9 N / max N + 0.05 (night: M = 0). Decoded N = max N (M - 0.05) / 0.9, 0 when M < 0.05.
//  * log3: three sub-networks 4-16-16-1 (pietras hidden, identity output), 1,107 weights:
//    l = ln(Y / Y_max + eps) (lit samples only) and the chromaticities r = R/S, b = B/S, S =
//    R+G+B. Decoded Y = Y_max max(0, e^l - eps), S = Y / (0.2126 r + 0.7152 (1 - r - b) + 0.0722
//    b).
// Output: linear sRGB on the photometric scale of the source model (Y in cd/m^2 for nishita).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/earth.h"
#include "skylight/nn/mlp.h"

namespace skylight::nn {

enum class PietrasKind { pietras, log3 };
std::string_view to_string(PietrasKind k);
std::optional<PietrasKind> parse_pietras_kind(std::string_view name);

// The sub-network layouts of a kind (all with 4 inputs and 1 output).
std::vector<MlpLayout> pietras_layouts(PietrasKind k);

// M's affine map of §III: M = kPietrasMScale N / max N + kPietrasMOffset.
inline constexpr double kPietrasMScale = 0.9;
inline constexpr double kPietrasMOffset = 0.05;
// log3: l = ln(Y / Y_max + kLog3Epsilon), trained on lit samples only (night is the shadow test's,
// PietrasNetwork::lit).
inline constexpr double kLog3Epsilon = 1e-6;

// One network input vector.
struct PietrasInput {
  double cos_view_zenith = 1.0;  // cos alpha0
  double cos_view_sun = 1.0;     // cos beta0
  double cos_sun_zenith = 1.0;   // cos theta0
  double density = 1.0;          // rho0 = exp(-h / H0), [0, 1]
};

// Where a network came from (informative, written into and read from the weights file).
struct PietrasProvenance {
  std::string source;    // the source model's registry name
  std::string colour;    // what the outputs are, e.g. "linear sRGB, cd/m^2 scale"
  std::string geometry;  // how the training inputs were sampled
  // fit::PietrasRegionPolicy::name of the training samples; files before the field: "full".
  std::string region = "full";
  // The source's parameters held fixed during training (the schema's names and values).
  std::vector<std::pair<std::string, double>> source_parameters;
  std::size_t samples = 0;
  std::uint64_t seed = 0;
  std::string trainer;
  std::vector<int> iterations;  // per sub-network
  double training_seconds = 0.0;
  std::string date, software;
};

struct PietrasNetwork {
  PietrasKind kind = PietrasKind::pietras;
  std::vector<Mlp> subnets;                        // pietras: R, G, B, M; log3: l, r, b
  double scale_height_m = kRayleighScaleHeight;    // H0 of rho0 [m]
  double top_altitude_m = kEarthAtmosphereHeight;  // the top above the ground [m] (rho0 floor)
  double ground_radius_m = kEarthGroundRadius;     // for the night bound (night_cos_sun_zenith)
  double max_value = 1.0;  // pietras: N, log3: Y (source rgb units) that the targets scale to 1
  PietrasProvenance provenance;

  std::size_t parameter_count() const;
  // rho0 at altitude h >= 0 (clamped to the top of the atmosphere).
  double density(double altitude_m) const;
  // The sun zenith cosine below which single scattering seen from altitude h is exactly 0: every
  // point of the atmosphere visible from the observer is in the planet's shadow (docs/PIETRAS.md).
  double night_cos_sun_zenith(double altitude_m) const;
  // False when every point of the view ray from altitude h that lies in the atmosphere (up to the
  // top, or to the ground where the ray meets it) is in the planet's shadow, or when the ray
  // misses the atmosphere: single scattering along it is then exactly 0 (nishita cuts its view
  // rays at the shadow boundaries, so its value is 0 there too). The shadow, the points x with
  // x.sun < 0 and |x - (x.sun) sun| < R0, is convex, so the test is of the segment's two ends.
  // Exact for any view, where night_cos_sun_zenith is a bound for all views at once.
  bool lit(double altitude_m, double cos_view_zenith, double cos_view_sun,
           double cos_sun_zenith) const;
  // Raw sub-network outputs (double reference path).
  std::vector<double> outputs(const PietrasInput& in) const;
  // Decoded linear sRGB (never negative luminance; 0 at night). The geometric shadow test (lit())
  // is applied by the callers that know the altitude (rgb_at).
  Rgb rgb(const PietrasInput& in) const;
  // For an observer at altitude h, a view and a sun given by their cosines: 0 where the view ray
  // is not lit(), else rgb().
  Rgb rgb_at(double altitude_m, double cos_view_zenith, double cos_view_sun,
             double cos_sun_zenith) const;
};

// PietrasNetwork::lit for a planet of ground radius R0 and an atmosphere top_altitude_m thick.
bool view_ray_lit(double ground_radius_m, double top_altitude_m, double altitude_m,
                  double cos_view_zenith, double cos_view_sun, double cos_sun_zenith);

// A network of kind k with the trainer's initial weights (train.h initial_network, Rng(seed)) and
// max_value 1: the evaluation cost of a trained one (benchmarks, tests).
PietrasNetwork initial_pietras_network(PietrasKind k, std::uint64_t seed);

// Decodes raw outputs (outputs.size() == subnets) into linear sRGB.
Rgb decode_pietras(PietrasKind k, double max_value, const double* outputs);

// The weights file (docs/PIETRAS.md): {"format": "skylight-nn-pietras", "version": 1, "network",
// "inputs", "scale_height_m", "top_altitude_m", "ground_radius_m", "max_value", "subnets":
// [{"widths", "activations", "parameters"}], "provenance"}. Shortest round-trip numbers.
inline constexpr std::string_view kPietrasFormat = "skylight-nn-pietras";
inline constexpr int kPietrasVersion = 1;
std::string to_json(const PietrasNetwork& net);
// True when text is a JSON object whose "format" is kPietrasFormat (no further checks).
bool is_pietras_json(std::string_view text);
// The strict loader: InvalidArgument "<where>: field '<name>' <why>".
PietrasNetwork pietras_from_json(std::string_view text, const std::string& where);

// Batch path for one observer and sun over many views: single-precision MlpBatch per sub-network.
class PietrasBatch {
 public:
  PietrasBatch(const PietrasNetwork& net, double altitude_m, double cos_sun_zenith);
  // r/g/b[i] for the view cosines cos_view_zenith[i], cos_view_sun[i]. Calling thread only.
  void rgb(const float* cos_view_zenith, const float* cos_view_sun, float* r, float* g, float* b,
           std::size_t n) const;

 private:
  PietrasKind kind_;
  double max_value_;
  bool night_;
  bool observer_lit_;  // the observer is in the atmosphere and sunlit: every view ray is lit
  double ground_radius_m_, top_altitude_m_, altitude_m_;
  float cos_sun_zenith_, density_;
  std::vector<MlpBatch> subnets_;
};

}  // namespace skylight::nn
