#include "skylight/models/hillaire.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <string>

#include "skylight/atmosphere/path_tracer.h"
#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/solar_disc.h"

namespace skylight {

namespace {

using atmosphere::Atmosphere;
using atmosphere::AtmosphereParameters;
using atmosphere::Spectral;

// The piece-wise trapezoid nodes of the ray p + s v inside the atmosphere (up to the ground or
// the top), `m` per piece u^2-spaced toward its lower end; calls node(s, weight, rho, t) with the
// components' densities rho at the node and their optical lengths t from p to it (the trapezoid
// rule over the same nodes).
template <class F>
void ray_nodes(const Atmosphere& atm, Vec3 p, Vec3 v, Vec3 sun, int m, F&& node) {
  const AtmosphereParameters& a = atm.parameters();
  const std::size_t nc = a.components.size();
  const atmosphere::ViewRay ray =
      atmosphere::split_view_ray(p, v, sun, a.ground_radius_m, a.top_radius_m,
                                 std::numeric_limits<double>::infinity(), atm.kink_radii());
  std::array<double, atmosphere::kMaxComponents> rho{}, prev_rho{}, t{};
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
}

// exp(-sum_i beta_e,i t_i) for every wavelength of `spec`.
void transmittance_of(const Spectral& spec, std::size_t nc,
                      const std::array<double, atmosphere::kMaxComponents>& t,
                      std::span<double> out) {
  for (std::size_t l = 0; l < out.size(); ++l) {
    double tau = 0.0;
    for (std::size_t i = 0; i < nc; ++i) tau += spec.extinction[i][l] * t[i];
    out[l] = std::exp(-tau);
  }
}

// sigma_s of every wavelength of `spec` for the densities rho.
void scattering_of(const Spectral& spec, std::size_t nc,
                   const std::array<double, atmosphere::kMaxComponents>& rho,
                   std::span<double> out) {
  for (std::size_t l = 0; l < out.size(); ++l) {
    double s = 0.0;
    for (std::size_t i = 0; i < nc; ++i) s += rho[i] * spec.scattering[i][l];
    out[l] = s;
  }
}

// Every field of an atmosphere that the multiple-scattering LUT depends on, exactly (hex floats):
// the LUT is per unit irradiance and independent of the sun and the observer.
std::string lut_key(const AtmosphereParameters& a) {
  std::string k = fmt::format("{:a} {:a} {:a}", a.ground_radius_m, a.top_radius_m,
                              a.ground_albedo.value_or(-1.0));
  for (const auto& c : a.components) {
    k += fmt::format("|{:a} {:a} {:a} {:a} {:a} {} {:a} {} {:a} {:a}", c.scale_height_m,
                     c.scattering_per_m, c.extinction_per_m, c.reference_nm, c.angstrom_exponent,
                     static_cast<int>(c.phase), c.g, static_cast<int>(c.profile), c.peak_altitude_m,
                     c.half_width_m);
    for (std::size_t i = 0; i < c.absorption_per_m.size(); ++i)
      k += fmt::format(" {:a}:{:a}", c.absorption_per_m.wavelengths()[i],
                       c.absorption_per_m.values()[i]);
  }
  return k;
}

// The LUTs of the last few atmospheres (a new sun or observer reuses its planet's LUT: the
// report's and the sweeps' many suns). Thread-safe; two threads computing the same key keep one.
class PsiCache {
 public:
  using Lut = std::shared_ptr<const std::vector<double>>;
  template <class Build>
  Lut get(const std::string& key, const Build& build) {
    {
      const std::lock_guard lock(mutex_);
      for (const auto& [k, lut] : entries_)
        if (k == key) return lut;
    }
    Lut lut = std::make_shared<const std::vector<double>>(build());
    const std::lock_guard lock(mutex_);
    entries_.insert(entries_.begin(), {key, lut});
    if (entries_.size() > kEntries) entries_.pop_back();
    return lut;
  }

