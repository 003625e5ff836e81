// SH lighting of a sky model (Habel, Mustata & Wimmer 2008; docs/SH.md): the model projected onto
// SH (sh/projection.h does the quadrature of any function), the polynomial table of eq. 1 fitted
// to a registry model's projections (sh/polynomial.h does the least squares), and L_min of the
// error measures (sh/approximation_error.h). sh/ knows no SkyModel; this is where the two meet.
#pragma once

#include <string>

#include "skylight/core/parameters.h"
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
  std::string model = "preetham";
  ParameterValues fixed;
  sh::PolynomialFitSettings polynomial{};
  sh::ProjectionOptions projection{};
};

// Projects the model at each grid point (sun at azimuth 0) and fits; the table records the model,
// the fixed parameters and the ground albedo. Throws InvalidArgument for an unknown model or
// parameter, a parameter both varied and fixed, and the settings sh::fit_polynomial refuses.
sh::PolynomialTable fit_sh_table(const ShFitSettings& settings);

// The converged projection of the table's model at (theta, tau), sun at azimuth phi, with the
// table's ground albedo (overriding options.ground_albedo): the reference that
// sh::evaluate_table approximates.
sh::Projection project_reference(const sh::PolynomialTable& table, double theta, double tau,
                                 double phi, int bands, const sh::ProjectionOptions& options = {});

}  // namespace skylight::fit
