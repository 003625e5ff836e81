// Renders a SkyModel into an image in one of the project's layouts (core/frame.h): the batch path
// over all pixels, on all threads.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/frame.h"
#include "skylight/io/image.h"
#include "skylight/models/evaluation.h"
#include "skylight/models/sky_model.h"

namespace skylight::render {

using io::ImageF;

// The image (core/camera.h: layout and size) and what is drawn in it (models/evaluation.h: the
// sky, sky + solar disc or the disc alone; the disc integrated over each pixel's footprint,
// average_sun_over_pixel).
struct RenderSettings : Camera {
  SunMode sun = SunMode::sky;
};

struct SkyImage {
  ImageF xyz;                      // CIE XYZ, Y in the model's luminance unit (cd/m^2)
  ImageF rgb;                      // linear sRGB, same scale
  std::vector<std::uint8_t> mask;  // 1 where the pixel sees no direction (outside a fisheye circle)

  // Pixel i (row-major) in both colour spaces, rounded to float.
  void set(std::size_t i, const Xyz& c, const Rgb& rgb) {
    float* px = xyz.data.data() + 3 * i;
    px[0] = static_cast<float>(c.X);
    px[1] = static_cast<float>(c.Y);
    px[2] = static_cast<float>(c.Z);
    float* pr = this->rgb.data.data() + 3 * i;
    pr[0] = static_cast<float>(rgb.r);
    pr[1] = static_cast<float>(rgb.g);
    pr[2] = static_cast<float>(rgb.b);
  }
};

// Direction of each pixel centre (unit vectors, ENU) as structure of arrays; `valid[i]` = 0 where
// the layout has no direction (such pixels get the zenith direction and are masked).
struct PixelDirections {
  std::vector<float> x, y, z;
  std::vector<std::uint8_t> valid;
};
PixelDirections pixel_directions(const RenderSettings& settings);

// The solar disc's radiance averaged over pixel (col, row): the pixel is supersampled wherever it
// may overlap the disc, so the sun's energy in a map does not depend on the resolution (a disc
// smaller than a pixel is spread over that pixel instead of being hit or missed by its centre).
Xyz average_sun_over_pixel(const SkyModel& model, const RenderSettings& settings, int col, int row);

// Memory render_sky needs [bytes]: kRenderBytesPerPixel per pixel (directions 13, batch XYZ 12,
// the XYZ and RGB images 24, mask 1, and the CLI's false-colour luminance and 8-bit previews).
inline constexpr std::size_t kRenderBytesPerPixel = 54;
std::size_t render_memory_bytes(const RenderSettings& settings);

// Renders the sky. Throws IoError up front when the image needs more memory than is available
// (render_memory_bytes), instead of failing part-way.
SkyImage render_sky(const SkyModel& model, const RenderSettings& settings);

}  // namespace skylight::render
