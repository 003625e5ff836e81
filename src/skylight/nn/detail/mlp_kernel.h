// The SIMD batch kernels of the MLP engine (mlp_kernel.cpp, Highway dynamic dispatch): a generic
// structure-of-arrays forward pass and the fused sky kernel that computes a sky network's
// per-direction inputs on the fly (see sky_network.h). Internal: use MlpBatch / SkyNetwork.
#pragma once

#include <cstddef>
#include <limits>

#include "skylight/nn/mlp.h"

namespace skylight::nn::detail {

// Widest layer the batch kernels accept (their per-vector scratch is sized for it).
inline constexpr int kMaxBatchWidth = 256;

// One layer in single precision: W (n_out x n_in, row-major), b (n_out), activation f.
struct BatchLayer {
  int n_in = 0;
  int n_out = 0;
  Activation f = Activation::identity;
  const float* w = nullptr;
  const float* b = nullptr;
};

// outputs[c][i] = network(inputs[.][i])_c, i < n.
void mlp_batch(const BatchLayer* layers, int n_layers, const float* const* inputs,
               float* const* outputs, std::size_t n);

// Per-direction inputs the fused sky kernel can compute from a unit view direction v (world
// frame) and the sun direction s. Everything that depends on the sun only is folded into the
// first layer's biases, and the rotation of eq. 10 into its weights, by SkyNetworkBatch.
enum class DirectionInput {
  x,            // v_x (east)
  y,            // v_y (north)
  z,            // v_z (up) = cos theta
  reference_y,  // v_y of the view rotated by eq. 10: ry_x v_x + ry_y v_y (SkyBatchParams)
  chord,        // d = |s - v| = 2 sin(gamma/2) (Satilmis et al. 2016, §III-B-1)
  log_chord,    // ln(d + kLogChordOffset)
  sqrt_z,       // sqrt(max(v_z, 0))
  aureole,      // 1 / (d^2 + kAureoleOffset)
};
// Offset inside ln(d + offset): keeps the input finite at the sun centre; 1e-2 resolves the
// aureole down to ~0.6 deg from the sun without a huge input range.
inline constexpr double kLogChordOffset = 1e-2;

// Offset of the aureole input 1 / (d^2 + offset): a Mie peak ((1 - g)^2 + g d^2)^(-3/2) has
// offset (1 - g)^2 / g, 0.05 for an asymmetry g ~ 0.8.
inline constexpr double kAureoleOffset = 0.05;

// How the last layer's outputs become radiance.
enum class SkyBatchOutput {
  squared,     // L = o^2: identity last layer whose weights carry sqrt(scale / 2) (L_s folded)
  power4,      // L = o^4: the root4 encoding, scale^(1/4) folded into the last layer
  power8,      // L = o^8: the root8 encoding, scale^(1/8) folded into the last layer
  inverse_ls,  // L = scale * 0.5 (1/y - 1)  (eq. 7 on y = the last layer's output)
  exp,         // L = scale * exp(y)  (log-radiance encoding)
};

struct SkyBatchParams {
  const BatchLayer* layers = nullptr;  // layers[0].n_in == n_inputs
  int n_layers = 0;
  const DirectionInput* inputs = nullptr;
  int n_inputs = 0;
  float sx = 0.0f, sy = 0.0f, sz = 1.0f;  // sun direction (unit, ENU)
  float ry_x = 0.0f, ry_y = 1.0f;         // reference_y = ry_x v_x + ry_y v_y
  SkyBatchOutput output = SkyBatchOutput::squared;
  float scale = 1.0f;
  // Each channel's radiance is clamped to this (SkyNetwork::max_radiance x target_scale).
  float max_value = std::numeric_limits<float>::infinity();
  // Use the unrolled kernel for one satilmis hidden layer of 4, 8, 12, 16, 24, 32 or 48 neurons
  // and 3..5 direction inputs where it applies; false forces the generic kernel. Each width x
  // input count is one fully unrolled instantiation per SIMD target (21 x ~5 make ~30 s of
  // compile time), so the list is kept short.
  bool allow_unrolled = true;
};

// rgb[c][i] = radiance of direction i (0 for v_z < 0); directions as structure of arrays.
void sky_batch(const SkyBatchParams& p, const float* x, const float* y, const float* z, float* r,
               float* g, float* b, std::size_t n);

}  // namespace skylight::nn::detail
