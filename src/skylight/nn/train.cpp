#include "skylight/nn/train.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <ostream>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/core/system.h"
#include "skylight/nn/detail/train_gradient.h"
#include "skylight/nn/detail/train_kernel.h"
#include "skylight/nn/random.h"

namespace skylight::nn {

namespace {

using detail::gradient;
using detail::kSlices;
using detail::slice_begin;
using detail::sse;

// Examples per Jacobian block in Levenberg-Marquardt: the products of J^T J run over blocks of
// this many examples (3 residual rows each).
constexpr std::size_t kJacobianBlock = 2048;

using Clock = std::chrono::steady_clock;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// Training state shared by the trainers: standardised inputs, targets, the clock, the log.
struct Context {
  const MlpLayout& layout;
  std::vector<double> x;  // standardised inputs
  std::span<const double> t;
  std::size_t n = 0;
  std::vector<double> vx;  // standardised validation inputs
  std::span<const double> vt;
  std::size_t vn = 0;
  const TrainOptions& opt;
  Clock::time_point start;
  std::vector<TrainLogEntry>* log = nullptr;
  int iteration = 0;  // global count, across restarts
  int restart = 0;
  std::string stop;
  // TrainOptions::keep_best_validation: the best iterate so far (standardised inputs).
  bool track_best = false;
  std::optional<Mlp> best;
  double best_validation = std::numeric_limits<double>::infinity();
  int best_iteration = 0;

  Context(const MlpLayout& l, const TrainOptions& o) : layout(l), opt(o) {}
  double cpu_start = 0.0;  // process_cpu_s() at the start
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start).count(); }
  // CPU time of the process since the start (all threads): the clock of time_limit_s.
  double cpu_seconds() const { return process_cpu_s() - cpu_start; }
  std::span<const double> input(std::size_t i) const {
    return std::span<const double>(x).subspan(i * layout.inputs(), layout.inputs());
  }
  std::span<const double> target(std::size_t i) const {
    return t.subspan(i * layout.outputs(), layout.outputs());
  }
};

// Logs one iteration; returns false when training must stop (time limit, callback, iterations).
bool log_iteration(Context& ctx, const Mlp& net, double train_sse, double step,
                   int last_iteration) {
  ++ctx.iteration;
  TrainLogEntry e;
  e.iteration = ctx.iteration;
  e.seconds = ctx.seconds();
  e.mse = train_sse / (static_cast<double>(ctx.n) * ctx.layout.outputs());
  e.step = step;
  e.restart = ctx.restart;
  if (ctx.vn > 0 && (ctx.iteration % std::max(1, ctx.opt.validation_every) == 0 ||
                     ctx.iteration == last_iteration)) {
    e.validation_mse =
        sse(net, ctx.vx, ctx.vt, ctx.vn) / (static_cast<double>(ctx.vn) * ctx.layout.outputs());
    if (ctx.track_best && e.validation_mse < ctx.best_validation) {
      ctx.best_validation = e.validation_mse;
      ctx.best = net;
      ctx.best_iteration = ctx.iteration;
    }
  }
  ctx.log->push_back(e);
  if (ctx.opt.progress && !ctx.opt.progress(e)) {
    ctx.stop = "callback";
    return false;
  }
  if (ctx.cpu_seconds() >= ctx.opt.time_limit_s) {
    ctx.stop = "time_limit";
    return false;
  }
  if (ctx.iteration >= last_iteration) {
    ctx.stop = "iterations";
    return false;
  }
  const int pat = ctx.opt.patience >= 0                             ? ctx.opt.patience
                  : ctx.opt.trainer == Trainer::levenberg_marquardt ? 50
                                                                    : 0;
  if (pat > 0 && ctx.log->size() > static_cast<std::size_t>(pat)) {
    const double before = (*ctx.log)[ctx.log->size() - 1 - pat].mse;
    if (e.mse > before * (1.0 - ctx.opt.min_improvement)) {
      ctx.stop = "converged";
      return false;
    }
  }
  return true;
}

// ---- trainers: each runs until log_iteration says stop (at iteration `last`)
// ----------------------

