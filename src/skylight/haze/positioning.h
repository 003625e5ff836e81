// Per-pixel positioning of Morales et al. 2017 §6.2 (eqs. 19-23; docs/HAZE.md "Positioning"): the
// camera of an image as an OpenGL model-view matrix M and projection matrix P, the world position
// of a pixel's depth sample by un-projection (eq. 22 with the remap R of eq. 23), and the view
// direction's zenith theta and azimuth phi (eqs. 20-21) in the conventions of docs/CONVENTIONS.md
// (East-North-Up world frame, azimuth from north towards east).
#pragma once

#include <array>

#include "skylight/core/frame.h"

namespace skylight::haze {

// A 4x4 matrix, row-major (m[4 r + c] is row r, column c); acts on column vectors.
using Mat4 = std::array<double, 16>;

Mat4 identity4();
Mat4 multiply(const Mat4& a, const Mat4& b);
// The inverse; InvalidArgument naming `what` when the matrix is singular (|det| relative to the
// entries' scale below 1e-12).
Mat4 invert(const Mat4& m, std::string_view what);

// Eq. 23: window coordinates [0, 1]^3 -> normalised device coordinates [-1, 1]^3.
Mat4 remap_matrix();

// The model-view matrix of a camera at the origin of the world frame (East-North-Up): the optical
// axis at azimuth `heading` (from north towards east) and elevation `pitch`, turned by `roll`
// about it (positive: clockwise as the camera sees it, the image's right edge going down); eye
// coordinates as OpenGL's: x to the image's right, y up, looking along -z. Radians.
Mat4 view_matrix(double heading, double pitch, double roll);

// gluPerspective: vertical field of view `fov_y` [rad] in (0, pi), aspect = width / height,
// 0 < near < far [m]. Window depth s_bar of an eye-space depth s is then eq. 19's inverse.
Mat4 perspective_matrix(double fov_y, double aspect, double near_m, double far_m);

// The vertical field of view of an image whose horizontal one is `fov_x` [rad].
double vertical_fov(double fov_x, double aspect);

// Un-projection of one image: pixel (col, row) has the window coordinates
// l_x = (col + 0.5) / width, l_y = 1 - (row + 0.5) / height (row 0 on top; OpenGL's window origin
// is the bottom left).
class ImagePositioning {
 public:
  // InvalidArgument when P M is singular or a size is < 1.
  ImagePositioning(const Mat4& view, const Mat4& projection, int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }

  // Eq. 22: (x, y, z, w) = (P M)^-1 R (l_x, l_y, s_bar, 1), divided by w [world units]. (The paper
  // writes the product as [M P R]^-1 in its own order; this is gluUnProject's, the inverse of
  // window = R^-1 P M X.)
  Vec3 position(double lx, double ly, double s_bar) const;
  // The forward map: window coordinates (l_x, l_y, s_bar) of a world point.
  std::array<double, 3> project(Vec3 world) const;
  // The camera's centre (M^-1 applied to the eye-space origin) [world units].
  Vec3 eye() const { return eye_; }

  // The unit direction of a pixel's ray, from its near-plane point (s_bar = 0) to its far-plane
  // point (s_bar = 1): the same for every depth on the ray, also for orthographic P.
  // InvalidArgument when the matrices give the point none (w = 0, or near = far point).
  Vec3 direction(double lx, double ly) const;
  Vec3 pixel_direction(int col, int row) const;
  // Eqs. 20-21 for a pixel's direction: theta = arccos(z / |v|); the paper's phi = arctan(y / x)
  // from its x axis becomes the azimuth from north towards east of docs/CONVENTIONS.md
  // (angles_from_direction).
  ZenithAzimuth pixel_angles(int col, int row) const;

  static double lx(int col, int width) { return (col + 0.5) / width; }
  static double ly(int row, int height) { return 1.0 - (row + 0.5) / height; }

 private:
  int width_, height_;
  Mat4 forward_;    // R^-1 P M
  Mat4 unproject_;  // (P M)^-1 R
  Vec3 eye_;
};

}  // namespace skylight::haze
