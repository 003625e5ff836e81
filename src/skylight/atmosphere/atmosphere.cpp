// Planet geometry, phase functions, optical-length tables and the fast single-scattering path.
// Equations: see atmosphere.h (Nishita et al. 1993; Pietras §II-IV).
#include "skylight/atmosphere/atmosphere.h"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <mutex>
#include <utility>

#include "skylight/atmosphere/detail/scatter_kernel.h"
#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"

namespace skylight::atmosphere {

// ---- parameters ---------------------------------------------------------------------------------

double Component::scattering(double nm) const {
  return scattering_per_m * std::pow(reference_nm / nm, angstrom_exponent);
}
double Component::extinction(double nm) const {
  return extinction_per_m * std::pow(reference_nm / nm, angstrom_exponent) + absorption_per_m(nm);
}
double Component::density(double h) const {
  if (profile == Profile::tent)
    return std::max(0.0, 1.0 - std::abs(h - peak_altitude_m) / half_width_m);
  return std::exp(-h / scale_height_m);
}

const ReferenceSpectra& bruneton_spectra() {
  static const ReferenceSpectra t = [] {
    constexpr std::string_view kPath = "bruneton/bruneton2017_solar_irradiance_ozone_xsec.csv";
    const auto csv = data::load_table(kPath, /*has_header=*/true, 3);
    return ReferenceSpectra{Spectrum::from_table(csv, 0, 1, kPath),
                            Spectrum::from_table(csv, 0, 2, kPath)};
  }();
  return t;
}

Component earth_rayleigh() {
  return {"rayleigh", kRayleighScaleHeight, kRayleighScattering550, kRayleighScattering550,
          550.0,      kRayleighExponent,    PhaseKind::rayleigh,    0.0};
}
Component earth_mie(double g) {
  return {"mie",
          kMieScaleHeight,
          kMieScattering,
          kMieExtinction,
          550.0,
          0.0,
          PhaseKind::cornette_shanks,
          g};
}
Component earth_ozone(double dobson) {
  Component c;
  c.name = "ozone";
  c.profile = Profile::tent;
  c.peak_altitude_m = kOzonePeakAltitude;
  c.half_width_m = kOzoneHalfWidth;
  const double peak_density = dobson * kDobsonUnit / kOzoneHalfWidth;  // [molecules m^-3]
  c.absorption_per_m = bruneton_spectra().ozone_cross_section.scaled(peak_density);
  return c;
}

namespace {
void require(bool ok, std::string_view field, double value, std::string_view range) {
  if (!ok || std::isnan(value))
    throw InvalidArgument(fmt::format("{} = {} is outside {}", field, value, range));
}
}  // namespace

void AtmosphereParameters::validate() const {
  require(std::isfinite(ground_radius_m) && ground_radius_m > 0, "ground radius", ground_radius_m,
          "(0, inf) m");
  require(std::isfinite(top_radius_m) && top_radius_m > ground_radius_m, "top radius", top_radius_m,
          "(ground radius, inf) m");
  require(components.size() <= kMaxComponents, "number of components",
          static_cast<double>(components.size()), fmt::format("[0, {}]", kMaxComponents));
  for (const auto& c : components) {
    if (c.profile == Profile::exponential)
      require(std::isfinite(c.scale_height_m) && c.scale_height_m > 0, c.name + " scale height",
              c.scale_height_m, "(0, inf) m");
    require(std::isfinite(c.scattering_per_m) && c.scattering_per_m >= 0, c.name + " scattering",
            c.scattering_per_m, "[0, inf) m^-1");
    require(std::isfinite(c.extinction_per_m) && c.extinction_per_m >= c.scattering_per_m,
            c.name + " extinction", c.extinction_per_m, "[scattering, inf) m^-1");
    require(std::isfinite(c.reference_nm) && c.reference_nm > 0, c.name + " reference wavelength",
            c.reference_nm, "(0, inf) nm");
    require(std::isfinite(c.angstrom_exponent), c.name + " exponent", c.angstrom_exponent,
            "finite");
    require(c.g > -1 && c.g < 1, c.name + " g", c.g, "(-1, 1)");
    if (c.profile == Profile::tent) {
      require(std::isfinite(c.peak_altitude_m), c.name + " peak altitude", c.peak_altitude_m,
              "finite m");
      require(std::isfinite(c.half_width_m) && c.half_width_m > 0, c.name + " half width",
              c.half_width_m, "(0, inf) m");
    }
    for (std::size_t k = 0; k < c.absorption_per_m.size(); ++k)
      require(c.absorption_per_m.values()[k] >= 0, fmt::format("{} absorption [{}]", c.name, k),
              c.absorption_per_m.values()[k], "[0, inf) m^-1");
  }
  if (ground_albedo)
    require(*ground_albedo >= 0 && *ground_albedo <= 1, "ground albedo", *ground_albedo, "[0, 1]");
}

// ---- phase functions ----------------------------------------------------------------------------

// Rayleigh: F(mu) = 3/(16 pi) (1 + mu^2)  [sr^-1]
double phase_rayleigh(double mu) {
  return 3.0 / (16.0 * kPi) * (1.0 + mu * mu);
}
// Henyey-Greenstein 1941: F(mu) = (1 - g^2) / (4 pi (1 + g^2 - 2 g mu)^{3/2})  [sr^-1]
double phase_henyey_greenstein(double mu, double g) {
  const double k = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) / (4.0 * kPi * k * std::sqrt(k));
}
// Cornette & Shanks 1992 (as in Nishita 1993 / Bruneton 2008):
//   F(mu) = 3/(8 pi) (1 - g^2)(1 + mu^2) / ((2 + g^2)(1 + g^2 - 2 g mu)^{3/2})  [sr^-1]
double phase_cornette_shanks(double mu, double g) {
  const double k = 1.0 + g * g - 2.0 * g * mu;
  return 3.0 / (8.0 * kPi) * (1.0 - g * g) * (1.0 + mu * mu) / ((2.0 + g * g) * k * std::sqrt(k));
}
double phase(const Component& c, double mu) {
  mu = clamp_cosine(mu);
  switch (c.phase) {
    case PhaseKind::rayleigh:
      return phase_rayleigh(mu);
    case PhaseKind::henyey_greenstein:
      return phase_henyey_greenstein(mu, c.g);
    case PhaseKind::cornette_shanks:
      return phase_cornette_shanks(mu, c.g);
  }
  return 0.0;
}

