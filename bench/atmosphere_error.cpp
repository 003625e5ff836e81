// The error of the multiple-scattering models against the Monte Carlo path tracer
// (docs/ATMOSPHERE.md): for each sun elevation, 10 view directions (zenith; elevations 45, 20,
// 5 deg at azimuths 0, 90 and 180, the sun at azimuth 180) and 450, 550,
// 650 nm, the relative error of `bruneton` (its default, converged orders), `hillaire` (and of
// `nishita`, single scattering, for scale) against path_trace (segments estimator, Earth defaults
// with 300 DU of ozone, black ground), over the cases whose path-traced standard error is below 0.5
// %. Prints the median, the 95th percentile and the maximum per sun elevation and over day (>= 10
// deg: sun zenith <= 80 deg), the low sun (3 deg) and twilight (< 0).
//
// `skylight_atmosphere_error orders VIEW_ZENITH SUN_ELEVATION VIEW_AZIMUTH [ALBEDO OZONE]` (deg;
// the sun at azimuth 180; the ground's albedo, 0: black; ozone [DU]) prints instead bruneton's
// orders 1-5 one by one against the path tracer's tallies (100 000 paths) at 450, 550 and 650 nm
// (with ALBEDO: 440, 550 and 680 nm). `truncation [PATHS]` and `day-set [PATHS] [ORDERS]`: below
// (docs/ATMOSPHERE.md, "Scattering orders").
// Observers on the ground and at 20 km.
//
// `skylight_atmosphere_error xyz` prints instead the spectral sampling's error (docs/ATMOSPHERE.md,
// "Spectral sampling"): X, Y, Z of nishita, hillaire and bruneton against a 5 nm trapezoid
// integration (380-780 nm) of each model's own spectral radiance, by day (sun 60, 45, 20, 5 deg)
// and at a low sun and in twilight (1, -1, -3, -5 deg), observers at 0 and 20 km, views at
// elevations 90, 30, 5, 1 deg and azimuths 0, 90, 180: the quadrature alone (the model's XYZ
// weights on its exact spectral radiance) and tristimulus() (with the sky-view LUT). Usage:
// skylight_atmosphere_error [PATHS (default 100000; twilight x 16)] [ORDERS (bruneton's
// --scattering-orders; 0 or none: its default, converged)] [CACHE.csv (the path tracer's results:
// read where a line has the case, else computed and appended; for comparing changes of the models
// on the same paths)]
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "skylight/atmosphere/path_tracer.h"
#include "skylight/core/colorimetry.h"
#include "skylight/core/math.h"
#include "skylight/models/bruneton.h"
#include "skylight/models/hillaire.h"
#include "skylight/models/nishita.h"

namespace {

using namespace skylight;

struct Errors {
  std::vector<double> bruneton, hillaire, nishita;
  int skipped = 0;
};

// Median, 95th percentile and maximum of relative errors, in % with `decimals`.
std::string stats(std::vector<double> e, int decimals = 2) {
  if (e.empty()) return "-";
  std::sort(e.begin(), e.end());
  return fmt::format("median {:5.{}f} %, p95 {:5.{}f} %, max {:6.{}f} % (n {})",
                     100 * e[e.size() / 2], decimals,
                     100 * e[static_cast<std::size_t>(0.95 * (e.size() - 1))], decimals,
                     100 * e.back(), decimals, e.size());
}

// The path tracer's radiance and standard error per wavelength of one case, from the cache file
// or computed (and appended to it).
struct Traced {
  std::vector<double> radiance, standard_error;
};
class TraceCache {
 public:
  explicit TraceCache(std::string path) : path_(std::move(path)) {
    if (path_.empty()) return;
    std::ifstream in(path_);
    std::string line;
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string key;
      std::getline(ls, key, ';');
      Traced t;
      double r = 0, e = 0;
      while (ls >> r >> e) {
        t.radiance.push_back(r);
        t.standard_error.push_back(e);
      }
      entries_[key] = t;
    }
  }
  template <class F>
  Traced get(const std::string& key, const F& trace) {
    if (const auto it = entries_.find(key); it != entries_.end()) return it->second;
    Traced t = trace();
    if (!path_.empty()) {
      std::ofstream out(path_, std::ios::app);
      out << key << ';';
      for (std::size_t l = 0; l < t.radiance.size(); ++l)
        out << fmt::format(" {:.17g} {:.17g}", t.radiance[l], t.standard_error[l]);
      out << '\n';
    }
    return entries_[key] = t;
  }

