#include "skylight/sh/polynomial.h"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/rotation.h"

namespace skylight::sh {
namespace {

// Largest polynomial degree of a table (fit_polynomial and table_from_json refuse more).
constexpr int kMaxDegree = 40;

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
                                     const ParameterValues& fixed, double theta, double tau,
                                     double phi) {
  SkyParameters sp;
  sp.sun = SunPosition{theta, phi};
  sp.values = fixed;
  if (!parameter.empty()) sp.values.set(parameter, tau);
  return make_sky_model(model, sp);
}

// sum_t p[t] x[t] with 8 independent partial sums, so that the compiler vectorises it without
// reassociating a single sum (no -ffast-math); an AVX2 clone is chosen at load time where the CPU
// has it (GCC function multiversioning). The eq. 1 evaluation's only hot loop.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
double
dot(const float* p, const double* x, int n) {
  double acc[8] = {};
  int t = 0;
  for (; t + 8 <= n; t += 8) {
    for (int k = 0; k < 8; ++k) acc[k] += static_cast<double>(p[t + k]) * x[t + k];
  }
  double tail = 0.0;
  for (; t < n; ++t) tail += static_cast<double>(p[t]) * x[t];
  return tail + (((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7])));
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
  const bool theta_only = s.parameter.empty();
  if (theta_only && s.degree_tau != 0) {
    throw InvalidArgument("a fit in theta only (no second parameter) needs degree_tau = 0, not " +
                          std::to_string(s.degree_tau));
  }
  if (!(s.theta_max >= s.theta_min) || (!theta_only && !(s.tau_max >= s.tau_min))) {
    throw InvalidArgument("the fitted parameter ranges must not be empty");
  }
  if (s.fixed.has(s.parameter)) {
    throw InvalidArgument("parameter '" + s.parameter + "' is both varied and fixed");
  }
  const int gt = s.grid_theta > 0 ? s.grid_theta : 2 * (s.degree_theta + 1) + 1;
  const int gv = theta_only ? 1 : s.grid_tau > 0 ? s.grid_tau : 2 * (s.degree_tau + 1) + 1;
  if (gt < s.degree_theta + 1 || gv < s.degree_tau + 1) {
    throw InvalidArgument("the fitting grid needs at least degree + 1 points per parameter");
  }
  PolynomialTable table;
  table.model = s.model;
  table.parameter = s.parameter;
  table.fixed = s.fixed;
  table.channels = s.channels;
  table.bands = s.bands;
  table.degree_theta = s.degree_theta;
  table.degree_tau = s.degree_tau;
  table.theta_min = s.theta_min;
  table.theta_max = s.theta_max;
  table.tau_min = theta_only ? 0.0 : s.tau_min;
  table.tau_max = theta_only ? 0.0 : s.tau_max;
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
    const auto model = make_model(s.model, s.parameter, s.fixed, theta, tau, 0.0);
    const auto proj = project_model(*model, s.channels, s.bands, s.projection);
    if (s.progress) s.progress(p + 1, points);
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
  if (!table.parameter.empty())
    check_range(table.parameter.c_str(), tau, table.tau_min, table.tau_max);
  SKYLIGHT_CHECK(
      table.degree_theta >= 0 && table.degree_theta <= kMaxDegree && table.degree_tau >= 0 &&
          table.degree_tau <= kMaxDegree &&
          table.coefficients.size() ==
              static_cast<std::size_t>(table.bands * (table.bands + 1) / 2 * 3 * table.terms()),
      "evaluate_table: degrees or coefficient count out of range");
  const int terms = table.terms();
  // The product matrix (T_i(u) T_j(v))_ij, shared by every coefficient (Habel 2008 §3.1).
  // On the stack: degrees are at most kMaxDegree (checked on fit and load).
  std::array<double, kMaxDegree + 1> ti{}, tj{};
  chebyshev(table.degree_theta, scaled(theta, table.theta_min, table.theta_max), ti.data());
  chebyshev(table.degree_tau, scaled(tau, table.tau_min, table.tau_max), tj.data());
  std::array<double, (kMaxDegree + 1) * (kMaxDegree + 1)> prod{};
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
        c.c[static_cast<std::size_t>(index(l, m))][ch] = dot(p, prod.data(), terms);
      }
    }
  }
  c = rotate_about_zenith(c, phi);
  return filter ? ringing_filter(c) : c;
}

Projection project_reference(const PolynomialTable& table, double theta, double tau, double phi,
                             int bands, const ProjectionOptions& options) {
  const auto model = make_model(table.model, table.parameter, table.fixed, theta, tau, phi);
  return project_model(*model, table.channels, bands, options);
}

}  // namespace skylight::sh