// ---- geometry -----------------------------------------------------------------------------------

// |p + s d|^2 = R^2  ->  s = -b -+ sqrt(b^2 - c), b = p.d, c = |p|^2 - R^2.
double ray_sphere_far(Vec3 p, Vec3 d, double radius) {
  const double b = dot(p, d);
  const double disc = b * b - (dot(p, p) - radius * radius);
  if (disc < 0) return -1.0;
  return -b + std::sqrt(disc);
}
double ray_sphere_near(Vec3 p, Vec3 d, double radius) {
  const double b = dot(p, d);
  const double disc = b * b - (dot(p, p) - radius * radius);
  if (disc < 0) return -1.0;
  return -b - std::sqrt(disc);
}

// In the planet's shadow: the sun ray p + s sun (s > 0) meets the sphere of radius R0, i.e.
// p.sun < 0 and the distance of p from the sun axis |p - (p.sun) sun| < R0 (Pietras §III:
// cos(theta_v) < 0 and r_v sin(theta_v) < R0).
bool in_planet_shadow(Vec3 p, Vec3 sun, double ground_radius) {
  const double ps = dot(p, sun);
  return ps < 0 && dot(p, p) - ps * ps < ground_radius * ground_radius;
}

ViewRay split_view_ray(Vec3 p, Vec3 d, Vec3 sun, double R0, double Rt, double max_distance,
                       std::span<const double> cut_radii) {
  SKYLIGHT_CHECK(cut_radii.size() <= static_cast<std::size_t>(kMaxCutRadii),
                 "split_view_ray: too many cut radii");
  ViewRay v;
  const double far_top = ray_sphere_far(p, d, Rt);
  if (far_top <= 0) return v;  // the line misses the atmosphere or it lies behind
  double s0 = std::max(0.0, ray_sphere_near(p, d, Rt));
  double s1 = far_top;
  // The ground is hit when the ray descends towards a sphere it meets (an observer exactly on
  // the ground looking down hits it at s = 0).
  const double near_ground = ray_sphere_near(p, d, R0);
  if (dot(p, d) < 0 && ray_sphere_far(p, d, R0) >= 0) {
    s1 = std::max(near_ground, 0.0);
    v.hits_ground = true;
  }
  s1 = std::min(s1, max_distance);
  if (!(s1 > s0)) return v;
  v.begin = s0;
  v.end = s1;

  double cuts[kMaxRayPieces + 1];
  int n = 0;
  cuts[n++] = s0;
  const auto add = [&](double s) {
    if (s > s0 && s < s1) cuts[n++] = s;
  };
  const double pd = dot(p, d);
  add(-pd);                      // lowest altitude of the line
  for (double rc : cut_radii) {  // |p + s d| = rc
    const double disc = pd * pd - (dot(p, p) - rc * rc);
    if (disc <= 0) continue;
    add(-pd - std::sqrt(disc));
    add(-pd + std::sqrt(disc));
  }
  // Shadow: |q + s e|^2 < R0^2 (q, e = p, d without their sun components) and (p + s d).sun < 0.
  const Vec3 q = p - dot(p, sun) * sun;
  const Vec3 e = d - dot(d, sun) * sun;
  const double A = dot(e, e), B = dot(q, e), C = dot(q, q) - R0 * R0;
  double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
  bool empty = false;
  if (A > 1e-300) {
    const double disc = B * B - A * C;
    if (disc <= 0) {
      empty = true;
    } else {
      const double sq = std::sqrt(disc);
      lo = (-B - sq) / A;
      hi = (-B + sq) / A;
    }
  } else if (C >= 0) {
    empty = true;
  }
  const double ps = dot(p, sun), ds = dot(d, sun);
  if (ds > 0) {
    hi = std::min(hi, -ps / ds);
  } else if (ds < 0) {
    lo = std::max(lo, -ps / ds);
  } else if (ps >= 0) {
    empty = true;
  }
  if (!empty && lo < hi) {
    add(lo);
    add(hi);
  }
  std::sort(cuts + 1, cuts + n);
  cuts[n] = s1;
  for (int k = 0; k < n; ++k) {
    const double a = cuts[k], b = cuts[k + 1];
    if (!(b > a)) continue;
    RayPiece& piece = v.pieces[v.count++];
    piece.a = a;
    piece.b = b;
    const Vec3 pa = p + a * d, pb = p + b * d;
    piece.anchor_at_a = dot(pa, pa) <= dot(pb, pb);
    piece.lit = !in_planet_shadow(p + (0.5 * (a + b)) * d, sun, R0);
  }
  return v;
}

