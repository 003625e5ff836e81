// The full-batch loss and gradient of the trainers (train.h): the layers of blocks of examples as
// matrix products (Eigen), the activations as array expressions, partial sums over fixed slices
// of the examples added in slice order. Internal to train.cpp.
#pragma once

#include <cstddef>
#include <span>

#include <vector>

#include "skylight/nn/mlp.h"
#include "skylight/nn/train.h"

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

// The Gauss-Newton system as the Levenberg-Marquardt trainer assembles it (block-sparse output
// layer, SIMD products): A = J^T J (P x P, column-major, both triangles), g = J^T r, e = r^T r,
// r = Psi(inputs) - targets over all examples (inputs used as given). For tests (train.cpp).
void gauss_newton_system(const Mlp& net, const Examples& examples, std::vector<double>& A,
                         std::vector<double>& g, double& e);
// E = sum (Psi - t)^2 over all examples and grad = dE/d(parameters) as the L-BFGS trainer computes
// them (blocks of examples as matrix products); inputs used as given. For tests (train.cpp).
double loss_gradient(const Mlp& net, const Examples& examples, std::vector<double>& grad);

}  // namespace skylight::nn::detail
