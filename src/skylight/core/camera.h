// The one pixel <-> direction camera of the project (docs/CONVENTIONS.md): an image of width x
// height pixels in one of the layouts of core/frame.h. `render` draws with it, `estimate` reads
// sky photos through it, `haze` finds a photo's horizon with it and `gpu` ports it to GLSL, so a
// rendered sky is read back pixel for pixel.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "skylight/core/frame.h"
#include "skylight/core/parameters.h"

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
  int width = 1024;         // [px], [1, kMaxImageSide]
  int height = 512;         // [px], [1, kMaxImageSide]; cubemap: width = 6 height
  FisheyeLayout fisheye{};  // Projection::fisheye: image circle of diameter min(width, height),
                            // centred, optical axis at the zenith
  PinholeLayout pinhole{};  // Projection::camera

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

// ---- an operation's image as the user gives it ----------------------------------------------

// Default field of view [deg]: a fisheye's across its image circle (the upper hemisphere), a
// pinhole camera's vertical one.
inline constexpr double kFisheyeFovDeg = 180.0;
inline constexpr double kPinholeFovDeg = 60.0;

// The image options of an operation (render, nn animate, estimate's photo, ...) in the user's
// units (degrees), absent values taking the projection's defaults; camera() makes the Camera.
struct ImageOptions {
  Projection projection = Projection::equirect;
  std::optional<int> width;  // absent: the operation's default (cubemap: 6 x height)
  int height = 512;
  FisheyeLens lens = FisheyeLens::equidistant;
  std::optional<double> fov_deg;  // absent: kFisheyeFovDeg (fisheye), kPinholeFovDeg (camera)
  double north_angle_deg = 0.0;
  double look_elevation_deg = 0.0, look_azimuth_deg = 0.0;
  int default_width = 1024;
  // A photo's camera calibration file (io/camera_calibration.h; the schema's --calibration, for
  // images read from files): its layout instead of the projection options. io::photo_camera
  // makes its camera; camera() refuses it.
  std::string calibration;
  std::string projection_flag = "projection";  // the schema's names of the two
  std::string calibration_flag = "calibration";

  // The camera, validated. The second form is for an image read from a file (its size).
  Camera camera() const;
  Camera camera(int width, int height) const;
  // The given options (names of its schema) that this projection does not read, e.g. --lens for
  // an equirect image, or every projection option beside a calibration file: a front end warns
  // about them.
  std::vector<std::string> unread(const ParameterValues& given) const;
  // Metadata of the projection's options: (key, value) of projection, fov, lens, north angle or
  // look direction as outputs record them.
  std::vector<std::pair<std::string, std::string>> metadata() const;
};

// Which options an operation's image takes and their defaults.
struct ImageSchemaOptions {
  std::vector<Projection> projections{Projection::equirect, Projection::hemisphere,
                                      Projection::fisheye, Projection::cubemap, Projection::camera};
  Projection default_projection = Projection::equirect;
  bool size = true;  // --width/--height (false: the size of an image read from a file)
  int width = 1024, height = 512;
  std::string projection_flag = "projection";  // e.g. "sky-projection" for a second image
  // "calibration", "sky-calibration": the projection flag's name with "calibration" for
  // "projection" (images read from files only).
  std::string calibration_flag() const;
  std::string description;  // of the projection, e.g. "the images' projection"
  // The options' values before any is given (the default projection and size).
  ImageOptions defaults() const {
    ImageOptions d;
    d.projection = default_projection;
    d.projection_flag = projection_flag;
    d.calibration_flag = calibration_flag();
    d.height = height;
    d.default_width = width;
    return d;
  }
};
ParameterSchema<ImageOptions> image_schema(const ImageSchemaOptions& options);

}  // namespace skylight
