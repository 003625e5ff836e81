// A Monte Carlo path tracer of the atmosphere of atmosphere.h: the radiance seen from a point in
// a direction, with every order of scattering (and of reflection by a Lambertian ground), per
// wavelength, in double precision, with standard errors. It is the reference that multiple
// scattering models are checked against, as single_scattering_reference checks nishita's tables;
// slow by design (docs/ATMOSPHERE.md).
//
// Paths are traced from the observer backwards, per wavelength:
//  * free paths by delta tracking (Woodcock): tentative collisions at the rate of the majorant
//    sum_i beta_e,i(lambda) (every density is <= 1), real with probability beta_e(y) / majorant;
//    the path's weight is multiplied by the single-scattering albedo beta_s(y) / beta_e(y) at each
//    real collision (absorption as a weight, not a termination);
//  * the next direction: a component chosen with probability beta_s,i / beta_s, its phase
//    function sampled exactly (Rayleigh by Cardano's formula, Henyey-Greenstein by inversion;
//    Cornette-Shanks as Henyey-Greenstein weighted by their ratio, 3 (1 + mu^2) / (2 (2 + g^2)));
//    at the ground a cosine-weighted direction (weight: the albedo).
// Two estimators of the sunlight reaching the path (the sun is a point source at infinity: the
// sampled paths never meet it, so no weighting between the two kinds of sampling is needed):
//  * segments (default): order 1 is single_scattering_reference (brute force, no noise); at every
//    later vertex the sun's single scattering along the whole next leg (and the ground's
//    reflection of it) is added by the fast path (Atmosphere::single_scattering, within 0.5 % of
//    the reference). No point of a leg is missed, so the planet's shadow (twilight) costs no
//    variance: what is sampled is only where the light scatters before its last leg.
//  * collisions: next-event estimation at each collision and ground hit, E0 T_sun(y) sum_i
//    beta_s,i(y) F_i(mu) / beta_s(y) and E0 T_sun (albedo / pi) max(0, n.sun), T_sun by Simpson
//    quadrature of each optical length (0 in the planet's shadow). No table anywhere: the
//    independent check of the segments estimator (path_tracer_test.cpp), noisy in twilight.
// The n-th vertex's estimate is the order-n radiance: order 1 is single scattering plus the
// ground's reflection of the direct sun. Orders beyond max_orders are not traced (a bias bounded
// by the last orders' values; the truncated fraction is reported).
#pragma once

#include <cstdint>
#include <vector>

#include "skylight/atmosphere/atmosphere.h"

namespace skylight::atmosphere {

enum class PathEstimator { segments, collisions };

struct PathTracerSettings {
  PathEstimator estimator = PathEstimator::segments;
  std::uint64_t paths = std::uint64_t{1} << 16;  // per wavelength
  int max_orders = 64;                           // events per path, 1 .. 1000
  std::uint64_t seed = 1;
  int sun_steps = 64;  // Simpson half-count per monotone piece of each sun ray (as the reference)
};

// Means and standard errors of the mean over the paths, per wavelength of the Spectral (in its
// solar irradiance's units per sr: W m^-2 sr^-1 nm^-1 for W m^-2 nm^-1).
struct PathTracerResult {
  std::vector<double> radiance, standard_error;
  // [order - 1][wavelength], orders 1 .. max_orders.
  std::vector<std::vector<double>> order_radiance, order_standard_error;
  // Paths that reached max_orders events (their higher orders are missing) [fraction].
  std::vector<double> truncated_fraction;
  std::uint64_t paths = 0;
};

// The radiance arriving at `position` (planet-centred [m], inside or above the atmosphere, not
// below the ground) from direction `view` (unit; toward where the light comes from, as
// single_scattering's view), the sun in direction `sun` (unit), the ground reflecting with
// p.ground_albedo (none: black). Paths are split into fixed chunks with their own seeds and run on
// the library's threads: the result depends on the seed and the settings only.
PathTracerResult path_trace(const AtmosphereParameters& p, Vec3 position, Vec3 view, Vec3 sun,
                            const Spectral& spec, const PathTracerSettings& settings = {});

// Exact sampling of the phase functions: mu = cos(scattering angle) for a uniform u in [0, 1).
double sample_rayleigh(double u);
double sample_henyey_greenstein(double u, double g);

}  // namespace skylight::atmosphere
