#include "skylight/daylight/plane_sky.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/math.h"

namespace skylight::daylight {
namespace {

// A cell's bounds: zenith angles theta0 < theta1, azimuths phi0 < phi1 [rad].
struct CellBounds {
  double theta0, theta1, phi0, phi1;
};

CellBounds bounds_of(const SkyGrid& g, std::size_t i) {
  const int sectors = g.spec().sectors;
  const auto r = static_cast<std::size_t>(i / static_cast<std::size_t>(sectors));
  const auto s = static_cast<double>(i % static_cast<std::size_t>(sectors));
  const double dphi = 2.0 * kPi / sectors;
  return {g.theta_edges()[r], g.theta_edges()[r + 1], s * dphi, (s + 1.0) * dphi};
}

Vec3 at(double theta, double phi) {
  return direction_from_angles(theta, phi);
}

// The closed form of the integral of n.w over a cell (valid where n.w >= 0 on the whole cell):
// n_x S (cos phi0 - cos phi1) + n_y S (sin phi1 - sin phi0) + n_z (sin^2 theta1 - sin^2 theta0)/2
// (phi1 - phi0), with S = [(theta - sin theta cos theta)/2] from theta0 to theta1.
double exact_weight(const CellBounds& c, Vec3 n) {
  const auto s2 = [](double t) { return 0.5 * (t - std::sin(t) * std::cos(t)); };
  const double S = s2(c.theta1) - s2(c.theta0);
  const double st0 = std::sin(c.theta0), st1 = std::sin(c.theta1);
  return n.x * S * (std::cos(c.phi0) - std::cos(c.phi1)) +
         n.y * S * (std::sin(c.phi1) - std::sin(c.phi0)) +
         n.z * 0.5 * (st1 * st1 - st0 * st0) * (c.phi1 - c.phi0);
}

// The sign of n.w over a cell from 9 points (corners, edge midpoints, centre): +1 in front
// everywhere, -1 behind everywhere, 0 crossed by the plane's horizon.
int plane_side(const CellBounds& c, Vec3 n) {
  bool pos = false, neg = false;
  for (double t : {c.theta0, 0.5 * (c.theta0 + c.theta1), c.theta1})
    for (double p : {c.phi0, 0.5 * (c.phi0 + c.phi1), c.phi1}) {
      const double d = dot(n, at(t, p));
      (d > 0.0 ? pos : neg) = true;
    }
  return pos && !neg ? 1 : (neg && !pos ? -1 : 0);
}

// The skyline's lowest and highest elevation [rad] over [phi0, phi1].
std::array<double, 2> skyline_range(const io::HorizonProfile& h, double phi0, double phi1) {
  const double e0 = h.elevation(phi0), e1 = h.elevation(phi1);
  double lo = std::min(e0, e1), hi = std::max(e0, e1);
  for (const auto& p : h.points()) {
    const double a = deg_to_rad(p.azimuth_deg);
    if (a > phi0 && a < phi1) {
      lo = std::min(lo, deg_to_rad(p.elevation_deg));
      hi = std::max(hi, deg_to_rad(p.elevation_deg));
    }
  }
  return {lo, hi};
}

// +1: the cell lies wholly above the skyline; -1: wholly below; 0: the skyline crosses it.
int skyline_side(const CellBounds& c, const io::HorizonProfile& h) {
  if (h.flat()) return 1;
  const auto [lo, hi] = skyline_range(h, c.phi0, c.phi1);
  const double low = 0.5 * kPi - c.theta1, high = 0.5 * kPi - c.theta0;
  if (low >= hi) return 1;
  if (high <= lo) return -1;
  return 0;
}

// K x K midpoints of a cell: the sum of max(0, n.w) [open] dw.
double subdivide(const CellBounds& c, Vec3 n, const io::HorizonProfile* horizon, int k) {
  double out = 0.0;
  const double dt = (c.theta1 - c.theta0) / k, dp = (c.phi1 - c.phi0) / k;
  for (int a = 0; a < k; ++a) {
    const double t0 = c.theta0 + a * dt, t1 = t0 + dt;
    const double omega = (std::cos(t0) - std::cos(t1)) * dp;
    for (int b = 0; b < k; ++b) {
      const Vec3 w = at(0.5 * (t0 + t1), c.phi0 + (b + 0.5) * dp);
      const double d = dot(n, w);
      if (d <= 0.0 || (horizon && !horizon->open(w))) continue;
      out += omega * d;
    }
  }
  return out;
}

// A cell wholly in front of the plane that the skyline crosses: k columns of azimuth, each
// integrated in closed form from theta0 down to the skyline at the column's middle azimuth.
double skyline_columns(const CellBounds& c, Vec3 n, const io::HorizonProfile& horizon, int k) {
  double out = 0.0;
  const double dp = (c.phi1 - c.phi0) / k;
  for (int b = 0; b < k; ++b) {
    const double p0 = c.phi0 + b * dp;
    const double theta_sky = 0.5 * kPi - horizon.elevation(p0 + 0.5 * dp);
    if (theta_sky <= c.theta0) continue;
    out += exact_weight({c.theta0, std::min(c.theta1, theta_sky), p0, p0 + dp}, n);
  }
  return out;
}

// A cell's weight for normal n through `horizon` (nullptr: flat).
double cell_weight(const CellBounds& c, Vec3 n, const io::HorizonProfile* horizon, int k) {
  const int plane = plane_side(c, n);
  const int sky = horizon ? skyline_side(c, *horizon) : 1;
  if (plane < 0 || sky < 0) return 0.0;
  if (plane > 0 && sky > 0) return exact_weight(c, n);
  if (plane > 0) return skyline_columns(c, n, *horizon, k);
  return subdivide(c, n, sky > 0 ? nullptr : horizon, k);
}

}  // namespace

Vec3 Plane::normal() const {
  const double sb = std::sin(tilt);
  return {sb * std::sin(azimuth), sb * std::cos(azimuth), std::cos(tilt)};
}

SkyGrid::SkyGrid(const SkyGridSpec& spec) : spec_(spec) {
  SKYLIGHT_CHECK(
      spec.band_rings > 0 && spec.upper_rings > 0 && spec.sectors >= 4 && spec.subdivision > 0,
      "a sky grid needs rings, sectors and a subdivision");
  // Elevation edges from the zenith down: the upper rings, then the band's.
  const double band = kHorizonBandHeight, upper = 0.5 * kPi - band;
  for (int r = 0; r <= spec.upper_rings; ++r) theta_edges_.push_back(upper * r / spec.upper_rings);
  for (int r = 1; r <= spec.band_rings; ++r)
    theta_edges_.push_back(upper + band * r / spec.band_rings);
  theta_edges_.back() = 0.5 * kPi;
  const std::size_t n = static_cast<std::size_t>(rings()) * static_cast<std::size_t>(spec.sectors);
  centre_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const CellBounds c = bounds_of(*this, i);
    const Vec3 m = at(0.5 * (c.theta0 + c.theta1), 0.5 * (c.phi0 + c.phi1));
    centre_.push_back(m);
    x_.push_back(static_cast<float>(m.x));
    y_.push_back(static_cast<float>(m.y));
    z_.push_back(static_cast<float>(m.z));
    double r = 0.0;
    for (double t : {c.theta0, c.theta1})
      for (double p : {c.phi0, c.phi1}) r = std::max(r, angle_between(m, at(t, p)));
    radius_.push_back(r);
    cos_inside_.push_back(r < kCircumsolarHalfAngle ? std::cos(kCircumsolarHalfAngle - r) : 2.0);
    cos_outside_.push_back(std::cos(std::min(kPi, kCircumsolarHalfAngle + r)));
    const double s0 = std::sin(c.theta0), s1 = std::sin(c.theta1);
    horizontal_.push_back(0.5 * (s1 * s1 - s0 * s0) * (c.phi1 - c.phi0));
    const double dt = (c.theta1 - c.theta0) / kShareSubdivision;
    const double dp = (c.phi1 - c.phi0) / kShareSubdivision;
    for (int a = 0; a < kShareSubdivision; ++a)
      for (int b = 0; b < kShareSubdivision; ++b) {
        const Vec3 d = at(c.theta0 + (a + 0.5) * dt, c.phi0 + (b + 0.5) * dp);
        share_x_.push_back(static_cast<float>(d.x));
        share_y_.push_back(static_cast<float>(d.y));
        share_z_.push_back(static_cast<float>(d.z));
      }
    if (i % static_cast<std::size_t>(spec.sectors) == 0)
      for (int a = 0; a < kShareSubdivision; ++a)
        share_omega_.push_back((std::cos(c.theta0 + a * dt) - std::cos(c.theta0 + (a + 1) * dt)) *
                               dp);
  }
}

