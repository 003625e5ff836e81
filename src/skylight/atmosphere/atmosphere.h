// Single scattering in a spherical planet's exponential atmosphere (Nishita et al. 1993), with the
// optical-length lookup tables of Pietras ("GPU-based multi-layer perceptron as efficient method
// for approximation complex light models in per-vertex lighting", §II-III), and a brute-force
// double-precision reference of the same equations (reference.cpp).
//
// Geometry: planet-centred Cartesian coordinates [m]. An observer at altitude h stands at
// (0, 0, R0 + h), so the ENU frame of core/frame.h is the planet frame there (z = local up).
// All directions are unit vectors. Sun at infinity, direction `sun` (towards the sun).
//
// The model (Pietras eq. 1, per wavelength lambda, per unit extraterrestrial irradiance I0):
//   I(lambda) = I0(lambda) * sum_i beta_s,i(lambda) F_i(mu) * integral over the view ray of
//               rho_i(s) exp(-sum_j beta_e,j(lambda) (t_j(P0 -> s) + t_j(s -> sun))) ds
// rho_i = exp(-h / H_i) (Pietras eq. 3; or a tent profile, parameters.h), t_j = integral of rho_j
// along a path [m] (the optical length, "amount of air"), mu = dot(view, sun) (cosine of the
// scattering angle), F_i the phase function [sr^-1]. Samples whose sun ray hits the planet are in
// its shadow and contribute 0 (Pietras §III). Units: beta [m^-1], F [sr^-1], ds [m] -> I [I0 units
// sr^-1], i.e. W m^-2 sr^-1 nm^-1 for I0 in W m^-2 nm^-1.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "skylight/atmosphere/parameters.h"
#include "skylight/core/frame.h"

