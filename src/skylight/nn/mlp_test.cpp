#include "skylight/nn/mlp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/nn/random.h"
#include "skylight/nn/train.h"

namespace skylight::nn {
namespace {

// Central differences with step kFdStep: truncation ~ h^2 f''' ~ 1e-10, round-off ~ 1e-16 / h
// ~ 1e-11, so analytic and numeric derivatives agree to far better than this.
constexpr double kFdStep = 1e-5;
constexpr double kDerivativeTolerance = 1e-7;
// Single-precision batch vs the double reference: each output is ~100 float operations
// (rounding 6e-8 each) on O(1) values; measured max 6.5e-7 absolute over these layouts (20000
// random inputs each). 2e-5 leaves room for weights of trained networks (larger cancellation).
constexpr double kBatchAbsoluteTolerance = 2e-5;
constexpr double kBatchRelativeTolerance = 2e-5;

constexpr Activation kAll[] = {Activation::identity, Activation::satilmis, Activation::pietras,
                               Activation::tanh,     Activation::sigmoid,  Activation::relu,
                               Activation::softplus};

TEST(Activation, NamesRoundTrip) {
  for (Activation a : kAll) EXPECT_EQ(parse_activation(to_string(a)), a);
  EXPECT_FALSE(parse_activation("swish").has_value());
}

TEST(Activation, DefinitionsAtKnownPoints) {
  EXPECT_DOUBLE_EQ(activate(Activation::satilmis, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(activate(Activation::satilmis, 2.0), 0.2);       // 1 / (1 + 4)
  EXPECT_DOUBLE_EQ(activate(Activation::pietras, 0.5), 1.0 / 3.0);  // 1 / (1 + 2^1)
  EXPECT_DOUBLE_EQ(activate(Activation::sigmoid, 0.0), 0.5);
  EXPECT_DOUBLE_EQ(activate(Activation::relu, -1.0), 0.0);
  EXPECT_NEAR(activate(Activation::softplus, 0.0), std::log(2.0), 1e-15);
  EXPECT_NEAR(activate(Activation::softplus, 800.0), 800.0, 1e-12);  // no overflow
  EXPECT_NEAR(activate(Activation::sigmoid, -800.0), 0.0, 1e-300);
}

TEST(Activation, DerivativesMatchFiniteDifferences) {
  for (Activation a : kAll) {
    for (double x : {-2.3, -0.7, -0.1, 0.3, 1.1, 2.9}) {
      const double fd = (activate(a, x + kFdStep) - activate(a, x - kFdStep)) / (2 * kFdStep);
      EXPECT_NEAR(activation_derivative(a, x, activate(a, x)), fd, kDerivativeTolerance)
          << to_string(a) << " at " << x;
    }
  }
}

TEST(MlpLayout, PaperNetworkHas123Weights) {
  const auto l = MlpLayout::make(6, {12}, 3, Activation::satilmis, Activation::satilmis);
  EXPECT_EQ(l.parameter_count(), 123u);  // 12 (6 + 1) + 3 (12 + 1)
  EXPECT_EQ(l.weight_offset(2), 84u);
  EXPECT_EQ(l.bias_offset(2), 120u);
  EXPECT_EQ(l.describe(), "6-12-3 satilmis/satilmis");
}

TEST(MlpLayout, RejectsBadLayouts) {
  EXPECT_THROW(MlpLayout::make(0, {4}, 3, Activation::tanh, Activation::identity), InvalidArgument);
  MlpLayout l;
  l.widths = {2, 3};
  EXPECT_THROW(l.validate(), InvalidArgument);  // no activation for the layer
  EXPECT_THROW(Mlp(MlpLayout::make(2, {}, 1, Activation::tanh, Activation::tanh), {1.0}),
               InvalidArgument);  // 3 parameters needed
}

TEST(Mlp, ForwardIsEquation6) {
  // 2-2-1 satilmis network with hand-set weights.
  const auto l = MlpLayout::make(2, {2}, 1, Activation::satilmis, Activation::satilmis);
  // W2 = [[1, 2], [0, -1]], b2 = [0.5, 1]; W3 = [[3, -2]], b3 = [0.25]
  const Mlp net(l, {1, 2, 0, -1, 0.5, 1, 3, -2, 0.25});
  const double v0 = 0.3, v1 = -0.4;
  auto f = [](double x) { return 1.0 / (1.0 + x * x); };
  const double h0 = f(1 * v0 + 2 * v1 + 0.5), h1 = f(0 * v0 - 1 * v1 + 1);
  const double expected = f(3 * h0 - 2 * h1 + 0.25);
  const std::vector<double> in = {v0, v1};
  EXPECT_DOUBLE_EQ(net(in)[0], expected);
  MlpWorkspace ws(l);
  forward(net, in, ws);
  EXPECT_DOUBLE_EQ(ws.output()[0], expected);
}

// E(w) = sum_c g_c Psi_c(in; w) for fixed g: backward() must give dE/dw.
TEST(Mlp, GradientMatchesFiniteDifferences) {
  for (Activation hidden : kAll) {
    const auto l = MlpLayout::make(3, {5, 4}, 2, hidden, Activation::satilmis);
    Rng rng(11);
    Mlp net = initial_network(l, rng);
    const std::vector<double> in = {0.4, -1.2, 0.7}, g = {0.8, -1.3};
    MlpWorkspace ws(l);
    forward(net, in, ws);
    std::vector<double> grad(l.parameter_count(), 0.0);
    backward(net, ws, g, grad);
    auto E = [&] {
      const auto y = net(in);
      return g[0] * y[0] + g[1] * y[1];
    };
    for (std::size_t p = 0; p < l.parameter_count(); ++p) {
      double& w = net.parameters()[p];
      const double w0 = w;
      w = w0 + kFdStep;
      const double ep = E();
      w = w0 - kFdStep;
      const double em = E();
      w = w0;
      EXPECT_NEAR(grad[p], (ep - em) / (2 * kFdStep), kDerivativeTolerance)
          << to_string(hidden) << " parameter " << p;
    }
  }
}

TEST(Mlp, JacobianRowsAreOneHotGradients) {
  const auto l = MlpLayout::make(4, {6}, 3, Activation::satilmis, Activation::satilmis);
  Rng rng(5);
  const Mlp net = initial_network(l, rng);
  const std::vector<double> in = {1.5, 0.2, -0.3, 0.9};
  MlpWorkspace ws(l);
  forward(net, in, ws);
  const std::size_t P = l.parameter_count();
  std::vector<double> jac(3 * P);
  jacobian(net, ws, jac);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> g(3, 0.0), grad(P, 0.0);
    g[c] = 1.0;
    backward(net, ws, g, grad);
    for (std::size_t p = 0; p < P; ++p) EXPECT_EQ(jac[c * P + p], grad[p]);
  }
  // The output layer's weights of channel c do not move the other channels.
  const std::size_t w3 = l.weight_offset(2);
  EXPECT_EQ(jac[0 * P + w3 + 6], 0.0);  // dPsi_0 / d(output weight row 1, column 0)
  EXPECT_NE(jac[1 * P + w3 + 6], 0.0);
}

TEST(MlpBatch, MatchesScalarReference) {
  struct Case {
    std::vector<int> hidden;
    Activation act, out;
  };
  const Case cases[] = {
      {{12}, Activation::satilmis, Activation::satilmis},
      {{7, 5}, Activation::tanh, Activation::identity},  // widths not multiples of 4
      {{9}, Activation::pietras, Activation::sigmoid},
      {{16, 3}, Activation::softplus, Activation::relu},
      {{4}, Activation::sigmoid, Activation::softplus},
  };
  const std::size_t n = 101;  // not a multiple of any lane count: exercises the tail
  for (const auto& cs : cases) {
    const auto l = MlpLayout::make(6, cs.hidden, 3, cs.act, cs.out);
    Rng rng(3);
    const Mlp net = initial_network(l, rng, 1.5);
    std::vector<std::vector<float>> in(6, std::vector<float>(n));
    for (auto& v : in) {
      for (auto& x : v) x = static_cast<float>(rng.uniform(-2.0, 2.0));
    }
    std::vector<std::vector<float>> out(3, std::vector<float>(n));
    const float* ip[6];
    float* op[3];
    for (int k = 0; k < 6; ++k) ip[k] = in[k].data();
    for (int c = 0; c < 3; ++c) op[c] = out[c].data();
    MlpBatch(net).forward(ip, op, n);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<double> v(6);
      for (int k = 0; k < 6; ++k) v[k] = in[k][i];  // the same (float) inputs
      const auto y = net(v);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(out[c][i], y[c],
                    kBatchAbsoluteTolerance + kBatchRelativeTolerance * std::abs(y[c]))
            << l.describe() << " example " << i << " output " << c;
      }
    }
  }
}

}  // namespace
}  // namespace skylight::nn