void run_backprop(Context& ctx, Mlp& net, int last, Rng& rng) {
  const std::size_t P = net.layout().parameter_count();
  const int n_out = net.layout().outputs();
  std::vector<double> grad(P), velocity(P, 0.0), g(n_out);
  std::vector<std::size_t> order(ctx.n);
  std::iota(order.begin(), order.end(), 0);
  MlpWorkspace ws(net.layout());
  auto params = net.parameters();
  for (;;) {
    rng.shuffle(std::span<std::size_t>(order));
    for (std::size_t i : order) {
      forward(net, ctx.input(i), ws);
      const auto y = ws.output();
      const auto t = ctx.target(i);
      for (int c = 0; c < n_out; ++c) g[c] = y[c] - t[c];  // d/dPsi of 1/2 sum (Psi - y)^2
      std::fill(grad.begin(), grad.end(), 0.0);
      backward(net, ws, g, grad);
      // Delta w(t) = -beta dE_i/dw + mu Delta w(t-1)
      for (std::size_t p = 0; p < P; ++p) {
        velocity[p] = ctx.opt.momentum * velocity[p] - ctx.opt.learning_rate * grad[p];
        params[p] += velocity[p];
      }
    }
    if (!log_iteration(ctx, net, sse(net, ctx.x, ctx.t, ctx.n), ctx.opt.learning_rate, last)) {
      return;
    }
  }
}

void run_adam(Context& ctx, Mlp& net, int last, Rng& rng) {
  const std::size_t P = net.layout().parameter_count();
  const double beta1 = 0.9, beta2 = 0.999, eps = 1e-8;
  std::vector<double> grad(P), m(P, 0.0), v(P, 0.0);
  std::vector<std::size_t> order(ctx.n);
  std::iota(order.begin(), order.end(), 0);
  auto params = net.parameters();
  const std::size_t B = std::max(1, ctx.opt.batch_size);
  long step = 0;
  const int first = ctx.iteration;
  for (;;) {
    // Cosine decay from adam_learning_rate to adam_final_learning_rate over [first, last].
    const double progress = std::clamp(
        static_cast<double>(ctx.iteration - first) / std::max(1, last - first), 0.0, 1.0);
    const double lr = ctx.opt.adam_final_learning_rate +
                      0.5 * (ctx.opt.adam_learning_rate - ctx.opt.adam_final_learning_rate) *
                          (1.0 + std::cos(kPi * progress));
    rng.shuffle(std::span<std::size_t>(order));
    for (std::size_t b = 0; b < ctx.n; b += B) {
      const std::size_t nb = std::min(B, ctx.n - b);
      gradient(net, ctx.x, ctx.t, std::span<const std::size_t>(order).subspan(b, nb), nb, grad);
      ++step;
      const double c1 = 1.0 - std::pow(beta1, static_cast<double>(step));
      const double c2 = 1.0 - std::pow(beta2, static_cast<double>(step));
      for (std::size_t p = 0; p < P; ++p) {
        const double gp = grad[p] / static_cast<double>(nb);
        m[p] = beta1 * m[p] + (1.0 - beta1) * gp;
        v[p] = beta2 * v[p] + (1.0 - beta2) * gp * gp;
        params[p] -= lr * (m[p] / c1) / (std::sqrt(v[p] / c2) + eps);
      }
    }
    if (!log_iteration(ctx, net, sse(net, ctx.x, ctx.t, ctx.n), lr, last)) return;
  }
}

// L-BFGS's memory of the last kHistory steps s and gradient changes y, rho = 1 / (s . y).
struct LbfgsMemory {
  static constexpr std::size_t kHistory = 10;
  std::vector<std::vector<double>> S, Y;
  std::vector<double> rho;

  void clear() {
    S.clear();
    Y.clear();
    rho.clear();
  }
  // Two-loop recursion: d = -H g; returns gamma, the scale of the initial H.
  double direction(const std::vector<double>& g, std::vector<double>& d) const {
    const std::size_t P = g.size();
    std::vector<double> q(g.begin(), g.end()), alpha(S.size());
    for (int k = static_cast<int>(S.size()) - 1; k >= 0; --k) {
      alpha[k] = rho[k] * std::inner_product(S[k].begin(), S[k].end(), q.begin(), 0.0);
      for (std::size_t p = 0; p < P; ++p) q[p] -= alpha[k] * Y[k][p];
    }
    double gamma = 1.0 / std::sqrt(std::inner_product(g.begin(), g.end(), g.begin(), 1e-300));
    if (!S.empty()) {
      gamma = std::inner_product(S.back().begin(), S.back().end(), Y.back().begin(), 0.0) /
              std::inner_product(Y.back().begin(), Y.back().end(), Y.back().begin(), 1e-300);
    }
    for (std::size_t p = 0; p < P; ++p) q[p] *= gamma;
    for (std::size_t k = 0; k < S.size(); ++k) {
      const double beta = rho[k] * std::inner_product(Y[k].begin(), Y[k].end(), q.begin(), 0.0);
      for (std::size_t p = 0; p < P; ++p) q[p] += S[k][p] * (alpha[k] - beta);
    }
    for (std::size_t p = 0; p < P; ++p) d[p] = -q[p];
    return gamma;
  }
  // Keeps the pair when the curvature s . y is positive (relative to |s| |y|).
  void add(std::vector<double> s, std::vector<double> y) {
    const double sy = std::inner_product(s.begin(), s.end(), y.begin(), 0.0);
    if (!(sy > 1e-12 * std::sqrt(std::inner_product(y.begin(), y.end(), y.begin(), 0.0) *
                                 std::inner_product(s.begin(), s.end(), s.begin(), 0.0))))
      return;
    if (S.size() == kHistory) {
      S.erase(S.begin());
      Y.erase(Y.begin());
      rho.erase(rho.begin());
    }
    S.push_back(std::move(s));
    Y.push_back(std::move(y));
    rho.push_back(1.0 / sy);
  }
};