 private:
  static constexpr std::size_t kEntries = 8;
  std::mutex mutex_;
  std::vector<std::pair<std::string, Lut>> entries_;
};

PsiCache& psi_cache() {
  static PsiCache cache;
  return cache;
}

// The LUT's sun-cosine axis: u in [0, 1] -> mu_s = sign(w) w^2, w = 2 u - 1 (denser at the
// horizon, mu_s = 0, where the light changes fastest at sunset), and back.
double lut_mu_s(double u) {
  const double w = 2.0 * u - 1.0;
  return std::copysign(w * w, w);
}
double lut_mu_s_coordinate(double mu_s) {
  return 0.5 * (1.0 + std::copysign(std::sqrt(std::abs(mu_s)), mu_s));
}

}  // namespace

const ParameterSchema<HillaireParameters>& HillaireParameters::schema() {
  static const auto s = [] {
    ParameterSchema<HillaireParameters> s;
    s.inherit(NishitaParameters::schema())
        .redefault("ozone", ParameterValue(atmosphere::kEarthOzoneColumn),
                   "ozone column of an absorbing layer at 10-40 km (Bruneton 2017 profile; 0: "
                   "none)");
    return s;
  }();
  return s;
}

HillaireModel::LutWeight HillaireModel::lut_weight(double nm) const {
  // lut_nm_ is ascending.
  const auto it = std::lower_bound(lut_nm_.begin(), lut_nm_.end(), nm);
  if (it == lut_nm_.begin()) return {0, 0, 0.0};
  if (it == lut_nm_.end()) return {lut_nm_.size() - 1, lut_nm_.size() - 1, 0.0};
  const auto j = static_cast<std::size_t>(it - lut_nm_.begin());
  const double a = lut_nm_[j - 1], b = lut_nm_[j];
  return {j - 1, j, (nm - a) / (b - a)};
}

HillaireModel::HillaireModel(const HillaireParameters& params)
    : SkyModel(params.sun), params_(params) {
  single_ = std::make_unique<NishitaModel>(static_cast<const NishitaParameters&>(params_));
  const Atmosphere& atm = single_->atmosphere();
  const AtmosphereParameters& a = atm.parameters();
  observer_ = single_->observer();
  sun_ = params.sun.direction();
  const Spectral& xyz = single_->xyz_spectral();
  lut_nm_.push_back(kNishitaMinNm);
  lut_nm_.insert(lut_nm_.end(), xyz.nm.begin(), xyz.nm.end());
  lut_nm_.push_back(kNishitaMaxNm);
  for (double nm : xyz.nm) xyz_lut_.push_back(lut_weight(nm));
  for (int k = 0; k < kNishitaXyzCount; ++k) sun_transmittance_[k] = sun_transmittance(xyz.nm[k]);
  const std::size_t nl = lut_nm_.size();
  psi_ = psi_cache().get(lut_key(a), [&] {
    std::vector<double> psi;
    // Per unit irradiance; the first scattering with an isotropic phase function (HG with g = 0
    // is exactly 1 / (4 pi)); the tables are shared with the single scattering's (same profiles).
    const Spectral unit = atmosphere::make_spectral(a, lut_nm_, std::vector<double>(nl, 1.0));
    AtmosphereParameters iso = a;
    for (auto& c : iso.components) {
      c.phase = atmosphere::PhaseKind::henyey_greenstein;
      c.g = 0.0;
    }
    const Atmosphere iso_atm(iso, atm.settings());
    const int nh = kHillaireLutAltitudes, nmu = kHillaireLutSunCosines;
    psi.assign(nl * nh * nmu, 0.0);
    const double R0 = a.ground_radius_m, top = a.top_radius_m - R0;
    const std::size_t nc = a.components.size();
    const double p_u = 1.0 / (4.0 * kPi);
    const double dw = 4.0 * kPi / (kHillaireLutPolar * kHillaireLutAzimuths);
    parallel_for(static_cast<std::size_t>(nh * nmu), 1, [&](std::size_t b, std::size_t e) {
      std::vector<double> l1(nl), l2(nl), f(nl), tr(nl), sig(nl);
      for (std::size_t job = b; job < e; ++job) {
        const int ih = static_cast<int>(job) / nmu, jm = static_cast<int>(job) % nmu;
        // The top row sits just below the top (a ray from the top itself has no length upward).
        const double h = std::min(top * ih / (nh - 1), top * (1.0 - 1e-6));
        const double mu_s = lut_mu_s(static_cast<double>(jm) / (nmu - 1));
        const Vec3 x{0, 0, R0 + h};
        const Vec3 sun{safe_sqrt(1.0 - mu_s * mu_s), 0, mu_s};
        std::fill(l2.begin(), l2.end(), 0.0);
        std::fill(f.begin(), f.end(), 0.0);
        for (int ip = 0; ip < kHillaireLutPolar; ++ip) {
          const double mu = -1.0 + (ip + 0.5) * 2.0 / kHillaireLutPolar;
          for (int ia = 0; ia < kHillaireLutAzimuths; ++ia) {
            const double phi = (ia + 0.5) * kPi / kHillaireLutAzimuths;
            const double s = safe_sqrt(1.0 - mu * mu);
            const Vec3 v{s * std::cos(phi), s * std::sin(phi), mu};
            // L': the isotropic single scattering toward x (and the ground's direct sun).
            iso_atm.single_scattering(x, v, sun, unit, l1);
            // L_f: the integral of T sigma_s along the ray.
            ray_nodes(atm, x, v, sun, kHillaireLutRayNodes,
                      [&](double, double w, const auto& rho, const auto& t) {
                        scattering_of(unit, nc, rho, sig);
                        transmittance_of(unit, nc, t, tr);
                        for (std::size_t l = 0; l < nl; ++l) f[l] += w * tr[l] * sig[l] * p_u * dw;
                      });
            for (std::size_t l = 0; l < nl; ++l) l2[l] += l1[l] * p_u * dw;
          }
        }
        for (std::size_t l = 0; l < nl; ++l)
          psi[(l * nh + ih) * nmu + jm] = l2[l] / (1.0 - std::min(f[l], 0.999));
      }
    });
    return psi;
  });
  // The sky-view LUT of this observer and sun.
  const double r_obs = length(observer_);
  horizon_zenith_ = kPi / 2 + std::acos(std::min(1.0, a.ground_radius_m / r_obs));
  sky_.assign(
      static_cast<std::size_t>(kHillaireSkyZeniths) * kHillaireSkyAzimuths * kNishitaXyzCount, 0.0);
  parallel_for(static_cast<std::size_t>(kHillaireSkyZeniths * kHillaireSkyAzimuths), 8,
               [&](std::size_t b, std::size_t e) {
                 for (std::size_t job = b; job < e; ++job) {
                   const int i = static_cast<int>(job) / kHillaireSkyAzimuths;
                   const int j = static_cast<int>(job) % kHillaireSkyAzimuths;
                   const double zenith = sky_zenith(i, kHillaireSkyZeniths);
                   const double azimuth = sun().azimuth + kPi * j / (kHillaireSkyAzimuths - 1);
                   multiple_scattering(
                       direction_from_angles(zenith, azimuth), xyz, xyz_lut_,
                       std::span<double>(&sky_[job * kNishitaXyzCount], kNishitaXyzCount));
                 }
               });
}

// Rows: the upper half (row < mid) l = 1 - row / mid, zenith = horizon (1 - l^2); the lower half
// l = (row - mid) / (rows - 1 - mid), zenith = horizon + (pi - horizon) l^2: both dense at the
// horizon, where the sky changes fastest.
double HillaireModel::sky_zenith(double row, int rows) const {
  const double mid = 0.5 * (rows - 1);
  if (row <= mid) {
    const double l = 1.0 - row / mid;
    return horizon_zenith_ * (1.0 - l * l);
  }
  const double l = (row - mid) / mid;
  return horizon_zenith_ + (kPi - horizon_zenith_) * l * l;
}

double HillaireModel::sky_row(double zenith, int rows) const {
  const double mid = 0.5 * (rows - 1);
  if (zenith <= horizon_zenith_)
    return mid * (1.0 - std::sqrt(std::max(0.0, 1.0 - zenith / horizon_zenith_)));
  return mid + mid * std::sqrt(std::min(1.0, (zenith - horizon_zenith_) / (kPi - horizon_zenith_)));
}

double HillaireModel::psi(std::size_t k, double altitude_m, double mu_s) const {
  const int nh = kHillaireLutAltitudes, nmu = kHillaireLutSunCosines;
  const AtmosphereParameters& a = single_->atmosphere().parameters();
  const double top = a.top_radius_m - a.ground_radius_m;
  const double x = std::clamp(altitude_m / top, 0.0, 1.0) * (nh - 1);
  const double y = lut_mu_s_coordinate(std::clamp(mu_s, -1.0, 1.0)) * (nmu - 1);
  const int i = std::min(static_cast<int>(x), nh - 2), j = std::min(static_cast<int>(y), nmu - 2);
  const double fx = x - i, fy = y - j;
  const double* t = &(*psi_)[k * nh * nmu];
  const auto at = [&](int ii, int jj) { return t[ii * nmu + jj]; };
  return (1 - fx) * ((1 - fy) * at(i, j) + fy * at(i, j + 1)) +
         fx * ((1 - fy) * at(i + 1, j) + fy * at(i + 1, j + 1));
}

void HillaireModel::multiple_scattering(Vec3 view, const Spectral& spec,
                                        const std::vector<LutWeight>& weights,
                                        std::span<double> out) const {
  const Atmosphere& atm = single_->atmosphere();
  const AtmosphereParameters& a = atm.parameters();
  const std::size_t nl = spec.nm.size(), nc = a.components.size();
  std::fill(out.begin(), out.end(), 0.0);
  std::vector<double> tr(nl), sig(nl);
  const Vec3 v = normalize(view);
  ray_nodes(atm, observer_, v, sun_, kHillaireRayNodes,
            [&](double dist, double w, const auto& rho, const auto& t) {
              const Vec3 y = observer_ + dist * v;
              const double r = length(y);
              const double h = r - a.ground_radius_m;
              const double mu_s = dot(y, sun_) / r;
              scattering_of(spec, nc, rho, sig);
              transmittance_of(spec, nc, t, tr);
              for (std::size_t l = 0; l < nl; ++l) {
                const LutWeight& lw = weights[l];
                const double p = (1 - lw.t) * psi(lw.k0, h, mu_s) + lw.t * psi(lw.k1, h, mu_s);
                out[l] += w * tr[l] * sig[l] * p * spec.solar[l];
              }
            });
}

void HillaireModel::build_batch_lut() const {
  const int rows = kHillaireBatchZeniths, cols = kHillaireBatchAzimuths;
  batch_.assign(static_cast<std::size_t>(rows) * cols * 3, 0.0f);
  parallel_for(static_cast<std::size_t>(rows * cols), 64, [&](std::size_t b, std::size_t e) {
    for (std::size_t job = b; job < e; ++job) {
      const int i = static_cast<int>(job) / cols, j = static_cast<int>(job) % cols;
      const double azimuth = sun().azimuth + kPi * j / (cols - 1);
      const Xyz c = tristimulus(direction_from_angles(sky_zenith(i, rows), azimuth));
      batch_[3 * job] = static_cast<float>(c.X);
      batch_[3 * job + 1] = static_cast<float>(c.Y);
      batch_[3 * job + 2] = static_cast<float>(c.Z);
    }
  });
}

void HillaireModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  SKYLIGHT_CHECK(out.size() == dirs.size(), "tristimulus_batch: size mismatch");
  std::call_once(batch_once_, [this] { build_batch_lut(); });
  const int rows = kHillaireBatchZeniths, cols = kHillaireBatchAzimuths;
  const double sun_az = sun().azimuth;
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    const double zenith = std::acos(std::clamp(static_cast<double>(dirs.z[k]), -1.0, 1.0));
    const double phi =
        std::abs(wrap_azimuth(std::atan2(dirs.x[k], dirs.y[k]) - sun_az + kPi) - kPi);
    const double y = std::clamp(sky_row(zenith, rows), 0.0, rows - 1.0);
    const double x = std::clamp(phi / kPi, 0.0, 1.0) * (cols - 1);
    const int i = std::min(static_cast<int>(y), rows - 2),
              j = std::min(static_cast<int>(x), cols - 2);
    const float fy = static_cast<float>(y - i), fx = static_cast<float>(x - j);
    const float* a = &batch_[(static_cast<std::size_t>(i) * cols + j) * 3];
    const float* c = a + static_cast<std::size_t>(cols) * 3;
    float v[3];
    for (int ch = 0; ch < 3; ++ch)
      v[ch] =
          (1 - fy) * ((1 - fx) * a[ch] + fx * a[3 + ch]) + fy * ((1 - fx) * c[ch] + fx * c[3 + ch]);
    out.X[k] = v[0];
    out.Y[k] = v[1];
    out.Z[k] = v[2];
  }
}