 private:
  std::string path_;
  std::map<std::string, Traced> entries_;
};

// The relative error of each of X, Y, Z, the largest of the three.
double xyz_error(const Xyz& a, const Xyz& b) {
  return std::max({std::abs(a.X / b.X - 1), std::abs(a.Y / b.Y - 1), std::abs(a.Z / b.Z - 1)});
}

int xyz_sampling() {
  struct Tally {
    std::vector<double> quadrature, tristimulus;
  };
  std::map<std::string, std::array<Tally, 2>> tallies;  // model -> day, twilight
  for (const double altitude : {0.0, 20000.0})
    for (const double sun_el : {60.0, 45.0, 20.0, 5.0, 1.0, -1.0, -3.0, -5.0}) {
      BrunetonParameters p;
      p.sun = {.zenith = deg_to_rad(90 - sun_el), .azimuth = deg_to_rad(180)};
      p.observer_altitude_m = altitude;
      const NishitaModel n(p);
      HillaireParameters hp;
      static_cast<NishitaParameters&>(hp) = p;
      const HillaireModel h(hp);
      const BrunetonModel b(p);
      const int set = sun_el >= 5.0 ? 0 : 1;
      for (const double el : {90.0, 30.0, 5.0, 1.0})
        for (const double az : {0.0, 90.0, 180.0}) {
          const Vec3 v = direction_from_angles(deg_to_rad(90 - el), deg_to_rad(az));
          const auto dense = [&](const SkyModel& m) {
            std::vector<double> nm, l;
            for (double x = 380; x <= 780; x += 5) {
              nm.push_back(x);
              l.push_back(*m.spectral_radiance(v, x));
            }
            return spectral_radiance_to_xyz(nm, l);
          };
          const Xyz dn = dense(n);
          tallies[fmt::format("nishita ({} CMF samples, {:g} nm)", kNishitaXyzCount,
                              kNishitaXyzStep)][set]
              .tristimulus.push_back(xyz_error(n.tristimulus(v), dn));
          for (const PhysicalSkyModel* m : {static_cast<const PhysicalSkyModel*>(&h),
                                            static_cast<const PhysicalSkyModel*>(&b)}) {
            const Xyz d = dense(*m);
            std::vector<double> at_nodes;
            for (const double x : m->xyz_spectral().nm)
              at_nodes.push_back(*m->spectral_radiance(v, x));
            Tally& t = tallies[fmt::format("{} ({} spline weights, {:g} nm)", m->name(),
                                           kPhysicalXyzCount, kPhysicalXyzStep)][set];
            t.quadrature.push_back(xyz_error(m->to_xyz(at_nodes), d));
            t.tristimulus.push_back(xyz_error(m->tristimulus(v), d));
          }
        }
    }
  for (const auto& [name, t] : tallies)
    for (int set = 0; set < 2; ++set)
      fmt::print("{:<40} {:<17} quadrature {:<50} tristimulus {}\n", name,
                 set == 0 ? "day" : "low sun, twilight", stats(t[set].quadrature, 3),
                 stats(t[set].tristimulus, 3));
  return 0;
}