// Backtracking Armijo line search from x_old along d. The first trial (step 1, accepted on most
// iterations) evaluates E and its gradient in one pass; after a rejection the step is the
// minimiser of the quadratic through f, slope and the rejected E (kept in [0.1, 0.5] of the last
// step), trials evaluate E alone (no backward pass) and the gradient is computed once, at the
// accepted step. Leaves the parameters at the last trial; ok false: no step accepted.
struct LineSearch {
  bool ok = false;
  double step = 1.0, f_new = 0.0;
};
LineSearch armijo(const Context& ctx, Mlp& net, const std::vector<double>& x_old,
                  const std::vector<double>& d, double f, double slope,
                  std::vector<double>& g_new) {
  auto params = net.parameters();
  LineSearch ls;
  ls.f_new = f;
  bool have_gradient = false;
  for (int k = 0; k < 30; ++k) {
    for (std::size_t p = 0; p < params.size(); ++p) params[p] = x_old[p] + ls.step * d[p];
    have_gradient = k == 0;
    ls.f_new = have_gradient ? gradient(net, ctx.x, ctx.t, {}, ctx.n, g_new)
                             : sse(net, ctx.x, ctx.t, ctx.n);
    if (ls.f_new <= f + 1e-4 * ls.step * slope) {
      ls.ok = true;
      break;
    }
    const double curvature = ls.f_new - f - slope * ls.step;  // > 0 after a rejection
    const double q = std::isfinite(ls.f_new) && curvature > 0.0
                         ? -slope * ls.step * ls.step / (2.0 * curvature)
                         : 0.1 * ls.step;
    ls.step = std::clamp(q, 0.1 * ls.step, 0.5 * ls.step);
  }
  if (ls.ok && !have_gradient) ls.f_new = gradient(net, ctx.x, ctx.t, {}, ctx.n, g_new);
  return ls;
}

void run_lbfgs(Context& ctx, Mlp& net, int last) {
  const std::size_t P = net.layout().parameter_count();
  auto params = net.parameters();
  std::vector<double> g(P), g_new(P), d(P), x_old(P);
  LbfgsMemory memory;
  double f = gradient(net, ctx.x, ctx.t, {}, ctx.n, g);
  for (;;) {
    const double gamma = memory.direction(g, d);
    double slope = std::inner_product(g.begin(), g.end(), d.begin(), 0.0);
    if (!(slope < 0.0)) {  // not a descent direction: reset to steepest descent
      memory.clear();
      for (std::size_t p = 0; p < P; ++p) d[p] = -g[p] * gamma;
      slope = std::inner_product(g.begin(), g.end(), d.begin(), 0.0);
    }
    std::copy(params.begin(), params.end(), x_old.begin());
    const LineSearch ls = armijo(ctx, net, x_old, d, f, slope, g_new);
    if (!ls.ok) {
      std::copy(x_old.begin(), x_old.end(), params.begin());
      memory.clear();
      if (!log_iteration(ctx, net, f, 0.0, last)) return;
      continue;
    }
    std::vector<double> s(P), y(P);
    for (std::size_t p = 0; p < P; ++p) {
      s[p] = params[p] - x_old[p];
      y[p] = g_new[p] - g[p];
    }
    memory.add(std::move(s), std::move(y));
    g.swap(g_new);
    f = ls.f_new;
    if (!log_iteration(ctx, net, f, ls.step, last)) return;
  }
}

