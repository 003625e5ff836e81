// The `bruneton` sky model: precomputed multiple scattering after Bruneton & Neyret 2008 and
// Bruneton 2017 ("A Qualitative and Quantitative Evaluation of 8 Clear Sky Models", and its
// reference implementation): the scattering orders computed one after the other on tables over
// (altitude, sun cosine, view cosine, view azimuth from the sun's), in `nishita`'s atmosphere
// (atmosphere.h) with `nishita`'s parameters and `--scattering-orders N`.
//
// With L_n the radiance of order n (n events: scatterings or ground reflections) and E_n the
// irradiance of the ground by L_n (Bruneton & Neyret 2008 eqs. 4-7):
//   L_1            = nishita's single scattering with the ground's reflection of the direct sun;
//   J_n(y, w)      = sum_c beta_s,c(lambda) rho_c(y) integral over the sphere of
//                    p_c(w . w') L_{n-1}(y, w') dw'                    (the scattering density)
//   L_n(x, w)      = integral along the ray of T(x, y) J_n(y, w) ds
//                    + T(x, g) (albedo / pi) E_{n-1}(g)             (g: where the ray meets the
//                                                                      ground, if it does)
//   E_n(g)         = integral over the upper hemisphere of L_n(g, w') cos(w') dw'.
// The view sees L_1 (exactly, as nishita) plus L_2 + ... + L_N: the ray integral of
// J_2 + ... + J_N and the ground's reflection of E_1 + ... + E_{N-1}.
//
// Where this differs from Bruneton 2017 (docs/ATMOSPHERE.md): the single scattering is not read
// from a table but integrated along each view ray (nishita's fast path, within 0.2 % of the brute
// force): tables hold only the smooth orders >= 2; the tables hold the phase integral per
// scattering component without its density, sum_n integral p_c L_{n-1} dw' (J = sum_c beta_c rho_c
// Q_c), so that altitude interpolates a smooth function; the sphere integral is a product
// integration (each cell's phase integral from 3 x 3 sub-samples, rows normalised to 1, so the
// Mie peak conserves energy) on the table's own directions, whose view cosines are split at the
// horizon as Bruneton's; the view ray's orders >= 2 are held in the sky-view LUT of
// physical_sky.h (Hillaire 2020), not in a 4D table lookup per pixel.
#pragma once

#include <memory>
#include <vector>

#include "skylight/models/physical_sky.h"

namespace skylight {

// Table nodes: altitudes (h = H (i / (n - 1))^2: dense at the ground) x sun cosines
// (mu_s = sign(w) w^2, w uniform on [-1, 1]: dense at the horizon) x directions: view cosines
// (half below, half above the horizon of the node's altitude, each half's cells dense at the
// horizon) x azimuths from the sun's (cells on [0, pi]; the radiance is symmetric about the sun's
// vertical plane).
inline constexpr int kBrunetonAltitudes = 12;
inline constexpr int kBrunetonSunCosines = 40;
inline constexpr int kBrunetonViewCosines = 32;
inline constexpr int kBrunetonAzimuths = 12;
// Trapezoid intervals per piece of a table node's ray (u^2-spaced toward its lower end).
inline constexpr int kBrunetonRayNodes = 8;
// Sub-samples per axis of each cell in the phase integrals.
inline constexpr int kBrunetonPhaseSubsamples = 3;
inline constexpr int kMaxScatteringOrders = 10;

// `nishita`'s parameters, with the ozone layer on by default (Earth's 300 DU), and the number of
// scattering orders.
struct BrunetonParameters : NishitaParameters {
  int scattering_orders = 4;
  BrunetonParameters() { ozone_du = atmosphere::kEarthOzoneColumn; }
  static const ParameterSchema<BrunetonParameters>& schema();
};

// The precomputed tables of one atmosphere and number of orders, per unit extraterrestrial
// irradiance at the tables' wavelengths (PhysicalSkyModel::lut_wavelengths()).
struct BrunetonTables {
  // Indices of the scattering components (those with beta_s > 0) and, per one of them,
  // Q_c = sum_{n=2..N} integral p_c L_{n-1} dw' at the nodes, [altitude][direction][sun
  // cosine][wavelength] [sr^-1 per unit irradiance].
  std::vector<std::size_t> components;
  std::vector<std::vector<float>> q;
  // E_1 + ... + E_{N-1} at the ground, [sun cosine][wavelength] [per unit irradiance].
  std::vector<double> ground_irradiance;
  std::size_t wavelengths = 0;
  double cpu_seconds = 0.0;  // the precomputation's (all threads)
};

// The tables of an atmosphere and number of orders (>= 2) at the wavelengths lut_nm: read from
// the file cache when SKYLIGHT_TABLE_CACHE names a directory that holds them (io/table_cache.h),
// else computed with the library's threads, reporting each order (core/progress.h), and stored
// there. The models share them in memory per atmosphere besides.
BrunetonTables load_or_compute_tables(const atmosphere::Atmosphere& atm,
                                      const std::vector<double>& lut_nm, int orders);

class BrunetonModel final : public PhysicalSkyModel {
 public:
  explicit BrunetonModel(const BrunetonParameters& params);
  static constexpr std::string_view kName = "bruneton";
  static ModelInfo registry_entry();

  std::string_view name() const override { return kName; }
  ParameterValues parameter_values() const override;
  Domain domain() const override;

  // Orders 2 .. N along the view ray: the ray integral of T (J_2 + ... + J_N) and the ground's
  // reflection of E_1 + ... + E_{N-1} (0 for N = 1).
  void multiple_scattering(Vec3 view, const atmosphere::Spectral& spec,
                           const std::vector<LutWeight>& weights,
                           std::span<double> out) const override;
  // The tables (null for --scattering-orders 1).
  const BrunetonTables* tables() const { return tables_.get(); }

 private:
  BrunetonParameters params_;
  std::shared_ptr<const BrunetonTables> tables_;
};

}  // namespace skylight
