// Brute-force reference of the single-scattering integral (atmosphere.h), used by the tests to
// check the table-driven fast path (docs/ARCHITECTURE.md, "Testing"). Same equations, no tables:
//  * the view ray is cut at its lowest point and at the planet-shadow boundaries
//    (split_view_ray), every piece - lit or not - is sampled at rs.view_nodes + 1 nodes
//    s = anchor +- L u^2, u uniform;
//  * the optical length from the start of the ray to each node is the running trapezoidal
//    integral of rho over those nodes (the actual ray, in double precision);
//  * the optical length from each node to the sun is optical_length_quadrature along the actual
//    sun ray (Simpson, 2 rs.sun_steps intervals per monotone piece);
//  * the outer integral is the trapezoidal rule over the nodes of each lit piece.
#include <algorithm>
#include <cmath>
#include <vector>

#include "skylight/atmosphere/atmosphere.h"
#include "skylight/core/error.h"

namespace skylight::atmosphere {

void Atmosphere::single_scattering_reference(Vec3 p, Vec3 view, Vec3 sun, const Spectral& spec,
                                             std::span<double> out, const ReferenceSettings& rs,
                                             double max_distance) const {
  const std::size_t nl = spec.nm.size(), nc = params_.components.size();
  SKYLIGHT_CHECK(out.size() == nl, "single_scattering_reference: output size");
  SKYLIGHT_CHECK(rs.view_nodes >= 1 && rs.sun_steps >= 1, "bad ReferenceSettings");
  std::fill(out.begin(), out.end(), 0.0);
  const double R0 = params_.ground_radius_m, Rt = params_.top_radius_m;
  const ViewRay ray = split_view_ray(p, view, sun, R0, Rt, max_distance, kink_radii_);
  // An empty ray that ends on the ground (observer on it, looking down) still reflects.
  if (ray.count == 0 && !ray.hits_ground) return;

  std::vector<double> t_view(nc, 0.0);  // running optical length from the ray start
  std::vector<double> acc(nc * nl, 0.0);
  std::vector<double> prev_rho(nc), rho(nc), f_prev(nc * nl), f(nc * nl);
  const int m = rs.view_nodes;
  for (int pi = 0; pi < ray.count; ++pi) {
    const RayPiece& piece = ray.pieces[pi];
    const double len = piece.b - piece.a;
    double prev_s = 0.0;
    for (int k = 0; k <= m; ++k) {
      // Nodes in increasing s whichever end is the anchor.
      const double u =
          piece.anchor_at_a ? static_cast<double>(k) / m : static_cast<double>(m - k) / m;
      const double s = piece.anchor_at_a ? piece.a + len * u * u : piece.b - len * u * u;
      const Vec3 q = p + s * view;
      const double r = length(q);
      for (std::size_t i = 0; i < nc; ++i) rho[i] = params_.components[i].density(r - R0);
      if (k > 0)
        for (std::size_t i = 0; i < nc; ++i)
          t_view[i] += 0.5 * (rho[i] + prev_rho[i]) * (s - prev_s);
      // Integrand rho_i exp(-sum_j beta_e,j (t_view,j + t_sun,j)) of this node (0 if unlit).
      std::fill(f.begin(), f.end(), 0.0);
      if (piece.lit) {
        const double mu_s = dot(q, sun) / r;
        std::vector<double> t_sun(nc);
        bool shadow = false;
        for (std::size_t i = 0; i < nc; ++i) {
          t_sun[i] =
              optical_length_quadrature(r, mu_s, params_.components[i], R0, Rt, rs.sun_steps);
          if (!std::isfinite(t_sun[i])) shadow = true;  // grazing the ground at a boundary node
        }
        if (!shadow)
          for (std::size_t l = 0; l < nl; ++l) {
            double tau = 0.0;
            for (std::size_t i = 0; i < nc; ++i)
              tau += spec.extinction[i][l] * (t_view[i] + t_sun[i]);
            const double T = std::exp(-tau);
            for (std::size_t i = 0; i < nc; ++i) f[i * nl + l] = rho[i] * T;
          }
      }
      if (k > 0 && piece.lit)
        for (std::size_t j = 0; j < nc * nl; ++j) acc[j] += 0.5 * (f[j] + f_prev[j]) * (s - prev_s);
      prev_s = s;
      prev_rho = rho;
      f_prev = f;
    }
  }
  const double mu = dot(view, sun);
  for (std::size_t i = 0; i < nc; ++i) {
    const double ph = phase(params_.components[i], mu);
    for (std::size_t l = 0; l < nl; ++l)
      out[l] += spec.solar[l] * spec.scattering[i][l] * ph * acc[i * nl + l];
  }
  if (params_.ground_albedo && ray.hits_ground && ray.end < max_distance) {
    // Reflected direct sunlight, with both transmittances by direct quadrature.
    const Vec3 g = p + ray.end * view;
    const double mu_s = dot(g, sun) / length(g);
    if (mu_s > 0)
      for (std::size_t l = 0; l < nl; ++l) {
        double tau = 0.0;
        for (std::size_t i = 0; i < nc; ++i)
          tau += spec.extinction[i][l] *
                 (t_view[i] +
                  optical_length_quadrature(R0, mu_s, params_.components[i], R0, Rt, rs.sun_steps));
        out[l] += *params_.ground_albedo * spec.solar[l] / kPi * mu_s * std::exp(-tau);
      }
  }
}

}  // namespace skylight::atmosphere