Vec3 SkyGrid::share_direction(std::size_t i, std::size_t j) const {
  const std::size_t k = i * kShareSamples + j;
  return {share_x_[k], share_y_[k], share_z_[k]};
}

double SkyGrid::share_solid_angle(std::size_t i, std::size_t j) const {
  const std::size_t ring = i / static_cast<std::size_t>(spec_.sectors);
  return share_omega_[ring * kShareSubdivision + j / kShareSubdivision];
}

bool SkyGrid::in_band(std::size_t i) const {
  return i / static_cast<std::size_t>(spec_.sectors) >= static_cast<std::size_t>(spec_.upper_rings);
}

const SkyGrid& default_sky_grid() {
  static const SkyGrid grid;
  return grid;
}

PlaneWeights plane_weights(const SkyGrid& grid, const Plane& plane,
                           const io::HorizonProfile& horizon) {
  PlaneWeights w;
  w.grid = &grid;
  w.plane = plane;
  w.horizon = &horizon;
  const Vec3 n = plane.normal();
  const int k = grid.spec().subdivision;
  w.plane_weight.resize(grid.size());
  w.horizontal_weight.resize(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const CellBounds c = bounds_of(grid, i);
    w.plane_weight[i] = cell_weight(c, n, &horizon, k);
    w.horizontal_weight[i] =
        horizon.flat() ? grid.horizontal_weight(i) : cell_weight(c, {0, 0, 1}, &horizon, k);
    if (grid.in_band(i))
      w.band_flat += horizon.flat() ? w.plane_weight[i] : cell_weight(c, n, nullptr, k);
  }
  w.share_weight.resize(grid.size() * kShareSamples);
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (w.plane_weight[i] <= 0.0) continue;
    for (std::size_t j = 0; j < kShareSamples; ++j) {
      const Vec3 d = grid.share_direction(i, j);
      const double c = dot(n, d);
      if (c > 0.0 && horizon.open(d))
        w.share_weight[i * kShareSamples + j] =
            static_cast<float>(c * grid.share_solid_angle(i, j));
    }
  }
  return w;
}

