// Sky models fitted to luminance samples (docs/ESTIMATE.md).
#include "skylight/fit/luminance_fit.h"

#include <Eigen/Dense>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "skylight/core/error.h"
#include "skylight/core/golden_section.h"
#include "skylight/core/least_squares.h"
#include "skylight/core/numbers.h"
#include "skylight/core/random.h"
#include "skylight/core/robust.h"
#include "skylight/core/statistics.h"

namespace skylight::fit {
namespace {

using Method = EstimationPolicy::Method;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Golden-section search ends when the bracket is this narrow (far below any use of the value).
constexpr double kGoldenTolerance = 1e-9;
// Salts of the RANSAC / bootstrap generators: seed ^ salt (the profile scan's one generator
// serves both; the grid's has one each).
// Samples that score a RANSAC minimal set of the profile fit (of 6000 by default: 2 % in the
// inlier fraction, far below the gap between a clear-sky fit and a cloud-driven one).
constexpr std::size_t kRansacScoreSamples = 1000;
constexpr std::uint64_t kProfileSalt = 0x5851f42d4c957f2dULL;
constexpr std::uint64_t kGridRansacSalt = 0x2545f4914f6cdd1dULL;
constexpr std::uint64_t kGridBootstrapSalt = 0x9e3779b97f4a7c15ULL;

// A point of the fit: the model's parameters (axes order), ln s and the cost sum r_i^2.
struct Point {
  std::vector<double> p;
  double log_scale = 0.0, cost = kInfinity;
};

// The patches of sky that the bootstrap draws whole: zenith bands kBootstrapBlockDeg wide, each cut
// into azimuth sectors about as wide at the band's middle (about 90 patches over the sky). A
// cloud, or any error shared by neighbouring pixels, is one patch's error: the bootstrap of
// single samples would take its pixels as independent and understate sigma (docs/ESTIMATE.md,
// "Uncertainty").
constexpr double kBootstrapBlockDeg = 15.0;
// Fewer patches than this among the inliers: the bootstrap draws single samples.
constexpr std::ptrdiff_t kMinBootstrapBlocks = 10;

int sky_block(Vec3 view) {
  const ZenithAzimuth za = angles_from_direction(view);
  const int bands = static_cast<int>(std::lround(90.0 / kBootstrapBlockDeg));
  const int band =
      std::clamp(static_cast<int>(za.zenith / (kBootstrapBlockDeg * kDegree)), 0, bands - 1);
  const double middle = (band + 0.5) * kBootstrapBlockDeg * kDegree;
  const int sectors =
      std::max(1, static_cast<int>(std::lround(360.0 * std::sin(middle) / kBootstrapBlockDeg)));
  const double azimuth = za.azimuth - 2 * kPi * std::floor(za.azimuth / (2 * kPi));
  const int sector = std::min(sectors - 1, static_cast<int>(azimuth / (2 * kPi) * sectors));
  return band * 1000 + sector;
}

std::vector<std::size_t> all_indices(std::size_t n) {
  std::vector<std::size_t> idx(n);
  std::iota(idx.begin(), idx.end(), std::size_t{0});
  return idx;
}

// The samples as the fit evaluates them, and the model's prepared ln L.
class Problem {
 public:
  Problem(const EstimationPolicy& policy, std::string_view model,
          std::span<const LuminanceSample> samples, const SunPosition& sun)
      : policy_(policy) {
    const std::size_t need = policy.axes.size() + 1;
    if (samples.size() < need)
      throw InvalidArgument(fmt::format("the fit of model '{}' needs at least {} samples, not {}",
                                        model, need, samples.size()));
    if (!(sun.zenith >= 0.0 && sun.zenith < kPi / 2))
      throw InvalidArgument(fmt::format(
          "the sun is at zenith angle {} deg: the fit of model '{}' needs it above the horizon",
          rad_to_deg(sun.zenith), model));
    std::vector<Vec3> views;
    for (const auto& x : samples) {
      SKYLIGHT_CHECK(x.luminance > 0.0 && std::isfinite(x.luminance) && x.view.z > 0.0,
                     "samples are sky pixels with positive luminance above the horizon");
      views.push_back(x.view);
      log_y_.push_back(std::log(x.luminance));
      block_.push_back(sky_block(x.view));
    }
    log_l_ = policy.prepare(sun, views);
  }

