#include "skylight/analysis/illumination.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "skylight/core/error.h"
#include "skylight/models/sky_model.h"

namespace skylight::analysis {
namespace {

// Midpoint rule on a 90 x 180 hemisphere grid for a luminance linear in cos(theta): the cos^2
// term's error is O(h^2) ~ (pi/180)^2 / 24 relative, about 1.3e-5.
constexpr double kIlluminanceQuadratureRelTol = 5e-5;
// The solar disc's polar grid: cos(theta) varies linearly across the disc (0.27 deg), so the
// midpoint rings integrate it to second order in the radius: ~1e-5 relative at 60 deg.
constexpr double kDirectSunRelTol = 1e-4;

TEST(Illumination, OvercastSkyMatchesItsClosedForm) {
  // Traditional overcast sky L = Lz (1 + 2 cos Z) / 3: E = 2 pi Lz int_0^1 mu (1 + 2 mu) / 3 dmu
  // = Lz pi 7 / 9.
  SkyParameters p;
  p.values.set("cie-type", 16);
  p.values.set("zenith-luminance", 1e4);
  p.sun = {deg_to_rad(40.0), kPi};
  const auto sky = make_sky_model("cie", p);
  const double E = diffuse_horizontal_illuminance(*sky, 90, 180);
  EXPECT_NEAR(E, 1e4 * kPi * 7.0 / 9.0, kIlluminanceQuadratureRelTol * E);
  // The uniform sky (type 5): E = pi Lz.
  p.values.set("cie-type", 5);
  const auto uniform = make_sky_model("cie", p);
  EXPECT_NEAR(diffuse_horizontal_illuminance(*uniform, 90, 180), 1e4 * kPi,
              kIlluminanceQuadratureRelTol * 1e4 * kPi);
  // No sun: the direct part is 0 and no irradiance (the CIE sky has no spectrum).
  const auto h =
      horizontal_illumination(*sky, IlluminationSettings{.n_theta = 30, .n_phi = 60}, true);
  EXPECT_FALSE(h.has_sun);
  EXPECT_EQ(h.direct_lx, 0.0);
  EXPECT_FALSE(h.diffuse_w_m2.has_value());
}

TEST(Illumination, UniformSolarDiscGivesRadianceTimesSolidAngle) {
  SkyParameters p;
  p.values.set("turbidity", 3.0);
  p.sun = {deg_to_rad(60.0), kPi};
  const auto sky = make_sky_model("preetham", p);
  const double L = sky->sun_tristimulus(p.sun.direction()).Y;  // Preetham's disc is uniform
  const double r = sky->sun_angular_radius();
  const double want = L * 2 * kPi * (1 - std::cos(r)) * std::cos(p.sun.zenith);
  EXPECT_NEAR(direct_horizontal_illuminance(*sky, 8, 16), want, kDirectSunRelTol * want);
  IlluminationSettings s;
  s.n_theta = 30;
  s.n_phi = 60;
  s.n_theta_spectral = 6;
  s.n_phi_spectral = 12;
  s.nm_step = 40.0;
  const auto h = horizontal_illumination(*sky, s, true);
  EXPECT_TRUE(h.has_sun);
  ASSERT_TRUE(h.diffuse_w_m2.has_value());
  ASSERT_TRUE(h.direct_w_m2.has_value());
  EXPECT_GT(*h.diffuse_w_m2, 0.0);
  EXPECT_GT(*h.direct_w_m2, *h.diffuse_w_m2);  // clear sky, sun at 30 deg elevation
  EXPECT_GT(h.global_lx(), h.diffuse_lx);
}
}  // namespace
}  // namespace skylight::analysis
