// What the precomputed multiple-scattering models integrate along rays and key their tables by,
// shared by `hillaire`, `bruneton` (models/) and the orders' tables
// (atmosphere/scattering_orders.h): the trapezoid nodes of a ray through the atmosphere with the
// densities and optical lengths at each, the transmittance and scattering coefficients there, a
// wavelength's place among a table's wavelengths, and an atmosphere's exact key with a small cache
// of tables per key. No sky model.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "skylight/atmosphere/atmosphere.h"

namespace skylight::atmosphere {

// Every field of an atmosphere that a precomputed table depends on, exactly (hex floats): the
// tables are per unit irradiance and independent of the sun and the observer.
std::string atmosphere_key(const AtmosphereParameters& a);

// The tables of the last `Entries` keys, the most recently used kept (a new sun or observer reuses
// its planet's tables: the report's and the sweeps' many suns; a model rebuilt for the same sun
// reuses its sky-view LUT). Thread-safe; two threads computing the same key keep one.
template <class T, std::size_t Entries = 8>
class AtmosphereTableCache {
 public:
  using Table = std::shared_ptr<const T>;
  template <class Build>
  Table get(const std::string& key, const Build& build) {
    {
      const std::lock_guard lock(mutex_);
      for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (it->first == key) {
          std::rotate(entries_.begin(), it, it + 1);
          return entries_.front().second;
        }
    }
    Table table = std::make_shared<const T>(build());
    const std::lock_guard lock(mutex_);
    entries_.insert(entries_.begin(), {key, table});
    if (entries_.size() > Entries) entries_.pop_back();
    return table;
  }

 private:
  std::mutex mutex_;
  std::vector<std::pair<std::string, Table>> entries_;
};

// The piece-wise trapezoid nodes of the ray p + s v inside the atmosphere (up to the ground or
// the top), `m` per piece u^2-spaced toward its lower end; calls node(s, weight, rho, t) with the
// components' densities rho at the node and their optical lengths t from p to it (the trapezoid
// rule over the same nodes). Returns whether the ray ends on the ground (its last node there).
using Densities = std::array<double, kMaxComponents>;
template <class F>
bool ray_nodes(const Atmosphere& atm, Vec3 p, Vec3 v, Vec3 sun, int m, F&& node) {
  const AtmosphereParameters& a = atm.parameters();
  const std::size_t nc = a.components.size();
  const ViewRay ray = split_view_ray(p, v, sun, a.ground_radius_m, a.top_radius_m,
                                     std::numeric_limits<double>::infinity(), atm.kink_radii());
  Densities rho{}, prev_rho{}, t{};
  double prev_s = ray.count > 0 ? ray.pieces[0].a : 0.0;
  bool first = true;
  for (int pi = 0; pi < ray.count; ++pi) {
    const RayPiece& piece = ray.pieces[pi];
    const double len = piece.b - piece.a;
    if (len <= 0) continue;
    for (int k = 0; k <= m; ++k) {
      // Nodes in increasing s whichever end is the anchor.
      const double u =
          piece.anchor_at_a ? static_cast<double>(k) / m : static_cast<double>(m - k) / m;
      const double s = piece.anchor_at_a ? piece.a + len * u * u : piece.b - len * u * u;
      const double ua = piece.anchor_at_a ? static_cast<double>(std::min(k + 1, m)) / m
                                          : static_cast<double>(std::max(m - k - 1, 0)) / m;
      const double ub = piece.anchor_at_a ? static_cast<double>(std::max(k - 1, 0)) / m
                                          : static_cast<double>(std::min(m - k + 1, m)) / m;
      // Trapezoid weight: half the spacing to the two neighbours within the piece.
      const double w = 0.5 * len * std::abs(ua * ua - ub * ub);
      const double h = length(p + s * v) - a.ground_radius_m;
      for (std::size_t i = 0; i < nc; ++i) rho[i] = a.components[i].density(h);
      if (!first)
        for (std::size_t i = 0; i < nc; ++i) t[i] += 0.5 * (rho[i] + prev_rho[i]) * (s - prev_s);
      first = false;
      node(s, w, rho, t);
      prev_rho = rho;
      prev_s = s;
    }
  }
  return ray.hits_ground;
}

// exp(-sum_i beta_e,i t_i) for every wavelength of `spec`.
void transmittance_of(const Spectral& spec, std::size_t components, const Densities& t,
                      std::span<double> out);
// sigma_s of every wavelength of `spec` for the densities rho.
void scattering_of(const Spectral& spec, std::size_t components, const Densities& rho,
                   std::span<double> out);

// Where a wavelength lies among a table's ascending wavelengths: v = (1 - t) v[k0] + t v[k1]
// (the end values outside them).
struct WavelengthWeight {
  std::size_t k0 = 0, k1 = 0;
  double t = 0.0;
};
WavelengthWeight wavelength_weight(const std::vector<double>& table_nm, double nm);

}  // namespace skylight::atmosphere
