#include "skylight/nn/train.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"
#include "skylight/nn/detail/train_gradient.h"
#include "skylight/nn/random.h"

namespace skylight::nn {
namespace {

// A smooth 2-input, 2-output problem in (0, 1) like the encoded sky targets.
struct Toy {
  std::vector<double> x, y;
  std::size_t n = 0;
  Examples examples() const { return {x, y, n}; }
};
Toy toy(std::size_t n, std::uint64_t seed) {
  Toy t;
  t.n = n;
  Rng rng(seed);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = rng.uniform(-1.0, 1.0), b = rng.uniform(0.0, 2.0);
    t.x.insert(t.x.end(), {a, b});
    t.y.push_back(0.5 + 0.3 * std::sin(2.0 * a) * std::exp(-0.5 * b));
    t.y.push_back(0.3 + 0.4 / (1.0 + a * a + 0.5 * b));
  }
  return t;
}

const MlpLayout kToyLayout = MlpLayout::make(2, {8}, 2, Activation::satilmis, Activation::satilmis);

// MSE each trainer must reach on the toy problem within its iteration budget in the tests
// below. The targets have variance ~1e-2; measured over seeds 1-4: LM (60 iterations) 0.9-5.4e-6,
// L-BFGS (300) 5.9-8.7e-6, Adam (150 epochs) 1.6-2.9e-5, backprop (150 epochs) 0.7-1.1e-4.
// Thresholds are ~3-4x the worst seed.
constexpr double kLmToyMse = 2e-5;
constexpr double kLbfgsToyMse = 3e-5;
constexpr double kAdamToyMse = 1e-4;
constexpr double kBackpropToyMse = 4e-4;

TrainResult run(Trainer tr, int iterations, std::uint64_t seed = 1, const Toy& t = toy(300, 1)) {
  TrainOptions o;
  o.trainer = tr;
  o.max_iterations = iterations;
  o.seed = seed;
  o.batch_size = 32;
  o.adam_learning_rate = 1e-2;
  return train(kToyLayout, t.examples(), o);
}

TEST(Train, LevenbergMarquardtConverges) {
  const auto r = run(Trainer::levenberg_marquardt, 60);
  EXPECT_LT(r.mse, kLmToyMse);
  EXPECT_LT(r.log.back().mse, r.log.front().mse);
}

TEST(Train, LbfgsConverges) {
  EXPECT_LT(run(Trainer::lbfgs, 300).mse, kLbfgsToyMse);
}

TEST(Train, AdamConverges) {
  EXPECT_LT(run(Trainer::adam, 150).mse, kAdamToyMse);
}

TEST(Train, BackpropConverges) {
  EXPECT_LT(run(Trainer::backprop, 150).mse, kBackpropToyMse);
}

TEST(Train, DeterministicForASeedOnAnyThreadCount) {
  for (Trainer tr : {Trainer::levenberg_marquardt, Trainer::adam, Trainer::lbfgs}) {
    set_thread_count(1);
    const auto a = run(tr, 8, 42);
    set_thread_count(2);
    const auto b = run(tr, 8, 42);
    set_thread_count(0);
    const auto c = run(tr, 8, 43);
    ASSERT_EQ(a.net.parameters().size(), b.net.parameters().size());
    for (std::size_t p = 0; p < a.net.parameters().size(); ++p) {
      ASSERT_EQ(a.net.parameters()[p], b.net.parameters()[p]) << to_string(tr) << " " << p;
    }
    EXPECT_NE(a.net.parameters()[0], c.net.parameters()[0]) << to_string(tr);
  }
}

// The returned network takes raw inputs: its MSE equals the last logged (standardised) MSE.
TEST(Train, StandardisationIsFoldedIntoTheFirstLayer) {
  Toy t = toy(200, 3);
  for (std::size_t i = 0; i < t.n; ++i) t.x[2 * i + 1] = 50.0 + 10.0 * t.x[2 * i + 1];  // offset
  const auto r = run(Trainer::levenberg_marquardt, 10, 1, t);
  EXPECT_NEAR(r.mse, r.log.back().mse, 1e-9 * r.mse);
}

// Warm start: the initial network's standardisation is unfolded and folded back. With Adam at
// learning rate 0 the parameters do not move, so the result is the initial network up to that
// round trip's round-off (inputs offset and scaled as above: |mean| ~ 60, std ~ 6).
constexpr double kWarmStartRoundTrip = 1e-12;  // relative to the largest parameter
TEST(Train, WarmStartContinuesFromTheInitialNetwork) {
  Toy t = toy(200, 3);
  for (std::size_t i = 0; i < t.n; ++i) t.x[2 * i + 1] = 50.0 + 10.0 * t.x[2 * i + 1];
  const TrainResult first = run(Trainer::levenberg_marquardt, 10, 1, t);
  TrainOptions o;
  o.trainer = Trainer::adam;
  o.adam_learning_rate = o.adam_final_learning_rate = 0.0;
  o.max_iterations = 2;
  o.initial = &first.net;
  const TrainResult same = train(kToyLayout, t.examples(), o);
  double scale = 0.0;
  for (double v : first.net.parameters()) scale = std::max(scale, std::abs(v));
  for (std::size_t i = 0; i < first.net.parameters().size(); ++i)
    EXPECT_NEAR(same.net.parameters()[i], first.net.parameters()[i], kWarmStartRoundTrip * scale);
  // Continuing with LM lowers the error from where the first run stopped.
  o.trainer = Trainer::levenberg_marquardt;
  o.max_iterations = 20;
  const TrainResult more = train(kToyLayout, t.examples(), o);
  EXPECT_LT(more.mse, first.mse);
  EXPECT_LE(more.log.front().mse, first.mse * (1.0 + 1e-9));
  // Another layout is refused.
  Rng rng(1);
  const Mlp other =
      initial_network(MlpLayout::make(2, {4}, 2, Activation::satilmis, Activation::satilmis), rng);
  o.initial = &other;
  EXPECT_THROW(train(kToyLayout, t.examples(), o), InvalidArgument);
}

TEST(Train, RestartsKeepTheBestAndLogEveryRestart) {
  TrainOptions o;
  o.restarts = 3;
  o.restart_iterations = 4;
  o.max_iterations = 10;
  const Toy t = toy(200, 1);
  const auto r = train(kToyLayout, t.examples(), o);
  int per_restart[4] = {0, 0, 0, 0};
  for (const auto& e : r.log) ++per_restart[e.restart];
  EXPECT_EQ(per_restart[1], 4);
  EXPECT_EQ(per_restart[3], 4);
  EXPECT_EQ(per_restart[0], 6);  // the kept one continues to iteration 10
  EXPECT_EQ(r.iterations, 10);
}

TEST(Train, ProgressCallbackStopsAndLogIsCsv) {
  TrainOptions o;
  o.max_iterations = 50;
  int calls = 0;
  o.progress = [&](const TrainLogEntry&) { return ++calls < 3; };
  const Toy t = toy(100, 1);
  const Toy v = toy(50, 2);
  const Examples vex = v.examples();
  o.validation = &vex;
  o.validation_every = 1;
  const auto r = train(kToyLayout, t.examples(), o);
  EXPECT_EQ(r.stop, "callback");
  EXPECT_EQ(r.log.size(), 3u);
  EXPECT_FALSE(std::isnan(r.log[0].validation_mse));
  std::ostringstream os;
  write_log_csv(os, r.log);
  EXPECT_EQ(os.str().substr(0, os.str().find('\n')),
            "restart,iteration,seconds,mse,validation_mse,step");
}

// Early stopping: the network returned is the measured iterate of the lowest validation error
// (a few training examples, so that training past it raises the validation error), and
// kept_iteration names it. The returned network is folded back to raw inputs: its validation MSE
// equals the logged one up to rounding.
constexpr double kFoldedMseTolerance = 1e-9;

TEST(Train, KeepBestValidationReturnsTheLowestMeasuredIterate) {
  const Toy t = toy(12, 3);
  const Toy v = toy(200, 4);
  const Examples vex = v.examples();
  TrainOptions o;
  o.max_iterations = 120;
  o.patience = 0;
  o.validation = &vex;
  o.validation_every = 5;
  o.keep_best_validation = true;
  const auto r = train(kToyLayout, t.examples(), o);
  double best = std::numeric_limits<double>::infinity();
  int best_iteration = 0;
  for (const auto& e : r.log)
    if (!std::isnan(e.validation_mse) && e.validation_mse < best) {
      best = e.validation_mse;
      best_iteration = e.iteration;
    }
  ASSERT_GT(best_iteration, 0);
  EXPECT_LT(best_iteration, r.iterations);  // training went past the best
  EXPECT_EQ(r.kept_iteration, best_iteration);
  EXPECT_NEAR(mean_squared_error(r.net, vex), best, kFoldedMseTolerance * best);
  o.keep_best_validation = false;
  const auto last = train(kToyLayout, t.examples(), o);
  EXPECT_EQ(last.kept_iteration, 0);
  EXPECT_GE(mean_squared_error(last.net, vex), mean_squared_error(r.net, vex));
}

// The block-sparse, SIMD J^T J of the LM trainer equals the dense product of the Jacobians.
constexpr double kNormalEquationsTolerance = 1e-10;

TEST(Train, GaussNewtonSystemMatchesDenseJacobian) {
  const auto layout = MlpLayout::make(2, {5, 4}, 3, Activation::satilmis, Activation::satilmis);
  Rng rng(4);
  const Mlp net = initial_network(layout, rng);
  Toy t = toy(150, 5);
  std::vector<double> y3;  // three outputs: the toy's two and their product
  for (std::size_t i = 0; i < t.n; ++i) {
    y3.insert(y3.end(), {t.y[2 * i], t.y[2 * i + 1], t.y[2 * i] * t.y[2 * i + 1]});
  }
  const Examples ex{t.x, y3, t.n};
  std::vector<double> A, g;
  double e = 0.0;
  detail::gauss_newton_system(net, ex, A, g, e);
  const std::size_t P = layout.parameter_count();
  std::vector<double> A_ref(P * P, 0.0), g_ref(P, 0.0), jac(3 * P);
  double e_ref = 0.0;
  MlpWorkspace ws(layout);
  for (std::size_t i = 0; i < t.n; ++i) {
    forward(net, std::span<const double>(t.x).subspan(2 * i, 2), ws);
    jacobian(net, ws, jac);
    for (int c = 0; c < 3; ++c) {
      const double r = ws.output()[c] - y3[3 * i + c];
      e_ref += r * r;
      for (std::size_t p = 0; p < P; ++p) {
        g_ref[p] += jac[c * P + p] * r;
        for (std::size_t q = 0; q < P; ++q) A_ref[p + q * P] += jac[c * P + p] * jac[c * P + q];
      }
    }
  }
  EXPECT_NEAR(e, e_ref, kNormalEquationsTolerance);
  for (std::size_t p = 0; p < P; ++p) {
    EXPECT_NEAR(g[p], g_ref[p], kNormalEquationsTolerance) << p;
    for (std::size_t q = 0; q < P; ++q) {
      EXPECT_NEAR(A[p + q * P], A_ref[p + q * P], kNormalEquationsTolerance) << p << "," << q;
    }
  }
}

// The blocked gradient (matrix products, array activations) sums the same terms as backward()
// per example, in another order: equal to double round-off over a few hundred examples.
constexpr double kBlockedGradientTolerance = 1e-10;

TEST(Train, BlockedGradientMatchesPerExampleBackprop) {
  // Every activation with an array path, more examples than one block, two outputs.
  for (const auto& [hidden, output] : {std::pair{Activation::pietras, Activation::pietras},
                                       std::pair{Activation::pietras, Activation::identity},
                                       std::pair{Activation::satilmis, Activation::sigmoid},
                                       std::pair{Activation::tanh, Activation::softplus}}) {
    const auto layout = MlpLayout::make(2, {6, 5}, 2, hidden, output);
    Rng rng(9);
    const Mlp net = initial_network(layout, rng);
    const Toy t = toy(700, 6);
    std::vector<double> grad;
    const double e = detail::loss_gradient(net, t.examples(), grad);
    const std::size_t P = layout.parameter_count();
    std::vector<double> ref(P, 0.0), g(2);
    double e_ref = 0.0;
    MlpWorkspace ws(layout);
    for (std::size_t i = 0; i < t.n; ++i) {
      forward(net, std::span<const double>(t.x).subspan(2 * i, 2), ws);
      for (int c = 0; c < 2; ++c) {
        const double r = ws.output()[c] - t.y[2 * i + c];
        e_ref += r * r;
        g[c] = 2.0 * r;
      }
      backward(net, ws, g, ref);
    }
    EXPECT_NEAR(e, e_ref, kBlockedGradientTolerance * e_ref) << layout.describe();
    for (std::size_t p = 0; p < P; ++p) {
      EXPECT_NEAR(grad[p], ref[p], kBlockedGradientTolerance * (1.0 + std::abs(ref[p])))
          << layout.describe() << " parameter " << p;
    }
  }
}

TEST(Train, RejectsMismatchedExamples) {
  const Toy t = toy(10, 1);
  const Examples bad{t.x, std::span<const double>(t.y).first(5), t.n};
  EXPECT_THROW(train(kToyLayout, bad, {}), InvalidArgument);
}

}  // namespace
}  // namespace skylight::nn
