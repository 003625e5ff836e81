#include "skylight/daylight/transposition.h"

#include <algorithm>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/models/perez_allweather.h"

namespace skylight::daylight {
namespace {

// Perez et al. 1990, the table of the irradiance model's coefficients f11, f12, f13 (F1) and
// f21, f22, f23 (F2) per clearness bin 1..8, "all sites composite" (the set pvlib names
// allsitescomposite1990 and uses by default). The paper is not in ../shared/papers/: taken from
// the published table as pvlib carries it (BSD-3) and checked digit for digit against a second
// independent copy (docs/IRRADIANCE.md).
constexpr std::array<std::array<double, 6>, 8> kPerez1990Coefficients = {{
    {-0.008, 0.588, -0.062, -0.060, 0.072, -0.022},
    {0.130, 0.683, -0.151, -0.019, 0.066, -0.029},
    {0.330, 0.487, -0.221, 0.055, -0.064, -0.026},
    {0.568, 0.187, -0.295, 0.109, -0.152, -0.014},
    {0.873, -0.392, -0.362, 0.226, -0.462, 0.001},
    {1.132, -1.237, -0.412, 0.288, -0.823, 0.056},
    {1.060, -1.600, -0.359, 0.264, -1.127, 0.131},
    {0.678, -0.327, -0.250, 0.156, -1.377, 0.251},
}};

// The sun is up and above the skyline.
bool sun_open(const SunPosition& sun, const io::HorizonProfile& horizon) {
  return sun.zenith < 0.5 * kPi && horizon.open(sun.direction());
}

}  // namespace

double HorizontalLight::global_horizontal() const {
  return direct_normal * std::max(std::cos(sun.zenith), 0.0) + diffuse_horizontal;
}

double direct_on_plane(const HorizontalLight& light, const Plane& plane,
                       const io::HorizonProfile& horizon) {
  if (!sun_open(light.sun, horizon)) return 0.0;
  return light.direct_normal * std::max(0.0, dot(plane.normal(), light.sun.direction()));
}

double ground_on_plane(double shaded_global, double albedo, const Plane& plane) {
  return shaded_global * albedo * 0.5 * (1.0 - std::cos(plane.tilt));
}

PlaneLight isotropic_transposition(const HorizontalLight& light, const Plane& plane, double albedo,
                                   const io::HorizonProfile& horizon, const HorizonViews& views) {
  PlaneLight p;
  const bool open = sun_open(light.sun, horizon);
  p.direct = direct_on_plane(light, plane, horizon);
  p.sky_diffuse = light.diffuse_horizontal * views.sky_view;
  p.isotropic = p.sky_diffuse;
  p.circumsolar = 0.0;
  p.horizon = 0.0;
  const double direct_horizontal =
      open ? light.direct_normal * std::max(std::cos(light.sun.zenith), 0.0) : 0.0;
  p.ground_diffuse = ground_on_plane(
      direct_horizontal + light.diffuse_horizontal * views.horizontal_view, albedo, plane);
  return p;
}

const std::array<double, 6>& perez1990_coefficients(int bin) {
  SKYLIGHT_CHECK(bin >= 1 && bin <= 8, "Perez 1990 bins are 1..8");
  return kPerez1990Coefficients[static_cast<std::size_t>(bin - 1)];
}

Perez1990 perez1990_state(const HorizontalLight& light, double air_mass,
                          double extraterrestrial_w_m2) {
  SKYLIGHT_CHECK(light.diffuse_horizontal > 0.0 && extraterrestrial_w_m2 > 0.0,
                 "Perez 1990 needs diffuse light and the extraterrestrial irradiance");
  Perez1990 s;
  const double Z = std::min(light.sun.zenith, 0.5 * kPi);
  s.epsilon = sky_clearness(light.diffuse_horizontal, light.direct_normal, Z);
  s.delta = light.diffuse_horizontal * air_mass / extraterrestrial_w_m2;
  s.bin = clearness_bin(s.epsilon);
  const auto& f = perez1990_coefficients(s.bin);
  s.f1 = std::max(0.0, f[0] + f[1] * s.delta + f[2] * Z);
  s.f2 = f[3] + f[4] * s.delta + f[5] * Z;
  return s;
}

PlaneLight perez1990_transposition(const HorizontalLight& light, const Plane& plane, double albedo,
                                   const io::HorizonProfile& horizon, const HorizonViews& views,
                                   const Perez1990& s) {
  PlaneLight p;
  const double D = light.diffuse_horizontal;
  const bool open = sun_open(light.sun, horizon);
  p.direct = direct_on_plane(light, plane, horizon);
  const double cos_z = std::cos(light.sun.zenith);
  const double b = std::max(cos_z, kPerezMinSunCosine);
  const double a = std::max(0.0, dot(plane.normal(), light.sun.direction()));
  double iso = 0.0, circ = 0.0, hor = 0.0;
  if (D > 0.0) {
    iso = D * (1.0 - s.f1) * views.sky_view;
    circ = open ? D * s.f1 * a / b : 0.0;
    hor = D * s.f2 * std::sin(plane.tilt) * views.band_open;
    if (iso + circ + hor < 0.0) iso = circ = hor = 0.0;
  }
  p.isotropic = iso;
  p.circumsolar = circ;
  p.horizon = hor;
  p.sky_diffuse = iso + circ + hor;
  // The ground: the global horizontal light that reaches the site. With a flat horizon that is
  // the input's (direct cos Z + D); with a skyline, the direct light if the sun is open plus D
  // scaled by the model's horizontal diffuse light through the skyline over that without it.
  double diffuse_site = D;
  if (!horizon.flat() && D > 0.0) {
    const double circ_h = std::max(cos_z, 0.0) / b;
    const double flat = (1.0 - s.f1) + s.f1 * circ_h;
    const double shaded = (1.0 - s.f1) * views.horizontal_view + (open ? s.f1 * circ_h : 0.0);
    diffuse_site = flat > 0.0 ? D * shaded / flat : 0.0;
  }
  const double direct_horizontal = open ? light.direct_normal * std::max(cos_z, 0.0) : 0.0;
  p.ground_diffuse = ground_on_plane(direct_horizontal + diffuse_site, albedo, plane);
  return p;
}

}  // namespace skylight::daylight
