#include "skylight/atmosphere/scattering_orders.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <span>
#include <string>

#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/core/progress.h"
#include "skylight/core/system.h"
#include "skylight/io/table_cache.h"
#include "skylight/version.h"

namespace skylight::atmosphere {

namespace {

constexpr int kNr = kOrderTableAltitudes, kNs = kOrderTableSunCosines,
              kNmu = kOrderTableViewCosines, kNphi = kOrderTableAzimuths, kHalf = kNmu / 2,
              kDirs = kNmu * kNphi;
static_assert(kNmu % 2 == 0, "view cosines: half below and half above the horizon");
// The lowest altitude row: 1 m above the ground, so that its downward rays meet the ground at a
// positive distance (their ground reflection is then part of the single scattering).
constexpr double kLowestAltitude = 1.0;  // [m]
constexpr double kDarkDips = 3.0;

// The grid of one atmosphere's tables (bruneton.h).
struct Grid {
  Grid(double ground_radius, double atmosphere_height)
      : ground(ground_radius), height(atmosphere_height), min_mu_s(lowest_sun_cosine()) {}
  double ground = 0.0, height = 0.0;  // R0 [m]; top - R0 [m]
  double min_mu_s = 0.0;              // lowest_sun_cosine(), once per grid (the hot path reads it)