namespace skylight::atmosphere {

namespace detail {
struct KernelTable;
}  // namespace detail

// ---- phase functions [sr^-1], mu = cos(scattering angle) ----------------------------------------
double phase_rayleigh(double mu);                     // 3/(16 pi) (1 + mu^2)
double phase_henyey_greenstein(double mu, double g);  // (1-g^2)/(4 pi (1+g^2-2g mu)^{3/2})
double phase_cornette_shanks(double mu, double g);    // Cornette & Shanks 1992, eq. in parameters.h
double phase(const Component& c, double mu);

// ---- geometry -----------------------------------------------------------------------------------

// Distance along the ray p + s d (|d| = 1) to the far / near intersection with the sphere of
// radius `radius` centred at the origin; nullopt-like -1 when the line misses it.
double ray_sphere_far(Vec3 p, Vec3 d, double radius);
double ray_sphere_near(Vec3 p, Vec3 d, double radius);

// A sub-interval [a, b] of a view ray, traversed with samples concentrated at its lower end
// (`anchor_at_a`: the end with the lower altitude), and whether it is lit by the sun.
struct RayPiece {
  double a = 0, b = 0;
  bool anchor_at_a = true;
  bool lit = true;
};
// The part of the ray p + s d, s in [0, max_distance], inside the atmosphere and above the ground,
// split at the point of lowest altitude, at the boundaries of the planet's shadow (the
// half-cylinder of radius R0 behind the planet along -sun) and where it crosses the spheres of
// radii `cut_radii` (the kinks of tent profiles, Atmosphere::kink_radii). Returns the pieces
// (at most kMaxRayPieces), sorted by s; `hits_ground` says whether the ray (ignoring
// max_distance) ends on the ground.
inline constexpr int kMaxCutRadii = 3 * static_cast<int>(kMaxComponents);
inline constexpr int kMaxRayPieces = 4 + 2 * kMaxCutRadii;
struct ViewRay {
  RayPiece pieces[kMaxRayPieces];
  int count = 0;
  double begin = 0, end = 0;  // s range inside the atmosphere (0 pieces: empty)
  bool hits_ground = false;
};
ViewRay split_view_ray(Vec3 p, Vec3 d, Vec3 sun, double ground_radius, double top_radius,
                       double max_distance = std::numeric_limits<double>::infinity(),
                       std::span<const double> cut_radii = {});
// True if the sun ray from p hits the planet (p is in the planet's shadow).
bool in_planet_shadow(Vec3 p, Vec3 sun, double ground_radius);

// ---- optical length -----------------------------------------------------------------------------

// Reference optical length t = integral of rho(r(s) - R0) ds [m] of component c from radius r
// along a ray with cos(zenith) mu to the top of the atmosphere, by composite Simpson quadrature
// (2 n intervals per monotone piece, nodes concentrated at the lower end: s = a + L u^2). The ray
// must not hit the ground (returns +inf if it does).
double optical_length_quadrature(double r, double mu, const Component& c, double ground_radius,
                                 double top_radius, int n = 256);

// The spectra of data/bruneton (Bruneton 2017, 360-830 nm in 10 nm bins): extraterrestrial solar
// irradiance (ASTM G-173) [W m^-2 nm^-1] and ozone absorption cross-section [m^2 per molecule].
// Loaded once; throws IoError if the embedded table is malformed.
struct ReferenceSpectra {
  Spectrum solar_irradiance, ozone_cross_section;
};
const ReferenceSpectra& bruneton_spectra();

// Table resolution and view-ray sampling of the fast path.
struct FastSettings {
  int table_rho = 256;  // height levels, uniform in the level coordinate (density for exponential
                        // profiles, Pietras: rho_i = i/n; altitude for tents), see atmosphere.cpp
  int table_mu = 256;   // cos-zenith samples on [0, 1], uniform in sqrt(mu) (finer at the horizon)
  int table_quadrature = 32;  // Simpson half-count per table entry (2 x 32 intervals)
  // Gauss-Legendre samples per lit piece of the view ray, rounded up to a multiple of 4 (4-point
  // panels). 12 keeps the fast path within 0.2 % of the reference in the tests' sweep; 8 does not
  // (0.9 %), 16 changes the worst case by < 1e-5.
  int view_steps = 12;  // 1 .. 64 (the SIMD kernel's samples per piece)
};

// Spectral quantities for one list of wavelengths, prepared once per model.
struct Spectral {
  std::vector<double> nm;
  std::vector<double> solar;                    // I0(lambda) [W m^-2 nm^-1] (or any unit)
  std::vector<std::vector<double>> scattering;  // [component][lambda] beta_s [m^-1]
  std::vector<std::vector<double>> extinction;  // [component][lambda] beta_e [m^-1]
  // extinction as one float [component][padded] array, rows zero-padded to `padded` (a multiple
  // of 4) wavelengths for the SIMD kernel.
  std::vector<float> extinction_padded;
  std::size_t padded = 0;
};
Spectral make_spectral(const AtmosphereParameters& p, std::span<const double> nm,
                       std::span<const double> solar);

// Reference-path settings (reference.cpp).
struct ReferenceSettings {
  int view_nodes = 400;  // trapezoid intervals per piece of the view ray (u^2-spaced)
  int sun_steps = 64;    // Simpson half-count per monotone piece of each sun ray
};

class Atmosphere {
 public:
  explicit Atmosphere(const AtmosphereParameters& p, const FastSettings& s = {});
  ~Atmosphere();
  // Not copyable (kernel_tables_ point into tables_); moving keeps the tables' buffers.
  Atmosphere(const Atmosphere&) = delete;
  Atmosphere& operator=(const Atmosphere&) = delete;
  Atmosphere(Atmosphere&&) noexcept;
  Atmosphere& operator=(Atmosphere&&) noexcept;

  const AtmosphereParameters& parameters() const { return params_; }
  const FastSettings& settings() const { return settings_; }
  // Radii of the tent profiles' kinks inside the atmosphere (where view rays are cut).
  std::span<const double> kink_radii() const { return kink_radii_; }
  // Component i's optical-length table, [level index][mu index] (table_rho x table_mu).
  std::span<const float> table(std::size_t i) const { return *tables_.at(i); }

