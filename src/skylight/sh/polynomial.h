// Habel, Mustata & Wimmer 2008 §3.1, eq. 1: each SH coefficient of a sky as a polynomial in the
// sun's zenith angle theta and a second model parameter tau (Preetham: turbidity),
//   c_lm(theta, tau) = sum_ij (p_lm)_ij theta^i tau^j,  i = 0..d_i, j = 0..d_j,
// fitted by least squares to converged projections on a dense (theta, tau) grid.
//
// The raw monomial basis is ill-conditioned (condition ~1e19 for (13, 7) on theta in [0, pi/2],
// tau in [2.5, 6]); the fit and the stored table use the same polynomial space in the orthogonal,
// scaled basis T_i(u) T_j(v): Chebyshev polynomials of u, v in [-1, 1], the parameters mapped
// linearly from their ranges. The sun is at azimuth 0 in the fitting frame, where the sky is even
// in phi: only the m >= 0 (cos m phi) coefficients are stored; eq. 4 rotates to any azimuth.
// docs/SH.md describes the table and its JSON form.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "skylight/core/parameters.h"

#include "skylight/sh/projection.h"

namespace skylight::sh {

// The sun-zenith coordinate of the Chebyshev basis in theta (docs/SH.md, "Hosek fits"):
//  * theta: theta itself (Habel's eq. 1);
//  * elevation_cbrt: w = (eta / (pi/2))^(1/3), eta = pi/2 - theta the solar elevation, the
//    coordinate in which Hosek & Wilkie 2012 (§5) store every coefficient as a quintic Bezier
//    curve (so their sky has an infinite slope in theta at the horizon, smooth in w).
enum class ThetaAxis { theta, elevation_cbrt };

// Largest number of tau pieces of a table.
inline constexpr int kMaxTauPieces = 64;

// The polynomial of eq. 1 and the grid it is fitted on; the projections at the grid points come
// from the caller (fit/sh_fit.h projects a sky model's).
struct PolynomialFitSettings {
  // tau: the name of the second varying parameter (recorded in the table); empty: theta only
  // (then degree_tau must be 0 and the tau range is ignored, e.g. a CIE type).
  std::string parameter = "turbidity";
  Channels channels = Channels::xyz;
  int bands = 7;  // N
  // (d_i, d_j): Habel's (13, 7) reaches a worst E_mean of ~0.16 % at 5 bands, limited by the
  // turbidity degree; (17, 12) reaches ~0.002 % (docs/SH.md, "Measured so far").
  int degree_theta = 17;                        // d_i
  int degree_tau = 12;                          // d_j
  double theta_min = 0.0, theta_max = kPi / 2;  // sun zenith [rad]
  double tau_min = 2.5, tau_max = 6.0;          // Habel 2008 §2.2
  ThetaAxis theta_axis = ThetaAxis::theta;
  // tau split into this many equal pieces, each with its own polynomial of degree d_j in tau
  // (Hosek & Wilkie 2012 interpolate linearly between integer turbidities: 9 pieces over [1, 10]
  // put the knots there); 1: one polynomial over the range (eq. 1).
  int tau_pieces = 1;
  int grid_theta = 0;  // grid points, uniform in the theta axis' coordinate; 0 = 2 (d_i + 1) + 1
  int grid_tau = 0;    // per piece, both ends included (shared); 0 = 2 (d_j + 1) + 1
  // Called after each grid point's projection with (done, total); may be empty.
  std::function<void(int, int)> progress;
};

// The fitted table: for each tau piece, stored (l, m >= 0) and channel, (d_i + 1)(d_j + 1)
// coefficients of T_i(u) T_j(v), in float (the fit is in double). u: the theta axis' coordinate
// mapped from its range onto [-1, 1]; v: tau mapped from its piece onto [-1, 1].
struct PolynomialTable {
  // What was fitted: a registry model's name, its tau parameter (empty: theta only) and the
  // parameters held fixed (fit/sh_fit.h fills them; sh/ only records them).
  std::string model, parameter;
  ParameterValues fixed;
  Channels channels = Channels::xyz;
  int bands = 0, degree_theta = 0, degree_tau = 0;
  double theta_min = 0.0, theta_max = 0.0, tau_min = 0.0, tau_max = 0.0;
  ThetaAxis theta_axis = ThetaAxis::theta;
  int tau_pieces = 1;
  // The ground albedo of the projections (ProjectionOptions::ground_albedo); absent: black.
  std::optional<double> ground_albedo;
  // [((piece * N (N + 1) / 2 + l (l + 1) / 2 + m) * 3 + channel) * terms + i * (d_j + 1) + j],
  // m = 0..l, N = bands
  std::vector<float> coefficients;