  double altitude(int i) const {
    const double u = static_cast<double>(i) / (kNr - 1);
    return std::clamp(height * u * u, kLowestAltitude, height * (1.0 - 1e-6));
  }
  double altitude_coordinate(double h) const {
    return std::sqrt(std::clamp(h / height, 0.0, 1.0)) * (kNr - 1);
  }
  // The lowest sun cosine of the tables (below it the orders >= 2 are 0): three times the depth
  // of the horizon seen from the top of the atmosphere (Earth: 24 deg below the horizon), the sun
  // lighting air that lights air that lights the observer's.
  double lowest_sun_cosine() const {
    const double dip = std::acos(ground / (ground + height));
    return -std::sin(std::min(kPi / 2, kDarkDips * dip));
  }
  double min_sun_cosine() const { return min_mu_s; }
  double sun_cosine(int j) const {
    const double w = -1.0 + 2.0 * j / (kNs - 1);
    return w >= 0 ? w * w : min_sun_cosine() * w * w;
  }
  double sun_coordinate(double mu_s) const {
    const double w = mu_s >= 0 ? std::sqrt(std::min(mu_s, 1.0))
                               : -std::sqrt(std::min(mu_s / min_sun_cosine(), 1.0));
    return 0.5 * (1.0 + w) * (kNs - 1);
  }
  // The cosine of the horizon's direction at radius r (0 at the ground, below 0 above it).
  double horizon(double r) const {
    return -safe_sqrt(1.0 - (ground / std::max(r, ground)) * (ground / std::max(r, ground)));
  }
  // The view cosine at fraction `u` in [0, 1] of a half (0: at the horizon), below or above it:
  // the angle from the horizon grows as u^2 (cells dense at the horizon, a few degrees wide at
  // the zenith and the nadir).
  static double view_cosine(double mh, bool above, double u) {
    const double zh = std::acos(mh);
    return std::cos(above ? zh * (1.0 - u * u) : zh + (kPi - zh) * u * u);
  }
  // The inverse: u of a view cosine on its side.
  static double view_fraction(double mh, bool above, double mu) {
    const double zh = std::acos(mh), z = std::acos(std::clamp(mu, -1.0, 1.0));
    return std::sqrt(std::clamp(above ? 1.0 - z / zh : (z - zh) / (kPi - zh), 0.0, 1.0));
  }
  // Cell c of the view-cosine axis (c < kHalf: below the horizon, counted from it) at `offset`
  // of its width (0.5: its centre, the node).
  static double cell_cosine(double mh, int c, double offset) {
    const bool above = c >= kHalf;
    return view_cosine(mh, above, ((above ? c - kHalf : c) + offset) / kHalf);
  }
};

// Linear interpolation between v[i] and v[i + 1] with weight f on the second.
struct Lerp {
  int i = 0;
  double f = 0.0;
};
Lerp lerp_at(double x, int n) {
  x = std::clamp(x, 0.0, n - 1.0);
  const int i = std::min(static_cast<int>(x), n - 2);
  return {i, x - i};
}

// A point and direction's place in the tables: the view cosine relative to the point's own
// horizon (the same side and fraction at both altitude rows, as Bruneton's parametrisation).
struct Place {
  Lerp altitude, sun, azimuth;
  bool dark = false;   // the sun below the tables' lowest sun cosine: orders >= 2 are 0
  int view_first = 0;  // the first cell of the view cosine's pair (both on one side)
  double view_f = 0.0;
};
Place place_of(const Grid& g, double r, double mu, double mu_s, double cos_phi) {
  Place p;
  p.altitude = lerp_at(g.altitude_coordinate(r - g.ground), kNr);
  p.sun = lerp_at(g.sun_coordinate(mu_s), kNs);
  p.dark = mu_s < g.min_sun_cosine();
  p.azimuth = lerp_at(std::acos(std::clamp(cos_phi, -1.0, 1.0)) / kPi * kNphi - 0.5, kNphi);
  const double mh = g.horizon(r);
  const bool above = mu >= mh;
  const double u = Grid::view_fraction(mh, above, mu);
  const Lerp v = lerp_at(u * kHalf - 0.5, kHalf);
  p.view_first = (above ? kHalf : 0) + v.i;
  p.view_f = v.f;
  return p;
}

// The start of (altitude row i, direction d) in a table of [altitude][direction][sun
// cosine][wavelength] floats with nl wavelengths.
std::size_t row_of(int i, int d, std::size_t nl) {
  return (static_cast<std::size_t>(i) * kDirs + d) * kNs * nl;
}

// Between two sun cosines at or below the horizon the tables fall off as the planet's shadow
// rises through the air that lights the node (nearly a Gaussian of the sun's depression): there
// the interpolation is geometric in the tables' spectral sum S (v = R^f ((1 - f) v0 + f v1 / R),
// R = S1 / S0: exact for a common ratio, as linear for equal sums), which a linear interpolation
// overestimates by up to a fifth at 6 deg below the horizon (docs/ATMOSPHERE.md). Above the
// horizon, linear. `v0`, `v1`: the values at the two sun cosines; the result is added to out.
void blend_sun(const Grid& g, const Lerp& sun, double mu_s, const double* v0, const double* v1,
               std::size_t nl, double* out) {
  double r = 1.0, f = sun.f;
  const double m1 = g.sun_cosine(sun.i + 1);
  if (m1 <= 0.0) {
    const double m0 = g.sun_cosine(sun.i);
    double s0 = 0.0, s1 = 0.0;
    for (std::size_t l = 0; l < nl; ++l) {
      s0 += v0[l];
      s1 += v1[l];
    }
    if (s0 > 0.0 && s1 > 0.0) {
      r = s1 / s0;
      f = std::clamp((m0 * m0 - mu_s * mu_s) / (m0 * m0 - m1 * m1), 0.0, 1.0);
    }
  }
  // Above the horizon (r = 1) this is the linear interpolation: no pow in the day's hot path.
  const double scale = r == 1.0 ? 1.0 : std::pow(r, f), f1 = f / r;
  for (std::size_t l = 0; l < nl; ++l) out[l] += scale * ((1.0 - f) * v0[l] + f1 * v1[l]);
}

// The 8-corner interpolation of table v at p over altitude, view cosine and azimuth, times
// `scale`, at the sun cosines p.sun.i (added to v0) and p.sun.i + 1 (added to v1).
void add_corners(const float* v, std::size_t nl, const Place& p, double scale, double* v0,
                 double* v1) {
  const double wa[2] = {1.0 - p.altitude.f, p.altitude.f};
  const double wv[2] = {1.0 - p.view_f, p.view_f};
  const double wp[2] = {1.0 - p.azimuth.f, p.azimuth.f};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int c = 0; c < 2; ++c) {
        const double w = scale * wa[a] * wv[b] * wp[c];
        if (w == 0.0) continue;
        const int d = (p.view_first + b) * kNphi + p.azimuth.i + c;
        const float* q =
            v + row_of(p.altitude.i + a, d, nl) + static_cast<std::size_t>(p.sun.i) * nl;
        for (std::size_t l = 0; l < nl; ++l) {
          v0[l] += w * q[l];
          v1[l] += w * q[nl + l];
        }
      }
}

struct NodeTable {
  std::size_t nl = 0;
  std::vector<float> v;
  explicit NodeTable(std::size_t wavelengths)
      : nl(wavelengths), v(static_cast<std::size_t>(kNr) * kDirs * kNs * wavelengths, 0.0f) {}
  std::size_t row(int i, int d) const { return row_of(i, d, nl); }
};

// The product-integration matrix of one altitude row and phase function: P[d][d'] = the phase
// integral over the cell of d' (and its mirror image about the sun's plane) seen from the node
// direction of d, each row normalised to 1.
std::vector<float> phase_matrix(const Grid& g, int i, const Component& c) {
  const double mh = g.horizon(g.ground + g.altitude(i));
  constexpr int S = kOrderTablePhaseSubsamples;
  // kernel[m][m'][delta]: cell (m', k + delta) seen from node (m, k), delta in
  // [-(2 kNphi - 1), kNphi - 1].
  constexpr int kOff = 2 * kNphi - 1, kDeltas = 3 * kNphi - 1;
  std::vector<double> kernel(static_cast<std::size_t>(kNmu) * kNmu * kDeltas);
  const double dphi = kPi / kNphi;
  for (int m = 0; m < kNmu; ++m) {
    const double mu = Grid::cell_cosine(mh, m, 0.5), sm = safe_sqrt(1.0 - mu * mu);
    for (int m2 = 0; m2 < kNmu; ++m2) {
      for (int delta = -kOff; delta < kNphi; ++delta) {
        double sum = 0.0;
        for (int a = 0; a < S; ++a) {
          // Sub-cells uniform in the half's coordinate (as the cells), weighted by their width.
          const double u0 = static_cast<double>(a) / S, u1 = static_cast<double>(a + 1) / S;
          const int c2 = m2 >= kHalf ? m2 - kHalf : m2;
          const bool above = m2 >= kHalf;
          const double x0 = Grid::view_cosine(mh, above, (c2 + u0) / kHalf);
          const double x1 = Grid::view_cosine(mh, above, (c2 + u1) / kHalf);
          const double mu2 = 0.5 * (x0 + x1), s2 = safe_sqrt(1.0 - mu2 * mu2);
          const double dmu = std::abs(x1 - x0);
          for (int b = 0; b < S; ++b) {
            const double rel = (delta + (b + 0.5) / S - 0.5) * dphi;
            sum += phase(c, mu * mu2 + sm * s2 * std::cos(rel)) * dmu * dphi / S;
          }
        }
        kernel[(static_cast<std::size_t>(m) * kNmu + m2) * kDeltas + (delta + kOff)] = sum;
      }
    }
  }
  std::vector<float> p(static_cast<std::size_t>(kDirs) * kDirs);
  for (int m = 0; m < kNmu; ++m)
    for (int k = 0; k < kNphi; ++k) {
      const int d = m * kNphi + k;
      double total = 0.0;
      std::vector<double> row(kDirs);
      for (int m2 = 0; m2 < kNmu; ++m2)
        for (int k2 = 0; k2 < kNphi; ++k2) {
          const double* kr = &kernel[(static_cast<std::size_t>(m) * kNmu + m2) * kDeltas];
          const double v = kr[k2 - k + kOff] + kr[-k2 - 1 - k + kOff];
          row[m2 * kNphi + k2] = v;
          total += v;
        }
      for (int d2 = 0; d2 < kDirs; ++d2)
        p[static_cast<std::size_t>(d) * kDirs + d2] = static_cast<float>(row[d2] / total);
    }
  return p;
}

// out[i] = P[i] L[i] per altitude row (the sphere integral of every node).
void apply_phase(const std::vector<std::vector<float>>& p, const NodeTable& l, NodeTable& out) {
  const std::size_t w = static_cast<std::size_t>(kNs) * l.nl;
  parallel_for(static_cast<std::size_t>(kNr) * kDirs, 16, [&](std::size_t b, std::size_t e) {
    for (std::size_t job = b; job < e; ++job) {
      const int i = static_cast<int>(job / kDirs), d = static_cast<int>(job % kDirs);
      float* o = &out.v[out.row(i, d)];
      std::fill(o, o + w, 0.0f);
      const float* pr = &p[i][static_cast<std::size_t>(d) * kDirs];
      for (int d2 = 0; d2 < kDirs; ++d2) {
        const float a = pr[d2];
        const float* src = &l.v[l.row(i, d2)];
        for (std::size_t x = 0; x < w; ++x) o[x] += a * src[x];
      }
    }
  });
}

// The node of (altitude row, direction, sun cosine): position, view and sun directions.
struct Node {
  Vec3 x, view, sun;
  bool below = false;  // the view meets the ground
};
Node node_at(const Grid& g, int i, int d, int j) {
  const double r = g.ground + g.altitude(i);
  const int m = d / kNphi, k = d % kNphi;
  const double mu = Grid::cell_cosine(g.horizon(r), m, 0.5), phi = (k + 0.5) * kPi / kNphi;
  const double s = safe_sqrt(1.0 - mu * mu), mu_s = g.sun_cosine(j);
  return {Vec3{0, 0, r}, Vec3{s * std::cos(phi), s * std::sin(phi), mu},
          Vec3{safe_sqrt(1.0 - mu_s * mu_s), 0, mu_s}, m < kHalf};
}

// The ground's irradiance by the radiance `l` (its lowest altitude row, the directions above the
// horizon), [sun cosine][wavelength].
std::vector<double> ground_irradiance(const Grid& g, const NodeTable& l) {
  std::vector<double> e(static_cast<std::size_t>(kNs) * l.nl, 0.0);
  const double mh = g.horizon(g.ground + g.altitude(0));
  for (int m = kHalf; m < kNmu; ++m) {
    const double lo = std::max(0.0, Grid::cell_cosine(mh, m, 0.0)),
                 hi = std::max(0.0, Grid::cell_cosine(mh, m, 1.0));
    // integral of mu over the cell x the azimuth cell and its mirror image.
    const double w = 0.5 * (hi * hi - lo * lo) * 2.0 * kPi / kNphi;
    for (int k = 0; k < kNphi; ++k) {
      const float* src = &l.v[l.row(0, m * kNphi + k)];
      for (std::size_t x = 0; x < e.size(); ++x) e[x] += w * src[x];
    }
  }
  return e;
}

// The irradiance table at mu_s (blend_sun along the sun cosine), times `scale`, added to out;
// v0, v1: nl values of scratch.
void add_irradiance(const Grid& g, const std::vector<double>& e, std::size_t nl, double mu_s,
                    double scale, double* v0, double* v1, double* out) {
  if (mu_s < g.min_sun_cosine()) return;
  const Lerp s = lerp_at(g.sun_coordinate(mu_s), kNs);
  for (std::size_t l = 0; l < nl; ++l) {
    v0[l] = scale * e[s.i * nl + l];
    v1[l] = scale * e[(s.i + 1) * nl + l];
  }
  blend_sun(g, s, mu_s, v0, v1, nl, out);
}

// The source of orders >= 2 along a ray: at each node of ray_nodes, sum_c beta_c rho_c Q_c(place)
// times the transmittance, and the ground's reflection of `irradiance` where the ray ends on the
// ground. `spec` gives beta (per table wavelength: the tables' own, or a view's with `weights`).
struct RaySource {
  const Grid& grid;
  const Atmosphere& atm;
  const std::vector<std::size_t>& components;
  std::vector<const float*> q;  // per component, the tables' Q_c
  std::size_t nl = 0;           // the tables' wavelengths
  const std::vector<double>* irradiance = nullptr;
  double albedo = 0.0;
};

void integrate_ray(const RaySource& src, Vec3 x, Vec3 view, Vec3 sun, int ray_nodes_per_piece,
                   const Spectral& spec, const std::vector<WavelengthWeight>* weights,
                   std::span<double> out) {
  const std::size_t nl = spec.nm.size(), nt = src.nl;
  const std::size_t nc = src.atm.parameters().components.size();
  std::fill(out.begin(), out.end(), 0.0);
  std::vector<double> qv(nt), q0(nt), q1(nt), tr(nl), sig(nl);
  const double nu = dot(view, sun);
  // A value of the table wavelengths (qv's) at the l-th wavelength of spec.
  const auto at = [&](const std::vector<double>& v, std::size_t l) {
    return weights ? (1.0 - (*weights)[l].t) * v[(*weights)[l].k0] +
                         (*weights)[l].t * v[(*weights)[l].k1]
                   : v[l];
  };
  Densities last_t{};
  const bool hits = ray_nodes(
      src.atm, x, view, sun, ray_nodes_per_piece,
      [&](double s, double w, const Densities& rho, const Densities& t) {
        last_t = t;
        const Vec3 y = x + s * view;
        const double r = length(y);
        const double mu = dot(y, view) / r, mu_s = dot(y, sun) / r;
        const double den = std::sqrt(std::max(0.0, (1.0 - mu * mu) * (1.0 - mu_s * mu_s)));
        const double cos_phi = den > 1e-9 ? (nu - mu * mu_s) / den : 1.0;
        const Place p = place_of(src.grid, r, mu, mu_s, cos_phi);
        if (p.dark) return;  // the orders >= 2 are 0 here
        transmittance_of(spec, nc, t, tr);
        std::fill(sig.begin(), sig.end(), 0.0);
        for (std::size_t ci = 0; ci < src.components.size(); ++ci) {
          const std::size_t c = src.components[ci];
          if (rho[c] <= 0.0) continue;
          std::fill(qv.begin(), qv.end(), 0.0);
          std::fill(q0.begin(), q0.end(), 0.0);
          std::fill(q1.begin(), q1.end(), 0.0);
          add_corners(src.q[ci], nt, p, rho[c], q0.data(), q1.data());
          blend_sun(src.grid, p.sun, mu_s, q0.data(), q1.data(), nt, qv.data());
          for (std::size_t l = 0; l < nl; ++l) sig[l] += spec.scattering[c][l] * at(qv, l);
        }
        for (std::size_t l = 0; l < nl; ++l) out[l] += w * tr[l] * sig[l] * spec.solar[l];
      });
  if (src.irradiance == nullptr || src.albedo <= 0.0 || !hits) return;
  const double dist = ray_sphere_near(x, view, src.grid.ground);
  if (dist < 0.0) return;
  const Vec3 gp = x + dist * view;
  std::vector<double>& e = qv;  // the ground's irradiance at the table wavelengths
  std::fill(e.begin(), e.end(), 0.0);
  add_irradiance(src.grid, *src.irradiance, nt, dot(gp, sun) / length(gp), src.albedo / kPi,
                 q0.data(), q1.data(), e.data());
  transmittance_of(spec, nc, last_t, tr);
  for (std::size_t l = 0; l < nl; ++l) out[l] += tr[l] * at(e, l) * spec.solar[l];
}

// Adds to `sum` the geometric remainder of the orders above the last: last r / (1 - r) with
// r = last / before at each entry (0 where `before` is 0; at most kMaxRemainderRatio).
template <class T>
void add_remainder(std::span<const T> last, std::span<const T> before, std::span<T> sum) {
  for (std::size_t x = 0; x < sum.size(); ++x) {
    const double r = before[x] > 0 ? std::clamp(static_cast<double>(last[x]) / before[x], 0.0,
                                                kMaxRemainderRatio)
                                   : 0.0;
    sum[x] += static_cast<T>(last[x] * r / (1.0 - r));
  }
}

// A table of `nl` wavelengths filled at every node (altitude row, direction, sun cosine) by
// radiance(node, out), on the library's threads.
template <class F>
NodeTable at_every_node(const Grid& grid, std::size_t nl, const F& radiance) {
  NodeTable table(nl);
  parallel_for(static_cast<std::size_t>(kNr) * kDirs * kNs, 64, [&](std::size_t b, std::size_t e) {
    std::vector<double> out(nl);
    for (std::size_t job = b; job < e; ++job) {
      const int i = static_cast<int>(job / (kDirs * kNs));
      const int d = static_cast<int>(job / kNs % kDirs), j = static_cast<int>(job % kNs);
      radiance(node_at(grid, i, d, j), out);
      float* dst = &table.v[table.row(i, d) + static_cast<std::size_t>(j) * nl];
      for (std::size_t x = 0; x < nl; ++x) dst[x] = static_cast<float>(out[x]);
    }
  });
  return table;
}

// The phase matrices per scattering component (of `components`) and altitude row.
std::vector<std::vector<std::vector<float>>> phase_matrices(
    const Grid& grid, const AtmosphereParameters& a, const std::vector<std::size_t>& components) {
  std::vector<std::vector<std::vector<float>>> p(components.size(),
                                                 std::vector<std::vector<float>>(kNr));
  parallel_for(components.size() * kNr, 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t job = b; job < e; ++job)
      p[job / kNr][job % kNr] =
          phase_matrix(grid, static_cast<int>(job % kNr), a.components[components[job / kNr]]);
  });
  return p;
}