// J^T J (lower triangle), J^T r and E = r^T r at the current parameters.
struct NormalEquations {
  MatrixXd A;
  VectorXd g;
  double e = 0.0;
};

// Scratch of one normal_equations worker. Column c B + k of j (leading dimension ldj, rows >= P
// are padding) holds the Jacobian row of output c of example k; jo the output block of one
// channel; a_* the per-slice blocks of J^T J.
struct LmScratch {
  std::vector<double> j, r, row, jo;
  MatrixXd a_ss, a_so, a_oo;
};

// Scratch handed to the parallel workers for the duration of one training run (a worker takes
// one, fills it completely before reading it, and gives it back), so the megabytes of Jacobian
// blocks are allocated once per run instead of once per slice and iteration.
class ScratchPool {
 public:
  std::unique_ptr<LmScratch> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (free_.empty()) return std::make_unique<LmScratch>();
    auto s = std::move(free_.back());
    free_.pop_back();
    return s;
  }
  void give(std::unique_ptr<LmScratch> s) {
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(s));
  }

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<LmScratch>> free_;
};

// The shapes of normal_equations' blocks. With S shared parameters (all layers but the last) and
// O = n_(L-1) + 1 per output, a residual row of output c has S + O non-zeros; J holds B examples'
// rows per output, columns ldj apart; jo the output block, ldo apart.
struct BlockShape {
  Eigen::Index P, S, Hl, O, B, ldj, ldo;
  int n_in, n_out;
  Eigen::Index bias_last;  // parameter index of the last layer's first bias
  explicit BlockShape(const MlpLayout& l) {
    const int L = l.layers();
    P = static_cast<Eigen::Index>(l.parameter_count());
    n_in = l.inputs();
    n_out = l.outputs();
    S = static_cast<Eigen::Index>(l.weight_offset(L));
    Hl = static_cast<Eigen::Index>(l.widths[L - 1]);  // n_(L-1)
    O = Hl + 1;
    B = static_cast<Eigen::Index>(kJacobianBlock);
    const auto pad = static_cast<Eigen::Index>(detail::gemm_abt_row_padding());
    ldj = (P + pad - 1) / pad * pad;
    ldo = (O + pad - 1) / pad * pad;
    bias_last = static_cast<Eigen::Index>(l.bias_offset(L));
  }
  // Parameter index of output c's a-th parameter (a < Hl: weights, a = Hl: bias).
  Eigen::Index out_index(int c, Eigen::Index a) const {
    return a < Hl ? S + c * Hl + a : bias_last + c;
  }
};

// Adds examples i0 .. i0 + m - 1 to the blocks a_ss, a_so, a_oo of sc and to ne.g and ne.e.
void add_block(const Context& ctx, const Mlp& net, const BlockShape& sh, MlpWorkspace& ws,
               LmScratch& sc, std::size_t i0, Eigen::Index m, NormalEquations& ne) {
  const Eigen::Index P = sh.P, S = sh.S, O = sh.O, B = sh.B, ldj = sh.ldj, ldo = sh.ldo;
  Eigen::Map<MatrixXd, 0, Eigen::OuterStride<>> J(sc.j.data(), P, B * sh.n_out,
                                                  Eigen::OuterStride<>(ldj));
  Eigen::Map<VectorXd> r(sc.r.data(), B * sh.n_out);
  for (Eigen::Index k = 0; k < m; ++k) {
    const std::size_t i = i0 + static_cast<std::size_t>(k);
    forward(net, std::span<const double>(ctx.x).subspan(i * sh.n_in, sh.n_in), ws);
    jacobian(net, ws, sc.row);
    for (int c = 0; c < sh.n_out; ++c) {
      const double res = ws.output()[c] - ctx.t[i * sh.n_out + c];
      r[c * B + k] = res;
      ne.e += res * res;
      std::copy_n(sc.row.data() + c * P, P, J.col(c * B + k).data());
    }
  }
  for (int c = 0; c < sh.n_out; ++c) {
    const double* Js = J.col(c * B).data();
    for (Eigen::Index k = 0; k < m; ++k) {
      for (Eigen::Index a = 0; a < O; ++a) sc.jo[k * ldo + a] = Js[k * ldj + sh.out_index(c, a)];
    }
    const auto um = static_cast<std::size_t>(m);
    detail::gemm_abt(Js, ldj, Js, ldj, S, S, um, sc.a_ss.data(), S, true);
    detail::gemm_abt(Js, ldj, sc.jo.data(), ldo, S, O, um, sc.a_so.col(c * O).data(), S, false);
    detail::gemm_abt(sc.jo.data(), ldo, sc.jo.data(), ldo, O, O, um, sc.a_oo.col(c * O).data(), O,
                     true);
    const auto rc = r.segment(c * B, m);
    ne.g.head(S).noalias() += J.block(0, c * B, S, m) * rc;
    for (Eigen::Index a = 0; a < O; ++a) {
      double dot = 0.0;
      for (Eigen::Index k = 0; k < m; ++k) dot += sc.jo[k * ldo + a] * rc[k];
      ne.g[sh.out_index(c, a)] += dot;
    }
  }
}