// ---- optical length -----------------------------------------------------------------------------

namespace {

// 4-point Gauss-Legendre nodes and weights on [-1, 1] (Abramowitz & Stegun 25.4.30).
constexpr double kGaussNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                   0.8611363115940526};
constexpr double kGaussWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                     0.3478548451374538};

// Simpson's rule for integral_a^b rho ds with s = anchor +- L u^2, u in [0, 1], 2n intervals.
template <class Density>
double simpson_piece(double a, double b, bool anchor_at_a, int n, const Density& rho) {
  const double len = b - a;
  if (!(len > 0)) return 0.0;
  const int m = 2 * n;
  double sum = 0.0;
  for (int k = 0; k <= m; ++k) {
    const double u = static_cast<double>(k) / m;
    const double s = anchor_at_a ? a + len * u * u : b - len * u * u;
    const double w = (k == 0 || k == m) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    sum += w * rho(s) * 2.0 * len * u;  // ds/du = 2 L u
  }
  return sum / (3.0 * m);
}

}  // namespace

double optical_length_quadrature(double r, double mu, const Component& c, double R0, double Rt,
                                 int n) {
  // Ray from (0, 0, r) with direction (sqrt(1 - mu^2), 0, mu); radius r(s)^2 = r^2 + s^2 +
  // 2 r mu s.
  mu = clamp_cosine(mu);
  const double p2 = r * r * (1.0 - mu * mu);  // squared tangent radius
  if (mu < 0 && p2 < R0 * R0) return std::numeric_limits<double>::infinity();
  const double exit = -r * mu + safe_sqrt(r * r * (mu * mu - 1.0) + Rt * Rt);
  const auto rho = [&](double s) {
    return c.density(std::sqrt(std::max(r * r + s * s + 2.0 * r * mu * s, 0.0)) - R0);
  };
  // A tent's density has kinks at three altitudes: the ray is also cut where it crosses them, so
  // that Simpson's rule integrates a smooth function on every piece.
  double kinks[3];
  int nk = 0;
  if (c.profile == Profile::tent)
    for (double h : {c.peak_altitude_m - c.half_width_m, c.peak_altitude_m,
                     c.peak_altitude_m + c.half_width_m})
      if (R0 + h > std::sqrt(p2) && R0 + h < Rt) kinks[nk++] = R0 + h;
  // integral over [a, b] on which r(s) is monotone (rising: anchored at a), cut at the kinks.
  const auto monotone = [&](double a, double b, bool rising) {
    double cuts[5];
    int m = 0;
    cuts[m++] = a;
    for (int k = 0; k < nk; ++k) {
      const double root = safe_sqrt(r * r * (mu * mu - 1.0) + kinks[k] * kinks[k]);
      const double sk = rising ? -r * mu + root : -r * mu - root;
      if (sk > a && sk < b) cuts[m++] = sk;
    }
    for (int k = 2; k < m; ++k)  // insertion sort of <= 3 values
      for (int j = k; j > 1 && cuts[j] < cuts[j - 1]; --j) std::swap(cuts[j], cuts[j - 1]);
    cuts[m] = b;
    double sum = 0.0;
    for (int k = 0; k < m; ++k) sum += simpson_piece(cuts[k], cuts[k + 1], rising, n, rho);
    return sum;
  };
  if (mu >= 0) return monotone(0.0, exit, true);
  const double tangent = -r * mu;  // lowest point of the ray
  return monotone(0.0, tangent, false) + monotone(tangent, exit, true);
}