ScatteringOrderTables compute_tables(const Atmosphere& atm, const std::vector<double>& lut_nm,
                                     OrderSettings settings) {
  const int orders = settings.computed;
  const double cpu0 = process_cpu_s();
  const AtmosphereParameters& a = atm.parameters();
  const std::size_t nl = lut_nm.size();
  const Grid grid{a.ground_radius_m, a.top_radius_m - a.ground_radius_m};
  const Spectral unit = make_spectral(a, lut_nm, std::vector<double>(nl, 1.0));
  ScatteringOrderTables t;
  t.wavelengths = nl;
  for (std::size_t c = 0; c < a.components.size(); ++c)
    if (a.components[c].scattering_per_m > 0.0) t.components.push_back(c);
  const std::size_t ncs = t.components.size();
  // Steps: L_1 with the phase matrices, then each order.
  report_progress(0, orders, "bruneton's tables: phase matrices, order 1");
  const auto p = phase_matrices(grid, a, t.components);
  // L_1: the single scattering (with the ground's reflection of the direct sun) at every node.
  NodeTable l = at_every_node(grid, nl, [&](const Node& n, std::vector<double>& out) {
    atm.single_scattering(n.x, n.view, n.sun, unit, out);
  });
  t.ground_irradiance.assign(static_cast<std::size_t>(kNs) * nl, 0.0);
  std::vector<NodeTable> q(ncs, NodeTable(nl)), sum(ncs, NodeTable(nl));
  // The orders before the last (the remainder's ratio).
  std::vector<NodeTable> q_before;
  std::vector<double> e_before;
  for (int n = 2; n <= orders; ++n) {
    // E_{n-1} and J_n = sum_c beta_c rho_c (P_c L_{n-1}).
    const std::vector<double> e = ground_irradiance(grid, l);
    for (std::size_t x = 0; x < e.size(); ++x) t.ground_irradiance[x] += e[x];
    if (settings.remainder && n == orders) q_before = q;
    for (std::size_t c = 0; c < ncs; ++c) {
      apply_phase(p[c], l, q[c]);
      for (std::size_t x = 0; x < q[c].v.size(); ++x) sum[c].v[x] += q[c].v[x];
    }
    if (n == orders) {
      // The orders above N: J from J_N / J_{N-1}, E from E_{N-1} / E_{N-2} (none for N = 2:
      // J_1 is not tabulated, and E_1 alone has no ratio).
      if (settings.remainder && n >= 3) {
        for (std::size_t c = 0; c < ncs; ++c) add_remainder<float>(q[c].v, q_before[c].v, sum[c].v);
        add_remainder<double>(e, e_before, t.ground_irradiance);
      }
      break;
    }
    e_before = e;
    report_progress(n - 1, orders, fmt::format("bruneton's tables: order {}", n));
    // L_n at every node.
    RaySource src{grid, atm, t.components, {}, nl, &e, a.ground_albedo.value_or(0.0)};
    for (const NodeTable& qc : q) src.q.push_back(qc.v.data());
    l = at_every_node(grid, nl, [&](const Node& nd, std::vector<double>& out) {
      integrate_ray(src, nd.x, nd.view, nd.sun, kOrderTableRayNodes, unit, nullptr, out);
    });
  }
  for (NodeTable& s : sum) t.q.push_back(std::move(s.v));
  t.cpu_seconds = process_cpu_s() - cpu0;
  report_progress(
      orders, orders,
      fmt::format("bruneton's tables: {}, {:.1f} s CPU", settings.text(), t.cpu_seconds));
  return t;
}