// J^T J exploits that the last layer's parameters of output c (row c of W^L and bias w^L_{c 0})
// move output c only: a residual row of output c has S + O non-zeros, not P = S + n_L O. The
// blocks are
//   A_SS += sum_c J_S,c J_S,c^T,  A_{S O_c} += J_S,c J_O,c^T,  A_{O_c O_c} += J_O,c J_O,c^T
// (6-12-3: 1.6x fewer multiply-adds than the dense rank-k update), computed by gemm_abt
// (train_kernel.h).
void normal_equations(const Context& ctx, const Mlp& net, ScratchPool& pool,
                      std::vector<NormalEquations>& part, NormalEquations& total) {
  const MlpLayout& l = net.layout();
  const BlockShape sh(l);
  const Eigen::Index P = sh.P, S = sh.S, O = sh.O;
  parallel_for(kSlices, 1, [&](std::size_t b, std::size_t e) {
    MlpWorkspace ws(l);
    std::unique_ptr<LmScratch> scratch = pool.take();
    scratch->j.resize(static_cast<std::size_t>(sh.ldj * sh.B * sh.n_out));
    scratch->r.resize(static_cast<std::size_t>(sh.B * sh.n_out));
    scratch->row.resize(static_cast<std::size_t>(P * sh.n_out));
    scratch->jo.resize(static_cast<std::size_t>(sh.ldo * sh.B));
    MatrixXd& a_ss = scratch->a_ss;
    MatrixXd& a_so = scratch->a_so;
    MatrixXd& a_oo = scratch->a_oo;
    a_ss.resize(S, S);
    a_so.resize(S, O * sh.n_out);
    a_oo.resize(O, O * sh.n_out);
    for (std::size_t s = b; s < e; ++s) {
      NormalEquations& ne = part[s];
      ne.A.setZero(P, P);
      ne.g.setZero(P);
      ne.e = 0.0;
      a_ss.setZero();
      a_so.setZero();
      a_oo.setZero();
      const std::size_t end = slice_begin(s + 1, ctx.n, kSlices);
      for (std::size_t i0 = slice_begin(s, ctx.n, kSlices); i0 < end; i0 += kJacobianBlock)
        add_block(ctx, net, sh, ws, *scratch, i0,
                  static_cast<Eigen::Index>(std::min(kJacobianBlock, end - i0)), ne);
      // Assemble the lower triangle (output indices are all >= S, increasing in a).
      ne.A.topLeftCorner(S, S).triangularView<Eigen::Lower>() = a_ss;
      for (int c = 0; c < sh.n_out; ++c) {
        for (Eigen::Index a = 0; a < O; ++a) {
          const Eigen::Index ia = sh.out_index(c, a);
          ne.A.row(ia).head(S) += a_so.col(c * O + a).transpose();
          for (Eigen::Index q = 0; q <= a; ++q) ne.A(ia, sh.out_index(c, q)) += a_oo(a, c * O + q);
        }
      }
    }
    pool.give(std::move(scratch));
  });
  total.A.setZero(P, P);
  total.g.setZero(P);
  total.e = 0.0;
  for (const auto& ne : part) {
    total.A += ne.A;
    total.g += ne.g;
    total.e += ne.e;
  }
}