Spectral make_spectral(const AtmosphereParameters& p, std::span<const double> nm,
                       std::span<const double> solar) {
  SKYLIGHT_CHECK(nm.size() == solar.size(), "make_spectral: size mismatch");
  Spectral s;
  s.nm.assign(nm.begin(), nm.end());
  s.solar.assign(solar.begin(), solar.end());
  for (const auto& c : p.components) {
    std::vector<double> sc, ex;
    for (double l : nm) {
      sc.push_back(c.scattering(l));
      ex.push_back(c.extinction(l));
    }
    s.scattering.push_back(std::move(sc));
    s.extinction.push_back(std::move(ex));
  }
  s.padded = (nm.size() + 3) / 4 * 4;
  s.extinction_padded.assign(p.components.size() * s.padded, 0.0f);
  for (std::size_t i = 0; i < p.components.size(); ++i)
    for (std::size_t l = 0; l < nm.size(); ++l)
      s.extinction_padded[i * s.padded + l] = static_cast<float>(s.extinction[i][l]);
  return s;
}

// ---- tables (Pietras §II) -----------------------------------------------------------------------
//
// L_i[x, mu] = optical length of component i from the height level x along cos(zenith) mu >= 0
// to the top. The level coordinate x is the density for an exponential profile (Pietras samples
// rho uniformly, rho_j = j/n; altitude h = -H ln rho) and 1 - h / (r_top - R0) for a tent
// profile (whose density is not monotonic in h); either is uniform on [x_top, 1] (so the top row
// is exactly 0). mu = y^2 with y uniform on [0, 1], which puts more samples where L grows
// fastest, at the horizon. Each entry is computed directly by optical_length_quadrature (instead
// of Pietras' running sum of layer segments S[rho, c], which would add the interpolation error of
// every layer).