double HillaireModel::sun_transmittance(double nm) const {
  const Atmosphere& atm = single_->atmosphere();
  const AtmosphereParameters& a = atm.parameters();
  if (atmosphere::in_planet_shadow(observer_, sun_, a.ground_radius_m)) return 0.0;
  const double to_top = atmosphere::ray_sphere_far(observer_, sun_, a.top_radius_m);
  if (to_top <= 0) return 1.0;  // above the atmosphere, looking away from it
  const double l[1] = {nm}, one[1] = {1.0};
  const Spectral spec = atmosphere::make_spectral(a, l, one);
  double t[1] = {0.0};
  atm.transmittance(observer_, sun_, to_top, spec, t);
  return t[0];
}

double HillaireModel::sun_angular_radius() const {
  return kSolarAngularRadius;
}

Xyz HillaireModel::sun_tristimulus(Vec3 view) const {
  const Vec3 v = normalize(view);
  const double gamma = std::acos(std::clamp(dot(v, sun_), -1.0, 1.0));
  // The part of the disc behind the planet (below the horizon) is hidden by the ground.
  if (gamma > kSolarAngularRadius ||
      atmosphere::in_planet_shadow(observer_, v,
                                   single_->atmosphere().parameters().ground_radius_m))
    return {};
  const Spectral& xyz = single_->xyz_spectral();
  std::array<double, kNishitaXyzCount> r{};
  for (int k = 0; k < kNishitaXyzCount; ++k)
    r[k] = xyz.solar[k] * sun_transmittance_[k] * solar_disc_factor(gamma, xyz.nm[k]);
  return single_->to_xyz(r);
}

