// Transposition of horizontal light to a tilted plane (docs/IRRADIANCE.md): the isotropic sky and
// the Perez et al. 1990 model ("Modeling daylight availability and irradiance components from
// direct and global irradiance", Solar Energy 44(5), 271-289), with its circumsolar and horizon-
// brightening coefficients F1, F2 from the "all sites composite" irradiance table (the pvlib
// default), and a far horizon (io/horizon.h) that blocks the sun and parts of the sky.
//
// Conventions: angles in radians; the plane's tilt beta from horizontal (0 = facing up, pi/2 =
// vertical), its azimuth from north towards east (the direction its normal faces); light in any
// one unit (W/m^2 for perez1990, whose F1, F2 are fitted to irradiance).
#pragma once

#include <array>
#include <optional>

#include "skylight/core/frame.h"
#include "skylight/daylight/plane_sky.h"
#include "skylight/io/horizon.h"

namespace skylight::daylight {

// Perez 1990's floor of the sun's cosine in the circumsolar ratio a/b: cos 85 deg.
inline constexpr double kPerezMinSunCosine = 0.08715574274765817;  // cos(85 deg)

// The horizontal light of one hour (one unit throughout): direct normal and diffuse horizontal,
// the sun.
struct HorizontalLight {
  double direct_normal = 0.0, diffuse_horizontal = 0.0;
  SunPosition sun{};
  double global_horizontal() const;  // direct_normal cos Z (0 below the horizon) + diffuse
};

// The light on a plane, by part. The sky's parts (perez1990; the `sky` method's split of its own
// integral, daylight/plane_sky.h): circumsolar, the horizon band and the rest ("isotropic").
// The direct and ground parts are absent where the sky has no sun (a model without a solar disc
// or measured direct light), and then so is the global value.
struct PlaneLight {
  std::optional<double> direct = 0.0;
  double sky_diffuse = 0.0;
  std::optional<double> ground_diffuse = 0.0;
  std::optional<double> isotropic, circumsolar, horizon;
  std::optional<double> global() const {
    if (!direct || !ground_diffuse) return std::nullopt;
    return *direct + sky_diffuse + *ground_diffuse;
  }
};

// The direct light on the plane: direct_normal max(0, cos AOI), 0 when the sun is below the
// horizon or behind the skyline.
double direct_on_plane(const HorizontalLight& light, const Plane& plane,
                       const io::HorizonProfile& horizon);
// The ground's light: a Lambertian ground of reflectance `albedo` lit by the site's global
// horizontal light, seen by the plane through (1 - cos beta)/2. `shaded_global` is the global
// horizontal light that reaches the site (through the horizon).
double ground_on_plane(double shaded_global, double albedo, const Plane& plane);

// The isotropic sky: sky_diffuse = D sky_view; the ground from the shaded global horizontal
// light (direct horizontal + D horizontal_view).
PlaneLight isotropic_transposition(const HorizontalLight& light, const Plane& plane, double albedo,
                                   const io::HorizonProfile& horizon, const HorizonViews& views);

// Perez 1990's state of one hour (irradiance [W/m^2]): clearness epsilon (eq. 1), brightness
// Delta = D m / I0 (eq. 2) with the air mass m and extraterrestrial normal irradiance I0 the
// caller gives, the bin 1..8, and F1 = max(0, f11 + f12 Delta + f13 Z), F2 = f21 + f22 Delta +
// f23 Z (Z in radians; F2 is not clamped, as in the paper).
struct Perez1990 {
  double epsilon = 1.0, delta = 0.0;
  int bin = 1;
  double f1 = 0.0, f2 = 0.0;
};
// The coefficients f11, f12, f13, f21, f22, f23 of bin 1..8.
const std::array<double, 6>& perez1990_coefficients(int bin);
// The state for light in W/m^2 (diffuse_horizontal > 0), the air mass and I0 [W/m^2].
Perez1990 perez1990_state(const HorizontalLight& light, double air_mass,
                          double extraterrestrial_w_m2);
// The transposition: sky_diffuse = D [(1 - F1) (1 + cos beta)/2 + F1 a/b + F2 sin beta] with
// a = max(0, cos AOI), b = max(cos Z, cos 85 deg), and its three terms as isotropic, circumsolar
// and horizon. With a horizon: the isotropic term through sky_view in place of (1 + cos beta)/2,
// the circumsolar term 0 when the sun is behind the skyline, the horizon term times band_open;
// the ground from the shaded global horizontal light (the model applied to the horizontal
// plane, over its value with a flat horizon). A negative sum (F2 < 0 on a steep plane) is 0, and
// so are its terms (as pvlib does). No diffuse light: all sky terms 0.
PlaneLight perez1990_transposition(const HorizontalLight& light, const Plane& plane, double albedo,
                                   const io::HorizonProfile& horizon, const HorizonViews& views,
                                   const Perez1990& state);

}  // namespace skylight::daylight
