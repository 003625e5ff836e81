// A photo's capture as its camera recorded it (io/exif.h): `--exif FILE` names the JPEG, TIFF or
// DNG the HDR photo was made from; its time (with --utc-offset for cameras that write none) and
// GPS place give the sun through the SPA, its focal length the scale of a calibrated fisheye
// (io/camera_calibration.h). docs/ESTIMATE.md, "Real photos".
#pragma once

#include <optional>
#include <string>

#include "skylight/core/parameters.h"
#include "skylight/io/exif.h"
#include "skylight/sun/spa.h"

namespace skylight::estimate {

struct CaptureOptions {
  std::string exif;        // the capture's JPEG / TIFF / DNG; empty: none
  std::string utc_offset;  // "+HH:MM" / "-HH:MM"; empty: the EXIF's OffsetTimeOriginal
  static const ParameterSchema<CaptureOptions>& schema();
};

struct Capture {
  io::ExifInfo exif;
  // The focal length in pixels of a photo `photo_width` wide (the EXIF's, scaled by the photo's
  // width over the capture's PixelXDimension when the HDR was resized); absent without one.
  std::optional<double> focal_length_px;
};

// Reads the EXIF of options.exif (InvalidArgument / IoError naming the file).
Capture read_capture(const CaptureOptions& options, int photo_width);

// The SPA input of the capture: its EXIF time and UTC offset, the place from the given --lat /
// --lon or else the EXIF's GPS (and its altitude for --elevation), the other SPA options as
// given (`given`: names of sun::spa_parameter_specs()). InvalidArgument naming what is missing
// (the time, the offset, the place).
sun::SpaInput capture_solar_input(const Capture& capture, const CaptureOptions& options,
                                  const ParameterValues& given);

}  // namespace skylight::estimate
