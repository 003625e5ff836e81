// Hosek-Wilkie turbidity and albedo from luminance samples (docs/ESTIMATE.md).
#include "skylight/estimate/hosek_fit.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/random.h"
#include "skylight/models/hosek_wilkie.h"

namespace skylight::estimate {
namespace {

// The grid of step 1: T every 0.5 over the dataset's knots, albedo at its ends and middle.
constexpr int kGridT = 19;
constexpr int kGridAlbedo = 3;
constexpr double kAlbedoMin = 0.0, kAlbedoMax = 1.0;
// Central-difference steps for the Jacobian (the model is smooth in both: splines over knots).
constexpr double kStepT = 1e-4, kStepAlbedo = 1e-4;
constexpr int kMaxIterations = 100;
constexpr int kMaxLambdaTries = 12;
// LM stops when a step lowers the cost by less than this fraction (double round-off level).
constexpr double kRelativeDecrease = 1e-14;

// ln Y_HW(v_i; T, a) for the samples idx.
void log_model(std::span<const LuminanceSample> samples, std::span<const std::size_t> idx,
               const SunPosition& sun, double t, double a, std::vector<double>& out) {
  const HosekWilkieModel model(HosekParameters{sun, t, a});
  out.resize(idx.size());
  for (std::size_t k = 0; k < idx.size(); ++k)
    out[k] = std::log(
        std::max(model.tristimulus(samples[idx[k]].view).Y, std::numeric_limits<double>::min()));
}

struct State {
  double t = 0.0, a = 0.0, c = 0.0, cost = 0.0;
  std::size_t node = 0;  // the grid node it came from (grid searches only)
};

double cost_of(std::span<const double> log_y, std::span<const std::size_t> idx,
               const std::vector<double>& m, double c) {
  double s = 0.0;
  for (std::size_t k = 0; k < idx.size(); ++k) {
    const double r = log_y[idx[k]] - c - m[k];
    s += r * r;
  }
  return std::isfinite(s) ? s : std::numeric_limits<double>::infinity();
}

State levenberg_marquardt(std::span<const LuminanceSample> samples, std::span<const double> log_y,
                          std::span<const std::size_t> idx, const SunPosition& sun, State cur) {
  const std::size_t n = idx.size();
  std::vector<double> m, mt0, mt1, ma0, ma1, trial;
  log_model(samples, idx, sun, cur.t, cur.a, m);
  cur.cost = cost_of(log_y, idx, m, cur.c);
  double lambda = 1e-3;
  for (int it = 0; it < kMaxIterations; ++it) {
    const double t0 = std::max(kHwTurbidityMin, cur.t - kStepT);
    const double t1 = std::min(kHwTurbidityMax, cur.t + kStepT);
    const double a0 = std::max(kAlbedoMin, cur.a - kStepAlbedo);
    const double a1 = std::min(kAlbedoMax, cur.a + kStepAlbedo);
    log_model(samples, idx, sun, t0, cur.a, mt0);
    log_model(samples, idx, sun, t1, cur.a, mt1);
    log_model(samples, idx, sun, cur.t, a0, ma0);
    log_model(samples, idx, sun, cur.t, a1, ma1);
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < n; ++k) {
      const double r = log_y[idx[k]] - cur.c - m[k];
      const Eigen::Vector3d J(-(mt1[k] - mt0[k]) / (t1 - t0), -(ma1[k] - ma0[k]) / (a1 - a0), -1.0);
      JtJ += J * J.transpose();
      Jtr += J * r;
    }
    bool accepted = false, done = false;
    for (int tries = 0; tries < kMaxLambdaTries && !accepted; ++tries) {
      Eigen::Matrix3d A = JtJ;
      A.diagonal() *= 1.0 + lambda;
      const Eigen::Vector3d step = A.ldlt().solve(-Jtr);
      if (!step.allFinite()) return cur;
      State next;
      next.t = std::clamp(cur.t + step[0], kHwTurbidityMin, kHwTurbidityMax);
      next.a = std::clamp(cur.a + step[1], kAlbedoMin, kAlbedoMax);
      next.c = cur.c + step[2];
      log_model(samples, idx, sun, next.t, next.a, trial);
      next.cost = cost_of(log_y, idx, trial, next.c);
      if (next.cost < cur.cost) {
        done = cur.cost - next.cost <= kRelativeDecrease * cur.cost;
        cur = next;
        m.swap(trial);
        lambda = std::max(lambda * 0.1, 1e-12);
        accepted = true;
      } else {
        lambda *= 10.0;
      }
    }
    if (!accepted || done || cur.cost <= 0.0) break;
  }
  return cur;
}

}  // namespace

