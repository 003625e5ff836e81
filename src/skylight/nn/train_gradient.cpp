#include "skylight/nn/detail/train_gradient.h"

#include <Eigen/Dense>
#include <algorithm>
#include <numbers>
#include <numeric>
#include <vector>

#include "skylight/core/parallel.h"

namespace skylight::nn::detail {
namespace {

using Eigen::ArrayXXd;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// f_k on a block of pre-activations, elementwise as activate() (mlp.h): the activations of the
// Pietras and sky networks as array expressions (vectorised exp), the others per element.
void activate_block(Activation f, const ArrayXXd& a, ArrayXXd& y) {
  switch (f) {
    case Activation::identity:
      y = a;
      return;
    case Activation::pietras:  // 1 / (1 + 2^(2x)); exp overflows to inf, giving 0 as activate()
      y = (1.0 + (2.0 * std::numbers::ln2 * a).exp()).inverse();
      return;
    case Activation::sigmoid:
      y = (1.0 + (-a).exp()).inverse();
      return;
    case Activation::satilmis:
      y = (1.0 + a.square()).inverse();
      return;
    default:
      y = a.unaryExpr([f](double x) { return activate(f, x); });
  }
}

// delta *= f_k'(a, y) elementwise, as activation_derivative() (mlp.h).
void multiply_derivative(Activation f, const ArrayXXd& a, const ArrayXXd& y, ArrayXXd& delta) {
  switch (f) {
    case Activation::identity:
      return;
    case Activation::pietras:
      delta *= (-2.0 * std::numbers::ln2) * y * (1.0 - y);
      return;
    case Activation::sigmoid:
      delta *= y * (1.0 - y);
      return;
    case Activation::satilmis:
      delta *= -2.0 * a * y.square();
      return;
    case Activation::tanh:
      delta *= 1.0 - y.square();
      return;
    default:
      delta *= a.binaryExpr(y, [f](double x, double v) { return activation_derivative(f, x, v); });
  }
}

// Examples per block of the batched gradient: each layer of a block is one matrix product.
constexpr std::size_t kGradientBlock = 256;

// Per-thread buffers of the batched gradient (layer k's pre-activations a[k], outputs o[k] and
// dE/da delta[k], one column per example of the block).
struct GradientBlock {
  std::vector<ArrayXXd> a, o, delta;
  MatrixXd x;  // gathered inputs (mini-batches)
  explicit GradientBlock(const MlpLayout& l)
      : a(l.layers() + 1), o(l.layers() + 1), delta(l.layers() + 1) {}
};

// E and, unless grad is null, grad += dE/dw over the m examples whose inputs are the columns of x
// and targets those of t: the back-propagation of backward() (mlp.h) for a block of examples at
// once,
//   a^k = W^k o^(k-1) + w^k_0,  delta^L = 2 (o^L - t) f_L'(a^L),
//   delta^(k-1) = f_(k-1)'(a^(k-1)) (W^k)^T delta^k,  dE/dW^k = delta^k (o^(k-1))^T.
double gradient_block(const Mlp& net, const Eigen::Ref<const MatrixXd>& x,
                      const Eigen::Ref<const MatrixXd>& t, GradientBlock& b, double* grad) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const MlpLayout& l = net.layout();
  const int L = l.layers();
  const double* p = net.parameters().data();
  auto weights = [&](int k) {
    return Eigen::Map<const RowMajor>(p + l.weight_offset(k), l.widths[k], l.widths[k - 1]);
  };
  auto biases = [&](int k) {
    return Eigen::Map<const VectorXd>(p + l.bias_offset(k), l.widths[k]);
  };
  for (int k = 1; k <= L; ++k) {
    if (k == 1)
      b.a[1].matrix().noalias() = weights(1) * x;
    else
      b.a[k].matrix().noalias() = weights(k) * b.o[k - 1].matrix();
    b.a[k].matrix().colwise() += biases(k);
    activate_block(l.activations[k - 1], b.a[k], b.o[k]);
  }
  b.delta[L] = b.o[L] - t.array();
  const double e = b.delta[L].square().sum();
  if (grad == nullptr) return e;
  b.delta[L] *= 2.0;  // dE/dPsi
  multiply_derivative(l.activations[L - 1], b.a[L], b.o[L], b.delta[L]);
  for (int k = L; k >= 1; --k) {
    Eigen::Map<RowMajor> gw(grad + l.weight_offset(k), l.widths[k], l.widths[k - 1]);
    if (k == 1)
      gw.noalias() += b.delta[1].matrix() * x.transpose();
    else
      gw.noalias() += b.delta[k].matrix() * b.o[k - 1].matrix().transpose();
    Eigen::Map<VectorXd>(grad + l.bias_offset(k), l.widths[k]) +=
        b.delta[k].matrix().rowwise().sum();
    if (k == 1) break;
    b.delta[k - 1].matrix().noalias() = weights(k).transpose() * b.delta[k].matrix();
    multiply_derivative(l.activations[k - 2], b.a[k - 1], b.o[k - 1], b.delta[k - 1]);
  }
  return e;
}

}  // namespace

