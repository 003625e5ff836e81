// The common part of the multiple-scattering skies `hillaire` and `bruneton` (docs/ATMOSPHERE.md):
// nishita's single scattering computed exactly along each view ray (atmosphere.h), plus the
// radiance of the scattering orders >= 2 that each model defines (multiple_scattering()), held
// in a sky-view LUT per observer and sun (Hillaire 2020 §5.3); the batch path's whole-sky LUT;
// the solar disc (models/solar_disc.h) through the atmosphere's transmittance.
#pragma once

#include <algorithm>
#include <array>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "skylight/models/nishita.h"

namespace skylight {

// The sky-view LUT of the multiple scattering: view zeniths (denser toward the horizon, which is
// the middle row: Hillaire's non-linear mapping) x azimuths from the sun's (0 .. pi, the sky being
// symmetric about the sun's vertical plane). tristimulus() adds it, bilinearly interpolated, to
// the exact single scattering.
inline constexpr int kSkyViewZeniths = 64;
inline constexpr int kSkyViewAzimuths = 32;

// The batch path's LUT of the whole sky (single + multiple scattering, as XYZ) per observer and
// sun, on the same two axes (built on the first batch call): render-sized batches are bilinear
// lookups.
inline constexpr int kSkyBatchZeniths = 256;
inline constexpr int kSkyBatchAzimuths = 128;

// Trapezoid intervals per piece of a view ray for the ray integral of the multiple scattering
// (u^2-spaced toward the piece's lower end, as the brute-force reference's).
inline constexpr int kSkyViewRayNodes = 32;

// The XYZ quadrature of these skies (docs/ATMOSPHERE.md, "Spectral sampling"): the spectral
// radiance at 41 wavelengths, every 10 nm from 380 to 780 nm, weighted by spline_xyz_weights
// (core/xyz_quadrature.h) for the model's solar spectrum. Against a 5 nm integration of the
// model's own spectral radiance: within 0.04 % in X, Y and Z by day and 0.12 % at a low sun and in
// twilight (nishita's 20 CMF samples at 20 nm: 0.68 % and 2.1 %; `skylight_atmosphere_error xyz`).
inline constexpr int kPhysicalXyzCount = 41;
inline constexpr double kPhysicalXyzFirst = 380.0;  // [nm]
inline constexpr double kPhysicalXyzStep = 10.0;    // [nm]

// Every field of an atmosphere that a precomputed table depends on, exactly (hex floats): the
// tables are per unit irradiance and independent of the sun and the observer.
std::string atmosphere_key(const atmosphere::AtmosphereParameters& a);

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
using Densities = std::array<double, atmosphere::kMaxComponents>;
template <class F>
bool ray_nodes(const atmosphere::Atmosphere& atm, Vec3 p, Vec3 v, Vec3 sun, int m, F&& node) {
  const atmosphere::AtmosphereParameters& a = atm.parameters();
  const std::size_t nc = a.components.size();
  const atmosphere::ViewRay ray =
      atmosphere::split_view_ray(p, v, sun, a.ground_radius_m, a.top_radius_m,
                                 std::numeric_limits<double>::infinity(), atm.kink_radii());
  Densities rho{}, prev_rho{}, t{};
  double prev_s = ray.count > 0 ? ray.pieces[0].a : 0.0;
  bool first = true;
  for (int pi = 0; pi < ray.count; ++pi) {
    const atmosphere::RayPiece& piece = ray.pieces[pi];
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
void transmittance_of(const atmosphere::Spectral& spec, std::size_t components, const Densities& t,
                      std::span<double> out);
// sigma_s of every wavelength of `spec` for the densities rho.
void scattering_of(const atmosphere::Spectral& spec, std::size_t components, const Densities& rho,
                   std::span<double> out);

class PhysicalSkyModel : public SkyModel {
 public:
  // The single scattering alone: nishita with the same parameters.
  const NishitaModel& single_scattering() const { return *single_; }
  // The tables' wavelengths, ascending: 360 nm, nishita's XYZ wavelengths (390-770 nm every 20
  // nm), 830 nm (the ends of spectral_radiance's range; between them a table is interpolated
  // linearly in wavelength).
  const std::vector<double>& lut_wavelengths() const { return lut_nm_; }
  // Where a wavelength lies among lut_wavelengths(): v = (1 - t) v[k0] + t v[k1].
  struct LutWeight {
    std::size_t k0 = 0, k1 = 0;
    double t = 0.0;
  };
  LutWeight lut_weight(double nm) const;
  // The radiance of the orders >= 2 at each wavelength of `spec` (`weights`: each one's place
  // among lut_wavelengths()) seen along `view` from the observer (what the sky-view LUT holds at
  // its nodes; spectral_radiance uses it directly).
  virtual void multiple_scattering(Vec3 view, const atmosphere::Spectral& spec,
                                   const std::vector<LutWeight>& weights,
                                   std::span<double> out) const = 0;

  // The wavelengths, solar irradiance and coefficients of the XYZ quadrature (kPhysicalXyzCount).
  const atmosphere::Spectral& xyz_spectral() const { return xyz_; }
  // XYZ (Y in cd/m^2) of spectral radiances at those wavelengths.
  Xyz to_xyz(std::span<const double> radiance) const;
  Xyz tristimulus(Vec3 view) const override;
  // The fast path: the whole-sky LUT (kSkyBatchZeniths x kSkyBatchAzimuths), bilinear, in float;
  // its error against tristimulus() is bounded in the models' tests.
  void tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const override;
  std::optional<double> spectral_radiance(Vec3 view, double nm) const override;
  // The solar disc (models/solar_disc.h: kSolarAngularRadius, Hosek & Wilkie 2013's limb
  // darkening) seen through the atmosphere's transmittance from the observer (0 when the sun is
  // below the observer's horizon, behind the planet).
  bool has_sun() const override { return true; }
  double sun_angular_radius() const override;
  Xyz sun_tristimulus(Vec3 view) const override;
  std::optional<double> sun_spectral_radiance(Vec3 view, double nm) const override;

  // `eval --reference` of these models: the Monte Carlo path tracer of the same atmosphere, at the
  // XYZ quadrature's wavelengths (or the spectral ones).
  static ReferencePath path_tracer_reference();
  static std::string path_tracer_reference_description();
  // Its wavelengths for the options and the quantity's values from the spectral radiances there
  // (as NishitaModel's, with this model's XYZ quadrature).
  std::vector<double> reference_wavelengths(const EvaluationOptions& options) const;
  ReferenceValue reference_value(const EvaluationOptions& options, std::span<const double> radiance,
                                 std::span<const double> standard_error) const;

 protected:
  explicit PhysicalSkyModel(const NishitaParameters& params);
  // Fills the sky-view LUT: the derived model's constructor calls it last, once
  // multiple_scattering() can run. `tables_key`: what multiple_scattering() depends on besides the
  // solar spectrum, the observer and the sun (the atmosphere's key, the model's own settings); a
  // model with the same key, solar spectrum, observer and sun reuses the LUTs of the last built.
  void build_sky_view(const std::string& tables_key);
  const atmosphere::Atmosphere& atmosphere() const { return single_->atmosphere(); }
  Vec3 observer_, sun_;

 private:
  std::unique_ptr<NishitaModel> single_;
  std::vector<double> lut_nm_;
  atmosphere::Spectral xyz_;        // the XYZ quadrature's wavelengths
  std::vector<Cmf> xyz_weights_;    // and weights (spline_xyz_weights)
  std::vector<LutWeight> xyz_lut_;  // the XYZ wavelengths' places among lut_nm_
  // The transmittance from the observer to the top along the sun's direction, per XYZ wavelength.
  std::array<double, kPhysicalXyzCount> sun_transmittance_{};
  // That transmittance at the wavelengths of `spec` (0 behind the planet).
  void sun_transmittance(const atmosphere::Spectral& spec, std::span<double> out) const;
  // The sky-view LUT: [zenith row][azimuth column][XYZ wavelength] multiple-scattering radiance.
  std::shared_ptr<const std::vector<double>> sky_;
  std::string lut_key_;          // build_sky_view's key with the solar spectrum, observer and sun
  double horizon_zenith_ = 0.0;  // [rad] of the observer's horizon (pi/2 on the ground)
  // A LUT's row coordinate of a view zenith [rad] and back, for `rows` rows.
  double sky_row(double zenith, int rows) const;
  double sky_zenith(double row, int rows) const;
  // The batch LUT: [row][column] X, Y, Z in float, built once (thread-safe) on first use.
  mutable std::once_flag batch_once_;
  mutable std::shared_ptr<const std::vector<float>> batch_;
  std::vector<float> build_batch_lut() const;
};

}  // namespace skylight
