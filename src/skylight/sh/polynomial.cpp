#include "skylight/sh/polynomial.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/detail/evaluate_kernel.h"
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

// The theta axis' coordinate of a sun zenith angle (ThetaAxis).
double axis_coordinate(ThetaAxis axis, double theta) {
  if (axis == ThetaAxis::theta) return theta;
  return std::cbrt(std::max(0.0, kPi / 2 - theta) / (kPi / 2));
}
// Its inverse (a sun zenith angle of a coordinate).
double axis_theta(ThetaAxis axis, double w) {
  return axis == ThetaAxis::theta ? w : kPi / 2 - kPi / 2 * w * w * w;
}
// u in [-1, 1] of theta in the table's range (the coordinate may decrease with theta).
double theta_u(const PolynomialTable& t, double theta) {
  const double a = axis_coordinate(t.theta_axis, t.theta_min);
  const double b = axis_coordinate(t.theta_axis, t.theta_max);
  return scaled(axis_coordinate(t.theta_axis, theta), std::min(a, b), std::max(a, b));
}
// The tau piece of tau (the last one includes tau_max) and v in [-1, 1] within it.
int tau_piece(const PolynomialTable& t, double tau) {
  if (t.tau_pieces <= 1 || !(t.tau_max > t.tau_min)) return 0;
  const double x = (tau - t.tau_min) / (t.tau_max - t.tau_min) * t.tau_pieces;
  return std::clamp(static_cast<int>(std::floor(x)), 0, t.tau_pieces - 1);
}
double tau_v(const PolynomialTable& t, double tau, int piece) {
  const double w = (t.tau_max - t.tau_min) / t.tau_pieces;
  const double lo = t.tau_min + piece * w;
  return scaled(tau, lo, piece + 1 == t.tau_pieces ? t.tau_max : lo + w);
}

void check_range(const char* name, double x, double lo, double hi) {
  if (!(x >= lo && x <= hi)) {
    throw InvalidArgument(std::string(name) + " = " + std::to_string(x) +
                          " is outside the table's fitted range [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "]");
  }
}

}  // namespace

