#include "skylight/gpu/network.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "skylight/core/error.h"
#include "support/gpu_context.h"

namespace skylight::gpu {
namespace {

using testing_support::GpuTest;

// Single-precision weights (relative rounding 6e-8 each), float sums of <= 10 terms through three
// layers and the driver's exp/exp2 (a few ulp): 2e-5 of (1 + |Psi|) bounds the difference to the
// double reference for weights and inputs of order 1.
constexpr double kGpuMlpTolerance = 2e-5;

TEST_F(GpuTest, EveryActivationAndLayoutMatchesTheDoubleReference) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const nn::Activation acts[] = {nn::Activation::identity, nn::Activation::satilmis,
                                 nn::Activation::pietras,  nn::Activation::tanh,
                                 nn::Activation::sigmoid,  nn::Activation::relu,
                                 nn::Activation::softplus};
  // 5 inputs (two input textures), 6 outputs (two passes), the 4-8-4-1 shape of a Pietras
  // sub-network and the paper's 6-12-3.
  const std::vector<std::vector<int>> layouts = {{5, 9, 7, 6}, {4, 8, 4, 1}, {6, 12, 3}};
  const std::size_t n = 1500;  // two target rows
  for (const auto& widths : layouts) {
    for (nn::Activation a : acts) {
      nn::MlpLayout layout;
      layout.widths = widths;
      layout.activations.assign(widths.size() - 1, a);
      layout.activations.back() = nn::Activation::identity;
      std::vector<double> p(layout.parameter_count());
      for (double& v : p) v = u(rng);
      const nn::Mlp net(layout, p);
      std::vector<float> in(n * static_cast<std::size_t>(layout.inputs()));
      for (float& v : in) v = static_cast<float>(2.0 * u(rng));
      const std::vector<float> out = evaluate_mlp(net, in);
      ASSERT_EQ(out.size(), n * static_cast<std::size_t>(layout.outputs()));
      double worst = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        std::vector<double> x(in.begin() + static_cast<std::ptrdiff_t>(i * layout.inputs()),
                              in.begin() + static_cast<std::ptrdiff_t>((i + 1) * layout.inputs()));
        const std::vector<double> y = net(x);
        for (std::size_t c = 0; c < y.size(); ++c) {
          const double d = std::abs(out[i * y.size() + c] - y[c]) / (1.0 + std::abs(y[c]));
          worst = std::max(worst, d);
        }
      }
      EXPECT_LE(worst, kGpuMlpTolerance) << layout.describe();
    }
  }
}

TEST_F(GpuTest, InputCountMustMatchTheLayout) {
  const nn::Mlp net(nn::MlpLayout::make(3, {4}, 2, nn::Activation::tanh, nn::Activation::identity));
  const std::vector<float> in(7);
  EXPECT_THROW(evaluate_mlp(net, in), InvalidArgument);
  EXPECT_TRUE(evaluate_mlp(net, std::vector<float>{}).empty());
}

}  // namespace
}  // namespace skylight::gpu
