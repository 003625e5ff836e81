#include "skylight/sh/projection.h"

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/sh/basis.h"

namespace skylight::sh {
namespace {

// Below this |c_00| a channel is treated as zero when measuring relative change.
constexpr double kTinyScale = 1e-300;

Coefficients integrate(const std::function<Triple(Vec3)>& f, int bands, Region region, int n) {
  std::vector<double> mu, w;
  gauss_legendre(n, region == Region::upper_hemisphere ? 0.0 : -1.0, 1.0, mu, w);
  const int n_phi = region == Region::upper_hemisphere ? 2 * n : 4 * n;
  const double dphi = 2.0 * kPi / n_phi;
  const auto count = static_cast<std::size_t>(coefficient_count(bands));
  // One partial sum per ring, reduced in ring order afterwards.
  std::vector<std::vector<Triple>> rings(static_cast<std::size_t>(n),
                                         std::vector<Triple>(count, Triple{}));
  parallel_for(static_cast<std::size_t>(n), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> y(count);
    for (std::size_t r = begin; r < end; ++r) {
      const double z = mu[r];
      const double theta = std::acos(clamp_cosine(z));
      auto& acc = rings[r];
      for (int j = 0; j < n_phi; ++j) {
        const Vec3 d = direction_from_angles(theta, (j + 0.5) * dphi);
        const Triple v = f(d);
        evaluate_basis(bands, d, y);
        for (std::size_t i = 0; i < count; ++i) {
          for (int ch = 0; ch < 3; ++ch) acc[i][ch] += v[ch] * y[i];
        }
      }
      for (auto& a : acc) {
        for (double& x : a) x *= w[r] * dphi;
      }
    }
  });
  Coefficients out{bands, std::vector<Triple>(count, Triple{})};
  for (const auto& ring : rings) {
    for (std::size_t i = 0; i < count; ++i) {
      for (int ch = 0; ch < 3; ++ch) out.c[i][ch] += ring[i][ch];
    }
  }
  return out;
}

}  // namespace

void gauss_legendre(int n, double a, double b, std::vector<double>& nodes,
                    std::vector<double>& weights) {
  SKYLIGHT_CHECK(n >= 1, "gauss_legendre: n >= 1");
  nodes.assign(static_cast<std::size_t>(n), 0.0);
  weights.assign(static_cast<std::size_t>(n), 0.0);
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Tricomi's initial guess, then Newton on P_n.
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      // P_n' = n (x P_n - P_{n-1}) / (x^2 - 1)
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double wgt = 2.0 / ((1.0 - x * x) * dp * dp);
    const auto lo = static_cast<std::size_t>(i), hi = static_cast<std::size_t>(n - 1 - i);
    nodes[lo] = mid - half * x;
    nodes[hi] = mid + half * x;
    weights[lo] = weights[hi] = half * wgt;
  }
}

Projection project(const std::function<Triple(Vec3)>& f, int bands,
                   const ProjectionOptions& options) {
  check_bands(bands);
  SKYLIGHT_CHECK(options.min_nodes >= 1 && options.max_nodes >= options.min_nodes,
                 "project: bad node counts");
  SKYLIGHT_CHECK(options.tolerance > 0.0, "project: tolerance > 0");
  Projection result;
  result.coefficients = integrate(f, bands, options.region, options.min_nodes);
  result.nodes = options.min_nodes;
  for (int n = 2 * options.min_nodes; n <= options.max_nodes; n *= 2) {
    Coefficients next = integrate(f, bands, options.region, n);
    double change = 0.0;
    for (int ch = 0; ch < 3; ++ch) {
      const double scale = std::max(std::abs(next.c[0][ch]), kTinyScale);
      for (std::size_t i = 0; i < next.c.size(); ++i) {
        change = std::max(change, std::abs(next.c[i][ch] - result.coefficients.c[i][ch]) / scale);
      }
    }
    result.coefficients = std::move(next);
    result.nodes = n;
    result.last_change = change;
    if (change <= options.tolerance) {
      result.converged = true;
      break;
    }
  }
  return result;
}

Triple horizontal_irradiance(const Coefficients& c) {
  SKYLIGHT_CHECK(c.bands >= 2 && c.c.size() >= 4, "horizontal_irradiance: needs 2 bands");
  const double k = std::sqrt(4.0 * kPi / 3.0);
  const Triple& c10 = c.c[static_cast<std::size_t>(index(1, 0))];
  return {k * c10[0], k * c10[1], k * c10[2]};
}

void add_uniform_ground(Coefficients& c, const Triple& radiance) {
  check_bands(c.bands);
  std::vector<double> mu, w;
  gauss_legendre(c.bands, -1.0, 0.0, mu, w);
  std::vector<double> y(static_cast<std::size_t>(coefficient_count(c.bands)));
  for (std::size_t r = 0; r < mu.size(); ++r) {
    // Y_l0 does not depend on phi: evaluate at phi = 0.
    evaluate_basis(c.bands, Vec3{0.0, std::sqrt(std::max(0.0, 1.0 - mu[r] * mu[r])), mu[r]}, y);
    for (int l = 0; l < c.bands; ++l) {
      const double g = 2.0 * kPi * w[r] * y[static_cast<std::size_t>(index(l, 0))];
      for (int ch = 0; ch < 3; ++ch)
        c.c[static_cast<std::size_t>(index(l, 0))][ch] += g * radiance[ch];
    }
  }
}

}  // namespace skylight::sh