namespace {

// Checks the settings of a fit (InvalidArgument); returns the grid's points per parameter
// (theta, tau per piece).
std::array<int, 2> checked_grid(const PolynomialFitSettings& s) {
  check_bands(s.bands);
  if (s.degree_theta < 0 || s.degree_tau < 0 || s.degree_theta > kMaxDegree ||
      s.degree_tau > kMaxDegree) {
    throw InvalidArgument("polynomial degrees (" + std::to_string(s.degree_theta) + ", " +
                          std::to_string(s.degree_tau) + ") are outside [0, 40]");
  }
  const bool theta_only = s.parameter.empty();
  if (theta_only && s.degree_tau != 0) {
    throw InvalidArgument("a fit in theta only (no second parameter) needs degree_tau = 0, not " +
                          std::to_string(s.degree_tau));
  }
  if (s.tau_pieces < 1 || s.tau_pieces > kMaxTauPieces || (theta_only && s.tau_pieces != 1)) {
    throw InvalidArgument("tau pieces = " + std::to_string(s.tau_pieces) + " is outside [1, " +
                          std::to_string(kMaxTauPieces) + "] (1 for a fit in theta only)");
  }
  if (!(s.theta_max >= s.theta_min) || (!theta_only && !(s.tau_max >= s.tau_min))) {
    throw InvalidArgument("the fitted parameter ranges must not be empty");
  }
  const int gt = s.grid_theta > 0 ? s.grid_theta : 2 * (s.degree_theta + 1) + 1;
  const int gv = theta_only ? 1 : s.grid_tau > 0 ? s.grid_tau : 2 * (s.degree_tau + 1) + 1;
  if (gt < s.degree_theta + 1 || gv < s.degree_tau + 1 || (s.tau_pieces > 1 && gv < 2)) {
    throw InvalidArgument("the fitting grid needs at least degree + 1 points per parameter");
  }
  return {gt, gv};
}

// The grid: uniform in the theta axis' coordinate; in tau, gv points per piece with the ends
// shared by neighbouring pieces (one piece: gv points over the range).
std::vector<double> theta_grid(const PolynomialFitSettings& s, int gt) {
  const double w0 = axis_coordinate(s.theta_axis, s.theta_min);
  const double w1 = axis_coordinate(s.theta_axis, s.theta_max);
  std::vector<double> thetas(static_cast<std::size_t>(gt));
  for (int it = 0; it < gt; ++it) {
    thetas[static_cast<std::size_t>(it)] =
        gt == 1 ? s.theta_min
                : std::clamp(axis_theta(s.theta_axis, w0 + (w1 - w0) * it / (gt - 1)), s.theta_min,
                             s.theta_max);
  }
  return thetas;
}
std::vector<double> tau_grid(const PolynomialFitSettings& s, int n_tau) {
  std::vector<double> taus(static_cast<std::size_t>(n_tau));
  for (int q = 0; q < n_tau; ++q) {
    taus[static_cast<std::size_t>(q)] =
        n_tau == 1 ? s.tau_min : s.tau_min + (s.tau_max - s.tau_min) * q / (n_tau - 1);
  }
  return taus;
}

// Projections at every grid point: [point][(l (l + 1) / 2 + m) * 3 + channel].
Eigen::MatrixXd grid_projections(const PolynomialFitSettings& s, const GridProjection& project,
                                 const std::vector<double>& thetas,
                                 const std::vector<double>& taus) {
  const int gt = static_cast<int>(thetas.size()), n_tau = static_cast<int>(taus.size());
  Eigen::MatrixXd proj_all(gt * n_tau, stored_count(s.bands) * 3);
  for (int p = 0; p < gt * n_tau; ++p) {
    const double theta = thetas[static_cast<std::size_t>(p / n_tau)];
    const double tau = taus[static_cast<std::size_t>(p % n_tau)];
    const Coefficients proj = project(theta, tau);
    SKYLIGHT_CHECK(proj.bands >= s.bands, "fit_polynomial: the projection has too few bands");
    if (s.progress) s.progress(p + 1, gt * n_tau);
    for (int l = 0; l < s.bands; ++l) {
      for (int m = 0; m <= l; ++m) {
        for (int ch = 0; ch < 3; ++ch) {
          proj_all(p, (l * (l + 1) / 2 + m) * 3 + ch) =
              proj.c[static_cast<std::size_t>(index(l, m))][ch];
        }
      }
    }
  }
  return proj_all;
}

}  // namespace

