// The image camera flags of `skylight haze` (Morales 2017 eqs. 20-23; docs/HAZE.md).
#include "haze_camera.h"

#include "common.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"

namespace skylight::cli {
namespace {

haze::Mat4 to_mat4(const std::vector<double>& v) {
  haze::Mat4 m{};
  for (std::size_t i = 0; i < 16; ++i) m[i] = v[i];
  return m;
}

ParameterSpec matrix_spec(const char* name, const char* help) {
  return {name, "1", ParameterKind::numbers, -1e30, 1e30, 16, Absent{"no camera"}, help};
}

}  // namespace

void HazeCameraFlags::add(CLI::App& cmd) {
  auto* v = add_number(cmd,
                       {"vfov", "deg", ParameterKind::number, 0.01, 179.0, 1, Absent{"no camera"},
                        "image camera (pinhole): vertical field of view across the image; gives "
                        "every pixel its own airlight (--sky, --sky-model)"},
                       vfov_deg);
  auto* h = add_number(cmd,
                       {"hfov", "deg", ParameterKind::number, 0.01, 179.0, 1, Absent{"no camera"},
                        "image camera (pinhole): horizontal field of view (instead of --vfov)"},
                       hfov_deg);
  v->excludes(h);
  heading =
      add_number(cmd,
                 {"heading", "deg", ParameterKind::number, -360.0, 360.0, 1, ParameterValue(0.0),
                  "image camera: azimuth of the optical axis (north 0, east 90)"},
                 heading_deg);
  pitch = add_number(cmd,
                     {"pitch", "deg", ParameterKind::number, -90.0, 90.0, 1, ParameterValue(0.0),
                      "image camera: elevation of the optical axis"},
                     pitch_deg);
  roll = add_number(cmd,
                    {"roll", "deg", ParameterKind::number, -180.0, 180.0, 1, ParameterValue(0.0),
                     "image camera: turn about the optical axis, clockwise as the camera sees it"},
                    roll_deg);
  auto* vm = add_numbers(
      cmd,
      matrix_spec("view-matrix",
                  "image camera: OpenGL model-view matrix M, 16 numbers row-major, world frame "
                  "East-North-Up (instead of --heading/--pitch/--roll)"),
      view_matrix);
  auto* pm = add_numbers(
      cmd,
      matrix_spec("projection-matrix",
                  "image camera: OpenGL projection matrix P, 16 numbers row-major (instead of "
                  "--vfov/--hfov)"),
      projection_matrix);
  vm->excludes(heading)->excludes(pitch)->excludes(roll);
  pm->excludes(v)->excludes(h);
}

bool HazeCameraFlags::given() const {
  return vfov_deg || hfov_deg || !projection_matrix.empty() || !view_matrix.empty() ||
         heading->count() > 0 || pitch->count() > 0 || roll->count() > 0;
}

std::optional<haze::ImagePositioning> HazeCameraFlags::positioning(int width, int height,
                                                                   double near_m,
                                                                   double far_m) const {
  if (!given()) return std::nullopt;
  if (!vfov_deg && !hfov_deg && projection_matrix.empty())
    throw InvalidArgument(
        "the image camera needs a field of view: give --vfov, --hfov or --projection-matrix");
  const haze::Mat4 view = view_matrix.empty()
                              ? haze::view_matrix(wrap_azimuth(deg_to_rad(heading_deg)),
                                                  deg_to_rad(pitch_deg), deg_to_rad(roll_deg))
                              : to_mat4(view_matrix);
  const double aspect = static_cast<double>(width) / height;
  haze::Mat4 projection{};
  if (!projection_matrix.empty()) {
    projection = to_mat4(projection_matrix);
  } else {
    const double fov_y =
        vfov_deg ? deg_to_rad(*vfov_deg) : haze::vertical_fov(deg_to_rad(*hfov_deg), aspect);
    projection = haze::perspective_matrix(fov_y, aspect, near_m, far_m);
  }
  return haze::ImagePositioning(view, projection, width, height);
}

}  // namespace skylight::cli