// The tables' file form (io/table_cache.h): components, wavelengths, Q_c per component, the
// ground's irradiance, the precomputation's CPU time. The file key holds everything the tables
// depend on: the atmosphere's key with the orders, the wavelengths, the grid's sizes and this
// code's version (kTablesVersion: raised when the computation changes).
constexpr int kTablesVersion = 1;

std::string file_key(const std::string& key, const std::vector<double>& lut_nm) {
  std::string k = fmt::format("bruneton tables {} skylight {} | grid {} {} {} {} {} {} {:a} |",
                              kTablesVersion, kVersion, kNr, kNs, kNmu, kNphi, kOrderTableRayNodes,
                              kOrderTablePhaseSubsamples, kDarkDips);
  for (const double nm : lut_nm) k += fmt::format(" {:a}", nm);
  return k + " | " + key;
}

template <class T>
void append(std::vector<char>& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.insert(out.end(), reinterpret_cast<const char*>(&n), reinterpret_cast<const char*>(&n + 1));
  out.insert(out.end(), reinterpret_cast<const char*>(v.data()),
             reinterpret_cast<const char*>(v.data() + v.size()));
}
template <class T>
bool take(std::span<const char>& in, std::vector<T>& v) {
  std::uint64_t n = 0;
  if (in.size() < sizeof n) return false;
  std::memcpy(&n, in.data(), sizeof n);
  in = in.subspan(sizeof n);
  if (n > in.size() / sizeof(T)) return false;
  v.resize(n);
  std::memcpy(v.data(), in.data(), n * sizeof(T));
  in = in.subspan(n * sizeof(T));
  return true;
}

