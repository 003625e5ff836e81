#include "skylight/core/least_squares.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"

namespace skylight {
namespace {

// step = (J^T J with its diagonal x (1 + lambda))^-1 (-J^T r) by LDLT; fixed-size Eigen types for
// the small problems (the fits have 2-4 unknowns), whose rounding the tests' numbers were measured
// with.
template <int N>
bool damped_step(std::span<const double> jtj, std::span<const double> jtr, int n, double lambda,
                 std::span<double> step) {
  // J^T J is symmetric: its row-major data map as the column-major matrix.
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  Matrix A = Eigen::Map<const Matrix>(jtj.data(), n, n);
  A.diagonal() *= 1.0 + lambda;
  const Vector b = -Eigen::Map<const Vector>(jtr.data(), n);
  const Vector x = A.ldlt().solve(b);
  if (!x.allFinite()) return false;
  for (int k = 0; k < n; ++k) step[k] = x[k];
  return true;
}

bool solve_damped(std::span<const double> jtj, std::span<const double> jtr, int n, double lambda,
                  std::span<double> step) {
  switch (n) {
    case 2:
      return damped_step<2>(jtj, jtr, n, lambda, step);
    case 3:
      return damped_step<3>(jtj, jtr, n, lambda, step);
    case 4:
      return damped_step<4>(jtj, jtr, n, lambda, step);
    default:
      return damped_step<Eigen::Dynamic>(jtj, jtr, n, lambda, step);
  }
}

}  // namespace

LeastSquaresResult levenberg_marquardt(const LeastSquaresProblem& problem,
                                       std::vector<double> start,
                                       const LeastSquaresOptions& options) {
  const int n = problem.parameters;
  SKYLIGHT_CHECK(n >= 1 && static_cast<int>(start.size()) == n &&
                     static_cast<int>(problem.lower.size()) == n &&
                     static_cast<int>(problem.upper.size()) == n,
                 "levenberg_marquardt: parameter counts differ");
  LeastSquaresResult res;
  res.p = std::move(start);
  res.cost = problem.cost(res.p);
  std::vector<double> jtj(static_cast<std::size_t>(n * n)), jtr(static_cast<std::size_t>(n));
  std::vector<double> next(static_cast<std::size_t>(n)), step(static_cast<std::size_t>(n));
  double lambda = options.initial_lambda;
  for (int it = 0; it < options.max_iterations; ++it) {
    res.iterations = it + 1;
    std::fill(jtj.begin(), jtj.end(), 0.0);
    std::fill(jtr.begin(), jtr.end(), 0.0);
    problem.normal_equations(res.p, jtj, jtr);
    bool accepted = false, done = false;
    for (int tries = 0; tries < options.max_lambda_tries && !accepted; ++tries) {
      if (!solve_damped(jtj, jtr, n, lambda, step)) return res;  // ok = false
      for (int k = 0; k < n; ++k)
        next[k] = std::clamp(res.p[k] + step[k], problem.lower[k], problem.upper[k]);
      const double cost = problem.cost(next);
      if (std::isfinite(cost) && cost < res.cost) {
        done = res.cost - cost <= options.relative_decrease * res.cost;
        res.p = next;
        res.cost = cost;
        lambda = std::max(lambda * 0.1, options.min_lambda);
        accepted = true;
      } else {
        lambda *= 10.0;
      }
    }
    // No step lowers the cost (a minimum to working precision), or the last one barely did.
    if (!accepted || done || res.cost <= 0.0) break;
  }
  res.ok = std::isfinite(res.cost);
  return res;
}

}  // namespace skylight