// Gradient of E = sum (Psi - t)^2 over examples idx[0..n) (the first n when idx is empty), summed
// into grad (overwritten); returns E. Fixed slices of blocks of kGradientBlock examples, partial
// sums added in slice order (deterministic on any thread count).
double gradient(const Mlp& net, std::span<const double> x, std::span<const double> t,
                std::span<const std::size_t> idx, std::size_t n, std::span<double> grad) {
  const std::size_t P = net.layout().parameter_count();
  const int n_in = net.layout().inputs(), n_out = net.layout().outputs();
  const std::size_t slices = std::min<std::size_t>(kSlices, std::max<std::size_t>(1, n / 64));
  std::vector<std::vector<double>> part(slices, std::vector<double>(P, 0.0));
  std::vector<double> loss(slices, 0.0);
  parallel_for(slices, 1, [&](std::size_t sb, std::size_t se) {
    GradientBlock blk(net.layout());
    MatrixXd tb;
    for (std::size_t s = sb; s < se; ++s) {
      const std::size_t end = slice_begin(s + 1, n, slices);
      for (std::size_t i0 = slice_begin(s, n, slices); i0 < end; i0 += kGradientBlock) {
        const auto m = static_cast<Eigen::Index>(std::min(kGradientBlock, end - i0));
        if (idx.empty()) {
          // Row-major examples: a block is a column-major n_in x m (n_out x m) matrix.
          const Eigen::Map<const MatrixXd> xb(x.data() + i0 * n_in, n_in, m);
          const Eigen::Map<const MatrixXd> tm(t.data() + i0 * n_out, n_out, m);
          loss[s] += gradient_block(net, xb, tm, blk, part[s].data());
        } else {
          blk.x.resize(n_in, m);
          tb.resize(n_out, m);
          for (Eigen::Index k = 0; k < m; ++k) {
            const std::size_t i = idx[i0 + static_cast<std::size_t>(k)];
            for (int c = 0; c < n_in; ++c) blk.x(c, k) = x[i * n_in + c];
            for (int c = 0; c < n_out; ++c) tb(c, k) = t[i * n_out + c];
          }
          loss[s] += gradient_block(net, blk.x, tb, blk, part[s].data());
        }
      }
    }
  });
  std::fill(grad.begin(), grad.end(), 0.0);
  double e = 0.0;
  for (std::size_t s = 0; s < slices; ++s) {
    for (std::size_t p = 0; p < P; ++p) grad[p] += part[s][p];
    e += loss[s];
  }
  return e;
}

// Sum of squared errors over all n examples: gradient()'s blocks without the backward pass,
// parallel over fixed slices, ordered reduction.
double sse(const Mlp& net, std::span<const double> x, std::span<const double> t, std::size_t n) {
  const int n_in = net.layout().inputs(), n_out = net.layout().outputs();
  std::vector<double> part(kSlices, 0.0);
  parallel_for(kSlices, 1, [&](std::size_t sb, std::size_t se) {
    GradientBlock blk(net.layout());
    for (std::size_t s = sb; s < se; ++s) {
      const std::size_t end = slice_begin(s + 1, n, kSlices);
      for (std::size_t i0 = slice_begin(s, n, kSlices); i0 < end; i0 += kGradientBlock) {
        const auto m = static_cast<Eigen::Index>(std::min(kGradientBlock, end - i0));
        const Eigen::Map<const MatrixXd> xb(x.data() + i0 * n_in, n_in, m);
        const Eigen::Map<const MatrixXd> tm(t.data() + i0 * n_out, n_out, m);
        part[s] += gradient_block(net, xb, tm, blk, nullptr);
      }
    }
  });
  return std::accumulate(part.begin(), part.end(), 0.0);
}

}  // namespace skylight::nn::detail
