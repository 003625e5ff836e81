// The attenuation factor Gamma_c(T, s) of Morales et al. 2017 eq. 11: the camera-weighted mean of
// e^(-beta_sc(lambda, T, h0) s) over 380 .. 780 nm, by the trapezoid rule on the 5 nm grid (the
// embedded sensitivities' own samples; a user CSV is interpolated linearly onto it), and its
// lookup table in distance for the image operations (docs/HAZE.md).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "skylight/haze/coefficients.h"
#include "skylight/haze/sensitivity.h"

namespace skylight::haze {

using Rgb3 = std::array<double, 3>;

// Wavelength grid of the integrals: 380 .. 780 nm in 5 nm steps.
inline constexpr double kGridStepNm = 5.0;
inline constexpr std::size_t kGridSamples = 81;

// Camera-weighted spectral integrals on the 5 nm grid.
class SpectralWeights {
 public:
  explicit SpectralWeights(const CameraSensitivity& camera);
  // w_c(lambda_i) = trapezoid weight x q_c(lambda_i) / integral of q_c (sums to 1 per channel).
  const std::array<std::array<double, kGridSamples>, 3>& normalised() const { return w_; }
  // Trapezoid weight x q_c(lambda_i) [nm] (eq. 7: I_c = sum_i raw_c[i] L(lambda_i)).
  const std::array<std::array<double, kGridSamples>, 3>& raw() const { return raw_; }
  static double nm(std::size_t i) { return 380.0 + kGridStepNm * static_cast<double>(i); }

 private:
  std::array<std::array<double, kGridSamples>, 3> w_{}, raw_{};
};

// Eq. 11 for one atmosphere and camera, precomputed.
class Attenuation {
 public:
  Attenuation(const Atmosphere& atmosphere, const CameraSensitivity& camera);
  // Gamma_c(T, s) for a horizontal path of s [m] >= 0 at h0 (eq. 11, trapezoid).
  Rgb3 gamma(double s_m) const;
  // The largest |d^2 Gamma_c / ds^2| over s >= 0 [1/m^2]: sum_i w_c,i beta_i^2 (at s = 0, as every
  // term beta^2 e^(-beta s) decreases with s); bounds the table's interpolation error.
  double max_curvature_per_m2() const;
  const std::array<double, kGridSamples>& beta_per_m() const { return beta_; }

 private:
  SpectralWeights weights_;
  std::array<double, kGridSamples> beta_{};
};

// Gamma_c tabulated at s_i = i h, i = 0 .. n - 1, h = max_distance / (n - 1), linear in between
// (a GLSL port reads it as a 1D texture). Interpolation error <= h^2 / 8 x max curvature.
struct AttenuationTable {
  double step_m = 1.0;
  std::vector<float> gamma;  // 3 per entry (r, g, b)
  double error_bound = 0.0;  // the bound above [1]
  std::size_t size() const { return gamma.size() / 3; }
};

// The smallest table whose bound is at most `max_error` (at least 2 and at most 2^20 entries; the
// bound reached is stored in the table). The step is chosen for max(curvature,
// `curvature_floor_per_m2`), so that two tables made with the same floor share their grid.
AttenuationTable make_attenuation_table(const Attenuation& attenuation, double max_distance_m,
                                        double max_error, double curvature_floor_per_m2 = 0.0);

}  // namespace skylight::haze