  const EstimationPolicy& policy() const { return policy_; }
  std::size_t size() const { return log_y_.size(); }
  double log_y(std::size_t i) const { return log_y_[i]; }
  // Per sample its patch of sky (sky_block): the blocks of the bootstrap.
  std::span<const int> blocks() const { return block_; }
  // ln L at p for the samples idx.
  void model(std::span<const double> p, std::span<const std::size_t> idx,
             std::vector<double>& out) const {
    out.resize(idx.size());
    log_l_(p, idx, out);
  }
  // sum r_i^2 at (p, c), the model values m given.
  double cost(std::span<const std::size_t> idx, const std::vector<double>& m, double c) const {
    double s = 0.0;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const double r = log_y_[idx[k]] - c - m[k];
      s += r * r;
    }
    return std::isfinite(s) ? s : kInfinity;
  }
  // The profile at p: the best ln s (the mean of ln Y_i - ln L_i) and its cost.
  Point profile(std::span<const double> p, std::span<const std::size_t> idx,
                std::vector<double>& work) const {
    model(p, idx, work);
    double mean = 0.0;
    for (std::size_t k = 0; k < idx.size(); ++k) mean += log_y_[idx[k]] - work[k];
    mean /= static_cast<double>(idx.size());
    return {std::vector<double>(p.begin(), p.end()), mean, cost(idx, work, mean)};
  }
  // The samples with |r_i| < threshold at (p, c), and their sum of squares.
  Consensus consensus(const Point& q, double threshold, std::vector<double>& work) const {
    return consensus_over(all_indices(size()), q, threshold, work);
  }
  // The same over the samples idx only (m: their model values), the inliers as sample indices.
  Consensus consensus_over(std::span<const std::size_t> idx, const Point& q, double threshold,
                           std::vector<double>& work) const {
    model(q.p, idx, work);
    Consensus out;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const double r = log_y_[idx[k]] - q.log_scale - work[k];
      if (std::abs(r) < threshold) {
        out.inliers.push_back(idx[k]);
        out.sum_squares += r * r;
      }
    }
    return out;
  }
  Consensus consensus_of(const std::vector<double>& m, double c, double threshold) const {
    Consensus out;
    for (std::size_t i = 0; i < size(); ++i) {
      const double r = log_y_[i] - c - m[i];
      if (std::abs(r) < threshold) {
        out.inliers.push_back(i);
        out.sum_squares += r * r;
      }
    }
    return out;
  }

 private:
  const EstimationPolicy& policy_;
  std::vector<double> log_y_;
  std::vector<int> block_;
  EstimationPolicy::LogLuminance log_l_;
};

// Per sample of idx at x = (p, ln s): the residual r = ln Y - ln s - ln L(p) and its derivatives
// in (p, ln s), row by row (n + 1 values each): -d ln L / d p_a by central differences (clamped
// into the box), exactly -1 in ln s.
void jacobian_rows(const Problem& pr, std::span<const std::size_t> idx, std::span<const double> x,
                   std::vector<double>& rows, std::vector<double>& residuals) {
  const auto& axes = pr.policy().axes;
  const std::size_t n = axes.size();
  rows.assign(idx.size() * (n + 1), -1.0);
  std::vector<double> q(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n)), lo, hi, m;
  for (std::size_t a = 0; a < n; ++a) {
    const auto& axis = axes[a];
    const double h = std::min(axis.derivative_step, 0.5 * (axis.max - axis.min));
    const double p_lo = std::max(axis.min, x[a] - h), p_hi = std::min(axis.max, x[a] + h);
    q[a] = p_lo;
    pr.model(q, idx, lo);
    q[a] = p_hi;
    pr.model(q, idx, hi);
    q[a] = x[a];
    for (std::size_t k = 0; k < idx.size(); ++k)
      rows[k * (n + 1) + a] = -(hi[k] - lo[k]) / (p_hi - p_lo);
  }
  pr.model(x.first(n), idx, m);
  residuals.resize(idx.size());
  for (std::size_t k = 0; k < idx.size(); ++k) residuals[k] = pr.log_y(idx[k]) - x[n] - m[k];
}

