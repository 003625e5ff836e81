#include "skylight/daylight/transposition.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/math.h"
#include "skylight/core/random.h"
#include "skylight/models/perez_allweather.h"

namespace skylight::daylight {
namespace {

// The closed forms are evaluated in a different order of operations than the library's: round-off.
constexpr double kClosedFormTol = 1e-12;

// Random light, sun and plane over the whole range of each.
struct TranspositionCase {
  HorizontalLight light;
  Plane plane;
  double albedo;
};
TranspositionCase random_case(SplitMix64& rng) {
  TranspositionCase c;
  c.light.sun = {deg_to_rad(89.0 * rng.uniform()), 2.0 * kPi * rng.uniform()};
  c.light.direct_normal = 1000.0 * rng.uniform();
  c.light.diffuse_horizontal = 1.0 + 400.0 * rng.uniform();
  c.plane = {kPi * rng.uniform(), 2.0 * kPi * rng.uniform()};
  c.albedo = rng.uniform();
  return c;
}

TEST(Transposition, DirectAndGroundAreTheClosedFormsExactly) {
  const io::HorizonProfile flat;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SplitMix64 rng(seed);
    for (int k = 0; k < 500; ++k) {
      const TranspositionCase c = random_case(rng);
      const HorizonViews views{0.5 * (1.0 + std::cos(c.plane.tilt)), 1.0, 1.0};
      const Vec3 s = c.light.sun.direction(), n = c.plane.normal();
      const double cos_aoi = n.x * s.x + n.y * s.y + n.z * s.z;
      const double direct = c.light.direct_normal * std::max(0.0, cos_aoi);
      const double ghi =
          c.light.direct_normal * std::cos(c.light.sun.zenith) + c.light.diffuse_horizontal;
      const double ground = ghi * c.albedo * (1.0 - std::cos(c.plane.tilt)) / 2.0;
      const Perez1990 state = perez1990_state(c.light, kasten_air_mass(c.light.sun.zenith), 1367);
      for (const PlaneLight& p :
           {isotropic_transposition(c.light, c.plane, c.albedo, flat, views),
            perez1990_transposition(c.light, c.plane, c.albedo, flat, views, state)}) {
        EXPECT_NEAR(*p.direct, direct, kClosedFormTol * std::max(1.0, direct)) << seed << " " << k;
        EXPECT_NEAR(*p.ground_diffuse, ground, kClosedFormTol * std::max(1.0, ground));
      }
      const PlaneLight iso = isotropic_transposition(c.light, c.plane, c.albedo, flat, views);
      EXPECT_NEAR(iso.sky_diffuse,
                  c.light.diffuse_horizontal * (1.0 + std::cos(c.plane.tilt)) / 2.0,
                  kClosedFormTol * c.light.diffuse_horizontal);
    }
  }
}

// Perez et al. 1990's published F-coefficients (the all-sites composite irradiance set), spot
// checks of the table's corners and middle as printed.
TEST(Transposition, Perez1990CoefficientsAreThePublishedTable) {
  EXPECT_EQ(perez1990_coefficients(1)[0], -0.008);
  EXPECT_EQ(perez1990_coefficients(1)[1], 0.588);
  EXPECT_EQ(perez1990_coefficients(4)[4], -0.152);
  EXPECT_EQ(perez1990_coefficients(6)[1], -1.237);
  EXPECT_EQ(perez1990_coefficients(8)[0], 0.678);
  EXPECT_EQ(perez1990_coefficients(8)[5], 0.251);
}

// The model's terms as the paper writes them: F1 clamped at 0, F2 not; the circumsolar ratio a/b;
// a negative sum is 0 with its terms (a low sun: b = cos 85 deg and F2 < 0).
TEST(Transposition, Perez1990TermsFollowThePaper) {
  const io::HorizonProfile flat;
  HorizontalLight l{700.0, 120.0, {deg_to_rad(60.0), deg_to_rad(180.0)}};
  const Plane south_wall{kPi / 2, kPi};
  const Perez1990 s = perez1990_state(l, kasten_air_mass(l.sun.zenith), 1400.0);
  const auto& f = perez1990_coefficients(s.bin);
  const double Z = l.sun.zenith;
  EXPECT_DOUBLE_EQ(s.f1, std::max(0.0, f[0] + f[1] * s.delta + f[2] * Z));
  EXPECT_DOUBLE_EQ(s.f2, f[3] + f[4] * s.delta + f[5] * Z);
  const HorizonViews views{0.5, 1.0, 1.0};
  const PlaneLight p = perez1990_transposition(l, south_wall, 0.2, flat, views, s);
  const double a = std::max(0.0, dot(south_wall.normal(), l.sun.direction()));
  EXPECT_NEAR(*p.circumsolar, 120.0 * s.f1 * a / std::cos(deg_to_rad(60.0)), 1e-9);
  EXPECT_NEAR(*p.isotropic, 120.0 * (1.0 - s.f1) * 0.5, 1e-9);
  EXPECT_NEAR(*p.horizon, 120.0 * s.f2, 1e-9);
  EXPECT_NEAR(p.sky_diffuse, *p.isotropic + *p.circumsolar + *p.horizon, 1e-12);
  // The sun at 88 deg: b = cos 85 deg; this sky's F2 < 0 makes the wall's sum negative: all 0.
  l.sun.zenith = deg_to_rad(88.0);
  const Perez1990 low = perez1990_state(l, kasten_air_mass(l.sun.zenith), 1400.0);
  const PlaneLight q = perez1990_transposition(l, south_wall, 0.2, flat, views, low);
  const double aq = std::max(0.0, dot(south_wall.normal(), l.sun.direction()));
  const double sum = 120.0 * ((1.0 - low.f1) * 0.5 + low.f1 * aq / kPerezMinSunCosine + low.f2);
  ASSERT_LT(sum, 0.0);
  EXPECT_EQ(q.sky_diffuse, 0.0);
  EXPECT_EQ(*q.circumsolar, 0.0);
  EXPECT_EQ(*q.horizon, 0.0);
}

// A horizon of 0 deg everywhere is the flat horizon; one of 90 deg leaves no sky and no sun.
TEST(Transposition, HorizonAtZeroChangesNothingAndAtNinetyLeavesNoLight) {
  const io::HorizonProfile flat, zero = io::HorizonProfile::constant(0.0);
  const io::HorizonProfile wall = io::HorizonProfile::constant(90.0);
  SplitMix64 rng(7);
  for (int k = 0; k < 20; ++k) {
    const TranspositionCase c = random_case(rng);
    const Perez1990 s = perez1990_state(c.light, kasten_air_mass(c.light.sun.zenith), 1367.0);
    const auto light = [&](const io::HorizonProfile& h) {
      const HorizonViews v = horizon_views(plane_weights(default_sky_grid(), c.plane, h));
      return perez1990_transposition(c.light, c.plane, c.albedo, h, v, s);
    };
    const PlaneLight a = light(flat), b = light(zero), w = light(wall);
    EXPECT_EQ(*a.global(), *b.global()) << k;
    EXPECT_EQ(a.sky_diffuse, b.sky_diffuse);
    EXPECT_EQ(*w.direct, 0.0);
    EXPECT_EQ(w.sky_diffuse, 0.0);
    EXPECT_EQ(*w.ground_diffuse, 0.0);
  }
}

}  // namespace
}  // namespace skylight::daylight