// `truncation [PATHS]`: what the orders above N carry, from the path tracer's radiance by order
// (issue 45's set: 440, 550, 680 nm; observers at 0, 10, 50 and 100 km; ground albedo 0 and 0.3;
// ozone 0 and 300 DU; the sun at 60, 30 and 10 deg; the ten views), as a share of each case's
// radiance: the truncation error of N orders, and what is left after the orders above N are
// estimated as a geometric series from orders N - 1 and N (each node's ratio, as bruneton's
// converged default does: atmosphere/scattering_orders.h). Per wavelength and albedo, the
// median and maximum over the cases whose standard error is below 0.5 %.
int truncation(std::uint64_t paths) {
  const std::vector<double> nm{440, 550, 680};
  constexpr int kMaxN = 12;
  // [albedo][wavelength][N]: the shares cut, and left after the geometric estimate.
  std::map<double, std::array<std::array<std::vector<double>, kMaxN + 1>, 3>> cut, left;
  int skipped = 0;
  for (const double albedo : {0.0, 0.3})
    for (const double ozone : {0.0, 300.0})
      for (const double altitude : {0.0, 10000.0, 50000.0, 100000.0})
        for (const double sun_el : {60.0, 30.0, 10.0}) {
          NishitaParameters p;
          p.sun = {.zenith = deg_to_rad(90 - sun_el), .azimuth = deg_to_rad(180)};
          p.observer_altitude_m = altitude;
          if (albedo > 0) p.albedo = albedo;
          if (ozone > 0) p.ozone_du = ozone;
          const NishitaModel n(p);
          const auto spec = n.spectral_at(nm);
          atmosphere::PathTracerSettings s;
          s.paths = paths;
          for (const double el : {90.0, 45.0, 20.0, 5.0, -30.0})
            for (const double az : {0.0, 90.0, 180.0}) {
              if (std::abs(el) == 90 && az > 0) continue;
              const Vec3 v = direction_from_angles(deg_to_rad(90 - el), deg_to_rad(az));
              const auto r = atmosphere::path_trace(n.atmosphere().parameters(), n.observer(), v,
                                                    n.sun().direction(), spec, s);
              for (std::size_t l = 0; l < nm.size(); ++l) {
                if (!(r.radiance[l] > 0) || r.standard_error[l] > 0.005 * r.radiance[l]) {
                  ++skipped;
                  continue;
                }
                for (int N = 2; N <= kMaxN; ++N) {
                  double tail = 0;
                  for (std::size_t k = N; k < r.order_radiance.size(); ++k)
                    tail += r.order_radiance[k][l];
                  const double last = r.order_radiance[N - 1][l];
                  const double before = r.order_radiance[N - 2][l];
                  const double q = before > 0 ? std::clamp(last / before, 0.0, 0.95) : 0.0;
                  cut[albedo][l][N].push_back(tail / r.radiance[l]);
                  left[albedo][l][N].push_back(std::abs(tail - last * q / (1 - q)) / r.radiance[l]);
                }
              }
            }
        }
  const auto median_max = [](std::vector<double> e) {
    std::sort(e.begin(), e.end());
    return fmt::format("{:.2f}/{:.2f}", 100 * e[e.size() / 2], 100 * e.back());
  };
  fmt::print(
      "share of the radiance in the orders above N [%], median/max over the cases ({} "
      "wavelength-cases skipped: standard error above 0.5 %)\n",
      skipped);
  for (const auto& [albedo, by_nm] : cut)
    for (std::size_t l = 0; l < nm.size(); ++l) {
      fmt::print("albedo {:.1f} {} nm (n {}):\n  cut      ", albedo, nm[l], by_nm[l][2].size());
      for (int N = 3; N <= kMaxN; ++N) fmt::print(" N={:<2} {:<11}", N, median_max(by_nm[l][N]));
      fmt::print("\n  geometric");
      for (int N = 3; N <= kMaxN; ++N)
        fmt::print(" N={:<2} {:<11}", N, median_max(left.at(albedo)[l][N]));
      fmt::print("\n");
    }
  return 0;
}