// jtj += J^T J, jtr += J^T r for one row J (`size` values).
void accumulate_normal_equations(const double* J, double r, int size, std::span<double> jtj,
                                 std::span<double> jtr) {
  for (int i = 0; i < size; ++i) {
    for (int j = 0; j < size; ++j) jtj[static_cast<std::size_t>(i * size + j)] += J[i] * J[j];
    jtr[static_cast<std::size_t>(i)] += J[i] * r;
  }
}

// Levenberg-Marquardt in (p, ln s) from `start`, p clamped into the axes' box; the derivative of
// ln L in each parameter by central differences (clamped into the box), exactly -1 in ln s.
LeastSquaresResult least_squares(const Problem& pr, std::span<const std::size_t> idx,
                                 const Point& start) {
  const auto& axes = pr.policy().axes;
  const int n = static_cast<int>(axes.size());
  LeastSquaresProblem ls;
  ls.parameters = n + 1;
  for (const auto& a : axes) {
    ls.lower.push_back(a.min);
    ls.upper.push_back(a.max);
  }
  ls.lower.push_back(-kInfinity);
  ls.upper.push_back(kInfinity);
  std::vector<double> m, lo, hi, q;
  ls.cost = [&](std::span<const double> x) {
    pr.model(x.first(n), idx, m);
    return pr.cost(idx, m, x[n]);
  };
  std::vector<double> rows, residuals;
  ls.normal_equations = [&](std::span<const double> x, std::span<double> jtj,
                            std::span<double> jtr) {
    jacobian_rows(pr, idx, x, rows, residuals);
    for (std::size_t k = 0; k < idx.size(); ++k)
      accumulate_normal_equations(&rows[k * static_cast<std::size_t>(n + 1)], residuals[k], n + 1,
                                  jtj, jtr);
  };
  std::vector<double> x0 = start.p;
  x0.push_back(start.log_scale);
  return levenberg_marquardt(ls, std::move(x0));
}

Point to_point(const LeastSquaresResult& r) {
  Point q;
  q.p.assign(r.p.begin(), r.p.end() - 1);
  q.log_scale = r.p.back();
  q.cost = r.cost;
  return q;
}

// The value of grid point k of an axis.
double grid_value(const EstimationPolicy::Axis& a, int k) {
  const double step = (a.max - a.min) / (a.grid_points - 1);
  return a.min + step * k;
}

// ---- profile scan (one parameter) ---------------------------------------------------------------

struct Bracket {
  Point best;
  double lo = 0.0, hi = 0.0;
};

Bracket scan(const Problem& pr, std::span<const std::size_t> idx, std::vector<double>& work) {
  const auto& a = pr.policy().axes.front();
  Bracket b;
  int best_k = 0;
  for (int k = 0; k < a.grid_points; ++k) {
    const double v = grid_value(a, k);
    Point q = pr.profile(std::span<const double>(&v, 1), idx, work);
    if (q.cost < b.best.cost) {
      b.best = std::move(q);
      best_k = k;
    }
  }
  if (b.best.p.empty()) b.best.p = {a.min};
  b.lo = grid_value(a, std::max(0, best_k - 1));
  b.hi = grid_value(a, std::min(a.grid_points - 1, best_k + 1));
  return b;
}

Point golden(const Problem& pr, std::span<const std::size_t> idx, const Bracket& b,
             std::vector<double>& work) {
  const auto at = [&](double v) { return pr.profile(std::span<const double>(&v, 1), idx, work); };
  auto gs = golden_section(at, b.lo, b.hi, kGoldenTolerance,
                           [](const Point& u, const Point& v) { return u.cost <= v.cost; });
  Point best = gs.f1.cost <= gs.f2.cost ? std::move(gs.f1) : std::move(gs.f2);
  if (b.best.cost < best.cost) best = b.best;
  return best;
}

struct Fitted {
  Point point;
  std::string method;
  int iterations = 0;
};

// The scan, LM from its best point; the golden section where LM fails or ends worse.
Fitted profile_fit(const Problem& pr, std::span<const std::size_t> idx, std::vector<double>& work) {
  SKYLIGHT_CHECK(idx.size() >= 2, "the fit needs at least 2 samples");
  const Bracket b = scan(pr, idx, work);
  const LeastSquaresResult lm = least_squares(pr, idx, b.best);
  if (lm.ok && lm.cost <= b.best.cost) return {to_point(lm), "levenberg-marquardt", lm.iterations};
  return {golden(pr, idx, b, work), "bracketing", lm.iterations};
}