PolynomialTable fit_polynomial(const PolynomialFitSettings& s, const GridProjection& project) {
  const auto [gt, gv] = checked_grid(s);
  const bool theta_only = s.parameter.empty();
  PolynomialTable table;
  table.parameter = s.parameter;
  table.channels = s.channels;
  table.bands = s.bands;
  table.degree_theta = s.degree_theta;
  table.degree_tau = s.degree_tau;
  table.theta_min = s.theta_min;
  table.theta_max = s.theta_max;
  table.tau_min = theta_only ? 0.0 : s.tau_min;
  table.tau_max = theta_only ? 0.0 : s.tau_max;
  table.theta_axis = s.theta_axis;
  table.tau_pieces = s.tau_pieces;
  const int terms = table.terms();
  const int stored = stored_count(s.bands);
  const int n_tau = gv == 1 ? 1 : s.tau_pieces * (gv - 1) + 1;
  const std::vector<double> thetas = theta_grid(s, gt), taus = tau_grid(s, n_tau);
  const Eigen::MatrixXd proj_all = grid_projections(s, project, thetas, taus);
  table.coefficients.resize(static_cast<std::size_t>(s.tau_pieces) *
                            static_cast<std::size_t>(stored) * 3 * static_cast<std::size_t>(terms));
  std::vector<double> ti(static_cast<std::size_t>(s.degree_theta + 1));
  std::vector<double> tj(static_cast<std::size_t>(s.degree_tau + 1));
  for (int piece = 0; piece < s.tau_pieces; ++piece) {
    const int q0 = s.tau_pieces == 1 ? 0 : piece * (gv - 1);
    const int nq = s.tau_pieces == 1 ? n_tau : gv;
    Eigen::MatrixXd a(gt * nq, terms);
    Eigen::MatrixXd b(gt * nq, stored * 3);
    for (int it = 0; it < gt; ++it) {
      chebyshev(s.degree_theta, theta_u(table, thetas[static_cast<std::size_t>(it)]), ti.data());
      for (int iq = 0; iq < nq; ++iq) {
        const int row = it * nq + iq;
        chebyshev(s.degree_tau, tau_v(table, taus[static_cast<std::size_t>(q0 + iq)], piece),
                  tj.data());
        for (int i = 0; i <= s.degree_theta; ++i) {
          for (int j = 0; j <= s.degree_tau; ++j) {
            a(row, i * (s.degree_tau + 1) + j) =
                ti[static_cast<std::size_t>(i)] * tj[static_cast<std::size_t>(j)];
          }
        }
        b.row(row) = proj_all.row(it * n_tau + q0 + iq);
      }
    }
    const Eigen::MatrixXd x = a.colPivHouseholderQr().solve(b);
    const std::size_t base = static_cast<std::size_t>(piece) * static_cast<std::size_t>(stored) *
                             3 * static_cast<std::size_t>(terms);
    for (int k = 0; k < stored * 3; ++k) {
      for (int t = 0; t < terms; ++t) {
        table.coefficients[base + static_cast<std::size_t>(k) * static_cast<std::size_t>(terms) +
                           static_cast<std::size_t>(t)] = static_cast<float>(x(t, k));
      }
    }
  }
  return table;
}

namespace {

// Checks the arguments of an evaluation (InvalidArgument) and the table's consistency.
void check_evaluation(const PolynomialTable& table, double theta, double tau, int bands) {
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
          table.degree_tau <= kMaxDegree && table.tau_pieces >= 1 &&
          table.tau_pieces <= kMaxTauPieces &&
          table.coefficients.size() ==
              static_cast<std::size_t>(table.tau_pieces) *
                  static_cast<std::size_t>(table.bands * (table.bands + 1) / 2 * 3 * table.terms()),
      "evaluate_table: degrees or coefficient count out of range");
}

// The product vector (T_i(u) T_j(v))_ij at index i (d_j + 1) + j, shared by every coefficient
// (Habel 2008 §3.1); on the stack, degrees are at most kMaxDegree (checked on fit and load).
using ProductVector = std::array<double, (kMaxDegree + 1) * (kMaxDegree + 1)>;
void product_vector(const PolynomialTable& table, double theta, double tau, ProductVector& prod) {
  std::array<double, kMaxDegree + 1> ti{}, tj{};
  chebyshev(table.degree_theta, theta_u(table, theta), ti.data());
  chebyshev(table.degree_tau, tau_v(table, tau, tau_piece(table, tau)), tj.data());
  for (int i = 0; i <= table.degree_theta; ++i) {
    for (int j = 0; j <= table.degree_tau; ++j) {
      prod[static_cast<std::size_t>(i * (table.degree_tau + 1) + j)] =
          ti[static_cast<std::size_t>(i)] * tj[static_cast<std::size_t>(j)];
    }
  }
}

// The coefficients of tau's piece.
const float* piece_coefficients(const PolynomialTable& table, double tau) {
  return table.coefficients.data() + static_cast<std::size_t>(tau_piece(table, tau)) *
                                         static_cast<std::size_t>(stored_count(table.bands)) * 3 *
                                         static_cast<std::size_t>(table.terms());
}

// sinc(pi l / N) of eq. 5 for every (l, N), N <= kMaxBands, at [N * kMaxBands + l] (once).
const std::array<double, (kMaxBands + 1) * kMaxBands>& ringing_factors() {
  static const auto factors = [] {
    std::array<double, (kMaxBands + 1) * kMaxBands> f{};
    for (int n = 1; n <= kMaxBands; ++n) {
      for (int l = 0; l < n; ++l)
        f[static_cast<std::size_t>(n * kMaxBands + l)] = ringing_factor(l, n);
    }
    return f;
  }();
  return factors;
}

}  // namespace