void run_levenberg_marquardt(Context& ctx, Mlp& net, int last) {
  const auto P = static_cast<Eigen::Index>(net.layout().parameter_count());
  std::vector<NormalEquations> part(kSlices);
  NormalEquations ne;
  ScratchPool pool;
  normal_equations(ctx, net, pool, part, ne);
  double lambda = ctx.opt.lambda_initial;
  auto params = net.parameters();
  Eigen::Map<VectorXd> theta(params.data(), P);
  VectorXd theta_old(P), delta(P);
  MatrixXd M(P, P);
  for (;;) {
    // Marquardt scaling: damp with lambda diag(J^T J) (floored so that a dead unit is damped).
    const double diag_floor = 1e-9 * std::max(ne.A.diagonal().mean(), 1e-300);
    bool accepted = false;
    while (!accepted) {
      M = ne.A;
      for (Eigen::Index p = 0; p < P; ++p) M(p, p) += lambda * std::max(ne.A(p, p), diag_floor);
      Eigen::LLT<MatrixXd, Eigen::Lower> llt(M);
      if (llt.info() == Eigen::Success) {
        delta = llt.solve(-ne.g);
        theta_old = theta;
        theta += delta;
        const double e_new = sse(net, ctx.x, ctx.t, ctx.n);
        if (std::isfinite(e_new) && e_new < ne.e) {
          accepted = true;
          lambda = std::max(lambda * ctx.opt.lambda_down, 1e-12);
          break;
        }
        theta = theta_old;
      }
      lambda *= ctx.opt.lambda_up;
      if (lambda > ctx.opt.lambda_max) {
        ctx.stop = "lambda_max";
        return;
      }
    }
    normal_equations(ctx, net, pool, part, ne);
    if (!log_iteration(ctx, net, ne.e, lambda, last)) return;
  }
}

void run_trainer(Context& ctx, Mlp& net, int last, Rng& rng) {
  switch (ctx.opt.trainer) {
    case Trainer::backprop:
      return run_backprop(ctx, net, last, rng);
    case Trainer::adam:
      return run_adam(ctx, net, last, rng);
    case Trainer::lbfgs:
      return run_lbfgs(ctx, net, last);
    case Trainer::levenberg_marquardt:
      return run_levenberg_marquardt(ctx, net, last);
  }
}

}  // namespace

std::string_view to_string(Trainer t) {
  switch (t) {
    case Trainer::backprop:
      return "backprop";
    case Trainer::levenberg_marquardt:
      return "lm";
    case Trainer::adam:
      return "adam";
    case Trainer::lbfgs:
      return "lbfgs";
  }
  return "?";
}

std::optional<Trainer> parse_trainer(std::string_view name) {
  if (name == "backprop" || name == "bp") return Trainer::backprop;
  if (name == "lm" || name == "levenberg_marquardt") return Trainer::levenberg_marquardt;
  if (name == "adam") return Trainer::adam;
  if (name == "lbfgs") return Trainer::lbfgs;
  return std::nullopt;
}

Mlp initial_network(const MlpLayout& layout, Rng& rng, double gain) {
  Mlp net(layout);
  auto p = net.parameters();
  for (int k = 1; k <= layout.layers(); ++k) {
    const double a = gain * std::sqrt(3.0 / layout.widths[k - 1]);
    const std::size_t begin = layout.weight_offset(k);
    const std::size_t end = layout.bias_offset(k) + layout.widths[k];
    for (std::size_t i = begin; i < end; ++i) p[i] = rng.uniform(-a, a);
  }
  return net;
}

double inverse_activation(Activation a, double y) {
  constexpr double kEps = 1e-6;
  switch (a) {
    case Activation::identity:
      return y;
    case Activation::satilmis:  // 1/(1 + x^2) = y, x >= 0
      y = std::clamp(y, kEps, 1.0 - kEps);
      return std::sqrt(1.0 / y - 1.0);
    case Activation::pietras:  // 1/(1 + 2^(2x)) = y
      y = std::clamp(y, kEps, 1.0 - kEps);
      return std::log2(1.0 / y - 1.0) / 2.0;
    case Activation::tanh:
      return std::atanh(std::clamp(y, -1.0 + kEps, 1.0 - kEps));
    case Activation::sigmoid:
      y = std::clamp(y, kEps, 1.0 - kEps);
      return std::log(y / (1.0 - y));
    case Activation::relu:
      return std::max(y, 0.0);
    case Activation::softplus:
      y = std::max(y, kEps);
      return y > 30.0 ? y : std::log(std::expm1(y));
  }
  return y;
}

double mean_squared_error(const Mlp& net, const Examples& ex) {
  return sse(net, ex.inputs, ex.targets, ex.count) /
         (static_cast<double>(ex.count) * net.layout().outputs());
}

