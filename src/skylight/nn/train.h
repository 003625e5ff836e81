// Training an Mlp on examples (input vector, target vector): minimises the sum of squared errors
// E(w) = sum_examples sum_j (Psi(V)_j - y_j)^2 (Satilmis et al. 2016 eq. 9, in the network's
// output space: targets are the encoded radiances y = L_s^-1(L) of §III-C).
//
// Trainers:
//  * backprop: the paper's on-line back-propagation (§III-C, §IV): per example
//    Delta w(t) = -beta dE_i/dw + mu Delta w(t-1), beta = 0.01, mu = 0.9, examples shuffled each
//    epoch. For reproduction.
//  * levenberg_marquardt (default): full-batch Gauss-Newton with Marquardt damping,
//    (J^T J + lambda diag(J^T J)) delta = -J^T r. J^T J and J^T r are accumulated over a fixed
//    set of example slices on the library's thread pool and summed in slice order; the last
//    layer's block sparsity is used (output c's weights move output c only) and the products run
//    in a Highway kernel (detail/train_kernel.h). Eigen only solves the P x P system (Cholesky).
//  * adam: mini-batch Adam (Kingma & Ba 2015).
//  * lbfgs: full-batch L-BFGS (m = 10) with a backtracking Armijo line search (quadratic
//    interpolation; rejected trials evaluate E only). Its and Adam's gradient run the layers of
//    blocks of examples as matrix products (Eigen), the activations as array expressions.
//
// Determinism: the initial weights, shuffles and mini-batches come from Rng(seed); the result is
// bit-identical for a seed and an iteration count on any thread count, for one SIMD target (the
// J^T J kernel sums with FMA on AVX2/AVX-512, without on SSE4). A time limit, when it is what
// stops training, makes the result depend on the machine (TrainResult::stop says so).
//
// Inputs are standardised for training ((x - mean) / std over the training examples, a
// preconditioning) and the transform is folded back into the first layer afterwards, so the
// returned network takes the raw V_NN.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/nn/mlp.h"

namespace skylight::nn {

class Rng;

// Examples as row-major matrices (views, not owned).
struct Examples {
  std::span<const double> inputs;   // size() x n_0
  std::span<const double> targets;  // size() x n_L
  std::size_t count = 0;
};

enum class Trainer { backprop, levenberg_marquardt, adam, lbfgs };
std::string_view to_string(Trainer t);
std::optional<Trainer> parse_trainer(std::string_view name);

// One line of the training log, written after every iteration (LM / L-BFGS: one Jacobian or
// gradient evaluation; backprop / adam: one epoch over the examples).
struct TrainLogEntry {
  int iteration = 0;
  double seconds = 0.0;  // wall time since the start of training
  double mse = 0.0;      // E / (examples x outputs) on the training examples
  double validation_mse = std::numeric_limits<double>::quiet_NaN();  // when validation is given
  double step = 0.0;  // LM: lambda; L-BFGS: accepted step length; others: learning rate
  int restart = 0;    // which initialisation (0 = the one kept when restarts > 1)
};

struct TrainOptions {
  Trainer trainer = Trainer::levenberg_marquardt;
  std::uint64_t seed = 1;
  // Stops: whichever comes first. max_iterations as in TrainLogEntry::iteration. The defaults fit
  // the paper's 6-12-3 networks with LM: Preetham converges in ~300 iterations (~12 s on two
  // shared cores), Hosek in ~500 (~35 s).
  int max_iterations = 500;
  // CPU time of the process (all its threads) [s], not wall time: a result does not depend on the
  // machine's load (only on where, in iterations, the budget ends).
  double time_limit_s = 60.0;
  // Stop when the training MSE has not improved by a factor (1 - min_improvement) over the last
  // `patience` iterations; 0 = never, -1 = the trainer's default: 50 for LM (a plateau of LM is
  // final), never for the others (back-propagation and Adam improve by < 0.1% per 50 epochs long
  // before they converge).
  int patience = -1;
  double min_improvement = 1e-3;
  bool standardise_inputs = true;
  // Warm start: training continues from this network (raw inputs, as train() returns it; its
  // layout must equal the layout trained) instead of random weights; restarts, init_gain and
  // init_output_from_targets are then unused.
  const Mlp* initial = nullptr;
  // Independent initialisations, each trained for restart_iterations; the best continues: the
  // lowest error on the validation examples when they are given, else on the training examples.
  int restarts = 1;
  int restart_iterations = 20;
  // Scale of the initial weights: U(-a, a), a = init_gain sqrt(3 / fan_in); biases U(-a, a).
  double init_gain = 1.0;
  // Data-dependent start of the output layer: bias_c = f_L^-1(mean target_c) (for the
  // satilmis f_L on the branch o > 0) and the output weights scaled by output_weight_gain, so
  // training starts at the mean on one side of a symmetric f_L. Without it a satilmis output
  // starts at o ~ 0, the top of 1/(1 + o^2) where f' = 0, and examples split between the
  // branches o < 0 and o > 0: most seeds then end in a poor local minimum.
  bool init_output_from_targets = true;
  double output_weight_gain = 0.1;

  // backprop (Satilmis et al. 2016 §IV: beta = 0.01, mu = 0.9); E_i = 1/2 sum_j (Psi_j - y_j)^2.
  double learning_rate = 0.01;
  double momentum = 0.9;
  // Levenberg-Marquardt
  double lambda_initial = 1e-2;
  double lambda_up = 4.0;     // after a rejected step
  double lambda_down = 0.25;  // after an accepted step
  double lambda_max = 1e12;   // stop beyond
  // Adam
  double adam_learning_rate = 3e-3;
  double adam_final_learning_rate = 1e-4;  // cosine decay to this over max_iterations
  int batch_size = 256;

  // Optional held-out examples: validation_mse is logged every validation_every iterations.
  const Examples* validation = nullptr;
  int validation_every = 10;
  // Early stopping: with validation examples, the network returned is the iterate of the lowest
  // validation error among those measured (every validation_every iterations and the last) after
  // the restarts, not the last (TrainResult::kept_iteration).
  bool keep_best_validation = false;
  // Called after every iteration; return false to stop.
  std::function<bool(const TrainLogEntry&)> progress;
};

struct TrainResult {
  Mlp net;  // takes raw inputs (standardisation folded in)
  std::vector<TrainLogEntry> log;
  double seconds = 0.0;
  double mse = 0.0;  // final training MSE
  int iterations = 0;
  std::string stop;  // "iterations", "time_limit", "converged", "lambda_max", "callback"
  // With keep_best_validation: the iteration whose network is returned (== iterations when the
  // last was the best); 0 otherwise.
  int kept_iteration = 0;
};

// Initial parameters: layer k weights and biases U(-a, a), a = gain sqrt(3 / n_(k-1)).
Mlp initial_network(const MlpLayout& layout, Rng& rng, double gain = 1.0);
// x with f(x) = y on the branch used to start training (satilmis: x >= 0); y is clamped into
// f's open range.
double inverse_activation(Activation a, double y);

TrainResult train(const MlpLayout& layout, const Examples& examples, const TrainOptions& options);

// E / (count x outputs) of net on examples (parallel, deterministic).
double mean_squared_error(const Mlp& net, const Examples& examples);

// Machine-readable log: CSV with header
// "restart,iteration,seconds,mse,validation_mse,step".
void write_log_csv(std::ostream& os, const std::vector<TrainLogEntry>& log);

}  // namespace skylight::nn