Atmosphere::~Atmosphere() = default;
Atmosphere::Atmosphere(Atmosphere&&) noexcept = default;
Atmosphere& Atmosphere::operator=(Atmosphere&&) noexcept = default;

namespace {

// What one component's table depends on: its density profile, the planet's radii and the table's
// resolution; not its coefficients or phase function, nor the sun. Skies that differ only in
// those (a sun path, an animation, a sweep of g or albedo) share their tables.
struct TableKey {
  Profile profile = Profile::exponential;
  double scale_height_m = 0, peak_altitude_m = 0, half_width_m = 0;
  double ground_radius_m = 0, top_radius_m = 0;
  int rho = 0, mu = 0, quadrature = 0;
  bool operator==(const TableKey&) const = default;
};

// The tables of the last kTableCacheEntries distinct keys (256 KB each at the default 256 x 256),
// most recently used first. A table stays alive while an Atmosphere holds it, cached or not.
constexpr std::size_t kTableCacheEntries = 16;

class TableCache {
 public:
  template <class Build>
  std::shared_ptr<const std::vector<float>> get(const TableKey& key, const Build& build) {
    {
      const std::lock_guard lock(mutex_);
      if (auto t = take(key)) return t;
    }
    // Built outside the lock: threads building different atmospheres do not wait for each
    // other. Two threads building the same key keep the first one cached.
    auto table = std::make_shared<const std::vector<float>>(build());
    const std::lock_guard lock(mutex_);
    if (auto t = take(key)) return t;
    entries_.insert(entries_.begin(), {key, table});
    if (entries_.size() > kTableCacheEntries) entries_.pop_back();
    return table;
  }

 private:
  // The entry for key, moved to the front; null when absent. Caller holds mutex_.
  std::shared_ptr<const std::vector<float>> take(const TableKey& key) {
    const auto it = std::find_if(entries_.begin(), entries_.end(),
                                 [&](const auto& e) { return e.first == key; });
    if (it == entries_.end()) return nullptr;
    std::rotate(entries_.begin(), it, it + 1);
    return entries_.front().second;
  }

  std::mutex mutex_;
  std::vector<std::pair<TableKey, std::shared_ptr<const std::vector<float>>>> entries_;
};

TableCache& table_cache() {
  static TableCache cache;
  return cache;
}

}  // namespace

Atmosphere::Atmosphere(const AtmosphereParameters& p, const FastSettings& s)
    : params_(p), settings_(s) {
  params_.validate();
  SKYLIGHT_CHECK(s.table_rho >= 2 && s.table_mu >= 2 && s.table_quadrature >= 1 &&
                     s.view_steps >= 1 &&
                     static_cast<std::size_t>(s.view_steps) <= detail::kMaxPieceSamples,
                 "Atmosphere: bad FastSettings");
  const double R0 = p.ground_radius_m, Rt = p.top_radius_m;
  for (const auto& c : p.components) {
    if (c.profile == Profile::tent)
      for (double h : {c.peak_altitude_m - c.half_width_m, c.peak_altitude_m,
                       c.peak_altitude_m + c.half_width_m})
        if (h > 0 && R0 + h < Rt) kink_radii_.push_back(R0 + h);
    const bool tent = c.profile == Profile::tent;
    inv_height_.push_back(tent ? 1.0 / (Rt - R0) : 1.0 / c.scale_height_m);
    const double x_top = tent ? 0.0 : std::exp(-(Rt - R0) / c.scale_height_m);
    coord_top_.push_back(x_top);
    coord_scale_.push_back((s.table_rho - 1) / (1.0 - x_top));
    const TableKey key{c.profile,
                       tent ? 0.0 : c.scale_height_m,
                       tent ? c.peak_altitude_m : 0.0,
                       tent ? c.half_width_m : 0.0,
                       R0,
                       Rt,
                       s.table_rho,
                       s.table_mu,
                       s.table_quadrature};
    tables_.push_back(table_cache().get(key, [&] {
      std::vector<float> t(static_cast<std::size_t>(s.table_rho) * s.table_mu);
      for (int i = 1; i < s.table_rho; ++i) {  // row 0 (the top) stays 0
        const double x = x_top + (1.0 - x_top) * i / (s.table_rho - 1);
        const double h = tent ? (1.0 - x) * (Rt - R0) : -c.scale_height_m * std::log(x);
        const double r = std::min(Rt, R0 + h);
        for (int j = 0; j < s.table_mu; ++j) {
          const double y = static_cast<double>(j) / (s.table_mu - 1);
          t[static_cast<std::size_t>(i) * s.table_mu + j] = static_cast<float>(
              optical_length_quadrature(r, y * y, c, R0, Rt, s.table_quadrature));
        }
      }
      return t;
    }));
  }
  kernel_tables_ = std::make_unique<detail::KernelTable[]>(p.components.size());
  for (std::size_t i = 0; i < p.components.size(); ++i) {
    const Component& c = p.components[i];
    detail::KernelTable& t = kernel_tables_[i];
    t.data = tables_[i]->data();
    t.rows = s.table_rho;
    t.cols = s.table_mu;
    t.exponential = c.profile == Profile::exponential;
    t.inv_height = static_cast<float>(inv_height_[i]);
    t.coord_top = static_cast<float>(coord_top_[i]);
    t.coord_scale = static_cast<float>(coord_scale_[i]);
    t.peak = static_cast<float>(c.peak_altitude_m);
    t.inv_half_width = t.exponential ? 0.0f : static_cast<float>(1.0 / c.half_width_m);
  }
}

