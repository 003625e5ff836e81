// The project's one Levenberg-Marquardt routine (Levenberg 1944, Marquardt 1963) for small
// nonlinear least-squares problems in a box: the fits of sky models to photos (fit/) use it.
// The caller gives the cost and the normal equations J^T J, J^T r at a point; each iteration
// solves (J^T J + lambda diag(J^T J)) step = -J^T r (LDLT), clamps the new point into the box and
// keeps it when the cost falls (lambda / 10), else raises lambda tenfold and tries again.
#pragma once

#include <functional>
#include <span>
#include <vector>

namespace skylight {

struct LeastSquaresProblem {
  int parameters = 0;
  // Box of the parameters (inclusive; +-infinity for none); every step is clamped into it.
  std::vector<double> lower, upper;
  // Sum of squared residuals at p (+infinity when undefined).
  std::function<double(std::span<const double> p)> cost;
  // The normal equations at p: jtj (row-major n x n) = J^T J and jtr (n) = J^T r, r the residuals
  // and J their Jacobian; both arrive zeroed.
  std::function<void(std::span<const double> p, std::span<double> jtj, std::span<double> jtr)>
      normal_equations;
};

struct LeastSquaresOptions {
  int max_iterations = 100;
  // Damping increases tried per iteration before the routine stops (lambda x 10 each).
  int max_lambda_tries = 12;
  // Stop when a step lowers the cost by less than this fraction (double round-off level).
  double relative_decrease = 1e-14;
  double initial_lambda = 1e-3;
  double min_lambda = 1e-12;
};

struct LeastSquaresResult {
  std::vector<double> p;  // the last accepted point
  double cost = 0.0;
  int iterations = 0;
  // False when a step was not finite (a singular system), or the cost at the end is not finite.
  bool ok = false;
};

// Minimises problem.cost from `start` (inside the box). Stops when no damping lowers the cost, a
// step lowers it by less than options.relative_decrease, the cost reaches 0, or after
// options.max_iterations.
LeastSquaresResult levenberg_marquardt(const LeastSquaresProblem& problem,
                                       std::vector<double> start,
                                       const LeastSquaresOptions& options = {});

}  // namespace skylight
