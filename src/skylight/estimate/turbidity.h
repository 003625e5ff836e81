// Turbidity from a sky photograph (Morales et al. 2017 §3.4, eq. 8; docs/ESTIMATE.md): luminance
// samples of clear sky are compared with the Preetham model at the same sun position.
//
// Eq. 8 minimises sum_n |Y_i(T)/Y_ref(T) - Y_i/Y_ref| over T in [1, 20] with one reference pixel.
// Here (beyond the paper) the reference pixel is replaced by a free luminance scale s, fitted
// with T in log space:
//   r_i(T, s) = ln Y_i - ln s - ln f_i(T),   f_i(T) = F(theta_i, gamma_i; T) / F(0, theta_s; T)
// (f = the Preetham luminance relative to the zenith, Preetham 1999 A.2), minimised in least
// squares by Levenberg-Marquardt, with a bracketing search over T as the fallback, and RANSAC
// against clouds.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "skylight/core/frame.h"
#include "skylight/estimate/camera.h"
#include "skylight/estimate/photo.h"
#include "skylight/io/image.h"

namespace skylight::estimate {

// Turbidity range of the fit. Eq. 8 searches [1, 20]; below T = 1.643 Preetham's gradation factor
// 1 + A_Y exp(B_Y) changes sign at the zenith (docs/MODELS.md), so the relative luminance has no
// logarithm there: the fit starts at 1.7.
inline constexpr double kFitTurbidityMin = 1.7;
inline constexpr double kFitTurbidityMax = 20.0;

// One sample point: a view direction and the photo's luminance there (any positive unit).
struct LuminanceSample {
  Vec3 view;
  double luminance = 0.0;
};

// ln f(T) = ln F(theta, gamma; T) - ln F(0, theta_s; T): Preetham's luminance relative to the
// zenith luminance Yz (Preetham 1999 A.2, Perez coefficients of Y). F > 0 for T in the fit range.
double preetham_log_relative_luminance(double turbidity, Vec3 view, const SunPosition& sun);

struct TurbidityFit {
  double turbidity = 0.0;
  double log_scale = 0.0;  // ln s: the photo's Y = s x Preetham's Y / Yz
  double residual = 0.0;   // RMS of r_i at the optimum (ln luminance: ~ relative error)
  // "levenberg-marquardt", or "bracketing" when LM did not improve on the bracket.
  std::string method;
  int iterations = 0;  // LM iterations
};

// The least-squares fit of (T, ln s) to samples (at least 2) under a sun above the horizon:
// a coarse scan of T brackets the minimum of the profile cost (s eliminated in closed form), LM
// (Eigen) refines T and ln s from the best scan point, and a golden-section search inside the
// bracket replaces LM if LM fails or ends worse.
TurbidityFit fit_turbidity(std::span<const LuminanceSample> samples, const SunPosition& sun);
// The bracketing search alone (the fallback; also the slow reference in the tests).
TurbidityFit fit_turbidity_bracketing(std::span<const LuminanceSample> samples,
                                      const SunPosition& sun);

struct EstimateSettings {
  int samples = 100;              // N random sky pixels (Morales 2017 §7.1: N = 100)
  std::uint64_t seed = 1;         // of the sampling, RANSAC and bootstrap (SplitMix64)
  bool ransac = true;             // reject cloud pixels (§3.4)
  int ransac_iterations = 64;     // random minimal sets tried
  int ransac_minimal_set = 3;     // samples per minimal set (2 unknowns: T, s)
  double inlier_threshold = 0.1;  // |r_i| below this (ln luminance, ~10 %) = clear sky
  int bootstrap = 32;             // resamples of the inliers for turbidity_sigma
};

struct TurbidityEstimate {
  double turbidity = 0.0;
  // Standard deviation of T over bootstrap resamples of the inlier samples (refitted each time).
  double turbidity_sigma = 0.0;
  double inlier_fraction = 1.0;  // inliers / samples
  double residual = 0.0;         // RMS of ln-luminance residuals over the inliers
  double log_scale = 0.0;
  SunPosition sun;
  int samples = 0, inliers = 0;
  std::string method;  // of the final fit
};

// Draws settings.samples sky pixels (uniformly over the mask, with SplitMix64 seeded by
// settings.seed) and their luminance. Throws InvalidArgument when the mask has fewer sky pixels.
std::vector<LuminanceSample> sample_sky(const io::ImageF& image, const SkyCamera& camera,
                                        const SkyMask& mask, int samples, std::uint64_t seed);

// Samples, RANSAC (when enabled), the final fit on the inliers and the bootstrap spread.
TurbidityEstimate estimate_turbidity(std::span<const LuminanceSample> samples,
                                     const SunPosition& sun, const EstimateSettings& settings);
// The whole estimate from a photo: sample_sky + estimate_turbidity.
TurbidityEstimate estimate_turbidity(const io::ImageF& image, const SkyCamera& camera,
                                     const SkyMask& mask, const SunPosition& sun,
                                     const EstimateSettings& settings);

// A photo's samples as `skylight estimate` draws them: the sun (given, or found by detect_sun;
// InvalidArgument when it is not above the horizon), the sky mask (the automatic rules with the
// sun exclusion, and the user's mask when given) and settings.samples random sky pixels.
struct PhotoSamples {
  std::vector<LuminanceSample> samples;
  SunPosition sun;
  bool sun_detected = false;   // the sun came from detect_sun
  std::size_t sky_pixels = 0;  // in the mask the samples were drawn from
  SkyMask mask;                // that mask
};
PhotoSamples sample_photo(const io::ImageF& image, const SkyCamera& camera,
                          const std::optional<SunPosition>& sun, const MaskSettings& mask_settings,
                          const EstimateSettings& settings, const io::ImageF* user_mask = nullptr);

// A fitted sky drawn on the photo's pixels, for comparison with the photo: `luminance(view)` at the
// centre of every pixel whose direction is above the horizon, 0 elsewhere (one channel).
io::ImageF model_luminance_image(const SkyCamera& camera,
                                 const std::function<double(Vec3)>& luminance);
// The photo's luminance per pixel (pixel_luminance; one channel).
io::ImageF photo_luminance_image(const io::ImageF& image);

// The whole estimate from a photo: sample_photo + estimate_turbidity.
struct PhotoEstimate {
  TurbidityEstimate estimate;
  std::size_t sky_pixels = 0;
  bool sun_detected = false;
};
PhotoEstimate estimate_from_photo(const io::ImageF& image, const SkyCamera& camera,
                                  const std::optional<SunPosition>& sun,
                                  const MaskSettings& mask_settings,
                                  const EstimateSettings& settings,
                                  const io::ImageF* user_mask = nullptr);

}  // namespace skylight::estimate
