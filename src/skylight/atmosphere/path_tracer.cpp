#include "skylight/atmosphere/path_tracer.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"
#include "skylight/core/random.h"

namespace skylight::atmosphere {

double sample_rayleigh(double u) {
  // CDF of 3/8 (1 + mu^2) on [-1, 1]: (mu^3 + 3 mu + 4) / 8 = u, i.e. mu^3 + 3 mu - 2 q = 0 with
  // q = 4 u - 2; one real root (Cardano): mu = cbrt(q + sqrt(q^2 + 1)) + cbrt(q - sqrt(q^2 + 1)).
  const double q = 4.0 * u - 2.0;
  const double w = std::sqrt(q * q + 1.0);
  return std::clamp(std::cbrt(q + w) + std::cbrt(q - w), -1.0, 1.0);
}

double sample_henyey_greenstein(double u, double g) {
  if (std::abs(g) < 1e-6) return 2.0 * u - 1.0;
  const double t = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
  return std::clamp((1.0 + g * g - t * t) / (2.0 * g), -1.0, 1.0);
}

namespace {

// Paths per chunk: each chunk has its own generator (seeded from the settings' seed, the
// wavelength and the chunk), so the result does not depend on the thread count.
constexpr std::uint64_t kChunkPaths = 1024;
// A new segment starts this far [m] from the surface point it leaves (the ground's curvature and
// rounding would otherwise let it hit the sphere again at distance ~0).
constexpr double kSurfaceOffset = 1e-3;

// A unit vector with cosine mu to `axis` and a uniform azimuth about it.
Vec3 around(Vec3 axis, double mu, double phi) {
  const Vec3 helper = std::abs(axis.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 t = normalize(cross(helper, axis));
  const Vec3 b = cross(axis, t);
  const double s = safe_sqrt(1.0 - mu * mu);
  return normalize(s * std::cos(phi) * t + s * std::sin(phi) * b + mu * axis);
}

// Distance along p + s d (|d| = 1) to where it meets the ground going down, or +inf. A point on
// the ground looking below its horizon meets it at 0.
double ground_distance(Vec3 p, Vec3 d, double R0) {
  const double b = dot(p, d);
  if (b >= 0) return std::numeric_limits<double>::infinity();  // moving away from the centre
  const double c = dot(p, p) - R0 * R0;
  const double disc = b * b - c;
  if (disc < 0) return std::numeric_limits<double>::infinity();
  return std::max(0.0, -b - std::sqrt(disc));
}

// A real collision found by delta tracking on the segment from x along d: its point, the
// scattering of each component there and the total extinction.
struct Collision {
  bool found = false;
  Vec3 y{};
  std::array<double, kMaxComponents> sigma_s{};
  double sigma_s_total = 0.0, sigma_e = 0.0;
};

struct Tracer {
  const AtmosphereParameters& p;
  const Atmosphere& atm;
  // One Spectral per wavelength (each leg is traced and evaluated at one wavelength).
  const std::vector<Spectral>& single;
  const PathTracerSettings& s;
  std::size_t nc;

  // Delta tracking to the first real collision on [.., end) of the ray x + t d at wavelength l;
  // `end` is where the ray leaves the atmosphere or meets the ground.
  Collision collide(Vec3 x, Vec3 d, double t, double end, std::size_t l, SplitMix64& rng) const {
    const Spectral& one = single[l];
    double sigma_bar = 0.0;  // every density is <= 1
    for (std::size_t i = 0; i < nc; ++i) sigma_bar += one.extinction[i][0];
    Collision c;
    if (sigma_bar <= 0) return c;
    while (true) {
      t -= std::log(1.0 - rng.uniform()) / sigma_bar;
      if (t >= end) return c;
      c.y = x + t * d;
      const double h = length(c.y) - p.ground_radius_m;
      c.sigma_e = c.sigma_s_total = 0.0;
      for (std::size_t i = 0; i < nc; ++i) {
        const double rho = p.components[i].density(h);
        c.sigma_s[i] = rho * one.scattering[i][0];
        c.sigma_s_total += c.sigma_s[i];
        c.sigma_e += rho * one.extinction[i][0];
      }
      if (rng.uniform() * sigma_bar < c.sigma_e) {
        c.found = true;
        return c;
      }
    }
  }

  // The next direction after scattering at c coming along d: a component by its share of the
  // scattering, its phase function sampled; multiplies `weight` by the sampling's weight.
  Vec3 scatter(const Collision& c, Vec3 d, double& weight, SplitMix64& rng) const {
    double pick = rng.uniform() * c.sigma_s_total;
    std::size_t k = 0;
    while (k + 1 < nc && pick >= c.sigma_s[k]) pick -= c.sigma_s[k++];
    const Component& comp = p.components[k];
    double mu = 0.0;
    switch (comp.phase) {
      case PhaseKind::rayleigh:
        mu = sample_rayleigh(rng.uniform());
        break;
      case PhaseKind::henyey_greenstein:
        mu = sample_henyey_greenstein(rng.uniform(), comp.g);
        break;
      case PhaseKind::cornette_shanks:
        mu = sample_henyey_greenstein(rng.uniform(), comp.g);
        weight *= 3.0 * (1.0 + mu * mu) / (2.0 * (2.0 + comp.g * comp.g));
        break;
    }
    return around(d, mu, 2.0 * kPi * rng.uniform());
  }

  // exp(-optical depth) from y to the sun at wavelength l by quadrature; 0 in the planet's shadow.
  double sun_transmittance(Vec3 y, Vec3 sun, std::size_t l) const {
    const double r = length(y);
    const double mu = dot(y, sun) / r;
    double tau = 0.0;
    for (std::size_t i = 0; i < nc; ++i) {
      const double t = optical_length_quadrature(std::min(r, p.top_radius_m), mu, p.components[i],
                                                 p.ground_radius_m, p.top_radius_m, s.sun_steps);
      if (!std::isfinite(t)) return 0.0;
      tau += single[l].extinction[i][0] * t;
    }
    return std::exp(-tau);
  }

  // One path at wavelength l: adds its estimate of orders 2 .. max_orders (segment estimator) or
  // 1 .. max_orders (collision estimator) to `orders` (index order - 1); returns whether it was
  // cut at max_orders.
  bool trace(Vec3 x, Vec3 d, Vec3 sun, std::size_t l, SplitMix64& rng,
             std::vector<double>& orders) const {
    const double R0 = p.ground_radius_m, Rt = p.top_radius_m;
    const bool segments = s.estimator == PathEstimator::segments;
    const double E0 = single[l].solar[0];
    double weight = 1.0;
    for (int order = segments ? 1 : 0; order < s.max_orders;) {
      const double leave = ray_sphere_far(x, d, Rt);
      if (leave <= 0) return false;  // outside, looking away from the atmosphere
      const double ground = ground_distance(x, d, R0);
      const Collision c =
          collide(x, d, std::max(0.0, ray_sphere_near(x, d, Rt)), std::min(leave, ground), l, rng);
      if (c.found) {
        if (c.sigma_s_total <= 0) return false;  // a purely absorbing point: the path ends
        weight *= c.sigma_s_total / c.sigma_e;
        if (!segments) {
          // Next-event estimation toward the sun at the collision.
          ++order;
          double ph = 0.0;
          for (std::size_t i = 0; i < nc; ++i)
            ph += c.sigma_s[i] * phase(p.components[i], dot(d, sun));
          const double Ts = sun_transmittance(c.y, sun, l);
          orders[static_cast<std::size_t>(order - 1)] += weight * E0 * Ts * ph / c.sigma_s_total;
        }
        d = scatter(c, d, weight, rng);
        x = c.y;
      } else {
        if (ground > leave || !p.ground_albedo) return false;  // escaped, or a black ground
        const Vec3 g = x + ground * d;
        const Vec3 n = normalize(g);
        if (!segments) {
          // The ground's reflection of the direct sun.
          ++order;
          const double cos_sun = dot(n, sun);
          if (cos_sun > 0)
            orders[static_cast<std::size_t>(order - 1)] +=
                weight * E0 * sun_transmittance(g, sun, l) * *p.ground_albedo / kPi * cos_sun;
        }
        // A cosine-weighted bounce (weight: the albedo).
        weight *= *p.ground_albedo;
        if (weight <= 0) return false;
        d = around(n, std::sqrt(rng.uniform()), 2.0 * kPi * rng.uniform());
        x = g + kSurfaceOffset * n;
      }
      if (segments) {
        // The sun's single scattering (and the ground's reflection of it) along the new leg: the
        // radiance of one more order.
        ++order;
        double leg = 0.0;
        atm.single_scattering(x, d, sun, single[l], std::span<double>(&leg, 1));
        orders[static_cast<std::size_t>(order - 1)] += weight * leg;
      }
    }
    return true;
  }
};

// Per chunk and wavelength: sums of each order's estimate and of its square, of the total and of
// its square, and the truncated paths.
struct Sums {
  std::vector<double> order, order2;
  double total = 0, total2 = 0, truncated = 0;
};

// One job's paths (a chunk at one wavelength of nl) from `position` along v with the sun along sn,
// summed into `out`; `orders` is the buffer of one path's estimates.
void trace_job(const Tracer& tracer, const PathTracerSettings& settings, Vec3 position, Vec3 v,
               Vec3 sn, std::size_t job, std::size_t nl, std::vector<double>& orders, Sums& out) {
  const std::size_t no = static_cast<std::size_t>(settings.max_orders);
  const std::uint64_t chunk = job / nl;
  const std::size_t l = job % nl;
  SplitMix64 seeder(settings.seed * 0x9e3779b97f4a7c15ULL + job);
  SplitMix64 rng(seeder.next() ^ (chunk << 20) ^ l);
  out.order.assign(no, 0.0);
  out.order2.assign(no, 0.0);
  const std::uint64_t first = chunk * kChunkPaths;
  const std::uint64_t last = std::min(settings.paths, first + kChunkPaths);
  for (std::uint64_t k = first; k < last; ++k) {
    std::fill(orders.begin(), orders.end(), 0.0);
    out.truncated += tracer.trace(position, v, sn, l, rng, orders) ? 1.0 : 0.0;
    double total = 0.0;
    for (std::size_t o = 0; o < no; ++o) {
      total += orders[o];
      out.order[o] += orders[o];
      out.order2[o] += orders[o] * orders[o];
    }
    out.total += total;
    out.total2 += total * total;
  }
}

// The sums of all chunks at wavelength l (of nl), added in chunk order.
Sums wavelength_sums(const std::vector<Sums>& sums, std::uint64_t chunks, std::size_t nl,
                     std::size_t l, std::size_t no) {
  Sums all;
  all.order.assign(no, 0.0);
  all.order2.assign(no, 0.0);
  for (std::uint64_t c = 0; c < chunks; ++c) {
    const Sums& s = sums[c * nl + l];
    all.total += s.total;
    all.total2 += s.total2;
    all.truncated += s.truncated;
    for (std::size_t o = 0; o < no; ++o) {
      all.order[o] += s.order[o];
      all.order2[o] += s.order2[o];
    }
  }
  return all;
}

// The mean and its standard error from a sum and a sum of squares over n paths.
std::pair<double, double> moments(double sum, double sum2, double n) {
  const double mean = sum / n;
  const double var = std::max(0.0, (sum2 / n - mean * mean) * n / (n - 1.0));
  return std::pair{mean, std::sqrt(var / n)};
}

}  // namespace

PathTracerResult path_trace(const AtmosphereParameters& p, Vec3 position, Vec3 view, Vec3 sun,
                            const Spectral& spec, const PathTracerSettings& settings) {
  p.validate();
  if (settings.paths < 2 || settings.max_orders < 1 || settings.max_orders > 1000 ||
      settings.sun_steps < 1)
    throw InvalidArgument(
        fmt::format("path tracer: paths {} (>= 2), max_orders {} (1 .. 1000), sun_steps {} (>= 1)",
                    settings.paths, settings.max_orders, settings.sun_steps));
  if (length(position) < p.ground_radius_m * (1.0 - 1e-12))
    throw InvalidArgument("path tracer: the observer is below the ground");
  const std::size_t nl = spec.nm.size(), no = static_cast<std::size_t>(settings.max_orders);
  const Atmosphere atm(p);
  std::vector<Spectral> single;
  for (std::size_t l = 0; l < nl; ++l)
    single.push_back(make_spectral(p, std::span<const double>(&spec.nm[l], 1),
                                   std::span<const double>(&spec.solar[l], 1)));
  const Tracer tracer{p, atm, single, settings, p.components.size()};
  const std::uint64_t chunks = (settings.paths + kChunkPaths - 1) / kChunkPaths;
  // Per chunk and wavelength: sums of each order's estimate and of its square, of the total and
  // of its square, and the truncated paths (summed in chunk order below: thread-independent).
  std::vector<Sums> sums(chunks * nl);
  const Vec3 v = normalize(view), sn = normalize(sun);
  parallel_for(chunks * nl, 1, [&](std::size_t b, std::size_t e) {
    std::vector<double> orders(no);
    for (std::size_t job = b; job < e; ++job)
      trace_job(tracer, settings, position, v, sn, job, nl, orders, sums[job]);
  });
  PathTracerResult r;
  r.paths = settings.paths;
  const double n = static_cast<double>(settings.paths);
  r.radiance.assign(nl, 0.0);
  r.standard_error.assign(nl, 0.0);
  r.truncated_fraction.assign(nl, 0.0);
  r.order_radiance.assign(no, std::vector<double>(nl, 0.0));
  r.order_standard_error.assign(no, std::vector<double>(nl, 0.0));
  // Segments: order 1 is the brute-force single scattering (and the ground's reflection of the
  // direct sun), without noise.
  const bool segments = settings.estimator == PathEstimator::segments;
  if (segments) {
    ReferenceSettings rs;
    rs.sun_steps = settings.sun_steps;
    atm.single_scattering_reference(position, v, sn, spec, r.order_radiance[0], rs);
  }
  for (std::size_t l = 0; l < nl; ++l) {
    const Sums all = wavelength_sums(sums, chunks, nl, l, no);
    std::tie(r.radiance[l], r.standard_error[l]) = moments(all.total, all.total2, n);
    if (segments) r.radiance[l] += r.order_radiance[0][l];
    r.truncated_fraction[l] = all.truncated / n;
    for (std::size_t o = segments ? 1 : 0; o < no; ++o)
      std::tie(r.order_radiance[o][l], r.order_standard_error[o][l]) =
          moments(all.order[o], all.order2[o], n);
  }
  return r;
}

}  // namespace skylight::atmosphere
