#include "skylight/core/xyz_quadrature.h"

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"

namespace skylight {
namespace {

// The second derivatives of the natural cubic spline through (x_i, y_i) (M_0 = M_{n-1} = 0; the
// tridiagonal system solved by elimination).
std::vector<double> natural_spline_moments(std::span<const double> x, std::span<const double> y) {
  const std::size_t n = x.size();
  std::vector<double> m(n, 0.0), diag(n, 1.0), rhs(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
    const double lower = i > 1 ? h0 : 0.0;  // M_0 = 0 is known
    diag[i] = 2.0 * (h0 + h1);
    rhs[i] = 6.0 * ((y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0);
    if (i > 1) {
      const double f = lower / diag[i - 1];
      diag[i] -= f * h0;
      rhs[i] -= f * rhs[i - 1];
    }
  }
  for (std::size_t i = n - 2; i >= 1; --i) {
    const double upper = i + 2 < n ? x[i + 1] - x[i] : 0.0;  // M_{n-1} = 0 is known
    m[i] = (rhs[i] - upper * m[i + 1]) / diag[i];
  }
  return m;
}

}  // namespace

std::vector<Cmf> spline_xyz_weights(std::span<const double> nodes_nm,
                                    const std::function<double(double nm)>& e) {
  const std::size_t n = nodes_nm.size();
  SKYLIGHT_CHECK(n >= 3, "spline_xyz_weights: fewer than 3 nodes");
  for (std::size_t i = 0; i + 1 < n; ++i)
    SKYLIGHT_CHECK(nodes_nm[i + 1] > nodes_nm[i], "spline_xyz_weights: nodes must ascend");
  // The 1 nm samples from the first node to the last (the last one added if off the grid) and
  // their trapezoid weights.
  std::vector<double> nm, dl;
  for (double l = nodes_nm.front(); l < nodes_nm.back() - 1e-9; l += 1.0) nm.push_back(l);
  nm.push_back(nodes_nm.back());
  dl.assign(nm.size(), 0.0);
  for (std::size_t j = 0; j + 1 < nm.size(); ++j) {
    dl[j] += 0.5 * (nm[j + 1] - nm[j]);
    dl[j + 1] += 0.5 * (nm[j + 1] - nm[j]);
  }
  // CMF x E x trapezoid weight of each sample, once.
  std::vector<Cmf> ce(nm.size());
  for (std::size_t j = 0; j < nm.size(); ++j) {
    const Cmf c = cie1931_cmf(nm[j]);
    const double f = dl[j] * e(nm[j]);
    ce[j] = {f * c.x, f * c.y, f * c.z};
  }
  std::vector<Cmf> w(n);
  std::vector<double> unit(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double ek = e(nodes_nm[k]);
    SKYLIGHT_CHECK(ek > 0.0, "spline_xyz_weights: the known spectrum is not positive at a node");
    std::fill(unit.begin(), unit.end(), 0.0);
    unit[k] = 1.0;
    const std::vector<double> m = natural_spline_moments(nodes_nm, unit);
    std::size_t i = 0;  // the interval [nodes[i], nodes[i+1]] of the sample
    for (std::size_t j = 0; j < nm.size(); ++j) {
      while (i + 2 < n && nm[j] > nodes_nm[i + 1]) ++i;
      const double h = nodes_nm[i + 1] - nodes_nm[i];
      const double t = std::clamp((nm[j] - nodes_nm[i]) / h, 0.0, 1.0), u = 1.0 - t;
      const double phi = u * unit[i] + t * unit[i + 1] +
                         h * h / 6.0 * ((u * u * u - u) * m[i] + (t * t * t - t) * m[i + 1]);
      w[k].x += phi * ce[j].x;
      w[k].y += phi * ce[j].y;
      w[k].z += phi * ce[j].z;
    }
    w[k] = {w[k].x / ek, w[k].y / ek, w[k].z / ek};
  }
  return w;
}

Xyz weighted_xyz(std::span<const Cmf> weights, std::span<const double> radiance) {
  SKYLIGHT_CHECK(weights.size() == radiance.size(), "weighted_xyz: size mismatch");
  Xyz c;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    c.X += weights[k].x * radiance[k];
    c.Y += weights[k].y * radiance[k];
    c.Z += weights[k].z * radiance[k];
  }
  return {kMaxLuminousEfficacy * std::max(c.X, 0.0), kMaxLuminousEfficacy * std::max(c.Y, 0.0),
          kMaxLuminousEfficacy * std::max(c.Z, 0.0)};
}

}  // namespace skylight
