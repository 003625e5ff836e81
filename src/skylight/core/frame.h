// skylight's conventions, in one place (docs/CONVENTIONS.md). Every other file uses these helpers;
// code that changes convention (e.g. a paper's own angles) says so in a comment where it happens.
//
//  * Frame: right-handed East-North-Up. x = east, y = north, z = up (zenith).
//  * Angles are radians inside the library; degrees exist only at the CLI and in files.
//  * zenith angle theta in [0, pi] from +z; elevation = pi/2 - theta.
//  * azimuth phi from north (+y) towards east (+x), in [0, 2 pi) (the solar-position convention).
//  * direction(theta, phi) = (sin theta sin phi, sin theta cos phi, cos theta).
//  * gamma = angle between a view direction and the sun direction.
//  * Equirectangular maps: full sphere, row 0 = zenith, last row = nadir; column u <-> azimuth
//    phi = 2 pi (u + 0.5) / width; pixel centres at +0.5. Hemisphere maps are the top half.
//  * Fisheye maps: zenith at the image centre, north up, east on the LEFT (as seen looking up).
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string_view>

#include "skylight/core/math.h"

namespace skylight {

struct Vec3 {
  double x = 0.0;  // east
  double y = 0.0;  // north
  double z = 0.0;  // up
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3 operator*(double s, Vec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
constexpr double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3 a) {
  return std::sqrt(dot(a, a));
}
// Unit vector along a; a must be non-zero.
Vec3 normalize(Vec3 a);

// Zenith angle theta [rad] and azimuth phi [rad] of a direction.
struct ZenithAzimuth {
  double zenith = 0.0;   // theta in [0, pi]
  double azimuth = 0.0;  // phi in [0, 2 pi), from north towards east
};

// direction(theta, phi) = (sin theta sin phi, sin theta cos phi, cos theta)
Vec3 direction_from_angles(double zenith, double azimuth);
// Inverse of direction_from_angles for a unit (or any non-zero) vector. Azimuth of the zenith and
// nadir is 0 by definition.
ZenithAzimuth angles_from_direction(Vec3 d);
// Wraps any azimuth into [0, 2 pi).
double wrap_azimuth(double phi);

// Angle between two unit vectors, accurate at 0 and pi (atan2 of |a x b| and a.b; acos of the dot
// product loses half the digits near 0, exactly where the sun's aureole is).
double angle_between(Vec3 a, Vec3 b);

// The sun's position in the sky. Angles in radians.
struct SunPosition {
  double zenith = 0.0;   // theta_s in [0, pi]; > pi/2 means below the horizon
  double azimuth = kPi;  // phi_s in [0, 2 pi), from north towards east; default south
  double elevation() const { return kPi / 2 - zenith; }
  Vec3 direction() const { return direction_from_angles(zenith, azimuth); }
};

// ---------------------------------------------------------------------------------------------
// Image layouts. Pixel (col, row) has its centre at (col + 0.5, row + 0.5); row 0 is the top.

// Full-sphere equirectangular map: theta = pi (row + 0.5) / height, phi = 2 pi (col + 0.5) / width.
Vec3 equirect_direction(double col_centre, double row_centre, int width, int height);
// Upper-hemisphere equirectangular map: theta = (pi/2) (row + 0.5) / height.
Vec3 hemisphere_direction(double col_centre, double row_centre, int width, int height);

enum class FisheyeLens { equidistant, equisolid, orthographic, stereographic };
std::optional<FisheyeLens> parse_fisheye_lens(std::string_view name);
std::string_view to_string(FisheyeLens lens);

struct FisheyeLayout {
  FisheyeLens lens = FisheyeLens::equidistant;
  double fov = kPi;          // full field of view across the image circle [rad], (0, 2 pi)
  double north_angle = 0.0;  // north is drawn this many radians counter-clockwise from image up
  // A calibrated camera (io/camera_calibration.h): the optical axis at pixel position
  // centre = (col, row) (pixel centres at +0.5) and the image circle's radius [px] at fov / 2;
  // absent: the image's centre and min(width, height) / 2. mirrored: east on the right looking
  // up (a photo of a mirror, a flipped sensor readout).
  std::optional<std::array<double, 2>> centre{};
  std::optional<double> radius{};
  bool mirrored{false};
  bool calibrated() const { return centre || radius || mirrored; }
};

// The image circle of `layout` in a width x height image [px]: its calibrated centre (col, row)
// and radius at fov / 2, or the centred circle of diameter min(width, height).
struct FisheyeCircle {
  double col = 0.0, row = 0.0, radius = 1.0;
};
FisheyeCircle fisheye_image_circle(int width, int height, const FisheyeLayout& layout);

// The lens's mapping g(theta): the radius of zenith angle theta in units of the focal length
// (equidistant theta, equisolid 2 sin(theta/2), orthographic sin theta, stereographic
// 2 tan(theta/2)); nullopt where the lens cannot image theta.
std::optional<double> fisheye_lens_mapping(FisheyeLens lens, double theta);
// Radius (in units of the image-circle radius, 1 at theta = fov/2) of zenith angle theta:
// equidistant r ~ theta, equisolid r ~ 2 sin(theta/2), orthographic r ~ sin theta,
// stereographic r ~ 2 tan(theta/2). Returns nullopt when the lens cannot image theta.
std::optional<double> fisheye_radius(const FisheyeLayout& layout, double theta);
// Zenith angle imaged at normalised radius r (inverse of fisheye_radius), nullopt outside.
std::optional<double> fisheye_theta(const FisheyeLayout& layout, double r);

// Direction seen by fisheye pixel (col, row) of a width x height image whose image circle has
// diameter min(width, height) and is centred (or the layout's calibrated centre and radius);
// nullopt outside the image circle.
// The optical axis points to the zenith; looking up, north is at the top and east on the left.
std::optional<Vec3> fisheye_direction(double col_centre, double row_centre, int width, int height,
                                      const FisheyeLayout& layout);
// Inverse: pixel position (continuous, centres at +0.5) of a direction; nullopt if not imaged.
std::optional<std::array<double, 2>> fisheye_pixel(Vec3 d, int width, int height,
                                                   const FisheyeLayout& layout);

// Cube map as a horizontal strip of six square faces, width = 6 * height, in the order
// +X (east), -X (west), +Y (north), -Y (south), +Z (up), -Z (down). Each face is seen from inside
// the cube: the side faces have "up" (+Z) at the top; the +Z face has north at the top and east on
// the left (as seen looking up, like the fisheye); the -Z face has north at the top and east on the
// right (as seen looking down).
Vec3 cubemap_direction(double col_centre, double row_centre, int width, int height);

}  // namespace skylight