  // Optical length of component i from radius r along cos(zenith) mu to the top [m], from the
  // table. mu >= 0: bilinear lookup L[x, mu] at the level x of r (its density for exponential
  // profiles). mu < 0 (Pietras eq. 8, the reflection rule):
  //   L[x, mu] = 2 L[x_t, 0] - L[x, -mu],  x_t = the level of the tangent radius r sqrt(1 - mu^2)
  // (clamped to the ground). For rays that would hit the ground this is the optical
  // length through a transparent planet and is not used by single_scattering.
  double optical_length(std::size_t i, double r, double mu) const;

  // Fast single-scattered radiance (Pietras eq. 9 summed per wavelength) seen from position p
  // along view, up to the ground, the top of the atmosphere or max_distance, whichever is first.
  // out[k] for spec.nm[k]. Adds the Lambertian ground reflection when the ray ends on the ground
  // and params.ground_albedo is set (and max_distance does not stop it first).
  void single_scattering(Vec3 p, Vec3 view, Vec3 sun, const Spectral& spec, std::span<double> out,
                         double max_distance = std::numeric_limits<double>::infinity()) const;

  // Transmittance exp(-sum beta_e t) between p and p + distance * view (fast path).
  void transmittance(Vec3 p, Vec3 view, double distance, const Spectral& spec,
                     std::span<double> out) const;

  // Aerial perspective (Pietras §IV): light arriving at p from a surface point q = p + d view at
  // distance d with Lambertian reflectance `albedo[k]`: in-scattered light between p and q plus
  // the reflected direct sunlight attenuated by the transmittance of the segment.
  //   I = I_scatter(p -> q) + T(p, q) * albedo/pi * I0 * max(0, n.sun) * T_sun(q)
  // with n = the outward planet normal at q (q is taken as a point of a surface facing up) and
  // T_sun(q) = 0 when q is in the planet's shadow.
  void aerial_perspective(Vec3 p, Vec3 view, double distance, std::span<const double> albedo,
                          Vec3 sun, const Spectral& spec, std::span<double> out) const;

  // Brute-force reference of single_scattering (reference.cpp): same equations, every optical
  // length by direct quadrature along the actual ray, double precision, many steps. No tables.
  void single_scattering_reference(
      Vec3 p, Vec3 view, Vec3 sun, const Spectral& spec, std::span<double> out,
      const ReferenceSettings& rs = {},
      double max_distance = std::numeric_limits<double>::infinity()) const;

 private:
  // A direction's table coordinates, shared by all components: the mu cell of |mu| and, below
  // the horizontal, the altitude of the tangent point for the reflection rule.
  struct MuCoord {
    int i = 0;       // cell
    double a = 0.0;  // fraction in the cell
  };
  struct Direction {
    MuCoord mu;
    bool reflect = false;
    double tangent_altitude = 0.0;  // [m], >= 0
  };
  MuCoord mu_coord(double mu) const;
  Direction direction(double r, double mu) const;
  // Level coordinate of component i at altitude h (the table's row coordinate, atmosphere.cpp).
  double coord(std::size_t i, double h) const;
  double lookup(std::size_t i, double x, MuCoord c) const;
  // optical_length from altitude h with the direction's coordinates known.
  double optical_length(std::size_t i, double h, const Direction& d) const;
  void ground_reflection(Vec3 q, Vec3 sun, const Spectral& spec, std::span<double> io_factor) const;

  AtmosphereParameters params_;
  FastSettings settings_;
  std::vector<double> kink_radii_;
  std::vector<double> inv_height_;   // per component, 1/H (exponential) or 1/(r_top - R0) (tent)
  std::vector<double> coord_top_;    // per component, level coordinate at the top radius
  std::vector<double> coord_scale_;  // per component, (table_rho - 1) / (1 - coord_top)
  // Per component, [level index][mu index]; shared with other atmospheres of the same profile,
  // radii and table settings (a process-wide cache of recent tables, atmosphere.cpp).
  std::vector<std::shared_ptr<const std::vector<float>>> tables_;
  // Views of tables_ for the SIMD kernel (detail/scatter_kernel.h), one per component.
  std::unique_ptr<detail::KernelTable[]> kernel_tables_;
};

}  // namespace skylight::atmosphere
