// Colorimetry from the CIE's published tables (data/cie_colorimetry/, CC BY-SA 4.0, CIE):
// CIE 1931 2-degree colour-matching functions (360-830 nm, 1 nm), spectrum -> XYZ, xyY <-> XYZ,
// XYZ <-> linear sRGB (IEC 61966-2-1 primaries, D65 white), the CIE daylight basis S0/S1/S2
// (CIE 015:2018 Table 6, 300-830 nm, 5 nm), the melanopic action spectrum of CIE S 026:2018
// (Table 2, 380-780 nm, 1 nm) and correlated colour temperature helpers.
#pragma once

#include <array>
#include <span>

namespace skylight {

// Maximum luminous efficacy K_m = 683 lm/W (CIE; the definition of the candela at 540 THz).
inline constexpr double kMaxLuminousEfficacy = 683.0;

// CIE S 026:2018 melanopic efficacy of luminous radiation for D65, K_mel,v^D65 = 1.3262 mW/lm
// [W/lm]: melanopic equivalent daylight (D65) illuminance [lx] = melanopic irradiance [W/m^2] /
// kMelanopicEfficacyD65 (checked against the tables here in colorimetry_test.cpp).
inline constexpr double kMelanopicEfficacyD65 = 1.3262e-3;

// CIE 1931 XYZ. For a radiance-like quantity, Y is luminance in cd/m^2 unless stated otherwise.
struct Xyz {
  double X = 0.0, Y = 0.0, Z = 0.0;
};
// Linear Rec.709/sRGB primaries, D65 white (no transfer curve), same photometric scale as Xyz:
// Y = 0.2126 r + 0.7152 g + 0.0722 b.
struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;
};
struct Chromaticity {
  double x = 0.0, y = 0.0;
};

using Matrix3 = std::array<std::array<double, 3>, 3>;

// CIE 1931 2-degree colour-matching functions x-bar, y-bar, z-bar at wavelength nm, linearly
// interpolated in the 1 nm table; 0 outside 360-830 nm (the CIE metadata's "extrapolation: zero").
struct Cmf {
  double x = 0.0, y = 0.0, z = 0.0;
};
Cmf cie1931_cmf(double nm);
// The melanopic action spectrum s_mel(lambda) of CIE S 026:2018 (its a-opic table's last column,
// peak 1 at 490 nm), linear between the 1 nm rows and 0 outside 380-780 nm (the table's own
// interpolation and extrapolation rules).
double melanopic_sensitivity(double nm);

// Integral of a sampled spectrum against the CMFs, trapezoidal rule over the given wavelengths
// (ascending, nm): returns (integral S x-bar, S y-bar, S z-bar) d lambda, no K_m factor.
Xyz spectrum_to_xyz(std::span<const double> wavelengths_nm, std::span<const double> values);
// Spectral radiance [W m^-2 sr^-1 nm^-1] -> XYZ with Y = luminance [cd/m^2]
// (K_m times spectrum_to_xyz).
Xyz spectral_radiance_to_xyz(std::span<const double> wavelengths_nm,
                             std::span<const double> radiance);

// xyY -> XYZ: X = x Y / y, Z = (1 - x - y) Y / y. y <= 0 gives black.
Xyz xyY_to_xyz(Chromaticity xy, double Y);
// XYZ -> xy; black gives the D65 white point (a defined value, never NaN).
Chromaticity chromaticity(const Xyz& c);

// D65 white point of sRGB, IEC 61966-2-1: x = 0.3127, y = 0.3290.
inline constexpr Chromaticity kD65WhiteSrgb{0.3127, 0.3290};

// The matrices are derived once from the sRGB primaries (R 0.64,0.33; G 0.30,0.60; B 0.15,0.06)
// and the D65 white above, so that XYZ of white (Y = 1) maps to r = g = b = 1.
const Matrix3& xyz_to_srgb_matrix();
const Matrix3& srgb_to_xyz_matrix();
Rgb xyz_to_linear_srgb(const Xyz& c);
Xyz linear_srgb_to_xyz(const Rgb& c);

// ---- CIE daylight (CIE 015:2018 §4.1) ----------------------------------------------------------
// Basis functions S0, S1, S2 at nm, linearly interpolated in the 5 nm table; 0 outside 300-830 nm.
struct DaylightBasis {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0;
};
DaylightBasis daylight_basis(double nm);

// Relative spectral power of CIE daylight with chromaticity xy:
//   S(lambda) = S0 + M1 S1 + M2 S2,
//   M  = 0.0241 + 0.2562 x - 0.7341 y,
//   M1 = (-1.3515 - 1.7703 x + 5.9114 y) / M,   M2 = (0.0300 - 31.4424 x + 30.0717 y) / M.
// M1 and M2 are not rounded (CIE 015 rounds them to 3 decimals for the tabulated D illuminants).
// Meaningful near the daylight locus (CCT ~4000-25000 K); elsewhere the formula still returns
// finite numbers, which may be negative at some wavelengths.
class DaylightSpectrum {
 public:
  explicit DaylightSpectrum(Chromaticity xy);
  double m1() const { return m1_; }
  double m2() const { return m2_; }
  double operator()(double nm) const;
  // (integral S x-bar, S y-bar, S z-bar) d lambda over 360-830 nm (1 nm steps).
  Xyz integral_xyz() const;

 private:
  double m1_ = 0.0, m2_ = 0.0;
};
// M1, M2 of the formula above; a degenerate denominator (|M| < 1e-9) yields M1 = M2 = 0 (S0 only).
std::array<double, 2> daylight_m1_m2(Chromaticity xy);

// (integral S_i y-bar d lambda) for S0, S1, S2, 360-830 nm, 1 nm: lets a caller turn a luminance
// into a daylight spectrum without integrating per sample.
const std::array<double, 3>& daylight_basis_ybar_integrals();

// Chromaticity on the CIE daylight locus for correlated colour temperature T [K], 4000-25000 K
// (CIE 015:2018 eq. 4.7-4.9): x_D from the two cubic fits in 1/T, y_D = -3 x_D^2 + 2.870 x_D -
// 0.275. T is clamped into [4000, 25000].
Chromaticity daylight_chromaticity(double cct_kelvin);
// McCamy's (1992) cubic approximation of the correlated colour temperature [K] of xy:
// n = (x - 0.3320) / (0.1858 - y), CCT = 449 n^3 + 3525 n^2 + 6823.3 n + 5520.33.
double cct_mccamy(Chromaticity xy);

}  // namespace skylight
