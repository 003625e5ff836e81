#include "skylight/fit/sh_fit.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "skylight/analysis/hemisphere.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/core/parameters.h"
#include "skylight/core/statistics.h"
#include "skylight/sh/approximation_error.h"
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

const ParameterSchema<ShFitRequest>& ShFitRequest::schema() {
  static const ParameterSchema<ShFitRequest> s = [] {
    using R = ShFitRequest;
    const R d;
    std::vector<std::string> models;
    for (const auto& m : model_registry())
      if (m.sh_fit) models.push_back(m.name);
    ParameterSchema<R> s;
    ParameterSpec model{
        .name = "model",
        .kind = ParameterKind::text,
        .default_value = Required{},
        .description = "the model fitted (any of `skylight models` with a fit policy)"};
    model.choices = models;
    s.text(&R::model, model)
        .integer(&R::bands, {.name = "bands",
                             .unit = "1",
                             .kind = ParameterKind::integer,
                             .min = 1,
                             .max = sh::kMaxBands,
                             .default_value = ParameterValue(static_cast<double>(d.bands)),
                             .description = "SH bands N (degrees l = 0..N-1, N^2 coefficients)"})
        .numbers(
            &R::degrees,
            {.name = "degrees",
             .unit = "1",
             .kind = ParameterKind::numbers,
             .min = 0,
             .max = 40,
             .count = 2,
             .default_value = ParameterValue(std::vector<double>{17.0, 12.0}),
             .description = "polynomial degrees I,J in the sun zenith and the second parameter "
                            "(J = 0 for a zenith-only fit); hosek: 17,2 per turbidity piece"})
        .text(
            &R::parameter,
            {.name = "parameter",
             .kind = ParameterKind::text,
             .default_value =
                 Absent{"the model's fit policy: turbidity for preetham, hosek and nn, else none"},
             .description =
                 "the varying parameter tau (a number of the model's schema); 'none': the sun "
                 "zenith only"})
        .numbers(
            &R::range,
            {.name = "range",
             .unit = "1",
             .kind = ParameterKind::numbers,
             .min = -1e9,
             .max = 1e9,
             .count = 2,
             .default_value = Absent{"preetham: 2.5,6 (Habel 2008); others: the parameter's whole "
                                     "range"},
             .description = "range LO,HI of tau"})
        .numbers(&R::theta_range_deg, {.name = "theta-range",
                                       .unit = "deg",
                                       .kind = ParameterKind::numbers,
                                       .min = 0,
                                       .max = 90,
                                       .count = 2,
                                       .default_value = ParameterValue(d.theta_range_deg),
                                       .description = "range LO,HI of the sun zenith"})
        .numbers(&R::grid, {.name = "grid",
                            .unit = "1",
                            .kind = ParameterKind::numbers,
                            .min = 1,
                            .max = 1000,
                            .count = 2,
                            .default_value = Absent{"2 (degree + 1) + 1 points each"},
                            .description = "fitting grid points in theta, tau"})
        .custom(
            {.name = "set",
             .kind = ParameterKind::text,
             .default_value = Absent{"the model's defaults"},
             .description =
                 "NAME=VALUE: a model parameter held fixed (e.g. albedo=0.3, cie-type=7); "
                 "repeatable",
             .choices = {},
             .repeated = true},
            [](R& r, const ParameterValue& v) { r.set = split_repeated(std::get<std::string>(v)); },
            [](const R& r) -> std::optional<ParameterValue> {
              if (r.set.empty()) return std::nullopt;
              return join_repeated(r.set);
            })
        .choice(&R::channels,
                {.name = "channels",
                 .kind = ParameterKind::text,
                 .default_value = ParameterValue(std::string("xyz")),
                 .description = "the channels fitted: xyz (Y in cd/m^2) or linear-srgb"},
                {{"xyz", sh::Channels::xyz}, {"linear-srgb", sh::Channels::linear_srgb}})
        .number(&R::tolerance,
                {.name = "tolerance",
                 .unit = "1",
                 .min = 1e-9,
                 .max = 1e-1,
                 .default_value = ParameterValue(d.tolerance),
                 .description = "projection convergence: largest coefficient change relative to "
                                "c_00"})
        .custom(
            {.name = "theta-axis",
             .kind = ParameterKind::text,
             .default_value =
                 Absent{"the model's ShFitPolicy (e.g. hosek elevation-cbrt), else theta"},
             .description =
                 "the sun-zenith coordinate of the fit: theta, or elevation-cbrt ((elevation / "
                 "90 deg)^(1/3), Hosek's)",
             .choices = {"theta", "elevation-cbrt"}},
            [](R& r, const ParameterValue& v) {
              r.theta_axis = std::get<std::string>(v) == "theta" ? sh::ThetaAxis::theta
                                                                 : sh::ThetaAxis::elevation_cbrt;
            },
            [](const R& r) -> std::optional<ParameterValue> {
              if (!r.theta_axis) return std::nullopt;
              return std::string(*r.theta_axis == sh::ThetaAxis::theta ? "theta"
                                                                       : "elevation-cbrt");
            })
        .optional_integer(
            &R::tau_pieces,
            {.name = "tau-pieces",
             .unit = "1",
             .kind = ParameterKind::integer,
             .min = 1,
             .max = sh::kMaxTauPieces,
             .default_value =
                 Absent{"hosek: one per unit of turbidity (degrees 17,2, 4 turbidities "
                        "each); others: 1"},
             .description = "equal pieces of the tau range, each its own polynomial in tau"})
        .optional_number(
            &R::ground_albedo,
            {.name = "ground-albedo",
             .unit = "1",
             .min = 0,
             .max = 1,
             .default_value = Absent{"the lower hemisphere black"},
             .description =
                 "the lower hemisphere as a uniform ground of this albedo lit by the sky "
                 "and the sun (L = albedo E / pi)"});
    return s;
  }();
  return s;
}

