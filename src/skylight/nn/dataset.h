// Training and validation sets for a neural sky model (Satilmis et al. 2016, §III-B-1, §III-D,
// §IV-A): sky states (turbidity, sun position) x stratified view directions, the network's input
// vector V_NN per example, and the source model's radiance.
//
// Radiance here is always *normalised*: L = rgb / target_scale, rgb = the source model's
// SkyModel::rgb() (linear sRGB on its photometric scale). The network learns L through an
// OutputEncoding (L_s^-1 of eq. 7 in the paper).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"

namespace skylight::nn {

// One sky: the parameters a neural sky model is conditioned on. Angles in radians.
struct SkyState {
  double turbidity = 3.0;
  double sun_zenith = 0.0;
  double sun_azimuth = kPi;  // skylight convention: from north towards east; pi = south
  double ground_albedo = 0.5;
};

// What a network learns: for one sky state, the source's linear sRGB per view direction (unit
// vector, world frame). nn/ knows no sky model; models/neural_sky.h makes a SkySource from any
// registered SkyModel (its rgb()). A SkyFunction may be called from one thread at a time; the
// SkySource is called from several threads at once (one SkyFunction per state and thread).
using SkyFunction = std::function<Rgb(Vec3)>;
using SkySource = std::function<SkyFunction(const SkyState&)>;

// ---- network inputs
// --------------------------------------------------------------------------------

// The elements of the input vector. Satilmis et al. 2016 use V_NN = {sqrt t, theta_sun, v_x, v_y,
// v_z, d} (§III-B-1); the others are extensions for the architecture study.
enum class Input {
  sqrt_turbidity,  // sqrt(t): "replacing t with sqrt(t)" linearises the turbidity dependence
  sun_zenith,      // theta_sun [rad]
  view_x,          // v_x of the view rotated by eq. 10 (sun moved to azimuth pi)
  view_y,          // v_y of the rotated view
  view_z,          // v_z = cos theta_view
  chord,           // d = |omega_sun - omega_view| = 2 sin(gamma/2)
  log_chord,       // ln(d + kLogChordOffset) (nn/detail/mlp_kernel.h): resolves the aureole
  sqrt_view_z,     // sqrt(max(v_z, 0)) (the Hosek-Wilkie zenith term)
  aureole,         // 1 / (d^2 + kAureoleOffset) (nn/detail/mlp_kernel.h), the shape of a Mie peak
  cos_sun_zenith,  // cos theta_sun
  sun_elevation_cbrt,  // (elevation / (pi/2))^(1/3), the Hosek-Wilkie Bezier variable
  turbidity,           // t
};
std::string_view to_string(Input in);
std::optional<Input> parse_input(std::string_view name);
// True for inputs that depend on the sky state only: the batch path folds them into the first
// layer's biases, so they cost nothing per direction.
bool is_state_input(Input in);

using InputSpec = std::vector<Input>;
// V_NN of Satilmis et al. 2016.
InputSpec satilmis_inputs();
// "sqrt_turbidity,sun_zenith,..." <-> InputSpec; parse throws InvalidArgument.
std::string to_string(const InputSpec& spec);
InputSpec parse_inputs(std::string_view list);

// The view rotated about the zenith so that the sun lies at azimuth pi (Satilmis et al. 2016
// eq. 10: rotate = phi_sun - pi). The paper writes it in a frame whose x axis is at azimuth 0;
// in skylight's ENU frame (x east, y north, azimuth from north towards east) the same rotation
// of the azimuth by -rotate reads v_x = v'_x cos r - v'_y sin r, v_y = v'_y cos r + v'_x sin r.
Vec3 rotate_view_to_reference(Vec3 view, double sun_azimuth);
// V_NN for one example; out.size() == spec.size(). view: unit vector, world frame.
void compute_inputs(const InputSpec& spec, const SkyState& state, Vec3 view, std::span<double> out);

// ---- output encodings ------------------------------------------------------------------------

enum class OutputEncoding {
  satilmis,  // y = L_s^-1(L) = 1 / (1 + 2 L) (§III-C); L = L_s(y) = 0.5 (1/y - 1) (eq. 7)
  log,       // y = ln(max(L, kLogRadianceFloor)); L = e^y (relative errors uniformly weighted)
  root4,     // y = L^(1/4); L = y^4 (two multiplications instead of an exp)
  root8,     // y = L^(1/8) ~ 1 + ln(L)/8 over the sky's range; L = y^8 (three multiplications)
};
std::string_view to_string(OutputEncoding e);
std::optional<OutputEncoding> parse_output_encoding(std::string_view name);

// ln(L) of the log encoding is taken of max(L, this) (normalised units): the sky models are
// >= 0.03 on the paper's sets, but the source may return 0 (clamped fit) or below.
inline constexpr double kLogRadianceFloor = 1e-4;

// Target of the network for normalised radiance L. Every encoding takes max(L, 0) (log: max(L,
// floor)): the decoded radiance is >= 0 by construction and cannot represent negative values
// (Preetham's linear sRGB can be slightly negative near the horizon for a low sun: out-of-gamut
// colours).
double encode_radiance(OutputEncoding e, double L);
// Normalised radiance from the network output y.
double decode_radiance(OutputEncoding e, double y);

// ---- sampling protocol -------------------------------------------------------------------------

struct SamplingSpec {
  std::string source;  // what is sampled (a registry model's name, "images"): a label
  double target_scale = 1.0;
  std::vector<double> turbidities;
  // Sun zenith angles theta_k = (k + 0.5) / sun_count * pi/2 (midpoints of equal strata of
  // [0, pi/2]: avoids the degenerate sun exactly at the horizon, where Preetham extrapolates).
  int sun_count = 20;
  // false: every sun at azimuth pi (the paper's training azimuth); true: a uniformly random
  // azimuth per sky state (validation sets: exercises the rotation of eq. 10).
  bool vary_sun_azimuth = false;
  double ground_albedo = 0.5;
  // Views: stratified over the upper hemisphere, view_zeniths strata equal in theta in [0, pi/2]
  // x view_azimuths strata in [0, 2 pi), one jittered sample per stratum.
  int view_zeniths = 10;
  int view_azimuths = 20;
  std::uint64_t seed = 1;
};

// Satilmis et al. 2016 §III-D / §IV-A over a source's turbidities (which ones is the source's
// policy: models/sky_model.h, NeuralPolicy; e.g. Preetham t = 2, 3, .., 6 and 2.5, .., 5.5).
// Training: albedo 0.5; 20 sun zenith angles at azimuth pi; 10 x 20 views, seed 1. Validation:
// 7 sun zenith angles (azimuths varied); 10 x 20 views, seed 2. target_scale: the source's
// normalisation (the network learns rgb / target_scale).
SamplingSpec paper_training_spec(std::string_view source, std::vector<double> turbidities,
                                 double target_scale);
SamplingSpec paper_validation_spec(std::string_view source, std::vector<double> turbidities,
                                   double target_scale);

struct Dataset {
  SamplingSpec spec;
  InputSpec input_spec;
  std::vector<SkyState> states;
  // Per example i: its state, view (world frame), inputs (n_inputs values) and normalised
  // radiance L (3 values, r g b; raw source values, may be < 0 for Preetham).
  std::vector<int> state_index;
  std::vector<Vec3> views;
  std::vector<double> inputs;
  std::vector<double> radiance;

  std::size_t size() const { return views.size(); }
  int n_inputs() const { return static_cast<int>(input_spec.size()); }
  // Targets y = encode_radiance(L), size() x 3.
  std::vector<double> targets(OutputEncoding e) const;
  // The largest normalised radiance of any example and channel (0 for none).
  double max_radiance() const;
};

// Evaluates the source on every example (parallel over states).
Dataset build_dataset(const SamplingSpec& spec, const InputSpec& inputs, const SkySource& source);

}  // namespace skylight::nn