// `day-set [PATHS] [ORDERS]`: bruneton (default orders; ORDERS > 0: exactly that many) against
// the path tracer over issue 45's day set (440, 550, 680 nm; observers at 0, 10, 50 and 100 km;
// ground albedo 0 and 0.3; ozone 0 and 300 DU; the sun at 60, 30 and 10 deg; views at elevations
// 90, 45, 20, 5 and -30 deg, azimuths 0, 90 and 180 from the sun's opposite): the signed relative
// error's median, 95th percentile and maximum of its size, per albedo and wavelength and over
// all, the worst cases, and the tables' set-up time, over the cases whose standard error is below
// 0.5 %.
int day_set(std::uint64_t paths, int orders) {
  const std::vector<double> nm{440, 550, 680};
  std::map<std::string, std::vector<double>> errors;
  std::vector<std::pair<double, std::string>> worst;
  int skipped = 0;
  for (const double albedo : {0.0, 0.3})
    for (const double ozone : {0.0, 300.0})
      for (const double altitude : {0.0, 10000.0, 50000.0, 100000.0})
        for (const double sun_el : {60.0, 30.0, 10.0}) {
          BrunetonParameters p;
          p.sun = {.zenith = deg_to_rad(90 - sun_el), .azimuth = deg_to_rad(180)};
          p.observer_altitude_m = altitude;
          p.albedo = albedo > 0 ? std::optional<double>(albedo) : std::nullopt;
          p.ozone_du = ozone > 0 ? std::optional<double>(ozone) : std::nullopt;
          if (orders > 0) p.scattering_orders = orders;
          const auto t0 = std::chrono::steady_clock::now();
          const BrunetonModel b(p);
          if (altitude == 0.0 && sun_el == 60.0)
            fmt::print(
                "albedo {} ozone {}: tables {:.1f} s CPU, {:.1f} s wall (with the LUT)\n", albedo,
                ozone, b.tables() ? b.tables()->cpu_seconds : 0.0,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
          const NishitaModel& n = b.single_scattering();
          const auto spec = n.spectral_at(nm);
          atmosphere::PathTracerSettings s;
          s.paths = paths;
          for (const double el : {90.0, 45.0, 20.0, 5.0, -30.0})
            for (const double az : {0.0, 90.0, 180.0}) {
              if (std::abs(el) == 90 && az > 0) continue;
              const Vec3 v = direction_from_angles(deg_to_rad(90 - el), deg_to_rad(az));
              const auto r = atmosphere::path_trace(n.atmosphere().parameters(), n.observer(), v,
                                                    n.sun().direction(), spec, s);
              for (std::size_t l = 0; l < nm.size(); ++l) {
                if (!(r.radiance[l] > 0) || r.standard_error[l] > 0.005 * r.radiance[l]) {
                  ++skipped;
                  continue;
                }
                const double e = *b.spectral_radiance(v, nm[l]) / r.radiance[l] - 1;
                errors[fmt::format("albedo {:.1f} {} nm", albedo, nm[l])].push_back(std::abs(e));
                errors["all"].push_back(std::abs(e));
                worst.emplace_back(
                    std::abs(e),
                    fmt::format("{:+.2f} % (path tracer +- {:.2f} %): {} nm, albedo {}, ozone {}, "
                                "observer {} km, sun {} deg, view elevation {} azimuth {}",
                                100 * e, 100 * r.standard_error[l] / r.radiance[l], nm[l], albedo,
                                ozone, altitude / 1000, sun_el, el, az));
              }
            }
        }
  for (const auto& [name, e] : errors) fmt::print("{:<20} {}\n", name, stats(e));
  std::sort(worst.rbegin(), worst.rend());
  for (std::size_t i = 0; i < std::min<std::size_t>(8, worst.size()); ++i)
    fmt::print("  {}\n", worst[i].second);
  fmt::print("{} wavelength-cases skipped (standard error above 0.5 %)\n", skipped);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t paths = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100000;
  const int orders = argc > 2 ? std::atoi(argv[2]) : 0;
  constexpr double kMaxStandardError = 0.005;
  constexpr double kShownError = 0.03;  // bruneton's cases above it are printed one by one
  Errors day, low, twilight;
  if (argc >= 5 && std::string(argv[1]) == "orders") {
    const std::vector<double> nm =
        argc > 5 ? std::vector<double>{440, 550, 680} : std::vector<double>{450, 550, 650};
    const double vz = std::atof(argv[2]), se = std::atof(argv[3]), az = std::atof(argv[4]);
    const Vec3 v = direction_from_angles(deg_to_rad(vz), deg_to_rad(az));
    std::vector<double> prev(3, 0.0);
    BrunetonParameters bp;
    bp.sun = {.zenith = deg_to_rad(90 - se), .azimuth = deg_to_rad(180)};
    if (argc > 5 && std::atof(argv[5]) > 0) bp.albedo = std::atof(argv[5]);
    if (argc > 6)
      bp.ozone_du =
          std::atof(argv[6]) > 0 ? std::optional<double>(std::atof(argv[6])) : std::nullopt;
    const BrunetonModel b1(bp);
    const auto spec = b1.single_scattering().spectral_at(nm);
    atmosphere::PathTracerSettings s;
    s.paths = 100000;
    const auto r =
        atmosphere::path_trace(b1.single_scattering().atmosphere().parameters(),
                               b1.single_scattering().observer(), v, b1.sun().direction(), spec, s);
    for (int n = 1; n <= 5; ++n) {
      bp.scattering_orders = n;
      const BrunetonModel b(bp);
      for (int l = 0; l < 3; ++l) {
        const double x = *b.spectral_radiance(v, nm[l]);
        fmt::print("order {} nm {}: bruneton {:.5g} path {:.5g} +- {:.2g}\n", n, nm[l], x - prev[l],
                   r.order_radiance[n - 1][l], r.order_standard_error[n - 1][l]);
        prev[l] = x;
      }
    }
    return 0;
  }
  if (argc == 2 && std::string(argv[1]) == "xyz") return xyz_sampling();
  if (argc >= 2 && std::string(argv[1]) == "day-set")
    return day_set(argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 100000,
                   argc > 3 ? std::atoi(argv[3]) : 0);
  if (argc >= 2 && std::string(argv[1]) == "truncation")
    return truncation(argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 20000);
  TraceCache cache(argc > 3 ? argv[3] : "");
  for (const double altitude : {0.0, 20000.0})
    for (const double sun_el : {60.0, 30.0, 10.0, 3.0, -1.0, -3.0, -6.0}) {
      HillaireParameters hp;
      hp.sun = {.zenith = deg_to_rad(90 - sun_el), .azimuth = deg_to_rad(180)};
      hp.observer_altitude_m = altitude;
      const HillaireModel h(hp);
      BrunetonParameters bp;
      bp.sun = hp.sun;
      bp.observer_altitude_m = altitude;
      if (orders > 0) bp.scattering_orders = orders;
      const auto t0 = std::chrono::steady_clock::now();
      const BrunetonModel b(bp);
      if (sun_el == 60.0 && altitude == 0.0 && b.tables())
        fmt::print("bruneton precomputation: {:.2f} s CPU, {:.2f} s wall (with the sky-view LUT)\n",
                   b.tables()->cpu_seconds,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      const auto& atm = h.single_scattering().atmosphere();
      const std::vector<double> nm{450, 550, 650};
      const auto spec = h.single_scattering().spectral_at(nm);
      atmosphere::PathTracerSettings s;
      s.paths = sun_el < 0 ? 16 * paths : paths;
      Errors here;
      for (const double el : {90.0, 45.0, 20.0, 5.0})
        for (const double az : {0.0, 90.0, 180.0}) {
          if (el == 90 && az > 0) continue;
          const Vec3 v = direction_from_angles(deg_to_rad(90 - el), deg_to_rad(az));
          const Traced r = cache.get(
              fmt::format("{} {} {} {} {} {}", altitude, sun_el, el, az, s.paths, s.seed), [&] {
                const auto t =
                    atmosphere::path_trace(atm.parameters(), h.single_scattering().observer(), v,
                                           h.sun().direction(), spec, s);
                return Traced{t.radiance, t.standard_error};
              });
          for (std::size_t l = 0; l < nm.size(); ++l) {
            if (r.standard_error[l] > kMaxStandardError * r.radiance[l]) {
              ++here.skipped;
              continue;
            }
            here.bruneton.push_back(std::abs(*b.spectral_radiance(v, nm[l]) / r.radiance[l] - 1));
            if (here.bruneton.back() > kShownError)
              fmt::print(
                  "  bruneton {:+.2f} % at view elevation {} deg, azimuth {} deg, {} nm "
                  "(path tracer +- {:.2f} %; nishita {:+.2f} %)\n",
                  100 * (*b.spectral_radiance(v, nm[l]) / r.radiance[l] - 1), el, az, nm[l],
                  100 * r.standard_error[l] / r.radiance[l],
                  100 * (*h.single_scattering().spectral_radiance(v, nm[l]) / r.radiance[l] - 1));
            here.hillaire.push_back(std::abs(*h.spectral_radiance(v, nm[l]) / r.radiance[l] - 1));
            here.nishita.push_back(
                std::abs(*h.single_scattering().spectral_radiance(v, nm[l]) / r.radiance[l] - 1));
          }
        }
      Errors& all = sun_el >= 10 ? day : sun_el > 0 ? low : twilight;
      fmt::print(
          "{:5.0f} m, sun {:5.1f} deg: bruneton {}; hillaire {}; nishita {}; {} cases above 0.5 % "
          "error skipped\n",
          altitude, sun_el, stats(here.bruneton), stats(here.hillaire), stats(here.nishita),
          here.skipped);
      all.bruneton.insert(all.bruneton.end(), here.bruneton.begin(), here.bruneton.end());
      all.hillaire.insert(all.hillaire.end(), here.hillaire.begin(), here.hillaire.end());
      all.nishita.insert(all.nishita.end(), here.nishita.begin(), here.nishita.end());
    }
  fmt::print("day (sun 10-60 deg): bruneton {}; hillaire {}; nishita {}\n", stats(day.bruneton),
             stats(day.hillaire), stats(day.nishita));
  fmt::print("low sun (3 deg): bruneton {}; hillaire {}; nishita {}\n", stats(low.bruneton),
             stats(low.hillaire), stats(low.nishita));
  fmt::print("twilight (sun -1 to -6 deg): bruneton {}; hillaire {}; nishita {}\n",
             stats(twilight.bruneton), stats(twilight.hillaire), stats(twilight.nishita));
}
