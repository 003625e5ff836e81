// Morales et al. 2017 eqs. 20-23; docs/HAZE.md "Positioning".
#include "skylight/haze/positioning.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"

namespace skylight::haze {
namespace {

std::array<double, 4> apply(const Mat4& m, const std::array<double, 4>& v) {
  std::array<double, 4> out{};
  for (std::size_t r = 0; r < 4; ++r)
    for (std::size_t c = 0; c < 4; ++c) out[r] += m[4 * r + c] * v[c];
  return out;
}

}  // namespace

Mat4 identity4() {
  Mat4 m{};
  for (std::size_t i = 0; i < 4; ++i) m[5 * i] = 1.0;
  return m;
}

Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 m{};
  for (std::size_t r = 0; r < 4; ++r)
    for (std::size_t c = 0; c < 4; ++c)
      for (std::size_t k = 0; k < 4; ++k) m[4 * r + c] += a[4 * r + k] * b[4 * k + c];
  return m;
}

Mat4 invert(const Mat4& m, std::string_view what) {
  // Gauss-Jordan elimination with partial pivoting on [m | I].
  std::array<std::array<double, 8>, 4> a{};
  double scale = 0.0;
  for (std::size_t r = 0; r < 4; ++r)
    for (std::size_t c = 0; c < 4; ++c) {
      a[r][c] = m[4 * r + c];
      a[r][4 + c] = r == c ? 1.0 : 0.0;
      scale = std::max(scale, std::abs(m[4 * r + c]));
    }
  const auto singular = [&] {
    return InvalidArgument(fmt::format("{} is singular (no inverse)", what));
  };
  if (!(scale > 0.0) || !std::isfinite(scale)) throw singular();
  for (std::size_t col = 0; col < 4; ++col) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < 4; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (std::abs(a[pivot][col]) <= 1e-12 * scale) throw singular();
    std::swap(a[pivot], a[col]);
    const double inv = 1.0 / a[col][col];
    for (double& v : a[col]) v *= inv;
    for (std::size_t r = 0; r < 4; ++r) {
      if (r == col) continue;
      const double f = a[r][col];
      for (std::size_t c = 0; c < 8; ++c) a[r][c] -= f * a[col][c];
    }
  }
  Mat4 out{};
  for (std::size_t r = 0; r < 4; ++r)
    for (std::size_t c = 0; c < 4; ++c) out[4 * r + c] = a[r][4 + c];
  return out;
}

Mat4 remap_matrix() {
  return {2, 0, 0, -1, 0, 2, 0, -1, 0, 0, 2, -1, 0, 0, 0, 1};
}

Mat4 view_matrix(double heading, double pitch, double roll) {
  // Right, forward and up of the level camera (roll 0) in East-North-Up.
  const Vec3 right{std::cos(heading), -std::sin(heading), 0.0};
  const Vec3 forward{std::cos(pitch) * std::sin(heading), std::cos(pitch) * std::cos(heading),
                     std::sin(pitch)};
  const Vec3 up = cross(right, forward);
  // Roll about the optical axis, clockwise as seen by the camera.
  const double c = std::cos(roll), s = std::sin(roll);
  const Vec3 r = c * right - s * up;
  const Vec3 u = c * up + s * right;
  // Rows: the eye axes x = r, y = u, z = -forward (the camera at the origin: no translation).
  return {r.x,        r.y,        r.z,        0.0, u.x, u.y, u.z, 0.0,
          -forward.x, -forward.y, -forward.z, 0.0, 0.0, 0.0, 0.0, 1.0};
}

Mat4 perspective_matrix(double fov_y, double aspect, double near_m, double far_m) {
  SKYLIGHT_CHECK(fov_y > 0.0 && fov_y < kPi && aspect > 0.0 && near_m > 0.0 && far_m > near_m,
                 "perspective_matrix: fov in (0, pi), aspect > 0, 0 < near < far");
  const double f = 1.0 / std::tan(fov_y / 2.0);
  Mat4 m{};
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (far_m + near_m) / (near_m - far_m);
  m[11] = 2.0 * far_m * near_m / (near_m - far_m);
  m[14] = -1.0;
  return m;
}

double vertical_fov(double fov_x, double aspect) {
  return 2.0 * std::atan(std::tan(fov_x / 2.0) / aspect);
}

ImagePositioning::ImagePositioning(const Mat4& view, const Mat4& projection, int width, int height)
    : width_(width), height_(height) {
  if (width < 1 || height < 1)
    throw InvalidArgument(fmt::format("image size {}x{} for positioning", width, height));
  const Mat4 pm = multiply(projection, view);
  unproject_ = multiply(invert(pm, "the projection times the view matrix"), remap_matrix());
  forward_ = multiply(invert(remap_matrix(), "eq. 23's remap"), pm);
  const std::array<double, 4> e = apply(invert(view, "the view matrix"), {0.0, 0.0, 0.0, 1.0});
  eye_ = {e[0] / e[3], e[1] / e[3], e[2] / e[3]};
}

Vec3 ImagePositioning::position(double lx, double ly, double s_bar) const {
  const std::array<double, 4> v = apply(unproject_, {lx, ly, s_bar, 1.0});
  return {v[0] / v[3], v[1] / v[3], v[2] / v[3]};
}

std::array<double, 3> ImagePositioning::project(Vec3 world) const {
  const std::array<double, 4> v = apply(forward_, {world.x, world.y, world.z, 1.0});
  return {v[0] / v[3], v[1] / v[3], v[2] / v[3]};
}

Vec3 ImagePositioning::direction(double lx, double ly) const {
  const Vec3 v = position(lx, ly, 1.0) - position(lx, ly, 0.0);
  const double len = length(v);
  if (!(len > 0.0 && std::isfinite(len)))
    throw InvalidArgument(fmt::format(
        "the image camera gives window point ({:.4g}, {:.4g}) no view direction (its near or far "
        "point has w = 0 in eq. 22, or they coincide): check the projection matrix",
        lx, ly));
  return (1.0 / len) * v;
}

Vec3 ImagePositioning::pixel_direction(int col, int row) const {
  return direction(lx(col, width_), ly(row, height_));
}

ZenithAzimuth ImagePositioning::pixel_angles(int col, int row) const {
  return angles_from_direction(pixel_direction(col, row));
}

}  // namespace skylight::haze