std::vector<char> serialise(const ScatteringOrderTables& t) {
  std::vector<char> out;
  append(out, std::vector<std::uint64_t>(t.components.begin(), t.components.end()));
  append(out, std::vector<double>{static_cast<double>(t.wavelengths), t.cpu_seconds});
  for (const auto& q : t.q) append(out, q);
  append(out, t.ground_irradiance);
  return out;
}

// The tables of a file's payload, if its sizes are those of `expected` (the grid's, the
// wavelengths').
std::optional<ScatteringOrderTables> deserialise(std::span<const char> in, std::size_t wavelengths,
                                                 std::size_t components) {
  ScatteringOrderTables t;
  std::vector<std::uint64_t> c;
  std::vector<double> sizes;
  if (!take(in, c) || c.size() != components || !take(in, sizes) || sizes.size() != 2 ||
      sizes[0] != static_cast<double>(wavelengths))
    return std::nullopt;
  t.components.assign(c.begin(), c.end());
  t.wavelengths = wavelengths;
  t.cpu_seconds = sizes[1];
  t.q.resize(components);
  const std::size_t table = static_cast<std::size_t>(kNr) * kDirs * kNs * wavelengths;
  for (auto& q : t.q)
    if (!take(in, q) || q.size() != table) return std::nullopt;
  if (!take(in, t.ground_irradiance) ||
      t.ground_irradiance.size() != static_cast<std::size_t>(kNs) * wavelengths || !in.empty())
    return std::nullopt;
  for (const auto& q : t.q)
    for (const float v : q)
      if (!std::isfinite(v)) return std::nullopt;
  return t;
}

