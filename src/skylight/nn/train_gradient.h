// The full-batch loss and gradient of the trainers (train.h): the layers of blocks of examples as
// matrix products (Eigen), the activations as array expressions, partial sums over fixed slices
// of the examples added in slice order. Internal to train.cpp.
#pragma once

#include <cstddef>
#include <span>

#include "skylight/nn/mlp.h"

namespace skylight::nn::detail {

// Examples are split into this many contiguous slices; per-slice partial sums (loss, gradient,
// J^T J) are added in slice order. The split does not depend on the thread count, so neither do
// the results.
constexpr std::size_t kSlices = 16;
inline std::size_t slice_begin(std::size_t s, std::size_t n, std::size_t slices) {
  return s * n / slices;
}

// Gradient of E = sum (Psi - t)^2 over examples idx[0..n) (the first n when idx is empty) of the
// row-major inputs x and targets t, summed into grad (overwritten); returns E.
double gradient(const Mlp& net, std::span<const double> x, std::span<const double> t,
                std::span<const std::size_t> idx, std::size_t n, std::span<double> grad);
// E over the first n examples (the forward pass of gradient()'s blocks).
double sse(const Mlp& net, std::span<const double> x, std::span<const double> t, std::size_t n);

}  // namespace skylight::nn::detail