  int terms() const { return (degree_theta + 1) * (degree_tau + 1); }
  // Memory of `coefficients` [bytes].
  std::size_t bytes() const { return coefficients.size() * sizeof(float); }
};

// The SH coefficients (at least settings.bands bands, in settings.channels) of the function at
// (theta, tau), sun at azimuth 0.
using GridProjection = std::function<Coefficients(double theta, double tau)>;
// Calls `project` at each grid point and fits eq. 1 by least squares (Eigen, column-pivoting QR).
// Throws InvalidArgument for bad settings (degrees < 0, empty range, too few grid points). The
// table's model, fixed parameters and ground albedo are left for the caller to record.
PolynomialTable fit_polynomial(const PolynomialFitSettings& settings,
                               const GridProjection& project);

// Eq. 1 at (theta, tau), then eq. 4 (rotation to azimuth phi) and, if asked, eq. 5 (ringing
// filter for `bands` bands): the first `bands` <= table.bands bands. theta and tau outside the
// fitted ranges throw InvalidArgument.
// Fast path: the Chebyshev product vector in float, all stored coefficients as one float
// matrix-vector product (SIMD, sh/detail/evaluate_kernel.h), rotation and filter fused (the fitting
// frame's c_l,-m are zero). Within ~1e-6 of |c_00| of evaluate_table_reference
// (sh/polynomial_test.cpp), far below the fits' own error (docs/SH.md).
Coefficients evaluate_table(const PolynomialTable& table, double theta, double tau, double phi,
                            int bands, bool ringing_filter);
// Reference path: the same table, the sums in double, then rotate_about_zenith and
// ringing_filter (sh/rotation.h) as separate steps.
Coefficients evaluate_table_reference(const PolynomialTable& table, double theta, double tau,
                                      double phi, int bands, bool ringing_filter);

// The published monomial form of eq. 1, in double (export only; docs/SH.md), for tables in theta
// with one tau piece (InvalidArgument otherwise): for each stored
// coefficient in the table's layout, (d_i + 1)(d_j + 1) values p_ij of theta^i tau^j, theta in
// radians. The Chebyshev series is expanded exactly in long double; evaluating the monomials loses
// digits to cancellation (condition ~1e19 for (13, 7)), so this form is never evaluated here.
std::vector<double> monomial_coefficients(const PolynomialTable& table);

// The table as a C header: its description as comments and macros, the Chebyshev coefficients as
// a float array `<name>_chebyshev` in the table's layout and, with `monomial`, the published form
// as a double array `<name>_monomial`. `name` must be a C identifier.
std::string table_to_c_header(const PolynomialTable& table, const std::string& name, bool monomial);

// `skylight sh export`: the table as JSON, or as a C header (--c-header, --name, --monomial).
struct ExportOptions {
  bool c_header = false;
  std::string name = "skylight_sh_table";
  bool monomial = false;  // with c_header only (InvalidArgument otherwise)
  static const ParameterSchema<ExportOptions>& schema();
};
std::string export_table(const PolynomialTable& table, const ExportOptions& options);

// JSON form (docs/SH.md); load validates every field and throws InvalidArgument naming it.
std::string table_to_json(const PolynomialTable& table);
PolynomialTable table_from_json(const std::string& text, const std::string& where);

}  // namespace skylight::sh
