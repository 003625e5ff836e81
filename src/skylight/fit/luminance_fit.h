// Sky models fitted to a photo's luminance samples (`skylight estimate`; docs/ESTIMATE.md): the
// model's registry entry says which parameters are fitted, over which range, by which method and
// how its luminance is computed (models/sky_model.h, EstimationPolicy); here the methods, shared by
// every model, and one result type. Residuals in ln luminance with a free scale s:
//   r_i(p, s) = ln Y_i - ln s - ln L(v_i; p)
// (Morales et al. 2017 §3.4, eq. 8, with s in place of a reference pixel), minimised in least
// squares by Levenberg-Marquardt (core/least_squares.h) from the best point of a grid, robust to
// clouds by RANSAC and with bootstrap spreads (core/robust.h); a discrete parameter (a CIE type)
// is ranked instead.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/frame.h"
#include "skylight/estimate/photo.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"

namespace skylight::fit {

using estimate::LuminanceSample;

struct EstimateSettings {
  // N random sky pixels (Morales 2017 §7.1: N = 100); absent: estimate::kPhotoSamples, or every
  // sky pixel when the mask has no more.
  std::optional<int> samples;
  std::uint64_t seed = 1;         // of the sampling, RANSAC and bootstrap (SplitMix64)
  bool ransac = true;             // reject cloud pixels (§3.4); --no-ransac
  int ransac_iterations = 64;     // random minimal sets tried
  int ransac_minimal_set = 3;     // samples per minimal set
  double inlier_threshold = 0.1;  // |r_i| below this (ln luminance, ~10 %) = clear sky
  int bootstrap = 32;             // resamples of the inliers for the sigmas

  static const ParameterSchema<EstimateSettings>& schema();
};

// The model an estimate fits (`--model`): one of estimated_models(), default
// default_estimated_model().
ParameterSpec estimation_model_spec();

struct FittedParameter {
  std::string name;  // the model schema's, e.g. "turbidity"
  double value = 0.0;
  // Standard deviation over bootstrap resamples of the inliers (refitted each time); 0 without.
  double sigma = 0.0;
};

// One value of a ranked (discrete) parameter.
struct RankedValue {
  double value = 0.0;
  double log_scale = 0.0;
  double residual = 0.0;
  int inliers = 0;
  double inlier_fraction = 0.0;
};

struct LuminanceFit {
  std::string model;
  std::vector<FittedParameter> parameters;  // the policy's axes, in order
  double log_scale = 0.0;                   // ln s: the photo's Y = s x the model's L
  double residual = 0.0;  // RMS of r_i over the inliers (ln luminance: ~ relative error)
  int samples = 0, inliers = 0;
  double inlier_fraction = 1.0;  // inliers / samples
  // "levenberg-marquardt"; "bracketing" when LM did not improve on a profile scan's bracket;
  // "ranking" for a discrete parameter.
  std::string method;
  int iterations = 0;  // LM iterations of the final fit
  SunPosition sun;
  std::vector<RankedValue> ranking;  // ranking: every value, best first

  // The fitted parameter `name` (InvalidArgument when it was not fitted).
  const FittedParameter& parameter(std::string_view name) const;
};

// The estimation policy of model `name` (InvalidArgument for an unknown model or one that is not
// fitted to photos: the message lists those that are).
const EstimationPolicy& estimation_policy(std::string_view name);
// The models with an estimation policy, in registry order, and the one fitted by default.
std::vector<std::string> estimated_models();
std::string default_estimated_model();

// The fit of `model` to the samples (at least one more than its fitted parameters; views above
// the horizon, luminance > 0) under a sun above the horizon: RANSAC (when settings.ransac), the
// final fit on the inliers, the bootstrap sigmas (settings.bootstrap >= 2).
LuminanceFit fit_luminance(std::string_view model, std::span<const LuminanceSample> samples,
                           const SunPosition& sun, const EstimateSettings& settings);

// A one-parameter (profile_scan) model fitted to all samples, no RANSAC, no bootstrap: the scan,
// LM from its best point, the golden section in the bracket where LM fails or ends worse. With
// `bracketing_only`, the scan and the golden section alone (the slow reference of the tests).
LuminanceFit fit_profile(std::string_view model, std::span<const LuminanceSample> samples,
                         const SunPosition& sun, bool bracketing_only = false);

// The fitted sky drawn on the photo's pixels, for comparison with the photo: s L(v; p) at the
// centre of every pixel whose direction is above the horizon, 0 elsewhere (one channel).
io::ImageF fitted_luminance_image(const LuminanceFit& fit, const Camera& camera);

// The whole estimate from a photo: estimate::sample_photo (sun given or found, mask, samples) and
// fit_luminance.
struct PhotoFit {
  LuminanceFit fit;
  std::size_t sky_pixels = 0;
  bool sun_detected = false;
  estimate::SkyMask mask;
};
PhotoFit estimate_from_photo(std::string_view model, const io::ImageF& image, const Camera& camera,
                             const std::optional<SunPosition>& sun,
                             const estimate::MaskSettings& mask_settings,
                             const EstimateSettings& settings,
                             const io::ImageF* user_mask = nullptr);

}  // namespace skylight::fit
