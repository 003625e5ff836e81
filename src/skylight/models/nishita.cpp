#include "skylight/models/nishita.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "skylight/core/data.h"
#include "skylight/core/error.h"

namespace skylight {
namespace {

std::array<double, kNishitaXyzCount> xyz_wavelengths() {
  std::array<double, kNishitaXyzCount> w{};
  for (int k = 0; k < kNishitaXyzCount; ++k) w[k] = kNishitaXyzFirst + kNishitaXyzStep * k;
  return w;
}

}  // namespace

double solar_spectral_irradiance(double nm) {
  return atmosphere::bruneton_spectra().solar_irradiance(nm);
}

NishitaModel::NishitaModel(const SkyParameters& p, const atmosphere::FastSettings& settings)
    : SkyModel(p) {
  require_in_range("sun_zenith", p.sun.zenith, 0.0, kPi);
  require_in_range("observer_altitude", p.observer_altitude_m, 0.0, kNishitaMaxAltitude);
  if (p.solar_irradiance) require_in_range("solar_irradiance", *p.solar_irradiance, 1e-30, 1e30);
  const atmosphere::AtmosphereParameters ap =
      p.atmosphere.value_or(atmosphere::AtmosphereParameters{});
  atmosphere_ = std::make_unique<atmosphere::Atmosphere>(ap, settings);
  observer_ = {0.0, 0.0, ap.ground_radius_m + p.observer_altitude_m};
  sun_ = p.sun.direction();
  const auto nm = xyz_wavelengths();
  std::array<double, kNishitaXyzCount> solar{};
  for (int k = 0; k < kNishitaXyzCount; ++k) solar[k] = irradiance(nm[k]);
  xyz_spectral_ = atmosphere::make_spectral(ap, nm, solar);
  for (int k = 0; k < kNishitaXyzCount; ++k) cmf_[k] = cie1931_cmf(nm[k]);
}

double NishitaModel::irradiance(double nm) const {
  return parameters().solar_irradiance ? *parameters().solar_irradiance
                                       : solar_spectral_irradiance(nm);
}

// X = K_m sum_k x-bar(lambda_k) I(lambda_k) d lambda (midpoint rule over 20 nm bins), same for Y,
// Z.
Xyz NishitaModel::to_xyz(const std::array<double, kNishitaXyzCount>& radiance) const {
  Xyz c{0, 0, 0};
  for (int k = 0; k < kNishitaXyzCount; ++k) {
    const Cmf& m = cmf_[k];
    c.X += m.x * radiance[k];
    c.Y += m.y * radiance[k];
    c.Z += m.z * radiance[k];
  }
  const double f = kMaxLuminousEfficacy * kNishitaXyzStep;
  return {c.X * f, c.Y * f, c.Z * f};
}

Xyz NishitaModel::tristimulus(Vec3 view) const {
  std::array<double, kNishitaXyzCount> r{};
  atmosphere_->single_scattering(observer_, normalize(view), sun_, xyz_spectral_, r);
  return to_xyz(r);
}

Xyz NishitaModel::tristimulus_reference(Vec3 view, const atmosphere::ReferenceSettings& rs) const {
  std::array<double, kNishitaXyzCount> r{};
  atmosphere_->single_scattering_reference(observer_, normalize(view), sun_, xyz_spectral_, r, rs);
  return to_xyz(r);
}

std::optional<double> NishitaModel::spectral_radiance(Vec3 view, double nm) const {
  if (!(nm >= kNishitaMinNm && nm <= kNishitaMaxNm)) return std::nullopt;
  const double l[1] = {nm}, s[1] = {irradiance(nm)};
  const auto spec = atmosphere::make_spectral(atmosphere_->parameters(), l, s);
  double out[1] = {0.0};
  atmosphere_->single_scattering(observer_, normalize(view), sun_, spec, out);
  return out[0];
}

Domain NishitaModel::domain() const {
  Domain d;
  if (parameters().sun.zenith > kPi / 2)
    d.issues.push_back({"sun_zenith", Validity::extrapolated,
                        "sun below the horizon: single scattering only (planet shadow included); "
                        "twilight skies are dominated by multiple scattering, not modelled"});
  return d;
}

}  // namespace skylight
