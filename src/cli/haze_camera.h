// The camera of an image for `skylight haze add|retarget|remove|composite` (haze_cmd.cpp): a
// pinhole from --vfov/--hfov, --heading, --pitch, --roll, or the raw OpenGL matrices
// --view-matrix and --projection-matrix (Morales 2017 eq. 22; haze/positioning.h, docs/HAZE.md).
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <vector>

#include "skylight/haze/positioning.h"

namespace skylight::cli {

struct HazeCameraFlags {
  std::optional<double> vfov_deg, hfov_deg;
  double heading_deg = 0.0, pitch_deg = 0.0, roll_deg = 0.0;
  std::vector<double> view_matrix, projection_matrix;
  CLI::Option *heading = nullptr, *pitch = nullptr, *roll = nullptr;

  void add(CLI::App& cmd);
  // Whether the image has a camera (a field of view or a projection matrix given).
  bool given() const;
  // The image's positioning for a width x height image; near and far are the pinhole's clip
  // planes (the depth map's when normalised; directions do not depend on them). nullopt without a
  // camera; InvalidArgument for an incomplete camera (angles without a field of view).
  std::optional<haze::ImagePositioning> positioning(int width, int height, double near_m,
                                                    double far_m) const;
};

}  // namespace skylight::cli
