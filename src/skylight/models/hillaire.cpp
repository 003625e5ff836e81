#include "skylight/models/hillaire.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "skylight/core/error.h"
#include "skylight/core/frame.h"
#include "skylight/core/math.h"
#include "skylight/core/parallel.h"

namespace skylight {

namespace {

using atmosphere::Atmosphere;
using atmosphere::atmosphere_key;
using atmosphere::AtmosphereParameters;
using atmosphere::AtmosphereTableCache;
using atmosphere::ray_nodes;
using atmosphere::scattering_of;
using atmosphere::Spectral;
using atmosphere::transmittance_of;

AtmosphereTableCache<std::vector<double>>& psi_cache() {
  static AtmosphereTableCache<std::vector<double>> cache;
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
    s.inherit(OzoneLayerParameters::schema());
    return s;
  }();
  return s;
}

HillaireModel::HillaireModel(const HillaireParameters& params)
    : PhysicalSkyModel(params), params_(params) {
  const Atmosphere& atm = atmosphere();
  const AtmosphereParameters& a = atm.parameters();
  const std::vector<double>& lut_nm = lut_wavelengths();
  const std::size_t nl = lut_nm.size();
  const std::string key = atmosphere_key(a);
  psi_ = psi_cache().get(key, [&] {
    std::vector<double> psi;
    // Per unit irradiance; the first scattering with an isotropic phase function (HG with g = 0
    // is exactly 1 / (4 pi)); the tables are shared with the single scattering's (same profiles).
    const Spectral unit = atmosphere::make_spectral(a, lut_nm, std::vector<double>(nl, 1.0));
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
  build_sky_view(key);
}

double HillaireModel::psi(std::size_t k, double altitude_m, double mu_s) const {
  const int nh = kHillaireLutAltitudes, nmu = kHillaireLutSunCosines;
  const AtmosphereParameters& a = atmosphere().parameters();
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
  const Atmosphere& atm = atmosphere();
  const AtmosphereParameters& a = atm.parameters();
  const std::size_t nl = spec.nm.size(), nc = a.components.size();
  std::fill(out.begin(), out.end(), 0.0);
  std::vector<double> tr(nl), sig(nl);
  const Vec3 v = normalize(view);
  ray_nodes(atm, observer_, v, sun_, kSkyViewRayNodes,
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

ParameterValues HillaireModel::parameter_values() const {
  return HillaireParameters::schema().values_of(params_);
}

Domain HillaireModel::domain() const {
  return sun_below_horizon(Validity::extrapolated,
                           "the approximation's error grows in twilight (docs/ATMOSPHERE.md)");
}

ModelInfo HillaireModel::registry_entry() {
  ModelInfo info = registry_entry_of(
      kName, "every order", "the approximation's error against the Monte Carlo path tracer");
  info.description =
      "Physically based single scattering plus Hillaire's (2020) multiple-scattering LUT "
      "(orders >= 2 as isotropic in-scattering from a 32 x 32 table over altitude and sun "
      "angle) in nishita's atmosphere; ozone on by default";
  info.parameters = HillaireParameters::schema().specs();
  info.make = model_factory<HillaireModel, HillaireParameters>();
  info.report = ReportPolicy{
      .title = "Hillaire 2020 (Earth defaults)", .colour = "#17becf", .physical_atmosphere = true};
  return info;
}

}  // namespace skylight