double Atmosphere::coord(std::size_t i, double h) const {
  if (params_.components[i].profile == Profile::tent) return 1.0 - h * inv_height_[i];
  return std::exp(-h * inv_height_[i]);
}

// The table's mu coordinate: y = sqrt(mu) (mu in [0, 1]) scaled to cells, shared by components.
Atmosphere::MuCoord Atmosphere::mu_coord(double mu) const {
  const int nm = settings_.table_mu;
  const double fy = std::sqrt(std::clamp(mu, 0.0, 1.0)) * (nm - 1);
  const int iy = std::min(static_cast<int>(fy), nm - 2);
  return {iy, fy - iy};
}

// Bilinear lookup in (x, sqrt(mu)).
double Atmosphere::lookup(std::size_t i, double x, MuCoord c) const {
  const int nr = settings_.table_rho, nm = settings_.table_mu;
  const double fx = std::clamp((x - coord_top_[i]) * coord_scale_[i], 0.0, nr - 1.0);
  const int ix = std::min(static_cast<int>(fx), nr - 2);
  const double ax = fx - ix, ay = c.a;
  const float* row0 = tables_[i]->data() + static_cast<std::size_t>(ix) * nm + c.i;
  const float* row1 = row0 + nm;
  return (1 - ax) * ((1 - ay) * row0[0] + ay * row0[1]) + ax * ((1 - ay) * row1[0] + ay * row1[1]);
}

Atmosphere::Direction Atmosphere::direction(double r, double mu) const {
  if (mu >= 0) return {mu_coord(mu), false, 0.0};
  const double R0 = params_.ground_radius_m;
  return {mu_coord(-mu), true, std::max(r * safe_sqrt(1.0 - mu * mu) - R0, 0.0)};
}

double Atmosphere::optical_length(std::size_t i, double h, const Direction& d) const {
  const double l = lookup(i, coord(i, h), d.mu);
  if (!d.reflect) return l;
  // Pietras eq. 8: L[x, c] = 2 L[x_t, 0] - L[x, -c], x_t the level of the tangent point (the
  // ray's lowest point, clamped to the ground).
  return std::max(2.0 * lookup(i, coord(i, d.tangent_altitude), MuCoord{0, 0.0}) - l, 0.0);
}

double Atmosphere::optical_length(std::size_t i, double r, double mu) const {
  return optical_length(i, r - params_.ground_radius_m, direction(r, mu));
}

