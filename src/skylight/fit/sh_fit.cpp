#include "skylight/fit/sh_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "skylight/analysis/hemisphere.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/sh/basis.h"

namespace skylight::fit {
namespace {

using sh::Channels;
using sh::Triple;

std::unique_ptr<SkyModel> make_model(const std::string& model, const std::string& parameter,
                                     const ParameterValues& fixed, double theta, double tau,
                                     double phi) {
  SkyParameters sp;
  sp.sun = SunPosition{theta, phi};
  sp.values = fixed;
  if (!parameter.empty()) sp.values.set(parameter, tau);
  return make_sky_model(model, sp);
}

}  // namespace

Triple model_value(const SkyModel& model, Channels channels, Vec3 d) {
  if (channels == Channels::xyz) {
    const Xyz v = model.tristimulus(d);
    return {v.X, v.Y, v.Z};
  }
  const Rgb v = model.rgb(d);
  return {v.r, v.g, v.b};
}

Triple sun_horizontal_irradiance(const SkyModel& model, Channels channels) {
  const double r = model.sun_angular_radius();
  if (!model.has_sun() || !(r > 0.0)) return {};
  const Vec3 s = direction_from_angles(model.sun().zenith, model.sun().azimuth);
  // An orthonormal frame (s, a, b) about the sun's direction.
  const Vec3 a = normalize(std::abs(s.z) < 0.9 ? cross(s, Vec3{0.0, 0.0, 1.0})
                                               : cross(s, Vec3{1.0, 0.0, 0.0}));
  const Vec3 b = cross(s, a);
  constexpr int kRings = 8, kAzimuths = 32;  // ample for a smooth limb-darkened disc
  std::vector<double> mu, w;
  sh::gauss_legendre(kRings, std::cos(r), 1.0, mu, w);
  Triple e{};
  for (int i = 0; i < kRings; ++i) {
    const double ca = mu[static_cast<std::size_t>(i)], sa = std::sqrt(std::max(0.0, 1.0 - ca * ca));
    for (int j = 0; j < kAzimuths; ++j) {
      const double beta = 2.0 * kPi * (j + 0.5) / kAzimuths;
      const Vec3 d = normalize(ca * s + (sa * std::cos(beta)) * a + (sa * std::sin(beta)) * b);
      if (d.z <= 0.0) continue;
      const Xyz v = model.sun_tristimulus(d);
      Triple t{v.X, v.Y, v.Z};
      if (channels == Channels::linear_srgb) {
        const Rgb rgb = xyz_to_linear_srgb(v);
        t = {rgb.r, rgb.g, rgb.b};
      }
      const double weight = w[static_cast<std::size_t>(i)] * (2.0 * kPi / kAzimuths) * d.z;
      for (int ch = 0; ch < 3; ++ch) e[ch] += weight * t[ch];
    }
  }
  return e;
}

sh::Projection project_model(const SkyModel& model, Channels channels, int bands,
                             const sh::ProjectionOptions& options) {
  sh::ProjectionOptions o = options;
  o.region = sh::Region::upper_hemisphere;
  if (!o.ground_albedo) {
    return sh::project([&](Vec3 d) { return model_value(model, channels, d); }, bands, o);
  }
  const double rho = *o.ground_albedo;
  if (!(rho >= 0.0 && rho <= 1.0)) {
    throw InvalidArgument("ground albedo " + std::to_string(rho) + " is outside [0, 1]");
  }
  // The sky's irradiance needs c_10: project at least 2 bands, then keep the first `bands`.
  sh::Projection p =
      sh::project([&](Vec3 d) { return model_value(model, channels, d); }, std::max(bands, 2), o);
  const Triple e_sky = sh::horizontal_irradiance(p.coefficients);
  const Triple e_sun = sun_horizontal_irradiance(model, channels);
  p.coefficients.bands = bands;
  p.coefficients.c.resize(static_cast<std::size_t>(sh::coefficient_count(bands)));
  Triple ground{};
  for (int ch = 0; ch < 3; ++ch) ground[ch] = rho * (e_sky[ch] + e_sun[ch]) / kPi;
  sh::add_uniform_ground(p.coefficients, ground);
  return p;
}

Triple minimum_over_sky(const SkyModel& model, Channels channels, int n_theta) {
  SKYLIGHT_CHECK(n_theta >= 1, "minimum_over_sky: n_theta >= 1");
  const auto grid = analysis::hemisphere_grid(n_theta, 4 * n_theta);
  Triple lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
            std::numeric_limits<double>::infinity()};
  for (const Vec3& d : grid.directions) {
    const Triple v = model_value(model, channels, d);
    for (int ch = 0; ch < 3; ++ch) lo[ch] = std::min(lo[ch], v[ch]);
  }
  for (int ch = 0; ch < 3; ++ch) {
    if (!(lo[ch] > 0.0)) {
      throw InvalidArgument("model '" + std::string(model.name()) + "': channel " +
                            std::to_string(ch) + " has minimum " + std::to_string(lo[ch]) +
                            " over the sky; the relative SH errors need L_min > 0");
    }
  }
  return lo;
}

sh::PolynomialTable fit_sh_table(const ShFitSettings& s) {
  const sh::PolynomialFitSettings& poly = s.polynomial;
  if (!poly.parameter.empty() && s.fixed.has(poly.parameter)) {
    throw InvalidArgument("parameter '" + poly.parameter + "' is both varied and fixed");
  }
  sh::PolynomialTable table = sh::fit_polynomial(poly, [&](double theta, double tau) {
    const auto model = make_model(s.model, poly.parameter, s.fixed, theta, tau, 0.0);
    return project_model(*model, poly.channels, poly.bands, s.projection).coefficients;
  });
  table.model = s.model;
  table.fixed = s.fixed;
  table.ground_albedo = s.projection.ground_albedo;
  return table;
}

sh::Projection project_reference(const sh::PolynomialTable& table, double theta, double tau,
                                 double phi, int bands, const sh::ProjectionOptions& options) {
  const auto model = make_model(table.model, table.parameter, table.fixed, theta, tau, phi);
  sh::ProjectionOptions o = options;
  o.ground_albedo = table.ground_albedo;
  return project_model(*model, table.channels, bands, o);
}

}  // namespace skylight::fit
