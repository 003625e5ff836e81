#include "skylight/models/perez.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/parameters.h"

namespace skylight {

const ParameterSchema<PerezParameters>& PerezParameters::schema() {
  static const auto s = [] {
    ParameterSchema<PerezParameters> s;
    s.optional_numbers(
        &PerezParameters::coefficients,
        {.name = "perez",
         .unit = "1",
         .kind = ParameterKind::numbers,
         .min = -kPerezCoefficientLimit,
         .max = kPerezCoefficientLimit,
         .count = 5,
         .default_value = Required{},
         .description = "coefficients A,B,C,D,E of F = (1 + A e^{B/cos theta})(1 + C e^{D gamma} "
                        "+ E cos^2 gamma)"});
    s.optional_number(&PerezParameters::zenith_luminance,
                      {.name = "zenith-luminance",
                       .unit = "cd/m^2",
                       .min = kMinZenithLuminance,
                       .max = kMaxZenithLuminance,
                       .default_value = Required{},
                       .description = "absolute zenith luminance Lz"});
    return s;
  }();
  return s;
}

PerezModel::PerezModel(const PerezParameters& p) : SkyModel(p.sun), params_(p) {
  PerezParameters::schema().validate(p, model_context(kName));
  const auto& k = *p.coefficients;
  sun_up_ = p.sun.zenith <= 0.5 * kPi;
  const PerezCoefficients c{k[0], k[1], k[2], k[3], k[4], 1.0};
  const double f0 = perez_function(c, 1.0, p.sun.zenith);
  if (sun_up_ && !(f0 > 0.0)) {
    throw InvalidArgument(fmt::format(
        "perez coefficients {},{},{},{},{} give F(zenith) = {} <= 0 at sun zenith {} deg: the "
        "relative distribution cannot be normalised",
        k[0], k[1], k[2], k[3], k[4], f0, rad_to_deg(p.sun.zenith)));
  }
  // Bounds of |F|'s two factors over the sky (with the kernel's clamps): the float batch path
  // multiplies them, so each must stay far inside the float range, and so must Lz F / F(0, ts).
  const double grad_bound =
      1.0 + std::abs(c.A) * std::exp(std::clamp(std::max(c.B, c.B / kPerezMinCosTheta),
                                                -kPerezMaxExponent, kPerezMaxExponent));
  const double ind_bound =
      1.0 +
      std::abs(c.C) *
          std::max(1.0, std::exp(std::clamp(c.D * kPi, -kPerezMaxExponent, kPerezMaxExponent))) +
      std::abs(c.E);
  const double max_luminance = sun_up_ ? *p.zenith_luminance / f0 * grad_bound * ind_bound : 0.0;
  if (grad_bound > kPerezMaxFactor || ind_bound > kPerezMaxFactor ||
      !(max_luminance <= kPerezMaxLuminance))
    throw InvalidArgument(fmt::format(
        "{} {},{},{},{},{} with {} {} overflows: F's factors reach {:.3g} (gradation) and {:.3g} "
        "(indicatrix), the luminance up to {:.3g} cd/m^2 (limits {:g} and {:g})",
        spelled("perez"), k[0], k[1], k[2], k[3], k[4], spelled("zenith-luminance"),
        *p.zenith_luminance, grad_bound, ind_bound, max_luminance, kPerezMaxFactor,
        kPerezMaxLuminance));
  distribution_.mode = PerezDistribution::Mode::luminance;
  distribution_.coefficients[0] = c;
  distribution_.sun = p.sun.direction();
  distribution_.scale[0] = sun_up_ ? *p.zenith_luminance / f0 : 0.0;
}

ParameterValues PerezModel::parameter_values() const {
  return PerezParameters::schema().values_of(params_);
}

Xyz PerezModel::tristimulus(Vec3 view) const {
  return distribution_.evaluate(view);
}

void PerezModel::tristimulus_batch(const DirectionsSoA& dirs, const XyzSoA& out) const {
  distribution_.evaluate_batch(dirs, out);
}

Domain PerezModel::domain() const {
  Domain d;
  if (!sun_up_) {
    d.issues.push_back(
        {"sun_zenith", Validity::undefined,
         "sun below the horizon: the Perez distribution describes daylight; sky is 0"});
    return d;
  }
  // F's sign is set by (1 + A e^{B/cos}) at the horizon and (1 + C e^{D gamma} + E cos^2) across
  // gamma; check both factors over their ranges.
  const auto& k = *params_.coefficients;
  const PerezCoefficients c{k[0], k[1], k[2], k[3], k[4], 1.0};
  double min_grad = 1e300, min_ind = 1e300;
  for (int i = 0; i <= 90; ++i) {
    const double theta = i * kDegree;
    min_grad = std::min(min_grad, perez_function({c.A, c.B, 0, 0, 0, 1.0}, std::cos(theta), 0.0));
  }
  for (int i = 0; i <= 180; ++i)
    min_ind = std::min(min_ind, perez_function({0, 0, c.C, c.D, c.E, 1.0}, 1.0, i * kDegree));
  if (min_grad < 0.0 || min_ind < 0.0) {
    d.issues.push_back({"perez", Validity::unphysical,
                        "the coefficients make F negative somewhere on the sky; those directions "
                        "return 0"});
  }
  return d;
}

ModelInfo PerezModel::registry_entry() {
  return ModelInfo{
      .name = std::string(kName),
      .description =
          "Perez all-weather relative luminance (Perez et al. 1993) with user coefficients A..E",
      .output = "luminance Y [cd/m^2] = Lz F(theta,gamma)/F(0,theta_s); XYZ at D65 chromaticity",
      .parameters = PerezParameters::schema().specs(),
      .domain = "any coefficients that keep F > 0; sun above the horizon (below: 0)",
      .luminance_only = true,
      .make = model_factory<PerezModel, PerezParameters>(),
      // A clear sky: the CIE S 011 type 12 gradation and indicatrix coefficients as A..E.
      .example = ParameterValues()
                     .set("perez", std::vector<double>{-1.0, -0.32, 10.0, -3.0, 0.45})
                     .set("zenith-luminance", 5000.0),
      .neural = NeuralPolicy{},
      .sh_fit = ShFitPolicy{},
      // The report's Perez sky: the example's clear-sky coefficients.
      .report = ReportPolicy{.title = "Perez (example coefficients)", .colour = "#8c564b"},
  };
}

}  // namespace skylight
