#include "skylight/atmosphere/ray.h"

#include <fmt/format.h>

#include <cmath>

namespace skylight::atmosphere {

void transmittance_of(const Spectral& spec, std::size_t components, const Densities& t,
                      std::span<double> out) {
  for (std::size_t l = 0; l < out.size(); ++l) {
    double tau = 0.0;
    for (std::size_t i = 0; i < components; ++i) tau += spec.extinction[i][l] * t[i];
    out[l] = std::exp(-tau);
  }
}

void scattering_of(const Spectral& spec, std::size_t components, const Densities& rho,
                   std::span<double> out) {
  for (std::size_t l = 0; l < out.size(); ++l) {
    double s = 0.0;
    for (std::size_t i = 0; i < components; ++i) s += rho[i] * spec.scattering[i][l];
    out[l] = s;
  }
}

std::string atmosphere_key(const AtmosphereParameters& a) {
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

WavelengthWeight wavelength_weight(const std::vector<double>& table_nm, double nm) {
  const auto it = std::lower_bound(table_nm.begin(), table_nm.end(), nm);
  if (it == table_nm.begin()) return {0, 0, 0.0};
  if (it == table_nm.end()) return {table_nm.size() - 1, table_nm.size() - 1, 0.0};
  const auto j = static_cast<std::size_t>(it - table_nm.begin());
  const double a = table_nm[j - 1], b = table_nm[j];
  return {j - 1, j, (nm - a) / (b - a)};
}

}  // namespace skylight::atmosphere
