// The one pixel <-> direction camera of the project (docs/CONVENTIONS.md): an image of width x
// height pixels in one of the layouts of core/frame.h. `render` draws with it, `estimate` reads
// sky photos through it, `haze` finds a photo's horizon with it and `gpu` ports it to GLSL, so a
// rendered sky is read back pixel for pixel.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "skylight/core/frame.h"

namespace skylight {

enum class Projection { equirect, hemisphere, fisheye, cubemap, camera };
std::optional<Projection> parse_projection(std::string_view name);
std::string_view to_string(Projection p);

// A pinhole (perspective) camera at the observer (e.g. `nishita` with an observer altitude: the
// planet and its limb from orbit). The image centre looks along direction(look_zenith,
// look_azimuth) (core/frame.h); image up is the projection of the zenith (of north when looking
// straight up or down); vertical_fov spans the image height, square pixels.
struct PinholeLayout {
  double look_zenith = kPi / 2;   // [rad], [0, pi]; default: the horizon
  double look_azimuth = 0.0;      // [rad], from north towards east
  double vertical_fov = kPi / 3;  // [rad], (0, pi)
};

// Largest image side [px]: keeps width x height x 3 floats addressable and sane.
inline constexpr int kMaxImageSide = 32768;

struct Camera {
  Projection projection = Projection::equirect;
  int width = 1024;       // [px], [1, kMaxImageSide]
  int height = 512;       // [px], [1, kMaxImageSide]; cubemap: width = 6 height
  FisheyeLayout fisheye;  // Projection::fisheye: image circle of diameter min(width, height),
                          // centred, optical axis at the zenith
  PinholeLayout pinhole;  // Projection::camera

  // Direction seen at continuous pixel position (col, row) (pixel centres at +0.5, row 0 at the
  // top); nullopt where the layout images nothing (outside a fisheye's image circle, outside an
  // equirect image).
  std::optional<Vec3> direction(double col, double row) const;
  // Direction of the centre of pixel (col, row).
  std::optional<Vec3> pixel_direction(int col, int row) const {
    return direction(col + 0.5, row + 0.5);
  }
  // Inverse (fisheye and equirect layouts): the continuous pixel position of a direction, nullopt
  // where it is not imaged (and for the other layouts).
  std::optional<std::array<double, 2>> pixel(Vec3 d) const;
};

// Throws InvalidArgument naming the setting and value unless each side is in
// [1, kMaxImageSide], a cubemap is 6:1, the fisheye's field of view is within its lens's limits
// ((0, 2 pi]; orthographic (0, pi]; stereographic (0, 2 pi)) with a finite north angle, and the
// pinhole looks along a direction with a field of view in (0, pi).
void validate(const Camera& camera);

// The camera of a width x height image in `projection` (fisheye: `layout`), validated.
Camera image_camera(Projection projection, const FisheyeLayout& layout, int width, int height);

}  // namespace skylight