// ---- fast single scattering (Pietras eq. 9) -----------------------------------------------------
//
// I = sum_v b F rho_v exp(-b (L[x_0, cos a_0] - L[x_v, cos a_v] + L[x_v, cos theta_v])) dv
// per component and wavelength. For a ray that ends on the ground the view term uses the reversed
// (upward) rays instead, L[x_v, -cos a_v] - L[x_0, -cos a_0], which never cross the ground.
// The ray is cut at its lowest point and at the shadow boundaries (split_view_ray), so the
// integrand is smooth on each lit piece; each is integrated in u, s = anchor +- L u^2 (denser at
// the low, dense end), by composite 4-point Gauss-Legendre (view_steps / 4 panels). The samples
// of a piece go through the SIMD kernel together (scatter_kernel.h).

namespace {

// The n = 4 panels samples of one lit piece: s = anchor +- L u^2 at the nodes of composite
// 4-point Gauss-Legendre in u (panel k / 4 of n / 4, node k % 4), with their weights; then
// kSamplePadding padding lanes of weight 0.
void gauss_legendre_samples(const RayPiece& piece, std::size_t n, double* s_k, double* w_k) {
  const double h = 4.0 / static_cast<double>(n);
  const double len = piece.b - piece.a;
  for (std::size_t k = 0; k < n; ++k) {
    const double u = h * (static_cast<double>(k / 4) + 0.5 * (1.0 + kGaussNodes[k % 4]));
    s_k[k] = piece.anchor_at_a ? piece.a + len * u * u : piece.b - len * u * u;
    w_k[k] = 2.0 * len * u * 0.5 * h * kGaussWeights[k % 4];
  }
  for (std::size_t k = n; k < n + detail::kSamplePadding; ++k) {
    s_k[k] = s_k[n - 1];
    w_k[k] = 0.0;
  }
}

}  // namespace

void Atmosphere::single_scattering(Vec3 p, Vec3 view, Vec3 sun, const Spectral& spec,
                                   std::span<double> out, double max_distance) const {
  const std::size_t nl = spec.nm.size(), nc = params_.components.size();
  SKYLIGHT_CHECK(out.size() == nl, "single_scattering: output size");
  std::fill(out.begin(), out.end(), 0.0);
  const double R0 = params_.ground_radius_m;
  const ViewRay ray =
      split_view_ray(p, view, sun, R0, params_.top_radius_m, max_distance, kink_radii_);
  // An observer on the ground looking down has an empty ray (no in-scattering) that still ends
  // on the ground: its reflection is the limit of the observer's altitude -> 0+ (transmittance
  // 1), so the sky stays continuous in altitude (docs/MODELS.md, nishita).
  if (ray.count == 0 && !ray.hits_ground) return;

  // Optical lengths at the start of the ray (the observer, or where the ray enters from space).
  const Vec3 p0 = p + ray.begin * view;
  const double r0 = length(p0);
  const double mu0 = dot(p0, view) / r0;
  SKYLIGHT_CHECK(nc <= kMaxComponents, "single_scattering: too many components");
  float t0[kMaxComponents];
  for (std::size_t i = 0; i < nc; ++i)
    t0[i] = static_cast<float>(ray.hits_ground ? optical_length(i, r0, -mu0)
                                               : optical_length(i, r0, mu0));
  // acc[i][k] = sum over samples of rho_i T_k ds (float, see scatter_kernel.h).
  const std::size_t np = spec.padded;
  constexpr std::size_t kStackAcc = 512;
  float acc_stack[kStackAcc];
  std::vector<float> acc_heap;
  float* acc = acc_stack;
  if (nc * np > kStackAcc) {
    acc_heap.resize(nc * np);
    acc = acc_heap.data();
  }
  std::fill(acc, acc + nc * np, 0.0f);
  const int panels = (settings_.view_steps + 3) / 4;
  const std::size_t n = 4 * static_cast<std::size_t>(panels);
  double sw[2 * (detail::kMaxPieceSamples + detail::kSamplePadding)];
  double* s_k = sw;
  double* w_k = s_k + n + detail::kSamplePadding;
  detail::PieceSamples ps;
  ps.s = s_k;
  ps.w = w_k;
  ps.n = n;
  ps.pp = dot(p, p);
  ps.pv = dot(p, view);
  ps.ps = dot(p, sun);
  ps.vs = dot(view, sun);
  ps.ground_radius = R0;
  ps.hits_ground = ray.hits_ground;
  for (int pi = 0; pi < ray.count; ++pi) {
    const RayPiece& piece = ray.pieces[pi];
    if (!piece.lit) continue;
    gauss_legendre_samples(piece, n, s_k, w_k);
    detail::scatter_piece(kernel_tables_.get(), nc, t0, ps, spec.extinction_padded.data(), np, acc);
  }
  const double mu = dot(view, sun);
  for (std::size_t i = 0; i < nc; ++i) {
    const double f = phase(params_.components[i], mu);
    const double* bs = spec.scattering[i].data();
    const float* a = acc + i * np;
    for (std::size_t l = 0; l < nl; ++l) out[l] += spec.solar[l] * bs[l] * f * a[l];
  }

  // Ground reflection (Lambertian, direct sunlight only) when the ray ends on the ground.
  if (params_.ground_albedo && ray.hits_ground && ray.end < max_distance) {
    std::vector<double> g(nl);
    transmittance(p, view, ray.end, spec, g);
    ground_reflection(p + ray.end * view, sun, spec, g);
    for (std::size_t l = 0; l < nl; ++l) out[l] += *params_.ground_albedo * g[l];
  }
}

