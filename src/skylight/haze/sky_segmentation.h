// The visible sky of a photo segmented by a marker-controlled watershed, and the horizon region
// of Morales et al. 2017 §4 (eq. 12: "the visible sky is roughly segmented from the textureless
// area of the captured image using a watershed algorithm. Then, a horizon region within the
// visible sky pixels ... is estimated"); docs/HAZE.md "Sky segmentation".
#pragma once

#include <cstdint>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/math.h"
#include "skylight/estimate/photo.h"
#include "skylight/haze/image_haze.h"
#include "skylight/io/image.h"

namespace skylight::haze {

// The markers of the watershed. "Texture" is the mean over a (2 texture_radius + 1)^2 box of the
// gradient magnitude of the log-luminance (Sobel, per pixel).
//  * sky markers: pixels seeing at least sky_seed_elevation above the horizon whose texture is at
//    most sky_seed_texture and whose luminance is at least sky_seed_brightness x the median of
//    such low-texture pixels there (the smooth, bright sky around the zenith);
//  * non-sky markers: every imaged pixel at or below the horizon, and every pixel whose texture
//    is at least ground_texture and whose luminance is below the sky markers' median (textured
//    and darker than the sky: terrain, buildings, vegetation; the sun and bright cloud edges are
//    textured but brighter, and stay unmarked).
// The rest is flooded from the markers (Meyer's flooding, a priority queue) over the 4-connected
// pixel graph whose edges weigh the log-luminance gradient along them, |ln Y(p) - ln Y(q)|: each
// pixel takes the label of the neighbour it is first reached from across the lowest edge, so the
// sky / non-sky boundary falls on the skyline's edges (a watershed cut).
struct SegmentationSettings {
  double sky_seed_elevation = 60.0 * kDegree;  // [rad], [0, pi/2)
  double sky_seed_texture = 0.05;              // [log-luminance / px]
  double sky_seed_brightness = 0.5;            // [1]
  double ground_texture = 0.15;                // [log-luminance / px]
  int texture_radius = 2;                      // [px]
};

// Throws InvalidArgument for settings outside their ranges.
void validate(const SegmentationSettings& settings);

// The sky mask of an RGB (or luminance) photo seen through `camera`: 1 = sky. Pixels outside the
// fisheye's image circle and below the horizon are 0. InvalidArgument when the photo and camera
// sizes differ or no pixel qualifies as a sky marker.
estimate::SkyMask segment_sky(const io::ImageF& photo, const Camera& camera,
                              const SegmentationSettings& settings = {});

// The mask as an 8-bit one-channel image (255 = sky) and back (nonzero in any channel = sky; the
// size must be the camera's).
io::Image8 mask_image(const estimate::SkyMask& mask);
estimate::SkyMask mask_from_image(const io::ImageF& image, const Camera& camera);

// The horizon region of eq. 12 within a sky mask: per azimuth bin (kHorizonAzimuthBins over the
// full circle), the sky pixels above the horizon at most `band` above the lowest sky pixel of
// that bin, i.e. the visible sky just over the skyline, whatever its height.
inline constexpr int kHorizonAzimuthBins = 360;
std::vector<std::uint8_t> horizon_region(const estimate::SkyMask& mask, const Camera& camera,
                                         double band = kHorizonBand);

enum class HorizonRegion { watershed, band };

struct HorizonSettings {
  HorizonRegion region = HorizonRegion::watershed;  // the default of photo_airlight and the CLI
  double band = kHorizonBand;                       // [rad]
  SegmentationSettings segmentation;
  const estimate::SkyMask* mask = nullptr;  // watershed: a given sky mask instead of segment_sky
};

// Eq. 12 on the photo: HorizonRegion::band is photo_airlight(sky, camera, turbidity, theta, band)
// (the pixels within `band` above the horizon); HorizonRegion::watershed takes the horizon_region
// of the sky mask (given, or segment_sky). The brightest 1 % of the region as there.
PhotoAirlight photo_airlight(const io::ImageF& sky, const Camera& camera, double turbidity,
                             double theta, const HorizonSettings& settings);

}  // namespace skylight::haze
