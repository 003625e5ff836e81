// The error of the multiple-scattering models against the Monte Carlo path tracer
// (docs/ATMOSPHERE.md): for each sun elevation, 10 view directions (zenith; elevations 45, 20,
// 5 deg at azimuths 0, 90 and 180, the sun at azimuth 180) and 450, 550,
// 650 nm, the relative error of `hillaire` (and of `nishita`, single scattering, for scale)
// against path_trace (segments estimator, Earth defaults with 300 DU of ozone, black ground),
// over the cases whose path-traced standard error is below 0.5 %. Prints the median, the 95th
// percentile and the maximum per sun elevation and over day (>= 3 deg) and twilight (< 0).
//
// Usage: skylight_atmosphere_error [PATHS (default 100000; twilight x 4)]
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "skylight/atmosphere/path_tracer.h"
#include "skylight/core/math.h"
#include "skylight/models/hillaire.h"

namespace {

using namespace skylight;

struct Errors {
  std::vector<double> hillaire, nishita;
  int skipped = 0;
};

std::string stats(std::vector<double> e) {
  if (e.empty()) return "-";
  std::sort(e.begin(), e.end());
  return fmt::format("median {:5.2f} %, p95 {:5.2f} %, max {:6.2f} % (n {})", 100 * e[e.size() / 2],
                     100 * e[static_cast<std::size_t>(0.95 * (e.size() - 1))], 100 * e.back(),
                     e.size());
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t paths = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100000;
  constexpr double kMaxStandardError = 0.005;
  Errors day, twilight;
  for (const double sun_el : {60.0, 30.0, 10.0, 3.0, -1.0, -3.0, -6.0}) {
    HillaireParameters hp;
    hp.sun = {.zenith = deg_to_rad(90 - sun_el), .azimuth = deg_to_rad(180)};
    const HillaireModel h(hp);
    const auto& atm = h.single_scattering().atmosphere();
    const std::vector<double> nm{450, 550, 650};
    const auto spec = h.single_scattering().spectral_at(nm);
    atmosphere::PathTracerSettings s;
    s.paths = sun_el < 0 ? 4 * paths : paths;
    Errors here;
    for (const double el : {90.0, 45.0, 20.0, 5.0})
      for (const double az : {0.0, 90.0, 180.0}) {
        if (el == 90 && az > 0) continue;
        const Vec3 v = direction_from_angles(deg_to_rad(90 - el), deg_to_rad(az));
        const auto r = atmosphere::path_trace(atm.parameters(), h.single_scattering().observer(), v,
                                              h.sun().direction(), spec, s);
        for (std::size_t l = 0; l < nm.size(); ++l) {
          if (r.standard_error[l] > kMaxStandardError * r.radiance[l]) {
            ++here.skipped;
            continue;
          }
          here.hillaire.push_back(std::abs(*h.spectral_radiance(v, nm[l]) / r.radiance[l] - 1));
          here.nishita.push_back(
              std::abs(*h.single_scattering().spectral_radiance(v, nm[l]) / r.radiance[l] - 1));
        }
      }
    fmt::print("sun {:5.1f} deg: hillaire {}; nishita {}; {} cases above 0.5 % error skipped\n",
               sun_el, stats(here.hillaire), stats(here.nishita), here.skipped);
    Errors& all = sun_el >= 3 ? day : twilight;
    all.hillaire.insert(all.hillaire.end(), here.hillaire.begin(), here.hillaire.end());
    all.nishita.insert(all.nishita.end(), here.nishita.begin(), here.nishita.end());
  }
  fmt::print("day (sun 3-60 deg): hillaire {}; nishita {}\n", stats(day.hillaire),
             stats(day.nishita));
  fmt::print("twilight (sun -1 to -6 deg): hillaire {}; nishita {}\n", stats(twilight.hillaire),
             stats(twilight.nishita));
}