namespace {

int integer_intervals(double lo, double hi) {
  return std::clamp(static_cast<int>(std::lround(hi - lo)), 1, sh::kMaxTauPieces);
}

// The parameters held fixed (--set NAME=VALUE), each checked by the model's spec.
ParameterValues fixed_parameters(const ModelInfo& info, const std::vector<std::string>& set) {
  ParameterValues fixed;
  for (const auto& kv : set) {
    const auto eq = kv.find('=');
    const ParameterSpec* spec =
        eq == std::string::npos ? nullptr : info.find_parameter(kv.substr(0, eq));
    if (!spec) {
      throw InvalidArgument(
          fmt::format("{} {}: expected NAME=VALUE with NAME a parameter of model '{}'",
                      spelled("set"), excerpt(kv), info.name));
    }
    const ParameterValue v = spec->parse(kv.substr(eq + 1));
    spec->check(v, model_context(info.name));
    fixed.set(spec->name, v);
  }
  return fixed;
}

// tau's range: given, the policy's or the parameter's whole range; checked.
void set_tau_range(sh::PolynomialFitSettings& p, const ShFitRequest& r, const ParameterSpec& tau,
                   const ShFitPolicy& policy) {
  if (!r.range.empty()) {
    p.tau_min = r.range[0];
    p.tau_max = r.range[1];
  } else if (policy.range && p.parameter == policy.parameter) {
    p.tau_min = (*policy.range)[0];
    p.tau_max = (*policy.range)[1];
  } else {
    p.tau_min = tau.min;
    p.tau_max = tau.max;
  }
  if (!(p.tau_min < p.tau_max))
    throw InvalidArgument(spelled("range") + " LO,HI: LO must be below HI");
  tau.check(p.tau_min, spelled("range"));
  tau.check(p.tau_max, spelled("range"));
}

// The policy's table structure (Hosek's pieces) where the fit varies the policy's parameter.
void apply_structure(sh::PolynomialFitSettings& p, const ShFitRequest& r,
                     const ShFitPolicy& policy) {
  if (policy.parameter.empty() || p.parameter != policy.parameter) return;
  if (!r.theta_axis) p.theta_axis = policy.theta_axis;
  if (policy.unit_pieces && !r.tau_pieces) p.tau_pieces = integer_intervals(p.tau_min, p.tau_max);
  if (policy.degrees && r.degrees.empty()) {
    p.degree_theta = (*policy.degrees)[0];
    p.degree_tau = (*policy.degrees)[1];
  }
  if (policy.grid_tau > 0 && r.grid.empty() && p.tau_pieces > 1) p.grid_tau = policy.grid_tau;
}

}  // namespace

