// Projection of a sky onto real SH by quadrature refined until converged (Habel, Mustata & Wimmer
// 2008 §3.1: "calculated by sampling until the result converges", the model as a black box).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "skylight/core/frame.h"

namespace skylight::sh {

// Which three channels a set of coefficients holds (docs/SH.md): CIE 1931 XYZ, or linear sRGB
// (D65); a sky's on its photometric scale [cd/m^2] (fit/sh_fit.h projects a model's).
enum class Channels { xyz, linear_srgb };

using Triple = std::array<double, 3>;

// SH coefficients of a three-channel function: c[index(l, m)][channel], bands^2 entries.
struct Coefficients {
  int bands = 0;
  std::vector<Triple> c;
};

// The domain integrated over: the upper hemisphere (the sky; the lower hemisphere is black), or
// the whole sphere (for functions defined everywhere, e.g. an SH reconstruction).
enum class Region { upper_hemisphere, full_sphere };

struct ProjectionOptions {
  Region region = Region::upper_hemisphere;
  // Refinement stops when no coefficient changes by more than tolerance * max(|c_00|, tiny) of its
  // channel between two successive node counts.
  // The sky's kink at the sun (exp(D gamma) in gamma = |angle to the sun|) makes the product rule
  // converge as ~n^-3 (the change shrinks ~8x per doubling, docs/SH.md): 1e-6 is reached at
  // n = 256 (~0.1 s for 8 bands on one core), leaving ~1.5e-7 to the limit.
  double tolerance = 1e-6;
  int min_nodes = 16;    // Gauss-Legendre nodes in cos theta at the start (2x as many in phi)
  int max_nodes = 1024;  // refinement gives up beyond this (converged = false)
  // fit::project_model only: the lower hemisphere as a uniform Lambertian ground of albedo rho,
  // lit by the sky's own horizontal irradiance and the sun's: L_ground = rho (E_sky + E_sun) / pi
  // per channel (docs/SH.md, "Ground"); absent: the lower hemisphere is black.
  std::optional<double> ground_albedo;
};

struct Projection {
  Coefficients coefficients;
  int nodes = 0;             // Gauss-Legendre nodes in cos theta of the accepted result
  double last_change = 0.0;  // largest relative change at the last doubling
  bool converged = false;
};

// Gauss-Legendre nodes and weights on [a, b] (Newton on P_n; weights 2 / ((1 - x^2) P_n'(x)^2)).
void gauss_legendre(int n, double a, double b, std::vector<double>& nodes,
                    std::vector<double>& weights);

// c_lm = integral f(omega) Y_lm(omega) d omega over the domain, by the product rule: n
// Gauss-Legendre nodes in mu = cos theta (on [0, 1] or [-1, 1]) times 2n (4n for the full sphere)
// equally spaced azimuths (exact for trigonometric polynomials of degree < 2n); n doubles from
// min_nodes until converged. f is evaluated on all threads; the sums are reduced in a fixed order
// (deterministic).
Projection project(const std::function<Triple(Vec3)>& f, int bands,
                   const ProjectionOptions& options = {});
// The horizontal irradiance of the upper-hemisphere signal whose SH projection (lower hemisphere
// black) is c: E = integral_upper f cos theta d omega = sqrt(4 pi / 3) c_10 exactly (cos theta =
// sqrt(4 pi / 3) Y_10 is band-limited), per channel. Needs c.bands >= 2.
Triple horizontal_irradiance(const Coefficients& c);
// Adds a uniform radiance on the lower hemisphere: c_l0 += L 2 pi K_l0 integral_-1^0 P_l(mu) d mu
// (Gauss-Legendre, exact for the degree-l polynomial); the other coefficients are unchanged.
void add_uniform_ground(Coefficients& c, const Triple& radiance);

}  // namespace skylight::sh