void Atmosphere::transmittance(Vec3 p, Vec3 view, double distance, const Spectral& spec,
                               std::span<double> out) const {
  const std::size_t nl = spec.nm.size(), nc = params_.components.size();
  SKYLIGHT_CHECK(out.size() == nl, "transmittance: output size");
  std::fill(out.begin(), out.end(), 1.0);
  const ViewRay ray =
      split_view_ray(p, view, view, params_.ground_radius_m, params_.top_radius_m, distance);
  if (ray.count == 0) return;
  const Vec3 a = p + ray.begin * view, b = p + ray.end * view;
  const double ra = length(a), rb = length(b);
  const double ma = dot(a, view) / ra, mb = dot(b, view) / rb;
  std::vector<double> tau(nl, 0.0);
  for (std::size_t i = 0; i < nc; ++i) {
    const double t = ray.hits_ground ? optical_length(i, rb, -mb) - optical_length(i, ra, -ma)
                                     : optical_length(i, ra, ma) - optical_length(i, rb, mb);
    for (std::size_t l = 0; l < nl; ++l) tau[l] += spec.extinction[i][l] * std::max(t, 0.0);
  }
  for (std::size_t l = 0; l < nl; ++l) out[l] = std::exp(-tau[l]);
}

// io[k] *= I0 / pi * max(0, n.sun) * T_sun(q)   (the reflected radiance of a white Lambertian
// surface at q lit by the attenuated sun; 0 in the planet's shadow).
void Atmosphere::ground_reflection(Vec3 q, Vec3 sun, const Spectral& spec,
                                   std::span<double> io) const {
  const double r = length(q);
  const double mu_s = dot(q, sun) / r;
  if (mu_s <= 0 || in_planet_shadow(q, sun, params_.ground_radius_m)) {
    std::fill(io.begin(), io.end(), 0.0);
    return;
  }
  for (std::size_t l = 0; l < spec.nm.size(); ++l) {
    double tau = 0.0;
    for (std::size_t i = 0; i < params_.components.size(); ++i)
      tau += spec.extinction[i][l] * optical_length(i, r, mu_s);
    io[l] *= spec.solar[l] / kPi * mu_s * std::exp(-tau);
  }
}

void Atmosphere::aerial_perspective(Vec3 p, Vec3 view, double distance,
                                    std::span<const double> albedo, Vec3 sun, const Spectral& spec,
                                    std::span<double> out) const {
  const std::size_t nl = spec.nm.size();
  SKYLIGHT_CHECK(albedo.size() == nl && out.size() == nl, "aerial_perspective: sizes");
  single_scattering(p, view, sun, spec, out, distance);
  std::vector<double> t(nl);
  transmittance(p, view, distance, spec, t);
  ground_reflection(p + distance * view, sun, spec, t);
  for (std::size_t l = 0; l < nl; ++l) out[l] += albedo[l] * t[l];
}

}  // namespace skylight::atmosphere
