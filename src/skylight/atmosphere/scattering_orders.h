// The scattering orders of an atmosphere precomputed one after the other, after Bruneton & Neyret
// 2008 and Bruneton 2017 ("A Qualitative and Quantitative Evaluation of 8 Clear Sky Models", and
// its reference implementation), on tables over (altitude, sun cosine, view cosine, view azimuth
// from the sun's); the engine of the `bruneton` sky model (models/bruneton.h), which adds them to
// nishita's single scattering.
//
// With L_n the radiance of order n (n events: scatterings or ground reflections) and E_n the
// irradiance of the ground by L_n (Bruneton & Neyret 2008 eqs. 4-7):
//   L_1            = the single scattering with the ground's reflection of the direct sun;
//   J_n(y, w)      = sum_c beta_s,c(lambda) rho_c(y) integral over the sphere of
//                    p_c(w . w') L_{n-1}(y, w') dw'                    (the scattering density)
//   L_n(x, w)      = integral along the ray of T(x, y) J_n(y, w) ds
//                    + T(x, g) (albedo / pi) E_{n-1}(g)             (g: where the ray meets the
//                                                                      ground, if it does)
//   E_n(g)         = integral over the upper hemisphere of L_n(g, w') cos(w') dw'.
// A view sees L_2 + ... + L_N as the ray integral of J_2 + ... + J_N and the ground's reflection
// of E_1 + ... + E_{N-1} (orders_along_ray).
//
// Where this differs from Bruneton 2017 (docs/ATMOSPHERE.md): the tables hold only the smooth
// orders >= 2 (the single scattering is integrated along each view ray by the model); they hold
// the phase integral per scattering component without its density, sum_n integral p_c L_{n-1} dw'
// (J = sum_c beta_c rho_c Q_c), so that altitude interpolates a smooth function; the sphere
// integral is a product integration (each cell's phase integral from 3 x 3 sub-samples, rows
// normalised to 1, so the Mie peak conserves energy) on the table's own directions, whose view
// cosines are split at the horizon as Bruneton's.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "skylight/atmosphere/ray.h"

namespace skylight::atmosphere {

// Table nodes: altitudes (h = H (i / (n - 1))^2: dense at the ground) x sun cosines
// (mu_s = sign(w) w^2, w uniform on [-1, 1]: dense at the horizon) x directions: view cosines
// (half below, half above the horizon of the node's altitude, each half's cells dense at the
// horizon) x azimuths from the sun's (cells on [0, pi]; the radiance is symmetric about the sun's
// vertical plane).
inline constexpr int kOrderTableAltitudes = 12;
inline constexpr int kOrderTableSunCosines = 40;
inline constexpr int kOrderTableViewCosines = 32;
inline constexpr int kOrderTableAzimuths = 12;
// Trapezoid intervals per piece of a table node's ray (u^2-spaced toward its lower end).
inline constexpr int kOrderTableRayNodes = 8;
// Sub-samples per axis of each cell in the phase integrals.
inline constexpr int kOrderTablePhaseSubsamples = 3;

// The orders the tables hold: `computed` orders one after the other and, with `remainder`, the
// orders above them estimated at every table node (and for the ground's irradiance) as a
// geometric series whose ratio is that node's last two orders: J_{N+1} + J_{N+2} + ... =
// J_N r / (1 - r), r = J_N / J_{N-1} (at most kMaxRemainderRatio). Multiple scattering converges
// geometrically (each order is the last one scattered once more, so the ratio tends to a constant
// per node); Bruneton 2017 truncates at N instead, which leaves up to 4.3 % of the radiance out at
// 440 nm over a ground of albedo 0.3 with N = 4 (docs/ATMOSPHERE.md, "Scattering orders": measured
// by `skylight_atmosphere_error truncation` from the path tracer's radiance by order).
struct OrderSettings {
  int computed = 6;
  bool remainder = true;
  // Exactly n orders, the rest left out (Bruneton 2017's truncation; --scattering-orders n).
  static OrderSettings exactly(int n) { return {n, false}; }
  // "6 orders and the geometric remainder", "4 orders".
  std::string text() const;
};
// The default: 6 orders and the remainder. Against the path tracer's orders (issue 45's set: 440,
// 550, 680 nm; observers 0-100 km; albedo 0 and 0.3; ozone 0 and 300 DU; sun 10-60 deg) the
// remainder estimated from orders 5 and 6 misses at most 0.06 % of the radiance where 6 orders
// alone miss 0.71 % and 4 orders 4.3 %; the tables take 6 orders' time (about 6 s on 2 cores).
inline constexpr OrderSettings kConvergedOrders{6, true};
// The largest ratio of two orders used for the remainder (r / (1 - r) <= 9): a node where an
// order is not smaller than the last (a node the light barely reaches) adds at most 9 times it.
inline constexpr double kMaxRemainderRatio = 0.9;

// The precomputed tables of one atmosphere and its orders, per unit extraterrestrial irradiance
// at the tables' wavelengths.
struct ScatteringOrderTables {
  // Indices of the scattering components (those with beta_s > 0) and, per one of them,
  // Q_c = sum_{n=2..N} integral p_c L_{n-1} dw' (with the remainder, and its estimate above N) at
  // the nodes, [altitude][direction][sun cosine][wavelength] [sr^-1 per unit irradiance].
  std::vector<std::size_t> components;
  std::vector<std::vector<float>> q;
  // E_1 + ... + E_{N-1} (and its remainder) at the ground, [sun cosine][wavelength] [per unit
  // irradiance].
  std::vector<double> ground_irradiance;
  std::size_t wavelengths = 0;
  double cpu_seconds = 0.0;  // the precomputation's (all threads)
};

// The tables of an atmosphere and orders (>= 2 computed) at the wavelengths `nm`: read from the
// file cache when SKYLIGHT_TABLE_CACHE names a directory that holds them (io/table_cache.h), else
// computed with the library's threads, reporting each order (core/progress.h), and stored there.
ScatteringOrderTables load_or_compute_order_tables(const Atmosphere& atm,
                                                   const std::vector<double>& nm,
                                                   OrderSettings orders);
// The same, shared in memory by every caller of the process (the last 8 atmospheres: a model
// rebuilt for another sun or observer reuses its planet's tables).
std::shared_ptr<const ScatteringOrderTables> shared_order_tables(const Atmosphere& atm,
                                                                 const std::vector<double>& nm,
                                                                 OrderSettings orders);
// What the tables depend on besides their wavelengths: the atmosphere's key and the orders.
std::string order_tables_key(const Atmosphere& atm, OrderSettings orders);

// The radiance of the orders 2 .. N seen from `x` along `view` with the sun in direction `sun`:
// the ray integral (`ray_nodes_per_piece` trapezoid intervals per piece, ray.h) of
// T (J_2 + ... + J_N) and the ground's reflection of E_1 + ... + E_{N-1}, at each wavelength of
// `spec` times its solar irradiance. The tables' wavelengths are `spec`'s (weights null) or each
// of `spec`'s lies among them at `weights`.
void orders_along_ray(const ScatteringOrderTables& tables, const Atmosphere& atm, Vec3 x, Vec3 view,
                      Vec3 sun, int ray_nodes_per_piece, const Spectral& spec,
                      const std::vector<WavelengthWeight>* weights, std::span<double> out);

}  // namespace skylight::atmosphere