HorizonViews horizon_views(const PlaneWeights& w) {
  HorizonViews v;
  if (w.horizon->flat()) {
    v.sky_view = 0.5 * (1.0 + std::cos(w.plane.tilt));
    return v;
  }
  double plane = 0.0, horizontal = 0.0, band = 0.0;
  for (std::size_t i = 0; i < w.plane_weight.size(); ++i) {
    plane += w.plane_weight[i];
    horizontal += w.horizontal_weight[i];
    if (w.grid->in_band(i)) band += w.plane_weight[i];
  }
  v.sky_view = plane / kPi;
  v.horizontal_view = horizontal / kPi;
  v.band_open = w.band_flat > 0.0 ? band / w.band_flat : 1.0;
  return v;
}

SkyParts integrate_sky(const PlaneWeights& w, const std::vector<float>& L, Vec3 sun) {
  const SkyGrid& g = *w.grid;
  SKYLIGHT_CHECK(L.size() == g.size(), "one sky value per grid cell");
  SkyParts p;
  const double cos_circle = std::cos(kCircumsolarHalfAngle);
  const double sin_circle = std::sin(kCircumsolarHalfAngle);
  double band = 0.0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const double Li = L[i];
    p.horizontal_open += Li * w.horizontal_weight[i];
    p.horizontal_flat += Li * g.horizontal_weight(i);
    const double wi = w.plane_weight[i];
    if (wi <= 0.0) continue;
    p.total += Li * wi;
    // The circumsolar share of the cell: whole within the circle, none beyond, else subdivided.
    const double c = dot(g.centre(i), sun);
    double share = 0.0;
    if (c >= g.circumsolar_inside(i)) {
      share = 1.0;
    } else if (c > g.circumsolar_outside(i)) {
      double all = 0.0, inside = 0.0;
      // Each sample counts with the share of its own extent inside the circle, from its
      // centre's distance to the circle (to first order, (cos gamma - cos 25 deg) / sin 25 deg)
      // over its size: a sample the circle halves counts half.
      for (std::size_t j = 0; j < kShareSamples; ++j) {
        const double sw = w.share_weight[i * kShareSamples + j];
        if (sw <= 0.0) continue;
        all += sw;
        const double inside_by = (dot(g.share_direction(i, j), sun) - cos_circle) / sin_circle;
        const double size = std::sqrt(g.share_solid_angle(i, j));
        inside += sw * std::clamp(0.5 + inside_by / size, 0.0, 1.0);
      }
      share = all > 0.0 ? inside / all : 0.0;
    }
    p.circumsolar += Li * wi * share;
    if (g.in_band(i)) band += Li * wi * (1.0 - share);
  }
  p.horizon = band;
  p.rest = p.total - p.circumsolar - p.horizon;
  return p;
}