// ---- grid (any parameters) ----------------------------------------------------------------------

struct Grid {
  std::vector<std::vector<double>> nodes;  // parameter vectors, the first axis outermost
  std::vector<std::vector<double>> m;      // ln L of every sample at each node
};

Grid make_grid(const Problem& pr) {
  const auto& axes = pr.policy().axes;
  Grid g;
  std::vector<int> k(axes.size(), 0);
  const auto all = all_indices(pr.size());
  for (;;) {
    std::vector<double> p;
    for (std::size_t a = 0; a < axes.size(); ++a) p.push_back(grid_value(axes[a], k[a]));
    g.m.emplace_back();
    pr.model(p, all, g.m.back());
    g.nodes.push_back(std::move(p));
    std::size_t a = axes.size();
    while (a > 0 && ++k[a - 1] == axes[a - 1].grid_points) k[--a] = 0;
    if (a == 0) break;
  }
  return g;
}

// The best node for the samples idx (ln s in closed form), and which node it is.
Point best_node(const Problem& pr, const Grid& g, std::span<const std::size_t> idx,
                std::size_t* node = nullptr) {
  Point best{g.nodes.front(), 0.0, kInfinity};
  for (std::size_t n = 0; n < g.nodes.size(); ++n) {
    const auto& m = g.m[n];
    double c = 0.0;
    for (std::size_t i : idx) c += pr.log_y(i) - m[i];
    c /= static_cast<double>(idx.size());
    double cost = 0.0;
    for (std::size_t i : idx) cost += (pr.log_y(i) - c - m[i]) * (pr.log_y(i) - c - m[i]);
    if (cost < best.cost) {
      best = {g.nodes[n], c, cost};
      if (node) *node = n;
    }
  }
  return best;
}

LuminanceFit result(const Problem& pr, std::string_view model, const SunPosition& sun,
                    const Fitted& f, const std::vector<std::size_t>& inliers) {
  LuminanceFit out;
  out.model = std::string(model);
  const auto& axes = pr.policy().axes;
  for (std::size_t a = 0; a < axes.size(); ++a)
    out.parameters.push_back({axes[a].parameter, f.point.p[a], 0.0});
  out.log_scale = f.point.log_scale;
  out.residual = std::sqrt(f.point.cost / static_cast<double>(inliers.size()));
  out.samples = static_cast<int>(pr.size());
  out.inliers = static_cast<int>(inliers.size());
  out.inlier_fraction = static_cast<double>(inliers.size()) / static_cast<double>(pr.size());
  out.method = f.method;
  out.iterations = f.iterations;
  out.sun = sun;
  return out;
}

// The sigmas of the fit: the block bootstrap of the inliers (patches of sky, sky_block), each
// resample refitted by one Gauss-Newton step from the fit (the linearised bootstrap: the fit's
// residuals and derivatives computed once, a resample costs sums over its samples, not model
// evaluations; the nonlinearity over a few sigma is negligible for these fits).
std::vector<double> bootstrap_sigmas(const Problem& pr, const Point& fit,
                                     std::span<const std::size_t> inliers, int resamples,
                                     SplitMix64& rng) {
  const int n = static_cast<int>(pr.policy().axes.size());
  std::vector<double> x = fit.p;
  x.push_back(fit.log_scale);
  std::vector<double> rows, residuals;
  jacobian_rows(pr, inliers, x, rows, residuals);
  std::vector<std::size_t> row_of(pr.size(), 0);
  for (std::size_t k = 0; k < inliers.size(); ++k) row_of[inliers[k]] = k;
  const auto size = static_cast<std::size_t>(n + 1);
  std::vector<double> jtj(size * size), jtr(size);
  // A sky of a few patches (a small mask, a narrow crop) has too few blocks to resample: the
  // samples are drawn one by one there.
  std::vector<int> blocks;
  for (std::size_t i : inliers) blocks.push_back(pr.blocks()[i]);
  std::sort(blocks.begin(), blocks.end());
  const bool few_blocks =
      std::unique(blocks.begin(), blocks.end()) - blocks.begin() < kMinBootstrapBlocks;
  const auto one_step = [&](std::span<const std::size_t> r) {
    std::fill(jtj.begin(), jtj.end(), 0.0);
    std::fill(jtr.begin(), jtr.end(), 0.0);
    for (std::size_t i : r) {
      const std::size_t k = row_of[i];
      accumulate_normal_equations(&rows[k * size], residuals[k], n + 1, jtj, jtr);
    }
    const Eigen::MatrixXd A = Eigen::Map<const Eigen::MatrixXd>(jtj.data(), n + 1, n + 1);
    const Eigen::VectorXd step =
        A.ldlt().solve(-Eigen::Map<const Eigen::VectorXd>(jtr.data(), n + 1));
    std::vector<double> p = fit.p;
    for (int a = 0; a < n; ++a) p[static_cast<std::size_t>(a)] += step[a];
    return p;
  };
  return few_blocks ? bootstrap_sigma(inliers, resamples, rng, one_step)
                    : block_bootstrap_sigma(inliers, pr.blocks(), resamples, rng, one_step);
}

