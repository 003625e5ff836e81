// An environment-map sequence with the sun moving (`skylight nn animate`; docs/NN.md): the sun of
// each frame, from two positions (angles interpolated, the azimuth the short way round) or two
// times (times interpolated, the NREL SPA at --lat/--lon), the frames' image and file names.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "skylight/core/camera.h"
#include "skylight/core/frame.h"
#include "skylight/core/parameters.h"

namespace skylight::render {

struct AnimationOptions {
  std::vector<double> from, to;            // zenith,azimuth [deg]; or empty with the times
  std::string from_time, to_time;          // ISO 8601 with UTC offset; or empty with the angles
  std::optional<double> lat_deg, lon_deg;  // with the times
  int frames = 10;
  ImageOptions image;  // equirect, hemisphere or fisheye; 1024 x 512
  static const ParameterSchema<AnimationOptions>& schema();
  // The image options the frames take.
  static ImageSchemaOptions image_options();
  // Checks that one pair (angles or times) is complete: InvalidArgument naming the options.
  void validate() const;
  // The sun of frame k of n (k / (n - 1) of the way).
  SunPosition frame_sun(int k) const;
};

// PATTERN with its first run of '#' replaced by the zero-padded frame number (at least as many
// digits as the run, and as frames - 1 has). InvalidArgument when the pattern has no '#'.
std::string frame_path(const std::string& pattern, int frame, int frames);

}  // namespace skylight::render