std::vector<float> sky_luminance_on_grid(const SkyModel& model, const SkyGrid& grid) {
  const std::size_t n = grid.size();
  std::vector<float> X(n), Y(n), Z(n);
  tristimulus_parallel(model, {grid.x(), grid.y(), grid.z()}, {X, Y, Z});
  for (float& v : Y) v = std::max(v, 0.0f);
  return Y;
}

double sun_disc_on_plane(const SkyModel& model, Vec3 normal, const io::HorizonProfile& horizon,
                         const std::function<double(Vec3)>& radiance, int rings, int sectors) {
  if (!model.has_sun()) return 0.0;
  const double radius = model.sun_angular_radius();
  const Vec3 s = model.sun().direction();
  const Vec3 helper = std::abs(s.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 u = normalize(cross(helper, s)), v = cross(s, u);
  double e = 0.0;
  for (int i = 0; i < rings; ++i) {
    const double r0 = radius * i / rings, r1 = radius * (i + 1) / rings, rm = 0.5 * (r0 + r1);
    const double omega = (std::cos(r0) - std::cos(r1)) * 2.0 * kPi / sectors;
    for (int j = 0; j < sectors; ++j) {
      const double a = 2.0 * kPi * (j + 0.5) / sectors;
      const Vec3 d =
          normalize(std::cos(rm) * s + std::sin(rm) * (std::cos(a) * u + std::sin(a) * v));
      const double c = dot(normal, d);
      if (c <= 0.0 || !horizon.open(d)) continue;
      e += radiance(d) * c * omega;
    }
  }
  return e;
}

double sun_on_plane(const SkyModel& model, Vec3 normal, const io::HorizonProfile& horizon) {
  return sun_disc_on_plane(model, normal, horizon,
                           [&](Vec3 d) { return model.sun_tristimulus(d).Y; });
}

}  // namespace skylight::daylight