namespace {

// Standardisation x~ = (x - mean) / std per input (std of a constant input: 1).
struct Standardisation {
  std::vector<double> mean, stdev;
  Standardisation(const Examples& ex, int n_in, bool on) : mean(n_in, 0.0), stdev(n_in, 1.0) {
    if (!on) return;
    for (int k = 0; k < n_in; ++k) {
      double s = 0.0, s2 = 0.0;
      for (std::size_t i = 0; i < ex.count; ++i) s += ex.inputs[i * n_in + k];
      mean[k] = s / static_cast<double>(ex.count);
      for (std::size_t i = 0; i < ex.count; ++i) {
        const double dv = ex.inputs[i * n_in + k] - mean[k];
        s2 += dv * dv;
      }
      const double sd = std::sqrt(s2 / static_cast<double>(ex.count));
      stdev[k] = sd > 1e-12 ? sd : 1.0;
    }
  }
  void apply(std::span<const double> in, std::vector<double>& out) const {
    const auto n_in = mean.size();
    out.resize(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
      const std::size_t k = i % n_in;
      out[i] = (in[i] - mean[k]) / stdev[k];
    }
  }
  // f(w_ji, w_j0, i) for every weight of layer 1 (the standardisation's fold and unfold).
  template <class F>
  static void first_layer(Mlp& m, const F& f) {
    const MlpLayout& layout = m.layout();
    auto p = m.parameters();
    double* W = p.data() + layout.weight_offset(1);
    double* bias = p.data() + layout.bias_offset(1);
    for (int j = 0; j < layout.widths[1]; ++j)
      for (int i = 0; i < layout.inputs(); ++i)
        f(W[static_cast<std::size_t>(j) * layout.inputs() + i], bias[j], i);
  }
  // The standardisation unfolded from a network of raw inputs (the inverse of fold):
  // w~_ji = w_ji std_i, w~_j0 = w_j0 + sum_i w_ji mean_i.
  void unfold(Mlp& net) const {
    first_layer(net, [&](double& w, double& bias, int i) {
      bias += w * mean[i];
      w *= stdev[i];
    });
  }
  // Folded into layer 1: w_ji <- w~_ji / std_i, w_j0 <- w~_j0 - sum_i w~_ji mean_i / std_i.
  void fold(Mlp& net) const {
    first_layer(net, [&](double& w, double& bias, int i) {
      w /= stdev[i];
      bias -= w * mean[i];
    });
  }
};

// A random start; the output layer from the targets' mean (TrainOptions::init_output_from_targets).
Mlp initial_for_targets(const MlpLayout& layout, const Examples& ex, const TrainOptions& opt,
                        Rng& rng) {
  Mlp net = initial_network(layout, rng, opt.init_gain);
  if (!opt.init_output_from_targets) return net;
  const int n_out = layout.outputs(), L = layout.layers();
  std::vector<double> target_mean(n_out, 0.0);
  for (std::size_t i = 0; i < ex.count; ++i) {
    for (int c = 0; c < n_out; ++c) target_mean[c] += ex.targets[i * n_out + c];
  }
  for (double& m : target_mean) m /= static_cast<double>(ex.count);
  auto p = net.parameters();
  for (std::size_t i = layout.weight_offset(L); i < layout.bias_offset(L); ++i) {
    p[i] *= opt.output_weight_gain;
  }
  for (int c = 0; c < n_out; ++c) {
    p[layout.bias_offset(L) + c] = inverse_activation(layout.activations[L - 1], target_mean[c]);
  }
  return net;
}

// TrainOptions::restarts short runs from different starts; the one of lowest held-out error (the
// training error without held-out examples), its log entries counted in ctx.iteration. Every run's
// log goes to result.log.
Mlp best_of_restarts(Context& ctx, const Examples& ex, int last, TrainResult& result) {
  const TrainOptions& opt = ctx.opt;
  Mlp net;
  double best = std::numeric_limits<double>::infinity();
  std::vector<TrainLogEntry> kept;
  for (int r = 0; r < opt.restarts; ++r) {
    Rng rng = Rng::stream(opt.seed, static_cast<std::uint64_t>(r));
    Mlp candidate = initial_for_targets(ctx.layout, ex, opt, rng);
    ctx.restart = r + 1;
    ctx.iteration = 0;
    std::vector<TrainLogEntry> log;
    ctx.log = &log;
    run_trainer(ctx, candidate, std::min(opt.restart_iterations, last), rng);
    // Judged on the held-out examples when there are any: the training error cannot tell a start
    // that fits the examples but rings between them.
    const double e =
        ctx.vn > 0 ? sse(candidate, ctx.vx, ctx.vt, ctx.vn) : sse(candidate, ctx.x, ctx.t, ctx.n);
    result.log.insert(result.log.end(), log.begin(), log.end());
    if (e < best) {
      best = e;
      net = candidate;
      kept = log;
    }
    if (ctx.stop == "time_limit" || ctx.stop == "callback") break;
  }
  ctx.log = &result.log;
  ctx.restart = 0;
  ctx.iteration = static_cast<int>(kept.size());
  return net;
}

}  // namespace