void set_sigmas(LuminanceFit& fit, const std::vector<double>& sigma) {
  for (std::size_t a = 0; a < fit.parameters.size(); ++a) fit.parameters[a].sigma = sigma[a];
}

// RANSAC over profile fits of minimal sets; the fit on the consensus (and once more on the
// consensus of that fit); bootstrap by LM from the profile at the fitted value.
LuminanceFit fit_by_profile(const Problem& pr, std::string_view model, const SunPosition& sun,
                            const EstimateSettings& s) {
  const std::size_t n = pr.size();
  if (s.ransac && (s.ransac_minimal_set < 2 || static_cast<std::size_t>(s.ransac_minimal_set) > n))
    throw InvalidArgument(
        fmt::format("RANSAC minimal set of {} samples out of {}", s.ransac_minimal_set, n));
  SplitMix64 rng(s.seed ^ kProfileSalt);
  std::vector<double> work;
  const auto all = all_indices(n);
  std::vector<std::size_t> inliers = all;
  Fitted fit;
  if (s.ransac) {
    const RansacOptions o{s.ransac_iterations, static_cast<std::size_t>(s.ransac_minimal_set),
                          true};
    // Each minimal set is scored on kRansacScoreSamples of the samples (a random subset ranks
    // the sets as all would, at a fraction of the model evaluations); the consensus of the fit
    // on the best set's inliers is then taken over all samples.
    std::vector<std::size_t> scored = all;
    if (n > kRansacScoreSamples) {
      for (std::size_t k = 0; k < kRansacScoreSamples; ++k)
        std::swap(scored[k], scored[k + rng.below(n - k)]);
      scored.resize(kRansacScoreSamples);
    }
    const auto best = ransac(n, o, rng, [&](std::span<const std::size_t> minimal) {
      return pr.consensus_over(scored, profile_fit(pr, minimal, work).point, s.inlier_threshold,
                               work);
    });
    inliers = best.size() >= 2 ? best : all;
    // Refit on the consensus set, then once more on the consensus of that fit over all samples:
    // by LM from the first refit (near the optimum: no second scan), the scan if LM fails.
    fit = profile_fit(pr, inliers, work);
    if (auto again = pr.consensus(fit.point, s.inlier_threshold, work).inliers;
        again.size() >= 2 && again != inliers) {
      inliers = std::move(again);
      const LeastSquaresResult lm =
          least_squares(pr, inliers, pr.profile(fit.point.p, inliers, work));
      fit = lm.ok ? Fitted{to_point(lm), "levenberg-marquardt", lm.iterations}
                  : profile_fit(pr, inliers, work);
    }
  } else {
    fit = profile_fit(pr, inliers, work);
  }
  LuminanceFit out = result(pr, model, sun, fit, inliers);
  if (s.bootstrap >= 2) {
    set_sigmas(out, bootstrap_sigmas(pr, fit.point, inliers, s.bootstrap, rng));
  }
  return out;
}

