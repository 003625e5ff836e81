// Sky photographs as data for a fit (docs/ESTIMATE.md): luminance from RGB, the sky mask (a user
// mask and the automatic rules), the sun's position found in the image and the random sky samples
// that the fits (fit/luminance_fit.h) take.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/frame.h"
#include "skylight/core/parameters.h"
#include "skylight/io/image.h"

namespace skylight::estimate {

// Relative luminance of a linear RGB pixel with Rec. 709 / sRGB primaries and D65 white
// (IEC 61966-2-1): Y = 0.2126 R + 0.7152 G + 0.0722 B, the Y row of srgb_to_xyz_matrix()
// (core/colorimetry.h), so that Y of a rendered sky is the model's luminance. A one-channel image
// is taken as luminance itself.
double pixel_luminance(const io::ImageF& image, int col, int row);

// The automatic sky-mask rules. A pixel is sky when all hold:
//  * the camera images a direction there (inside the fisheye's image circle) and the direction of
//    its centre is above the horizon, elevation > min_elevation;
//  * every channel is finite and >= 0 and the luminance is > 0;
//  * no channel is saturated: >= saturation_fraction x the largest channel value of the image
//    (the plateau of a clipped exposure; in an unclipped image only the brightest pixel);
//  * the pixel's direction is more than sun_exclusion from the sun (disc, aureole, lens flare),
//    when the sun is known.
struct MaskSettings {
  double min_elevation = 0.0;            // [rad], [0, pi/2)  (--min-elevation, deg)
  double saturation_fraction = 0.999;    // [1], (0, 1]      (--saturation)
  double sun_exclusion = 5.0 * kDegree;  // [rad], [0, pi)   (--sun-exclusion, deg)

  static const ParameterSchema<MaskSettings>& schema();
};

struct SkyMask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> sky;  // width * height, row 0 at the top; 1 = usable sky pixel
  std::size_t count = 0;          // number of sky pixels
  bool at(int col, int row) const {
    return sky[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
               static_cast<std::size_t>(col)] != 0;
  }
};

// A user's sky mask from a file: .png (8-bit), .pfm, .exr or .hdr; one channel, the largest of the
// file's channels (nonzero = sky). IoError for a missing or corrupt file.
io::ImageF load_mask(const std::filesystem::path& path);

// The sky mask of `image` seen through `camera` by the automatic rules, restricted to the user's
// mask where one is given (nonzero in any channel = sky; it must have the image's size, otherwise
// InvalidArgument naming both sizes). `sun` enables the sun exclusion.
SkyMask sky_mask(const io::ImageF& image, const Camera& camera, const MaskSettings& settings,
                 const std::optional<SunPosition>& sun = std::nullopt,
                 const io::ImageF* user_mask = nullptr);

// The sun found in the image: the centroid of the connected region of pixels whose luminance is at
// least region_fraction x the brightest (the saturated plateau of a clipped sun, or the peak of an
// unclipped one), grown from the brightest imaged pixel above the horizon.
struct SunDetection {
  SunPosition sun;
  double col = 0.0, row = 0.0;  // centroid [px], continuous (pixel centres at +0.5)
  std::size_t region_pixels = 0;
  double peak_luminance = 0.0;  // in the image's unit
};
inline constexpr double kSunRegionFraction = 0.95;
// Throws InvalidArgument when no imaged pixel above the horizon has positive finite luminance, or
// when the centroid lies below the horizon.
SunDetection detect_sun(const io::ImageF& image, const Camera& camera,
                        double region_fraction = kSunRegionFraction);

// The image options of a sky photo (core/camera.h): fisheye or equirect, the size the file's;
// `projection_flag` names the projection's option (e.g. "sky-projection" for a second image).
ImageSchemaOptions photo_image_options(Projection default_projection = Projection::fisheye,
                                       std::string projection_flag = "projection",
                                       std::string description = "the photo's layout");

// One sample point: a view direction and the photo's luminance there (any positive unit).
struct LuminanceSample {
  Vec3 view;
  double luminance = 0.0;
};

// Draws `samples` sky pixels (uniformly over the mask, with SplitMix64 seeded by `seed`) and their
// luminance. Throws InvalidArgument when the mask has fewer sky pixels.
std::vector<LuminanceSample> sample_sky(const io::ImageF& image, const Camera& camera,
                                        const SkyMask& mask, int samples, std::uint64_t seed);

// Every sky pixel of the mask once, in image order, and its luminance.
std::vector<LuminanceSample> every_sky_pixel(const io::ImageF& image, const Camera& camera,
                                             const SkyMask& mask);

// Sky pixels an estimate samples by default: 5 % noise and 10 % cloud, T 2-8, sun zenith 15-75
// deg, spread the turbidity over 20 noise realisations by at most 0.084 (T 8, sun zenith 15 deg;
// docs/ESTIMATE.md, "Uncertainty"), where Morales et al. 2017's N = 100 spread it by 0.83.
inline constexpr int kPhotoSamples = 6000;

// A photo's samples as `skylight estimate` draws them: the sun (given, or found by detect_sun;
// InvalidArgument when it is not above the horizon), the sky mask (the automatic rules with the
// sun exclusion, and the user's mask when given) and `samples` random sky pixels (absent:
// kPhotoSamples, or every sky pixel when the mask has no more).
struct PhotoSamples {
  std::vector<LuminanceSample> samples;
  SunPosition sun;
  bool sun_detected = false;   // the sun came from detect_sun
  std::size_t sky_pixels = 0;  // in the mask the samples were drawn from
  SkyMask mask;                // that mask
};
PhotoSamples sample_photo(const io::ImageF& image, const Camera& camera,
                          const std::optional<SunPosition>& sun, const MaskSettings& mask_settings,
                          std::optional<int> samples, std::uint64_t seed,
                          const io::ImageF* user_mask = nullptr);

// The photo's luminance per pixel (pixel_luminance; one channel).
io::ImageF photo_luminance_image(const io::ImageF& image);

}  // namespace skylight::estimate