TrainResult train(const MlpLayout& layout, const Examples& ex, const TrainOptions& opt) {
  layout.validate();
  const int n_in = layout.inputs(), n_out = layout.outputs();
  if (ex.count == 0 || ex.inputs.size() != ex.count * n_in ||
      ex.targets.size() != ex.count * n_out) {
    throw InvalidArgument("train: examples do not match the layout " + layout.describe());
  }
  TrainResult result;
  Context ctx(layout, opt);
  ctx.start = Clock::now();
  ctx.cpu_start = process_cpu_s();
  ctx.log = &result.log;
  ctx.n = ex.count;
  ctx.t = ex.targets;
  const Standardisation standard(ex, n_in, opt.standardise_inputs);
  standard.apply(ex.inputs, ctx.x);
  if (opt.validation && opt.validation->count > 0) {
    standard.apply(opt.validation->inputs, ctx.vx);
    ctx.vt = opt.validation->targets;
    ctx.vn = opt.validation->count;
  }
  Mlp net;
  const int last = std::max(1, opt.max_iterations);
  if (opt.initial != nullptr) {
    const MlpLayout& given = opt.initial->layout();
    if (given.widths != layout.widths || given.activations != layout.activations)
      throw InvalidArgument("train: the initial network " + given.describe() +
                            " is not the layout trained, " + layout.describe());
    net = *opt.initial;
    standard.unfold(net);
  } else if (opt.restarts > 1) {
    net = best_of_restarts(ctx, ex, last, result);
  } else {
    Rng rng = Rng::stream(opt.seed, 0);
    net = initial_for_targets(layout, ex, opt, rng);
  }
  ctx.track_best = opt.keep_best_validation && ctx.vn > 0;
  if (ctx.stop != "time_limit" && ctx.stop != "callback" && ctx.iteration < last) {
    ctx.stop.clear();
    Rng rng = Rng::stream(opt.seed, 1000);
    run_trainer(ctx, net, last, rng);
  }
  if (ctx.track_best) {
    // The last iterate competes too (it is not measured when training stopped between
    // validations).
    const double e =
        sse(net, ctx.vx, ctx.vt, ctx.vn) / (static_cast<double>(ctx.vn) * layout.outputs());
    result.kept_iteration = ctx.iteration;
    if (ctx.best && ctx.best_validation < e) {
      net = *ctx.best;
      result.kept_iteration = ctx.best_iteration;
    }
  }
  standard.fold(net);
  result.net = std::move(net);
  result.seconds = ctx.seconds();
  result.mse = mean_squared_error(result.net, ex);
  result.iterations = ctx.iteration;
  result.stop = ctx.stop.empty() ? "iterations" : ctx.stop;
  return result;
}

namespace detail {
void gauss_newton_system(const Mlp& net, const Examples& ex, std::vector<double>& A,
                         std::vector<double>& g, double& e) {
  TrainOptions opt;
  Context ctx(net.layout(), opt);
  ctx.x.assign(ex.inputs.begin(), ex.inputs.end());
  ctx.t = ex.targets;
  ctx.n = ex.count;
  std::vector<NormalEquations> part(kSlices);
  NormalEquations ne;
  ScratchPool pool;
  normal_equations(ctx, net, pool, part, ne);
  const auto P = ne.A.rows();
  A.assign(static_cast<std::size_t>(P * P), 0.0);
  for (Eigen::Index j = 0; j < P; ++j) {
    for (Eigen::Index i = j; i < P; ++i) {
      A[i + j * P] = A[j + i * P] = ne.A(i, j);
    }
  }
  g.assign(ne.g.data(), ne.g.data() + P);
  e = ne.e;
}

double loss_gradient(const Mlp& net, const Examples& ex, std::vector<double>& grad) {
  grad.assign(net.layout().parameter_count(), 0.0);
  return gradient(net, ex.inputs, ex.targets, {}, ex.count, grad);
}
}  // namespace detail

void write_log_csv(std::ostream& os, const std::vector<TrainLogEntry>& log) {
  os << "restart,iteration,seconds,mse,validation_mse,step\n";
  os.precision(9);
  for (const auto& e : log) {
    os << e.restart << ',' << e.iteration << ',' << e.seconds << ',' << e.mse << ',';
    if (!std::isnan(e.validation_mse)) os << e.validation_mse;
    os << ',' << e.step << '\n';
  }
}

}  // namespace skylight::nn