// RANSAC on the grid's nodes; LM on the inliers from the best node (and once more on the
// consensus of that fit); bootstrap by LM from the fit.
LuminanceFit fit_by_grid(const Problem& pr, std::string_view model, const SunPosition& sun,
                         const EstimateSettings& s) {
  const std::size_t n = pr.size();
  const std::size_t need = pr.policy().axes.size() + 1;
  const Grid grid = make_grid(pr);
  std::vector<double> work;
  std::vector<std::size_t> inliers = all_indices(n);
  if (s.ransac) {
    SplitMix64 rng(s.seed ^ kGridRansacSalt);
    const RansacOptions o{
        s.ransac_iterations,
        std::min(n, std::max(need, static_cast<std::size_t>(std::max(0, s.ransac_minimal_set)))),
        false};
    auto best = ransac(n, o, rng, [&](std::span<const std::size_t> minimal) {
      std::size_t node = 0;
      const Point q = best_node(pr, grid, minimal, &node);
      return pr.consensus_of(grid.m[node], q.log_scale, s.inlier_threshold);
    });
    if (best.size() >= need) inliers = std::move(best);
  }
  const auto lm_fit = [&](std::span<const std::size_t> idx, const Point& start) {
    const LeastSquaresResult r = least_squares(pr, idx, start);
    return Fitted{to_point(r), "levenberg-marquardt", r.iterations};
  };
  Fitted fit = lm_fit(inliers, best_node(pr, grid, inliers));
  if (s.ransac) {
    if (auto again = pr.consensus(fit.point, s.inlier_threshold, work).inliers;
        again.size() >= need && again != inliers) {
      inliers = std::move(again);
      fit = lm_fit(inliers, best_node(pr, grid, inliers));
    }
  }
  LuminanceFit out = result(pr, model, sun, fit, inliers);
  if (s.bootstrap >= 2) {
    SplitMix64 rng(s.seed ^ kGridBootstrapSalt);
    set_sigmas(out, bootstrap_sigmas(pr, fit.point, inliers, s.bootstrap, rng));
  }
  return out;
}

// The surrogate's fit (EstimationPolicy::surrogate), then this model at its parameters: ln s the
// mean of the residuals over the samples (with RANSAC: over those within the threshold, found once
// more with this model), the residual this model's. The sigmas are the surrogate's.
LuminanceFit fit_by_surrogate(const Problem& pr, std::string_view model,
                              std::span<const LuminanceSample> samples, const SunPosition& sun,
                              const EstimateSettings& s) {
  const EstimationPolicy& policy = pr.policy();
  const EstimationPolicy& other = estimation_policy(policy.surrogate);
  SKYLIGHT_CHECK(other.surrogate.empty() && other.axes.size() == policy.axes.size(),
                 "a surrogate fits the same parameters itself");
  for (std::size_t a = 0; a < policy.axes.size(); ++a)
    SKYLIGHT_CHECK(other.axes[a].parameter == policy.axes[a].parameter,
                   "a surrogate fits the same parameters");
  const LuminanceFit found = fit_luminance(policy.surrogate, samples, sun, s);
  std::vector<double> p, work;
  for (const FittedParameter& q : found.parameters) p.push_back(q.value);
  std::vector<std::size_t> inliers = all_indices(pr.size());
  Point point = pr.profile(p, inliers, work);
  if (s.ransac) {
    if (auto again = pr.consensus(point, s.inlier_threshold, work).inliers;
        again.size() >= policy.axes.size() + 1) {
      inliers = std::move(again);
      point = pr.profile(p, inliers, work);
    }
  }
  LuminanceFit out =
      result(pr, model, sun,
             Fitted{point, found.method + ", searched with " + policy.surrogate, found.iterations},
             inliers);
  for (std::size_t a = 0; a < out.parameters.size(); ++a)
    out.parameters[a].sigma = found.parameters[a].sigma;
  return out;
}

