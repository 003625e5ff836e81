// The Perez-form luminance distribution shared by the `perez`, `preetham` and `cie` models, with a
// scalar double-precision reference and a SIMD single-precision batch path (Highway, dynamic
// dispatch to the best instruction set of the running CPU).
//
// Generalised Perez function (Perez, Seals & Michalsky 1993; Preetham et al. 1999 eq. A.2;
// CIE S 011:2003 with K = 1 - c exp(d pi/2)):
//   F(theta, gamma) = (1 + A exp(B / cos theta)) (K + C exp(D gamma) + E cos^2 gamma)
// theta: view zenith angle, gamma: angle between view and sun [rad]; A..E, K dimensionless.
#pragma once

#include <array>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/models/gpu_sky.h"
#include "skylight/models/sky_model.h"

namespace skylight {

// cos(theta) is clamped to at least this in the gradation term B / cos(theta): 0.01 rad-equivalent
// keeps theta <= 89.43 deg, so coefficient sets with B > 0 (Preetham's Y below T = 1.2, user Perez
// coefficients) cannot overflow at the horizon; with B < 0 the term is < e^-(|B| 100) there anyway.
inline constexpr double kPerezMinCosTheta = 0.01;
// Exponent arguments are clamped to [-80, 80] (e^80 ~ 5.5e34 fits in float), so extreme user
// coefficients saturate rather than overflow; no published coefficient set comes near.
inline constexpr double kPerezMaxExponent = 80.0;

struct PerezCoefficients {
  double A = 0.0, B = 0.0, C = 0.0, D = 0.0, E = 0.0;
  double K = 1.0;  // constant of the indicatrix factor (1 for Perez/Preetham)
};

// F(theta, gamma) with cos_theta already clamped by the caller or not (it is clamped here).
double perez_function(const PerezCoefficients& c, double cos_theta, double gamma);

// A ready-to-evaluate distribution: up to three Perez channels, each scaled.
//  * mode xyY: channels (Y, x, y): Y = scale_0 F_0 [cd/m^2], x = scale_1 F_1, y = scale_2 F_2,
//    converted to XYZ (Preetham).
//  * mode luminance: one channel Y = scale_0 F_0, XYZ with the fixed chromaticity `white`.
// Below the horizon (view z < 0) the result is 0. Negative Y (Preetham's negative-Yz region) is
// returned as 0: luminance cannot be negative.
struct PerezDistribution {
  enum class Mode { xyY, luminance };
  Mode mode = Mode::luminance;
  std::array<PerezCoefficients, 3> coefficients{};
  std::array<double, 3> scale{1.0, 1.0, 1.0};
  Chromaticity white = kD65WhiteSrgb;
  Vec3 sun{0.0, 0.0, 1.0};

  // Reference path (double precision, accurate gamma via angle_between).
  Xyz evaluate(Vec3 view) const;
  // Batch path (single precision SIMD). Error vs evaluate(): see kPerezBatchRelativeTolerance in
  // the tests; gamma uses the chord formula 2 asin(|v - s| / 2) so the aureole stays accurate.
  void evaluate_batch(const DirectionsSoA& dirs, const XyzSoA& out) const;
  // The same distribution as a shader's function (models/gpu_sky.h; perez.cpp): evaluate() in
  // float, its clamps included, with the angle to the sun by the chord as the batch path.
  GpuSky gpu_sky() const;
};

}  // namespace skylight
