// Scattering coefficients of the clear and hazy atmosphere for aerial perspective (Morales, Oishi
// & Ikeuchi 2017, "Real-time rendering of aerial perspective effect based on turbidity
// estimation", §3.1 and §5; docs/HAZE.md): Rayleigh (eq. 3) and Mie (eq. 4) as Preetham et al.
// (1999), Zhao's (2012) variant, and the paper's improved model (eqs. 14-18), at the observer's
// altitude h0; the weather classes of the paper's appendix Table 2.
#pragma once

#include <string>
#include <string_view>

namespace skylight::haze {

// Which pair of coefficients.
enum class ScatteringVariant {
  improved,  // Morales 2017 eqs. 15 and 18: K_R = 1.0396, c^(T) = (0.65 T - 0.65) 1e-16, K_M =
             // 0.0092
  preetham,  // eqs. 3 and 4 with Preetham's c(T) = (0.6544 T - 0.6510) 1e-16 and K(lambda)
  zhao,      // eqs. 3 and 4 with Zhao's c(T) = (0.6544 T - 0.6510) 1e-18 and K(lambda)
};

std::string_view to_string(ScatteringVariant v);
// "improved", Preetham's (the model's name) or "zhao"; InvalidArgument naming the text otherwise.
ScatteringVariant parse_scattering_variant(std::string_view text);

// Constants of eqs. 3 and 4 (Morales 2017 §3.1).
inline constexpr double kAirRefractiveIndex = 1.0003;         // n, visible spectrum
inline constexpr double kAirNumberDensity_per_m3 = 2.545e25;  // N, standard atmosphere
inline constexpr double kAirDepolarization = 0.035;           // p_n
inline constexpr double kRayleighScaleHeight_m = 7994.0;      // H_R0
inline constexpr double kMieScaleHeight_m = 1200.0;           // H_M0
inline constexpr double kJungeExponent = 4.0;                 // nu
// Eq. 14: K_R = 0.0141 / 0.0135 (Table 2's beta_R over eq. 3's, both at 550 nm, 0 m), as printed.
inline constexpr double kRayleighCorrection = 1.0396;
// Eq. 17: K_M, the Mie fudge factor fitted to Table 2.
inline constexpr double kImprovedMieFudge = 0.0092;

// The state of the air along a horizontal path at the observer's altitude.
// Ranges: atmosphere_schema() (haze/request.h).
struct Atmosphere {
  double turbidity = 2.0;   // T [1] (1: pure air)
  double altitude_m = 0.0;  // h0 [m] above sea level
  ScatteringVariant variant = ScatteringVariant::improved;
};

// InvalidArgument naming the field if a value is out of its range or not finite.
void validate(const Atmosphere& atmosphere);

// Eq. 3 (Preetham, Zhao) or eq. 15 (improved: x K_R): beta_R [1/m] at wavelength `nm` [nm] and
// altitude h [m]: 8 pi^3 (n^2 - 1)^2 / (3 N lambda^4) (6 + 3 p_n) / (6 - 7 p_n) e^(-h / H_R0).
double rayleigh_per_m(double nm, double altitude_m, ScatteringVariant variant);

// The concentration factor c(T) of eq. 4 (scaled so that eq. 4 with lambda in metres gives 1/m):
// eq. 16 (improved) or Preetham's / Zhao's (Morales §5.2).
double concentration(double turbidity, ScatteringVariant variant);

// Preetham's wavelength-dependent fudge factor K(lambda) [1]; piecewise linear through 0.650 at
// 380 nm, 0.666 at 450 nm, 0.678 at 550 nm, 0.686 at 680 nm and 0.690 at 780 nm (the range
// K in [0.65, 0.69] Morales §5.2 quotes, with the values at 450/550/680 nm of Hoffman & Preetham
// 2002), constant outside.
double preetham_fudge(double nm);

// Eq. 4 (Preetham, Zhao) or eq. 18 (improved): beta_M [1/m] =
// 0.434 c(T) pi (2 pi / lambda)^(nu - 2) K e^(-h / H_M0), lambda in metres.
double mie_per_m(double nm, double turbidity, double altitude_m, ScatteringVariant variant);

// beta_sc = beta_R + beta_M (eq. 2) [1/m].
double total_per_m(double nm, const Atmosphere& atmosphere);

// Appendix Table 2: the weather condition of a Mie coefficient at 550 nm and sea level
// [1/km]: "pure air" (0), "exceptionally clear" (<= 0.0639), "very clear" (<= 0.1819), "clear"
// (<= 0.3769), "light haze" (<= 0.9399), "haze" (<= 1.9459), "fog" (above).
std::string weather_class(double beta_mie_per_km);

}  // namespace skylight::haze