// Every value of the one integer parameter: ln s starts as the median of ln Y_i - ln L_i (clouds
// on less than half the samples do not move it), the inliers are |r_i| < threshold, ln s is
// refitted as their mean (and the inliers found again once). Ranked by inlier count, then by
// residual; best first.
LuminanceFit fit_by_ranking(const Problem& pr, std::string_view model, const SunPosition& sun,
                            const EstimateSettings& s) {
  const auto& axis = pr.policy().axes.front();
  const std::size_t n = pr.size();
  const auto all = all_indices(n);
  std::vector<double> m, g(n);
  std::vector<RankedValue> ranked;
  for (int v = static_cast<int>(axis.min); v <= static_cast<int>(axis.max); ++v) {
    const double value = v;
    pr.model(std::span<const double>(&value, 1), all, m);
    for (std::size_t i = 0; i < n; ++i) g[i] = pr.log_y(i) - m[i];
    RankedValue r;
    r.value = value;
    r.log_scale = median(g);
    for (int pass = 0; pass < 2; ++pass) {
      double sum = 0.0;
      int count = 0;
      for (double x : g)
        if (std::abs(x - r.log_scale) < s.inlier_threshold) {
          sum += x;
          ++count;
        }
      if (count == 0) break;
      r.log_scale = sum / count;
    }
    double ss = 0.0;
    for (double x : g)
      if (std::abs(x - r.log_scale) < s.inlier_threshold) {
        ss += (x - r.log_scale) * (x - r.log_scale);
        ++r.inliers;
      }
    r.residual = r.inliers > 0 ? std::sqrt(ss / r.inliers) : 0.0;
    r.inlier_fraction = static_cast<double>(r.inliers) / static_cast<double>(n);
    ranked.push_back(r);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const RankedValue& a, const RankedValue& b) {
    return a.inliers != b.inliers ? a.inliers > b.inliers : a.residual < b.residual;
  });
  LuminanceFit out;
  out.model = std::string(model);
  const RankedValue& best = ranked.front();
  out.parameters.push_back({axis.parameter, best.value, 0.0});
  out.log_scale = best.log_scale;
  out.residual = best.residual;
  out.samples = static_cast<int>(n);
  out.inliers = best.inliers;
  out.inlier_fraction = best.inlier_fraction;
  out.method = "ranking";
  out.sun = sun;
  out.ranking = std::move(ranked);
  return out;
}

}  // namespace

const ParameterSchema<EstimateSettings>& EstimateSettings::schema() {
  static const ParameterSchema<EstimateSettings> s = [] {
    using S = EstimateSettings;
    const S d;
    ParameterSchema<S> s;
    s.optional_integer(
         &S::samples,
         {.name = "samples",
          .unit = "1",
          .kind = ParameterKind::integer,
          .min = 2,
          .max = 1000000,
          .default_value = Absent{fmt::format("{}, or every sky pixel when there are no more",
                                              estimate::kPhotoSamples)},
          .description = "random sky pixels per estimate (N of Morales 2017 eq. 8, there 100)"})
        .integer(&S::seed, {.name = "seed",
                            .unit = "1",
                            .kind = ParameterKind::integer,
                            .min = 0,
                            .max = 2147483647,
                            .default_value = ParameterValue(static_cast<double>(d.seed)),
                            .description = "seed of the sampling, RANSAC and bootstrap"})
        .integer(&S::ransac_iterations,
                 {.name = "ransac-iterations",
                  .unit = "1",
                  .kind = ParameterKind::integer,
                  .min = 1,
                  .max = 100000,
                  .default_value = ParameterValue(static_cast<double>(d.ransac_iterations)),
                  .description = "random minimal sets RANSAC tries"})
        .number(&S::inlier_threshold,
                {.name = "inlier-threshold",
                 .unit = "1",
                 .min = 1e-6,
                 .max = 10.0,
                 .default_value = ParameterValue(d.inlier_threshold),
                 .description = "RANSAC: |ln Y - ln model| below this is clear sky"})
        .integer(&S::bootstrap,
                 {.name = "bootstrap",
                  .unit = "1",
                  .kind = ParameterKind::integer,
                  .min = 0,
                  .max = 10000,
                  .default_value = ParameterValue(static_cast<double>(d.bootstrap)),
                  .description = "bootstrap resamples of the inliers for the sigmas (0: none)"})
        .custom(
            {.name = "no-ransac",
             .kind = ParameterKind::flag,
             .default_value = ParameterValue(false),
             .description = "fit all samples (no outlier rejection)"},
            [](S& p, const ParameterValue& v) { p.ransac = !std::get<bool>(v); },
            [](const S& p) -> std::optional<ParameterValue> { return !p.ransac; });
    return s;
  }();
  return s;
}

ParameterSpec estimation_model_spec() {
  std::string models;
  for (const std::string& m : estimated_models())
    models +=
        fmt::format("{}{} ({})", models.empty() ? "" : ", ", m, estimation_policy(m).description);
  ParameterSpec s{.name = "model",
                  .kind = ParameterKind::text,
                  .default_value = ParameterValue(default_estimated_model()),
                  .description = "the model fitted: " + models};
  s.choices = estimated_models();
  return s;
}