AtmosphereTableCache<ScatteringOrderTables>& tables_cache() {
  static AtmosphereTableCache<ScatteringOrderTables> cache;
  return cache;
}

}  // namespace

std::string OrderSettings::text() const {
  return fmt::format("{} orders{}", computed, remainder ? " and the geometric remainder" : "");
}

std::string order_tables_key(const Atmosphere& atm, OrderSettings orders) {
  return atmosphere_key(atm.parameters()) + " " + orders.text();
}

ScatteringOrderTables load_or_compute_order_tables(const Atmosphere& atm,
                                                   const std::vector<double>& lut_nm,
                                                   OrderSettings settings) {
  const int orders = settings.computed;
  const std::string fk = file_key(order_tables_key(atm, settings), lut_nm);
  const auto file = io::table_cache_file("bruneton", fk);
  std::size_t components = 0;
  for (const auto& c : atm.parameters().components) components += c.scattering_per_m > 0.0;
  if (file)
    if (const auto payload = io::read_cached_table(*file, fk))
      if (auto t = deserialise(*payload, lut_nm.size(), components)) {
        report_progress(orders, orders, "bruneton's tables: read from the table cache");
        return std::move(*t);
      }
  ScatteringOrderTables t = compute_tables(atm, lut_nm, settings);
  if (file) io::write_cached_table(*file, fk, serialise(t));
  return t;
}

std::shared_ptr<const ScatteringOrderTables> shared_order_tables(const Atmosphere& atm,
                                                                 const std::vector<double>& nm,
                                                                 OrderSettings orders) {
  return tables_cache().get(file_key(order_tables_key(atm, orders), nm),
                            [&] { return load_or_compute_order_tables(atm, nm, orders); });
}

void orders_along_ray(const ScatteringOrderTables& tables, const Atmosphere& atm, Vec3 x, Vec3 view,
                      Vec3 sun, int ray_nodes_per_piece, const Spectral& spec,
                      const std::vector<WavelengthWeight>* weights, std::span<double> out) {
  const AtmosphereParameters& a = atm.parameters();
  const Grid grid{a.ground_radius_m, a.top_radius_m - a.ground_radius_m};
  RaySource src{grid,
                atm,
                tables.components,
                {},
                tables.wavelengths,
                &tables.ground_irradiance,
                a.ground_albedo.value_or(0.0)};
  for (const auto& qc : tables.q) src.q.push_back(qc.data());
  integrate_ray(src, x, view, sun, ray_nodes_per_piece, spec, weights, out);
}

}  // namespace skylight::atmosphere
