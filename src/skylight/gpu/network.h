// Any nn::Mlp evaluated by GL (docs/GPU.md): the network exported by nn/glsl.h runs once per
// pixel of a float target whose input textures hold one example per pixel. The reference the GL
// path is held to in the tests (Mlp::forward, every activation and layout).
#pragma once

#include <span>
#include <vector>

#include "skylight/nn/mlp.h"

namespace skylight::gpu {

// Psi(x) for n = inputs.size() / n_0 examples (row-major, n_0 values each); returns n x n_L
// values, row-major. Needs a current Context. Throws InvalidArgument when inputs.size() is not a
// multiple of n_0, GpuError from GL.
std::vector<float> evaluate_mlp(const nn::Mlp& net, std::span<const float> inputs);

}  // namespace skylight::gpu
