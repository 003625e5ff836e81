// A camera calibration file (JSON; docs/CONVENTIONS.md, "Camera calibration"): the layout of a
// real camera's photos — projection, fisheye lens and field of view, the image circle's centre and
// radius, mirroring, north angle — measured once and given with --calibration instead of
// hand-typed flags.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "skylight/core/camera.h"
#include "skylight/core/frame.h"

namespace skylight::io {

struct CameraCalibration {
  std::string name;  // the file, for messages
  Projection projection = Projection::fisheye;
  FisheyeLayout fisheye;                         // lens, fov, north angle, centre, radius, mirror
  std::optional<std::array<int, 2>> image_size;  // the photos' size it was made for
  // The camera of a width x height photo: InvalidArgument when the file names another size.
  // focal_length_px (from the photo's EXIF, io/exif.h; scaled to this width) gives a fisheye's
  // image-circle radius, f g(fov / 2), when the file gives none.
  Camera camera(int width, int height, std::optional<double> focal_length_px = {}) const;
};

// Parses a calibration (InvalidArgument "NAME: ..." for malformed JSON, an unknown key, a value
// of the wrong type or out of range).
CameraCalibration parse_camera_calibration(std::string_view json, std::string_view name);
// Reads and parses a calibration file (IoError when it cannot be read).
CameraCalibration read_camera_calibration(const std::filesystem::path& path);

// The camera of a photo as an operation's options describe it: the calibration file they name
// (ImageOptions::calibration), else their flags (ImageOptions::camera).
Camera photo_camera(const ImageOptions& options, int width, int height,
                    std::optional<double> focal_length_px = {});

}  // namespace skylight::io
