// Per-pixel airlight I^inf_c(T, phi, theta) (Morales et al. 2017 §6.2 step 3; docs/HAZE.md
// "Per-pixel airlight"): each pixel's view direction from the image's camera
// (haze/positioning.h, eqs. 20-22), then its airlight from a sky photo's horizon region (eqs.
// 12-13 at the pixel's zenith angle) or from a sky model seen through the camera (eq. 7) via a
// direction table.
#pragma once

#include <memory>
#include <vector>

#include "skylight/haze/image_haze.h"
#include "skylight/haze/positioning.h"

namespace skylight::haze {

// Default grid step of AirlightTable [rad].
inline constexpr double kAirlightTableStep = 1.0 * kDegree;

// A sky model's airlight (sky_model_airlight) on a regular grid over the upper hemisphere, zenith
// angle theta in [0, pi/2] and azimuth phi in [0, 2 pi] (periodic), read by bilinear
// interpolation in (theta, phi). Directions below the horizon take the horizon's value at their
// azimuth (the airlight of eq. 10 is the sky at infinite distance; the models' ground is not sky).
class AirlightTable {
 public:
  // step in (0, pi/4] [rad]; evaluates the model at every node (threads).
  AirlightTable(const SkyModel& model, const CameraSensitivity& camera,
                double step = kAirlightTableStep);
  Rgb3 at(Vec3 direction) const;
  std::size_t theta_nodes() const { return n_theta_; }
  std::size_t phi_nodes() const { return n_phi_; }

 private:
  std::size_t n_theta_ = 0, n_phi_ = 0;
  double step_theta_ = 0.0, step_phi_ = 0.0;
  std::vector<Rgb3> values_;  // [i_theta * n_phi + i_phi]
};

// Eqs. 12-13 per pixel: I^inf(theta') zeta(T, theta, theta') with theta the pixel's zenith angle
// (zeta clamps cos theta at 0.01, so below the horizon the horizon's value) and I^inf(theta'),
// theta' the horizon region's at the pixel's azimuth phi (eq. 12's "same azimuth"): the two
// PhotoAirlight::sectors around phi, each through eq. 13, linear in azimuth between the sectors'
// centres; without sectors the whole region's (PhotoAirlight::horizon, theta_prime).
std::shared_ptr<const AirlightMap> photo_airlight_map(const ImagePositioning& camera,
                                                      const PhotoAirlight& horizon,
                                                      double turbidity);

// A sky model's airlight per pixel through its AirlightTable.
std::shared_ptr<const AirlightMap> sky_model_airlight_map(const ImagePositioning& camera,
                                                          const AirlightTable& table);

}  // namespace skylight::haze
