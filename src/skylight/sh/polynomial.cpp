#include "skylight/sh/polynomial.h"

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/rotation.h"

namespace skylight::sh {
namespace {

// Number of stored (l, m >= 0) pairs of N bands: N (N + 1) / 2; (l, m) is at l (l + 1) / 2 + m.
int stored_count(int bands) {
  return bands * (bands + 1) / 2;
}

// T_0..T_d at u in [-1, 1] (Chebyshev recurrence T_{k+1} = 2 u T_k - T_{k-1}).
void chebyshev(int degree, double u, double* t) {
  t[0] = 1.0;
  if (degree >= 1) t[1] = u;
  for (int k = 2; k <= degree; ++k) t[k] = 2.0 * u * t[k - 1] - t[k - 2];
}

// The range [lo, hi] mapped onto [-1, 1].
double scaled(double x, double lo, double hi) {
  return hi > lo ? (2.0 * x - (lo + hi)) / (hi - lo) : 0.0;
}

std::unique_ptr<SkyModel> make_model(const std::string& model, const std::string& parameter,
                                     double theta, double tau, double phi) {
  SkyParameters sp;
  sp.sun = SunPosition{theta, phi};
  sp.values.set(parameter, tau);
  return make_sky_model(model, sp);
}

void check_range(const char* name, double x, double lo, double hi) {
  if (!(x >= lo && x <= hi)) {
    throw InvalidArgument(std::string(name) + " = " + std::to_string(x) +
                          " is outside the table's fitted range [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "]");
  }
}

}  // namespace

PolynomialTable fit_polynomial(const PolynomialFitSettings& s) {
  check_bands(s.bands);
  if (s.degree_theta < 0 || s.degree_tau < 0 || s.degree_theta > 40 || s.degree_tau > 40) {
    throw InvalidArgument("polynomial degrees (" + std::to_string(s.degree_theta) + ", " +
                          std::to_string(s.degree_tau) + ") are outside [0, 40]");
  }
  if (!(s.theta_max >= s.theta_min) || !(s.tau_max >= s.tau_min)) {
    throw InvalidArgument("the fitted parameter ranges must not be empty");
  }
  const int gt = s.grid_theta > 0 ? s.grid_theta : 2 * (s.degree_theta + 1) + 1;
  const int gv = s.grid_tau > 0 ? s.grid_tau : 2 * (s.degree_tau + 1) + 1;
  if (gt < s.degree_theta + 1 || gv < s.degree_tau + 1) {
    throw InvalidArgument("the fitting grid needs at least degree + 1 points per parameter");
  }
  PolynomialTable table{s.model,        s.parameter,  s.channels,  s.bands,
                        s.degree_theta, s.degree_tau, s.theta_min, s.theta_max,
                        s.tau_min,      s.tau_max,    {}};
  const int terms = table.terms();
  const int stored = stored_count(s.bands);
  const int points = gt * gv;
  Eigen::MatrixXd a(points, terms);
  Eigen::MatrixXd b(points, stored * 3);
  std::vector<double> ti(static_cast<std::size_t>(s.degree_theta + 1));
  std::vector<double> tj(static_cast<std::size_t>(s.degree_tau + 1));
  for (int p = 0; p < points; ++p) {
    const int it = p / gv, iv = p % gv;
    const double theta =
        gt == 1 ? s.theta_min : s.theta_min + (s.theta_max - s.theta_min) * it / (gt - 1);
    const double tau = gv == 1 ? s.tau_min : s.tau_min + (s.tau_max - s.tau_min) * iv / (gv - 1);
    chebyshev(s.degree_theta, scaled(theta, s.theta_min, s.theta_max), ti.data());
    chebyshev(s.degree_tau, scaled(tau, s.tau_min, s.tau_max), tj.data());
    for (int i = 0; i <= s.degree_theta; ++i) {
      for (int j = 0; j <= s.degree_tau; ++j) {
        a(p, i * (s.degree_tau + 1) + j) =
            ti[static_cast<std::size_t>(i)] * tj[static_cast<std::size_t>(j)];
      }
    }
    const auto model = make_model(s.model, s.parameter, theta, tau, 0.0);
    const auto proj = project_model(*model, s.channels, s.bands, s.projection);
    for (int l = 0; l < s.bands; ++l) {
      for (int m = 0; m <= l; ++m) {
        for (int ch = 0; ch < 3; ++ch) {
          b(p, (l * (l + 1) / 2 + m) * 3 + ch) =
              proj.coefficients.c[static_cast<std::size_t>(index(l, m))][ch];
        }
      }
    }
  }
  const Eigen::MatrixXd x = a.colPivHouseholderQr().solve(b);
  table.coefficients.resize(static_cast<std::size_t>(stored) * 3 * static_cast<std::size_t>(terms));
  for (int k = 0; k < stored * 3; ++k) {
    for (int t = 0; t < terms; ++t) {
      table.coefficients[static_cast<std::size_t>(k) * static_cast<std::size_t>(terms) +
                         static_cast<std::size_t>(t)] = static_cast<float>(x(t, k));
    }
  }
  return table;
}

Coefficients evaluate_table(const PolynomialTable& table, double theta, double tau, double phi,
                            int bands, bool filter) {
  check_bands(bands);
  if (bands > table.bands) {
    throw InvalidArgument("bands = " + std::to_string(bands) + " exceeds the table's " +
                          std::to_string(table.bands));
  }
  check_range("sun zenith [rad]", theta, table.theta_min, table.theta_max);
  check_range(table.parameter.c_str(), tau, table.tau_min, table.tau_max);
  const int terms = table.terms();
  // The product matrix (T_i(u) T_j(v))_ij, shared by every coefficient (Habel 2008 §3.1).
  std::vector<double> ti(static_cast<std::size_t>(table.degree_theta + 1));
  std::vector<double> tj(static_cast<std::size_t>(table.degree_tau + 1));
  chebyshev(table.degree_theta, scaled(theta, table.theta_min, table.theta_max), ti.data());
  chebyshev(table.degree_tau, scaled(tau, table.tau_min, table.tau_max), tj.data());
  std::vector<double> prod(static_cast<std::size_t>(terms));
  for (int i = 0; i <= table.degree_theta; ++i) {
    for (int j = 0; j <= table.degree_tau; ++j) {
      prod[static_cast<std::size_t>(i * (table.degree_tau + 1) + j)] =
          ti[static_cast<std::size_t>(i)] * tj[static_cast<std::size_t>(j)];
    }
  }
  Coefficients c{bands, std::vector<Triple>(static_cast<std::size_t>(coefficient_count(bands)))};
  for (int l = 0; l < bands; ++l) {
    for (int m = 0; m <= l; ++m) {
      for (int ch = 0; ch < 3; ++ch) {
        const float* p =
            table.coefficients.data() + static_cast<std::size_t>((l * (l + 1) / 2 + m) * 3 + ch) *
                                            static_cast<std::size_t>(terms);
        double sum = 0.0;
        for (int t = 0; t < terms; ++t)
          sum += static_cast<double>(p[t]) * prod[static_cast<std::size_t>(t)];
        c.c[static_cast<std::size_t>(index(l, m))][ch] = sum;
      }
    }
  }
  c = rotate_about_zenith(c, phi);
  return filter ? ringing_filter(c) : c;
}

Projection project_reference(const PolynomialTable& table, double theta, double tau, double phi,
                             int bands, const ProjectionOptions& options) {
  const auto model = make_model(table.model, table.parameter, theta, tau, phi);
  return project_model(*model, table.channels, bands, options);
}

}  // namespace skylight::sh