std::optional<double> HillaireModel::sun_spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= kNishitaMinNm && nm <= kNishitaMaxNm)) return std::nullopt;
  const Vec3 v = normalize(view);
  const double gamma = std::acos(std::clamp(dot(v, sun_), -1.0, 1.0));
  if (gamma > kSolarAngularRadius ||
      atmosphere::in_planet_shadow(observer_, v,
                                   single_->atmosphere().parameters().ground_radius_m))
    return 0.0;
  return single_->irradiance(nm) * sun_transmittance(nm) * solar_disc_factor(gamma, nm);
}

ParameterValues HillaireModel::parameter_values() const {
  return HillaireParameters::schema().values_of(params_);
}

Xyz HillaireModel::tristimulus(Vec3 view) const {
  std::array<double, kNishitaXyzCount> r{};
  const Vec3 v = normalize(view);
  single_->atmosphere().single_scattering(observer_, v, sun_, single_->xyz_spectral(), r);
  // The multiple scattering from the sky-view LUT (bilinear; azimuth from the sun's, folded).
  const double zenith = std::acos(std::clamp(v.z, -1.0, 1.0));
  const double phi = std::abs(wrap_azimuth(std::atan2(v.x, v.y) - sun().azimuth + kPi) - kPi);
  const double y = std::clamp(sky_row(zenith, kHillaireSkyZeniths), 0.0, kHillaireSkyZeniths - 1.0);
  const double x = std::clamp(phi / kPi, 0.0, 1.0) * (kHillaireSkyAzimuths - 1);
  const int i = std::min(static_cast<int>(y), kHillaireSkyZeniths - 2);
  const int j = std::min(static_cast<int>(x), kHillaireSkyAzimuths - 2);
  const double fy = y - i, fx = x - j;
  const auto at = [&](int ii, int jj) {
    return &sky_[(static_cast<std::size_t>(ii) * kHillaireSkyAzimuths + jj) * kNishitaXyzCount];
  };
  const double *a = at(i, j), *b = at(i, j + 1), *c = at(i + 1, j), *d = at(i + 1, j + 1);
  for (int k = 0; k < kNishitaXyzCount; ++k)
    r[k] += (1 - fy) * ((1 - fx) * a[k] + fx * b[k]) + fy * ((1 - fx) * c[k] + fx * d[k]);
  return single_->to_xyz(r);
}