const FittedParameter& LuminanceFit::parameter(std::string_view name) const {
  for (const auto& p : parameters)
    if (p.name == name) return p;
  throw InvalidArgument(
      fmt::format("the fit of model '{}' has no parameter '{}'", model, excerpt(name)));
}

const EstimationPolicy& estimation_policy(std::string_view name) {
  const ModelInfo* info = find_model(name);
  if (!info || !info->estimation) {
    std::string known;
    for (const auto& m : estimated_models()) known += (known.empty() ? "" : ", ") + m;
    throw InvalidArgument(
        fmt::format("model '{}' is not fitted to photos (fitted: {})", excerpt(name), known));
  }
  return *info->estimation;
}

std::vector<std::string> estimated_models() {
  std::vector<std::string> out;
  for (const auto& m : model_registry())
    if (m.estimation) out.push_back(m.name);
  return out;
}

std::string default_estimated_model() {
  for (const auto& m : model_registry())
    if (m.estimation && m.estimation->is_default) return m.name;
  SKYLIGHT_CHECK(false, "no model is the default of the photo fits");
  return {};
}

LuminanceFit fit_luminance(std::string_view model, std::span<const LuminanceSample> samples,
                           const SunPosition& sun, const EstimateSettings& settings) {
  const EstimationPolicy& policy = estimation_policy(model);
  const Problem pr(policy, model, samples, sun);
  if (!policy.surrogate.empty()) return fit_by_surrogate(pr, model, samples, sun, settings);
  switch (policy.method) {
    case Method::profile_scan:
      return fit_by_profile(pr, model, sun, settings);
    case Method::grid_ransac:
      return fit_by_grid(pr, model, sun, settings);
    case Method::ranking:
      return fit_by_ranking(pr, model, sun, settings);
  }
  SKYLIGHT_CHECK(false, "fit_luminance: unknown method");
  return {};
}

LuminanceFit fit_profile(std::string_view model, std::span<const LuminanceSample> samples,
                         const SunPosition& sun, bool bracketing_only) {
  const EstimationPolicy& policy = estimation_policy(model);
  SKYLIGHT_CHECK(policy.method == Method::profile_scan, "fit_profile: a profile_scan model");
  const Problem pr(policy, model, samples, sun);
  std::vector<double> work;
  const auto all = all_indices(pr.size());
  const Fitted f = bracketing_only
                       ? Fitted{golden(pr, all, scan(pr, all, work), work), "bracketing", 0}
                       : profile_fit(pr, all, work);
  return result(pr, model, sun, f, all);
}

io::ImageF fitted_luminance_image(const LuminanceFit& fit, const Camera& camera) {
  const EstimationPolicy& policy = estimation_policy(fit.model);
  std::vector<Vec3> views;
  std::vector<std::size_t> pixels;
  for (int row = 0; row < camera.height; ++row)
    for (int col = 0; col < camera.width; ++col)
      if (const auto d = camera.pixel_direction(col, row); d && d->z > 0.0) {
        views.push_back(*d);
        pixels.push_back(static_cast<std::size_t>(row) * static_cast<std::size_t>(camera.width) +
                         static_cast<std::size_t>(col));
      }
  io::ImageF out(camera.width, camera.height, 1);
  if (views.empty()) return out;
  std::vector<double> p;
  for (const auto& q : fit.parameters) p.push_back(q.value);
  std::vector<double> m(views.size());
  policy.prepare(fit.sun, views)(p, all_indices(views.size()), m);
  for (std::size_t k = 0; k < views.size(); ++k)
    out.data[pixels[k]] = static_cast<float>(std::exp(fit.log_scale + m[k]));
  return out;
}

PhotoFit estimate_from_photo(std::string_view model, const io::ImageF& image, const Camera& camera,
                             const std::optional<SunPosition>& sun,
                             const estimate::MaskSettings& mask_settings,
                             const EstimateSettings& settings, const io::ImageF* user_mask) {
  estimate::PhotoSamples ps = estimate::sample_photo(image, camera, sun, mask_settings,
                                                     settings.samples, settings.seed, user_mask);
  PhotoFit out;
  out.fit = fit_luminance(model, ps.samples, ps.sun, settings);
  out.sky_pixels = ps.sky_pixels;
  out.sun_detected = ps.sun_detected;
  out.mask = std::move(ps.mask);
  return out;
}

}  // namespace skylight::fit
