// A trained neural sky model (Satilmis et al. 2016 eq. 4): F_NN(V_NN) = L_s(Psi(V_NN)), here
// generalised to any input vector and output encoding, times the target scale:
//   rgb = target_scale * decode_radiance(encoding, Psi(V_NN(state, view))).
// Scalar reference path in double precision; batch path (SkyNetworkBatch) in single precision
// SIMD for one sky state over many directions.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/nn/dataset.h"
#include "skylight/nn/mlp.h"

namespace skylight::nn {

// Where a network came from (informative; written into and read from the weights file).
struct SkyNetworkProvenance {
  std::string source;               // the registry name of the model it learned
  std::vector<double> turbidities;  // the training sky states (empty: the source has none)
  double ground_albedo = 0.5;
  int sun_count = 0;  // sun zenith angles per turbidity, in [0, pi/2]
  int view_zeniths = 0, view_azimuths = 0;
  std::uint64_t seed = 0;
  std::string trainer;  // train.h Trainer name
  int iterations = 0;
  std::string stop;  // TrainResult::stop
  double training_seconds = 0.0;
  double training_mse = 0.0;  // E / (examples x 3) in the encoded output space
  // On the paper's validation set (metrics.h), when measured.
  std::optional<double> validation_rmse, validation_relative_median, validation_relative_p95;
  std::string date;      // ISO 8601 UTC, when it was trained
  std::string software;  // "skylight 0.1.0"
};

struct SkyNetwork {
  Mlp net;  // n_0 = inputs.size(), n_L = 3 (r, g, b)
  InputSpec inputs = satilmis_inputs();
  OutputEncoding encoding = OutputEncoding::satilmis;
  double target_scale = 1.0;  // rgb = target_scale * normalised radiance
  // The bound of the decoded normalised radiance (every path clamps each channel to it): training
  // sets kMaxRadianceMargin x the largest radiance it was trained on, so no view between the
  // training skies can decode to a sky far brighter than any it learnt (a network near the pole of
  // 1/y decodes to any value). Absent (files without "max_radiance"): unbounded.
  std::optional<double> max_radiance;
  SkyNetworkProvenance provenance;

  // Linear sRGB on the source model's scale for a view (unit vector, world frame); 0 below the
  // horizon (view z < 0), like the library's sky models.
  Rgb rgb(const SkyState& state, Vec3 view) const;
  // The network output Psi for a view (no horizon test), n_L values.
  std::vector<double> output(const SkyState& state, Vec3 view) const;
  // Normalised radiance of output y: decode_radiance per channel, within max_radiance.
  double radiance(double y) const {
    const double L = decode_radiance(encoding, y);
    return max_radiance ? std::min(L, *max_radiance) : L;
  }
};
// The training's bound: this many times the largest training radiance (the brightest training
// sky is already the brightest view of the brightest state; twice it leaves room for the states
// between the training ones, e.g. T between two training turbidities).
inline constexpr double kMaxRadianceMargin = 2.0;

// The weights file (docs/NN.md): a JSON object {"format": "skylight-nn-sky", "version": 1,
// "architecture": {widths, activations, parameter_order}, "inputs", "input_transform",
// "output_encoding", "target_scale", optional "max_radiance", "parameters", "provenance"}; numbers
// in shortest round-trip
// form, so a network survives save and load bit for bit.
inline constexpr std::string_view kSkyNetworkFormat = "skylight-nn-sky";
inline constexpr int kSkyNetworkVersion = 1;
std::string to_json(const SkyNetwork& sky);
// The one strict loader: malformed JSON, a wrong format or version, a missing, mistyped,
// non-finite or inconsistent field (widths vs activations, inputs, parameter count, 3 outputs)
// throws InvalidArgument "<where>: field '<name>' <why>". `where` names the file.
SkyNetwork sky_network_from_json(std::string_view text, const std::string& where);

// The batch path for one sky state: the state inputs (sqrt t, theta_sun, ...) are folded into
// the first layer's biases and the rotation of eq. 10 into its weights, so per direction the
// kernel computes only the direction inputs (v, d, ...) and the layers. With the satilmis
// encoding and the satilmis output activation the output needs no division:
// L_s(f(o)) = 0.5 (1 + o^2 - 1) = o^2 / 2, and sqrt(target_scale / 2) is folded into the last
// layer, so rgb = o^2. Error against SkyNetwork::rgb: kSkyBatchRelativeTolerance in the tests.
class SkyNetworkBatch {
 public:
  // allow_unrolled = false forces the generic kernel (tests, timing).
  SkyNetworkBatch(const SkyNetwork& sky, const SkyState& state, bool allow_unrolled = true);
  ~SkyNetworkBatch();
  // Move-only: the kernel's parameters point into its own buffers.
  SkyNetworkBatch(const SkyNetworkBatch&) = delete;
  SkyNetworkBatch& operator=(const SkyNetworkBatch&) = delete;
  SkyNetworkBatch(SkyNetworkBatch&&) noexcept;
  SkyNetworkBatch& operator=(SkyNetworkBatch&&) noexcept;
  // r/g/b[i] for directions (x, y, z)[i], unit vectors in the world frame; 0 below the horizon.
  // Calling thread only.
  void rgb(const float* x, const float* y, const float* z, float* r, float* g, float* b,
           std::size_t n) const;

 private:
  struct Kernel;  // the SIMD kernel's layers and inputs (sky_network.cpp, detail/mlp_kernel.h)
  std::unique_ptr<Kernel> kernel_;
};

}  // namespace skylight::nn
