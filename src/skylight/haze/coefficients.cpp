// Morales et al. 2017 eqs. 2-4 and 14-18; docs/HAZE.md.
#include "skylight/haze/coefficients.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "skylight/haze/request.h"
#include "skylight/models/preetham.h"

namespace skylight::haze {

std::string_view to_string(ScatteringVariant v) {
  switch (v) {
    case ScatteringVariant::improved:
      return "improved";
    case ScatteringVariant::preetham:
      // Preetham et al. 1999's coefficients (their Appendix), named as the model is.
      return PreethamModel::kName;
    case ScatteringVariant::zhao:
      return "zhao";
  }
  return "improved";
}

ScatteringVariant parse_scattering_variant(std::string_view text) {
  for (auto v : {ScatteringVariant::improved, ScatteringVariant::preetham, ScatteringVariant::zhao})
    if (text == to_string(v)) return v;
  throw InvalidArgument(fmt::format("scattering variant '{}' is not improved, {} or zhao",
                                    excerpt(text), PreethamModel::kName));
}

void validate(const Atmosphere& a) {
  // The ranges are the schema's, declared once (haze/request.cpp).
  atmosphere_schema().validate(a, "haze");
}

double rayleigh_per_m(double nm, double altitude_m, ScatteringVariant variant) {
  const double lambda_m = nm * 1e-9;
  const double n2 = kAirRefractiveIndex * kAirRefractiveIndex - 1.0;
  const double pn = kAirDepolarization;
  const double beta =
      8.0 * kPi * kPi * kPi * n2 * n2 / (3.0 * kAirNumberDensity_per_m3 * std::pow(lambda_m, 4.0)) *
      ((6.0 + 3.0 * pn) / (6.0 - 7.0 * pn)) * std::exp(-altitude_m / kRayleighScaleHeight_m);
  return variant == ScatteringVariant::improved ? beta * kRayleighCorrection : beta;
}

double concentration(double turbidity, ScatteringVariant variant) {
  switch (variant) {
    case ScatteringVariant::improved:  // eq. 16: zero at T = 1 (eq. 5: no particles)
      return (0.65 * turbidity - 0.65) * 1e-16;
    case ScatteringVariant::preetham:
      return (0.6544 * turbidity - 0.6510) * 1e-16;
    case ScatteringVariant::zhao:
      return (0.6544 * turbidity - 0.6510) * 1e-18;
  }
  return 0.0;
}

double preetham_fudge(double nm) {
  static constexpr std::array<double, 5> kNm{380.0, 450.0, 550.0, 680.0, 780.0};
  static constexpr std::array<double, 5> kK{0.650, 0.666, 0.678, 0.686, 0.690};
  if (nm <= kNm.front()) return kK.front();
  for (std::size_t i = 1; i < kNm.size(); ++i)
    if (nm <= kNm[i]) {
      const double t = (nm - kNm[i - 1]) / (kNm[i] - kNm[i - 1]);
      return kK[i - 1] + t * (kK[i] - kK[i - 1]);
    }
  return kK.back();
}

double mie_per_m(double nm, double turbidity, double altitude_m, ScatteringVariant variant) {
  const double lambda_m = nm * 1e-9;
  const double k = variant == ScatteringVariant::improved ? kImprovedMieFudge : preetham_fudge(nm);
  // Preetham's and Zhao's c(T) are slightly negative for T < 0.995: no negative scattering.
  const double c = std::max(0.0, concentration(turbidity, variant));
  return 0.434 * c * kPi * std::pow(2.0 * kPi / lambda_m, kJungeExponent - 2.0) * k *
         std::exp(-altitude_m / kMieScaleHeight_m);
}

double total_per_m(double nm, const Atmosphere& a) {
  return rayleigh_per_m(nm, a.altitude_m, a.variant) +
         mie_per_m(nm, a.turbidity, a.altitude_m, a.variant);
}

std::string weather_class(double beta_mie_per_km) {
  if (!(beta_mie_per_km >= 0.0))
    throw InvalidArgument(fmt::format("Mie coefficient {} /km is negative", beta_mie_per_km));
  if (beta_mie_per_km == 0.0) return "pure air";
  if (beta_mie_per_km <= 0.0639) return "exceptionally clear";
  if (beta_mie_per_km <= 0.1819) return "very clear";
  if (beta_mie_per_km <= 0.3769) return "clear";
  if (beta_mie_per_km <= 0.9399) return "light haze";
  if (beta_mie_per_km <= 1.9459) return "haze";
  return "fog";
}

}  // namespace skylight::haze
