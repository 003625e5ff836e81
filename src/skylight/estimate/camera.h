// Camera models of sky photographs (docs/ESTIMATE.md): which view direction each pixel of a photo
// sees. The mappings are the project's own (core/frame.h, docs/CONVENTIONS.md), the same that
// `render` draws with, so a rendered fisheye or equirect sky is read back pixel for pixel.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "skylight/core/frame.h"

namespace skylight::estimate {

enum class PhotoProjection { fisheye, equirect };
std::optional<PhotoProjection> parse_photo_projection(std::string_view name);
std::string_view to_string(PhotoProjection p);

// A photo's geometry: its size [px] and projection. Fisheye: image circle of diameter
// min(width, height), centred, optical axis at the zenith, `fisheye` = lens, field of view and
// north angle (core/frame.h). Equirect: the full sphere, row 0 at the zenith, column 0 north.
struct SkyCamera {
  PhotoProjection projection = PhotoProjection::fisheye;
  int width = 0;   // [px], >= 1
  int height = 0;  // [px], >= 1
  FisheyeLayout fisheye;

  // Direction seen at continuous pixel position (col, row) (pixel centres at +0.5); nullopt
  // where the projection images nothing (outside the fisheye's image circle).
  std::optional<Vec3> direction(double col, double row) const;
  // Direction of the centre of pixel (col, row).
  std::optional<Vec3> pixel_direction(int col, int row) const {
    return direction(col + 0.5, row + 0.5);
  }
  // Inverse: continuous pixel position of a direction, nullopt where it is not imaged.
  std::optional<std::array<double, 2>> pixel(Vec3 d) const;
};

// Throws InvalidArgument unless the size is positive and the fisheye's field of view is in
// (0, 2 pi) and within its lens's limits (orthographic <= pi).
void validate(const SkyCamera& camera);

// The camera of a width x height image in `projection` (fisheye: `layout`), validated.
SkyCamera image_camera(PhotoProjection projection, const FisheyeLayout& layout, int width,
                       int height);

}  // namespace skylight::estimate