std::optional<double> HillaireModel::spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= kNishitaMinNm && nm <= kNishitaMaxNm)) return std::nullopt;
  // One Spectral for both parts (nishita's spectral_radiance would build its own).
  const Spectral spec = single_->spectral_at(std::span<const double>(&nm, 1));
  const Vec3 v = normalize(view);
  double single[1] = {0.0}, ms[1] = {0.0};
  single_->atmosphere().single_scattering(observer_, v, sun_, spec, single);
  multiple_scattering(v, spec, {lut_weight(nm)}, ms);
  return single[0] + ms[0];
}

Domain HillaireModel::domain() const {
  Domain d;
  if (sun().zenith > kPi / 2)
    d.issues.push_back({"sun_zenith", Validity::extrapolated,
                        "sun below the horizon: the approximation's error grows in twilight "
                        "(docs/ATMOSPHERE.md)"});
  return d;
}

ModelInfo HillaireModel::registry_entry() {
  ModelInfo info = NishitaModel::registry_entry();
  info.name = std::string(kName);
  info.description =
      "Physically based single scattering plus Hillaire's (2020) multiple-scattering LUT "
      "(orders >= 2 as isotropic in-scattering from a 32 x 32 table over altitude and sun "
      "angle) in nishita's atmosphere; ozone on by default";
  info.output =
      "XYZ with Y [cd/m^2] for the ASTM G-173 extraterrestrial sun (20 nm bins 380-780 nm); "
      "spectral radiance [W m^-2 sr^-1 nm^-1] 360-830 nm; with --solar-irradiance E both per flat "
      "irradiance E; in-scattered light of every order, the ground reflects only with an "
      "explicit --albedo; --include-sun / --sun-only: the solar disc (0.2665 deg, limb-darkened, "
      "through the atmosphere's transmittance)";
  info.parameters = HillaireParameters::schema().specs();
  info.domain =
      "nishita's: any observer altitude 0-10000 km, any view direction and sun elevation; the "
      "approximation's error against the Monte Carlo path tracer: docs/ATMOSPHERE.md";
  info.make = model_factory<HillaireModel, HillaireParameters>();
  // The Monte Carlo path tracer of the same atmosphere (every order; standard errors). (The
  // entry starts as nishita's: its reference, the single scattering, is replaced here.)
  info.reference = [](const SkyModel& m, Vec3 view, const EvaluationOptions& o,
                      const ReferenceRequest& rq) {
    const auto& h = static_cast<const HillaireModel&>(m);
    const NishitaModel& n = h.single_scattering();
    const std::vector<double> nm = n.reference_wavelengths(o);
    const auto spec = n.spectral_at(nm);
    atmosphere::PathTracerSettings s;
    s.paths = rq.paths;
    s.seed = rq.seed;
    const auto r = atmosphere::path_trace(n.atmosphere().parameters(), n.observer(),
                                          normalize(view), h.sun().direction(), spec, s);
    return n.reference_value(o, r.radiance, r.standard_error);
  };
  info.reference_description =
      "the Monte Carlo path tracer of the same atmosphere (atmosphere/path_tracer.h: every order "
      "of scattering, segments estimator; standard errors)";
  info.report = ReportPolicy{
      .title = "Hillaire 2020 (Earth defaults)", .colour = "#17becf", .physical_reference = true};
  return info;
}

}  // namespace skylight
