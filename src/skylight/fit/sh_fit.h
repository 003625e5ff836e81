// SH lighting of a sky model (Habel, Mustata & Wimmer 2008; docs/SH.md): the model projected onto
// SH (sh/projection.h does the quadrature of any function), the polynomial table of eq. 1 fitted
// to a registry model's projections (sh/polynomial.h does the least squares), and L_min of the
// error measures (sh/approximation_error.h). sh/ knows no SkyModel; this is where the two meet.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "skylight/core/parameters.h"
#include "skylight/models/preetham.h"
#include "skylight/models/sky_model.h"
#include "skylight/sh/polynomial.h"
#include "skylight/sh/projection.h"

namespace skylight::fit {

// The model's sky in one direction, in the chosen channels (tristimulus() or rgb()).
sh::Triple model_value(const SkyModel& model, sh::Channels channels, Vec3 d);

// The sky of `model` (the solar disc excluded) on the upper hemisphere; with
// options.ground_albedo the lower hemisphere is a uniform Lambertian ground lit by the sky and
// the sun (sh::add_uniform_ground), otherwise black.
sh::Projection project_model(const SkyModel& model, sh::Channels channels, int bands,
                             const sh::ProjectionOptions& options = {});

// The sun's horizontal irradiance: the solar disc's radiance (SkyModel::sun_tristimulus, in the
// chosen channels) integrated over the disc times cos theta (Gauss-Legendre in the cosine of the
// angle from the disc's centre x uniform azimuths); 0 for models without a sun.
sh::Triple sun_horizontal_irradiance(const SkyModel& model, sh::Channels channels);

// L_min of eqs. 2-3: the minimum of the model over the upper hemisphere, per channel, on the
// midpoint grid of analysis::hemisphere_grid(n_theta, 4 n_theta) (cells of (90 / n_theta) deg).
// Throws InvalidArgument if a channel's minimum is not positive (the measures are then undefined).
sh::Triple minimum_over_sky(const SkyModel& model, sh::Channels channels, int n_theta = 90);

// A table of eq. 1 fitted to a registry model: the model, its parameters held fixed (e.g. hosek's
// albedo, cie's type; the rest at their defaults), the polynomial and the projections.
struct ShFitSettings {
  std::string model = std::string(PreethamModel::kName);
  ParameterValues fixed;
  sh::PolynomialFitSettings polynomial{};
  sh::ProjectionOptions projection{};
};

// `skylight sh fit` as the user asks for it: the model and the options, absent ones taking the
// model's ShFitPolicy (its registry entry) or the defaults. sh_fit_settings() resolves them.
struct ShFitRequest {
  std::string model;
  int bands = 7;
  std::vector<double> degrees;  // (theta, tau); empty: the policy's or (17, 12)
  std::string parameter;        // empty: the policy's; "none": the sun zenith only
  std::vector<double> range;    // tau's LO,HI; empty: the policy's or the whole range
  std::vector<double> theta_range_deg{0.0, 90.0};
  std::vector<double> grid;      // points in theta, tau; empty: 2 (degree + 1) + 1
  std::vector<std::string> set;  // NAME=VALUE: model parameters held fixed
  sh::Channels channels = sh::Channels::xyz;
  double tolerance = sh::ProjectionOptions{}.tolerance;
  std::optional<sh::ThetaAxis> theta_axis;  // absent: the policy's
  std::optional<int> tau_pieces;            // absent: the policy's (1 without one)
  std::optional<double> ground_albedo;      // absent: the lower hemisphere black

  static const ParameterSchema<ShFitRequest>& schema();
};

// The fit's settings: the request over the model's ShFitPolicy (InvalidArgument naming the option
// for an unknown model, one without a policy, a parameter that is not a number of its schema, an
// empty range, degrees or pieces the fit cannot take).
ShFitSettings sh_fit_settings(const ShFitRequest& request);

// Projects the model at each grid point (sun at azimuth 0) and fits; the table records the model,
// the fixed parameters and the ground albedo. Throws InvalidArgument for an unknown model or
// parameter, a parameter both varied and fixed, and the settings sh::fit_polynomial refuses.
sh::PolynomialTable fit_sh_table(const ShFitSettings& settings);

// The converged projection of the table's model at (theta, tau), sun at azimuth phi, with the
// table's ground albedo (overriding options.ground_albedo): the reference that
// sh::evaluate_table approximates.
sh::Projection project_reference(const sh::PolynomialTable& table, double theta, double tau,
                                 double phi, int bands, const sh::ProjectionOptions& options = {});

// Habel 2008 §3.2, Fig. 3 (`skylight sh error`): E_max (eq. 2) and E_mean (eq. 3) of a table
// against converged projections of its model at the cell midpoints of a (theta, tau) grid over
// the fitted range and (unless midpoints_only) at the range's ends (points[1] ignored for a table
// in theta only), per band count N and channel; the worst (and where) and the median over the
// points [fractions].
struct ShErrorOptions {
  std::vector<double> points{10.0, 7.0};
  // Also the ends of each range (sun at the range's first and last zenith, the first and last
  // tau): where the fits are worst (docs/SH.md); false: the cell midpoints only (Habel's Fig. 3).
  bool midpoints_only = false;
  static const ParameterSchema<ShErrorOptions>& schema();
};
struct ShErrorRow {
  int bands = 0, channel = 0;
  double e_mean_worst = 0, e_mean_median = 0, e_max_worst = 0, e_max_median = 0;
  double worst_theta = 0, worst_tau = 0;  // where E_mean is worst [rad], [tau's unit]
};
struct ShTableError {
  int points = 0;
  std::vector<ShErrorRow> rows;  // N = 1..bands, channels 0..2 within each
};
// progress(done, total) after each point (may be empty).
ShTableError table_error(const sh::PolynomialTable& table, const ShErrorOptions& options,
                         const std::function<void(int, int)>& progress = {});

}  // namespace skylight::fit