Coefficients evaluate_table(const PolynomialTable& table, double theta, double tau, double phi,
                            int bands, bool filter) {
  check_evaluation(table, theta, tau, bands);
  const int terms = table.terms();
  ProductVector prod;
  product_vector(table, theta, tau, prod);
  std::array<float, (kMaxDegree + 1) * (kMaxDegree + 1)> x;
  for (int t = 0; t < terms; ++t) {
    x[static_cast<std::size_t>(t)] = static_cast<float>(prod[static_cast<std::size_t>(t)]);
  }
  // Eq. 1 for the first `bands` bands: their rows come first in the table's layout.
  const int rows = stored_count(bands) * 3;
  std::array<float, kMaxBands*(kMaxBands + 1) / 2 * 3> c_fit;
  detail::dot_rows(piece_coefficients(table, tau), x.data(), static_cast<std::size_t>(rows),
                   static_cast<std::size_t>(terms), c_fit.data());
  // Eq. 5 on the zonal coefficients and eq. 4 fused: in the fitting frame c_l,-m = 0, so
  // c_lm(phi) = c_lm cos(m phi) and c_l,-m(phi) = c_lm sin(m phi).
  Coefficients c{bands, std::vector<Triple>(static_cast<std::size_t>(coefficient_count(bands)))};
  const double* f = ringing_factors().data() + bands * kMaxBands;
  for (int l = 0; l < bands; ++l) {
    const double s = filter ? f[l] : 1.0;
    const std::size_t k = static_cast<std::size_t>(l * (l + 1) / 2) * 3;
    for (int ch = 0; ch < 3; ++ch) {
      c.c[static_cast<std::size_t>(index(l, 0))][ch] = s * c_fit[k + static_cast<std::size_t>(ch)];
    }
  }
  const double c1 = std::cos(phi), s1 = std::sin(phi);
  double cm = 1.0, sm = 0.0;  // cos(m phi), sin(m phi) by angle addition, as in eq. 4's rotation
  for (int m = 1; m < bands; ++m) {
    const double cn = cm * c1 - sm * s1;
    sm = sm * c1 + cm * s1;
    cm = cn;
    for (int l = m; l < bands; ++l) {
      const std::size_t k = static_cast<std::size_t>(l * (l + 1) / 2 + m) * 3;
      Triple& pos = c.c[static_cast<std::size_t>(index(l, m))];
      Triple& neg = c.c[static_cast<std::size_t>(index(l, -m))];
      for (int ch = 0; ch < 3; ++ch) {
        const double v = c_fit[k + static_cast<std::size_t>(ch)];
        pos[ch] = v * cm;
        neg[ch] = v * sm;
      }
    }
  }
  return c;
}

Coefficients evaluate_table_reference(const PolynomialTable& table, double theta, double tau,
                                      double phi, int bands, bool filter) {
  check_evaluation(table, theta, tau, bands);
  const int terms = table.terms();
  ProductVector prod;
  product_vector(table, theta, tau, prod);
  Coefficients c{bands, std::vector<Triple>(static_cast<std::size_t>(coefficient_count(bands)))};
  for (int l = 0; l < bands; ++l) {
    for (int m = 0; m <= l; ++m) {
      for (int ch = 0; ch < 3; ++ch) {
        const float* p = piece_coefficients(table, tau) +
                         static_cast<std::size_t>((l * (l + 1) / 2 + m) * 3 + ch) *
                             static_cast<std::size_t>(terms);
        double sum = 0.0;
        for (int t = 0; t < terms; ++t) {
          sum += static_cast<double>(p[t]) * prod[static_cast<std::size_t>(t)];
        }
        c.c[static_cast<std::size_t>(index(l, m))][ch] = sum;
      }
    }
  }
  c = rotate_about_zenith(c, phi);
  return filter ? ringing_filter(c) : c;
}

}  // namespace skylight::sh