ShFitSettings sh_fit_settings(const ShFitRequest& r) {
  const ModelInfo* info = &require_model(r.model, "model");
  if (!info->sh_fit)
    throw InvalidArgument(
        fmt::format("{} {}: no SH table is fitted to this model (a table "
                    "cannot be fitted to a table)",
                    spelled("model"), info->name));
  const ShFitPolicy& policy = *info->sh_fit;
  ShFitSettings s;
  s.model = info->name;
  sh::PolynomialFitSettings& p = s.polynomial;
  p.parameter = r.parameter.empty() ? policy.parameter : r.parameter == "none" ? "" : r.parameter;
  const ParameterSpec* tau = p.parameter.empty() ? nullptr : info->find_parameter(p.parameter);
  if (!p.parameter.empty() && (!tau || tau->kind != ParameterKind::number)) {
    throw InvalidArgument(fmt::format("{}: '{}' is not a number parameter of model '{}'",
                                      spelled("parameter"), excerpt(p.parameter), info->name));
  }
  s.fixed = fixed_parameters(*info, r.set);
  const std::vector<double> degrees =
      r.degrees.empty() ? std::vector<double>{17.0, 12.0} : r.degrees;
  p.channels = r.channels;
  p.bands = r.bands;
  p.degree_theta = static_cast<int>(degrees[0]);
  p.degree_tau = tau ? static_cast<int>(degrees[1]) : 0;
  if (!tau && !r.degrees.empty() && degrees[1] != 0.0)
    throw InvalidArgument(spelled("degrees") +
                          " I,J: J must be 0 for a fit in the sun zenith only");
  if (degrees[0] != std::floor(degrees[0]) || degrees[1] != std::floor(degrees[1]))
    throw InvalidArgument(spelled("degrees") + " I,J: whole numbers expected");
  p.theta_min = deg_to_rad(r.theta_range_deg[0]);
  p.theta_max = deg_to_rad(r.theta_range_deg[1]);
  if (!(r.theta_range_deg[0] < r.theta_range_deg[1]))
    throw InvalidArgument(spelled("theta-range") + " LO,HI: LO must be below HI");
  if (tau) set_tau_range(p, r, *tau, policy);
  if (!tau && !r.range.empty())
    throw InvalidArgument(fmt::format(
        "{}: a fit in the sun zenith only has no second parameter (model '{}' fits none{})",
        spelled("range"), info->name, r.parameter == "none" ? ": --parameter none" : ""));
  if (!r.grid.empty()) {
    p.grid_theta = static_cast<int>(r.grid[0]);
    p.grid_tau = static_cast<int>(r.grid[1]);
  }
  p.theta_axis = r.theta_axis.value_or(sh::ThetaAxis::theta);
  p.tau_pieces = r.tau_pieces.value_or(1);
  if (tau) apply_structure(p, r, policy);
  if (!tau && p.tau_pieces != 1)
    throw InvalidArgument(spelled("tau-pieces") + ": a fit in the sun zenith only has one piece");
  s.projection.tolerance = r.tolerance;
  s.projection.ground_albedo = r.ground_albedo;
  return s;
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

const ParameterSchema<ShErrorOptions>& ShErrorOptions::schema() {
  static const ParameterSchema<ShErrorOptions> s = [] {
    ParameterSchema<ShErrorOptions> s;
    s.numbers(&ShErrorOptions::points,
              {.name = "points",
               .unit = "1",
               .kind = ParameterKind::numbers,
               .min = 1,
               .max = 1000,
               .count = 2,
               .default_value = ParameterValue(ShErrorOptions{}.points),
               .description = "test points (cell midpoints) in theta, tau; the ends of both "
                              "ranges are added unless --midpoints-only"})
        .flag(&ShErrorOptions::midpoints_only,
              {.name = "midpoints-only",
               .kind = ParameterKind::flag,
               .default_value = ParameterValue(false),
               .description = "the cell midpoints only (Habel 2008 Fig. 3), not the ranges' ends"});
    return s;
  }();
  return s;
}

ShTableError table_error(const sh::PolynomialTable& t, const ShErrorOptions& options,
                         const std::function<void(int, int)>& progress) {
  // The sampled values of one axis: its cell midpoints, then (unless midpoints_only) its ends.
  const auto axis = [&](double lo, double hi, int cells) {
    std::vector<double> v;
    for (int i = 0; i < cells; ++i) v.push_back(lo + (hi - lo) * (i + 0.5) / cells);
    if (!options.midpoints_only && hi > lo) {
      v.push_back(lo);
      v.push_back(hi);
    }
    return v;
  };
  const std::vector<double> thetas =
      axis(t.theta_min, t.theta_max, static_cast<int>(options.points[0]));
  const std::vector<double> taus =
      t.parameter.empty() ? std::vector<double>{t.tau_min}
                          : axis(t.tau_min, t.tau_max, static_cast<int>(options.points[1]));
  const int nt = static_cast<int>(thetas.size()), nv = static_cast<int>(taus.size());
  const int n_bands = t.bands;
  // [band N - 1][channel] -> values over the points
  std::vector<std::array<std::vector<double>, 3>> e_mean(static_cast<std::size_t>(n_bands)),
      e_max(static_cast<std::size_t>(n_bands));
  std::vector<std::array<double, 2>> at;  // (theta, tau) of each point
  for (int it = 0; it < nt; ++it) {
    for (int iv = 0; iv < nv; ++iv) {
      const double theta = thetas[static_cast<std::size_t>(it)];
      const double tau = taus[static_cast<std::size_t>(iv)];
      at.push_back({theta, tau});
      const sh::Projection ref = project_reference(t, theta, tau, 0.0, n_bands);
      const sh::Coefficients rec = sh::evaluate_table(t, theta, tau, 0.0, n_bands, false);
      const auto model = make_model(t.model, t.parameter, t.fixed, theta, tau, 0.0);
      const Triple l_min = minimum_over_sky(*model, t.channels);
      for (int n = 1; n <= n_bands; ++n) {
        const sh::ErrorMeasures m = sh::error_measures(ref.coefficients, rec, n, l_min);
        for (std::size_t ch = 0; ch < 3; ++ch) {
          e_mean[static_cast<std::size_t>(n - 1)][ch].push_back(m.e_mean[ch]);
          e_max[static_cast<std::size_t>(n - 1)][ch].push_back(m.e_max[ch]);
        }
      }
      if (progress) progress(it * nv + iv + 1, nt * nv);
    }
  }
  ShTableError out;
  out.points = nt * nv;
  for (int n = 1; n <= n_bands; ++n) {
    for (std::size_t ch = 0; ch < 3; ++ch) {
      const auto& a = e_mean[static_cast<std::size_t>(n - 1)][ch];
      const auto& b = e_max[static_cast<std::size_t>(n - 1)][ch];
      const auto worst = std::max_element(a.begin(), a.end());
      const auto& where = at[static_cast<std::size_t>(worst - a.begin())];
      out.rows.push_back({n, static_cast<int>(ch), *worst, median(a),
                          *std::max_element(b.begin(), b.end()), median(b), where[0], where[1]});
    }
  }
  return out;
}

}  // namespace skylight::fit