HosekFit fit_hosek(std::span<const LuminanceSample> samples, const SunPosition& sun,
                   const EstimateSettings& s) {
  if (samples.size() < 3) throw InvalidArgument("the Hosek-Wilkie fit needs at least 3 samples");
  if (!(sun.zenith >= 0.0 && sun.zenith < kPi / 2))
    throw InvalidArgument(
        fmt::format("the sun is at zenith angle {} deg: the fit needs it above the horizon",
                    rad_to_deg(sun.zenith)));
  const std::size_t n = samples.size();
  std::vector<double> log_y(n);
  for (std::size_t i = 0; i < n; ++i) log_y[i] = std::log(samples[i].luminance);
  std::vector<std::size_t> all(n);
  std::iota(all.begin(), all.end(), std::size_t{0});

  // Step 1: the grid.
  struct Node {
    double t, a;
    std::vector<double> m;
  };
  std::vector<Node> grid;
  for (int i = 0; i < kGridT; ++i)
    for (int j = 0; j < kGridAlbedo; ++j) {
      Node node{kHwTurbidityMin + 0.5 * i, 0.5 * j, {}};
      log_model(samples, all, sun, node.t, node.a, node.m);
      grid.push_back(std::move(node));
    }
  // Best grid node and ln s for the samples idx.
  auto best_node = [&](std::span<const std::size_t> idx) {
    State best;
    best.t = grid.front().t;
    best.a = grid.front().a;
    best.cost = std::numeric_limits<double>::infinity();
    for (std::size_t g = 0; g < grid.size(); ++g) {
      const Node& node = grid[g];
      double c = 0.0;
      for (std::size_t i : idx) c += log_y[i] - node.m[i];
      c /= static_cast<double>(idx.size());
      double cost = 0.0;
      for (std::size_t i : idx) cost += (log_y[i] - c - node.m[i]) * (log_y[i] - c - node.m[i]);
      if (cost < best.cost) best = {node.t, node.a, c, cost, g};
    }
    return best;
  };
  std::vector<double> work;
  auto consensus = [&](const State& st) {
    log_model(samples, all, sun, st.t, st.a, work);
    std::vector<std::size_t> in;
    for (std::size_t i = 0; i < n; ++i)
      if (std::abs(log_y[i] - st.c - work[i]) < s.inlier_threshold) in.push_back(i);
    return in;
  };

  // Step 2: RANSAC on the grid (the grid's ln Y are reused for the consensus of each trial).
  std::vector<std::size_t> inliers = all;
  if (s.ransac) {
    SplitMix64 rng(s.seed ^ 0x2545f4914f6cdd1dULL);
    const std::size_t m =
        std::min<std::size_t>(n, static_cast<std::size_t>(std::max(3, s.ransac_minimal_set)));
    std::vector<std::size_t> best, minimal(m);
    for (int it = 0; it < s.ransac_iterations; ++it) {
      for (std::size_t k = 0; k < m; ++k) {
        std::size_t i;
        do i = rng.below(n);
        while (std::find(minimal.begin(), minimal.begin() + static_cast<std::ptrdiff_t>(k), i) !=
               minimal.begin() + static_cast<std::ptrdiff_t>(k));
        minimal[k] = i;
      }
      const State trial = best_node(minimal);
      const Node& node = grid[trial.node];
      std::vector<std::size_t> in;
      for (std::size_t i = 0; i < n; ++i)
        if (std::abs(log_y[i] - trial.c - node.m[i]) < s.inlier_threshold) in.push_back(i);
      if (in.size() > best.size()) best = std::move(in);
    }
    if (best.size() >= 3) inliers = std::move(best);
  }

  // Step 3: LM on the inliers, and once more on the consensus of that fit.
  State fit = levenberg_marquardt(samples, log_y, inliers, sun, best_node(inliers));
  if (s.ransac) {
    if (auto again = consensus(fit); again.size() >= 3 && again != inliers) {
      inliers = std::move(again);
      fit = levenberg_marquardt(samples, log_y, inliers, sun, best_node(inliers));
    }
  }
  HosekFit out;
  out.turbidity = fit.t;
  out.albedo = fit.a;
  out.log_scale = fit.c;
  out.residual = std::sqrt(fit.cost / static_cast<double>(inliers.size()));
  out.samples = static_cast<int>(n);
  out.inliers = static_cast<int>(inliers.size());
  out.inlier_fraction = static_cast<double>(inliers.size()) / static_cast<double>(n);

  // Step 4: bootstrap.
  if (s.bootstrap >= 2) {
    SplitMix64 rng(s.seed ^ 0x9e3779b97f4a7c15ULL);
    std::vector<double> ts, as;
    std::vector<std::size_t> resample(inliers.size());
    for (int b = 0; b < s.bootstrap; ++b) {
      for (auto& i : resample) i = inliers[rng.below(inliers.size())];
      const State r = levenberg_marquardt(samples, log_y, resample, sun, fit);
      ts.push_back(r.t);
      as.push_back(r.a);
    }
    auto sd = [](const std::vector<double>& v) {
      const double mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
      double q = 0.0;
      for (double x : v) q += (x - mean) * (x - mean);
      return std::sqrt(q / static_cast<double>(v.size() - 1));
    };
    out.turbidity_sigma = sd(ts);
    out.albedo_sigma = sd(as);
  }
  return out;
}

}  // namespace skylight::estimate
