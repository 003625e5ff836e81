#include "skylight/models/nishita.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "skylight/atmosphere/atmosphere.h"
#include "skylight/core/error.h"
#include "support/error_message.h"

namespace skylight {
namespace {

// 20 midpoint samples (20 nm bins) against a 5 nm trapezoid integration 380-780 nm of the same
// spectral radiance: the spectra are smooth (lambda^-4 x a 10 nm-binned solar spectrum); observed
// <= 0.08 % in Y and <= 0.63 % in X, Z.
constexpr double kXyzVsDenseRelTol = 1.5e-2;

NishitaParameters nishita_params(double sun_elevation_deg, double altitude_m = 0.0) {
  NishitaParameters p;
  p.sun = {deg_to_rad(90 - sun_elevation_deg), kPi};
  p.observer_altitude_m = altitude_m;
  return p;
}

SkyParameters sky_parameters(double sun_elevation_deg) {
  SkyParameters p;
  p.sun = {deg_to_rad(90 - sun_elevation_deg), kPi};
  return p;
}

TEST(Nishita, RegisteredWithEarthDefaults) {
  const auto m = make_sky_model("nishita", sky_parameters(30));
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->name(), "nishita");
  const auto& a = dynamic_cast<const NishitaModel&>(*m).atmosphere().parameters();
  EXPECT_EQ(a.ground_radius_m, 6360e3);
  EXPECT_EQ(a.top_radius_m, 6420e3);
  ASSERT_EQ(a.components.size(), 2u);
  EXPECT_EQ(a.components[0].scale_height_m, 8000.0);
  EXPECT_EQ(a.components[1].scale_height_m, 1200.0);
  EXPECT_EQ(a.components[1].g, 0.8);
  // lambda^-4 from 13.558e-6 at 550 nm reproduces the published 680 and 440 nm values (Bruneton
  // 2017).
  constexpr double kRgbBetaRelTol = 3e-4;  // 4-digit values given
  EXPECT_NEAR(a.components[0].scattering(680), 5.802e-6, kRgbBetaRelTol * 5.802e-6);
  EXPECT_NEAR(a.components[0].scattering(440), 33.1e-6, kRgbBetaRelTol * 33.1e-6);
  EXPECT_EQ(a.components[1].extinction(440), 4.440e-6);
  EXPECT_FALSE(a.ground_albedo.has_value());
  EXPECT_TRUE(m->domain().valid());
  EXPECT_FALSE(make_sky_model("nishita", sky_parameters(-5))->domain().valid());
}

// The radii depend on each other (top > ground): every documented extreme of each is reachable
// with the other's default or extreme.
TEST(Nishita, EveryDocumentedExtremeOfTheRadiiIsReachable) {
  const ModelInfo& info = require_model("nishita");
  const ParameterSpec& ground = *info.find_parameter("ground-radius");
  const ParameterSpec& top = *info.find_parameter("top-radius");
  SkyParameters p = sky_parameters(30);
  p.values.set("ground-radius", ground.max);  // the top defaults to ground + 60 km
  EXPECT_NO_THROW(make_sky_model("nishita", p));
  p.values.set("top-radius", top.max);
  EXPECT_NO_THROW(make_sky_model("nishita", p));
  p.values.set("ground-radius", ground.min);
  p.values.set("top-radius", ground.min + 1.0);
  EXPECT_NO_THROW(make_sky_model("nishita", p));
  EXPECT_GT(top.max, ground.max);
}

TEST(Nishita, XyzFromTwentyWavelengthsMatchesDenseIntegration) {
  const NishitaModel m(nishita_params(35));
  for (Vec3 v : {Vec3{0, 0, 1}, direction_from_angles(deg_to_rad(85), 0.3),
                 direction_from_angles(deg_to_rad(60), kPi)}) {
    std::vector<double> nm, L;
    for (double l = 380; l <= 780; l += 5) {
      nm.push_back(l);
      L.push_back(*m.spectral_radiance(v, l));
    }
    const Xyz dense = spectral_radiance_to_xyz(nm, L);
    const Xyz fast = m.tristimulus(v);
    EXPECT_NEAR(fast.X, dense.X, kXyzVsDenseRelTol * dense.X);
    EXPECT_NEAR(fast.Y, dense.Y, kXyzVsDenseRelTol * dense.Y);
    EXPECT_NEAR(fast.Z, dense.Z, kXyzVsDenseRelTol * dense.Z);
    std::printf("XYZ 20 nm vs 5 nm: %.4f %.4f %.4f\n", fast.X / dense.X - 1, fast.Y / dense.Y - 1,
                fast.Z / dense.Z - 1);
  }
}

TEST(Nishita, UnitIrradianceAndObserverAltitude) {
  NishitaParameters p = nishita_params(40);
  p.solar_irradiance = 1.0;
  const NishitaModel ground(p);
  p.observer_altitude_m = 20e3;
  const NishitaModel high(p);
  const Vec3 up{0, 0, 1};
  // Less air above a high observer: the zenith is darker.
  EXPECT_LT(*high.spectral_radiance(up, 550), *ground.spectral_radiance(up, 550));
  // Flat irradiance E scales the radiance linearly.
  p.solar_irradiance = 2.5;
  const NishitaModel bright(p);
  constexpr double kLinearRelTol = 1e-12;  // the same sum times a constant
  EXPECT_NEAR(*bright.spectral_radiance(up, 550), 2.5 * *high.spectral_radiance(up, 550),
              kLinearRelTol * *bright.spectral_radiance(up, 550));
  EXPECT_FALSE(ground.spectral_radiance(up, 300).has_value());
}

TEST(Nishita, ReferenceTristimulusAgrees) {
  const NishitaModel m(nishita_params(15, 1000));
  constexpr double kRelTol = 5e-3;  // the fast-vs-reference bound of docs/MODELS.md (0.5 %)
  for (Vec3 v : {Vec3{0, 0, 1}, direction_from_angles(deg_to_rad(89), 0.0),
                 direction_from_angles(deg_to_rad(95), kPi)}) {
    const Xyz f = m.tristimulus(v), r = m.tristimulus_reference(v, {200, 32});
    EXPECT_NEAR(f.Y, r.Y, kRelTol * r.Y);
    EXPECT_NEAR(f.Z, r.Z, kRelTol * r.Z);
  }
}

TEST(Nishita, GroundReflectionOnlyWithAnAlbedo) {
  NishitaParameters p = nishita_params(40, 1000);
  const Vec3 down = direction_from_angles(deg_to_rad(150), 0.0);
  const double plain = NishitaModel(p).tristimulus(down).Y;
  p.albedo = 0.3;
  const double lit = NishitaModel(p).tristimulus(down).Y;
  EXPECT_GT(lit, plain * 1.5);
  // The same ground through a custom planet setup.
  NishitaSetup setup = nishita_params(40, 1000).setup();
  setup.atmosphere.ground_albedo = 0.3;
  EXPECT_EQ(NishitaModel(setup).tristimulus(down).Y, lit);
}

TEST(Nishita, BadParametersAreRejected) {
  NishitaParameters p = nishita_params(30);
  p.observer_altitude_m = -1;
  EXPECT_THROW(NishitaModel{p}, InvalidArgument);
  p.observer_altitude_m = 2e7;
  EXPECT_THROW(NishitaModel{p}, InvalidArgument);
  p = nishita_params(30);
  p.solar_irradiance = 0.0;
  EXPECT_THROW(NishitaModel{p}, InvalidArgument);
  p = nishita_params(30);
  p.top_radius_m = p.ground_radius_m - 1;
  EXPECT_THROW(NishitaModel{p}, InvalidArgument);
  NishitaSetup setup = nishita_params(30).setup();
  setup.atmosphere.top_radius_m = setup.atmosphere.ground_radius_m - 1;
  EXPECT_THROW(NishitaModel{setup}, InvalidArgument);
}

// NishitaSampler repeats NishitaModel's sum in the same order: equal to double round-off.
constexpr double kSamplerRelativeTolerance = 1e-12;

TEST(NishitaSampler, EqualsNishitaModel) {
  NishitaParameters p;
  const NishitaSampler sampler(p);
  for (double h : {0.0, 18000.0}) {
    for (double sz : {20.0, 93.0}) {
      p.observer_altitude_m = h;
      p.sun = {deg_to_rad(sz), deg_to_rad(135.0)};
      const NishitaModel m(p);
      for (Vec3 v :
           {Vec3{0, 0, 1}, normalize(Vec3{0.3, -0.5, 0.4}), normalize(Vec3{-1, 0.2, -0.1})}) {
        const Rgb a = m.rgb(v), b = sampler.rgb(h, v, p.sun.direction());
        const double scale = std::max({std::abs(a.r), std::abs(a.g), std::abs(a.b), 1e-30});
        EXPECT_NEAR(b.r, a.r, kSamplerRelativeTolerance * scale);
        EXPECT_NEAR(b.g, a.g, kSamplerRelativeTolerance * scale);
        EXPECT_NEAR(b.b, a.b, kSamplerRelativeTolerance * scale);
      }
    }
  }
}

}  // namespace
}  // namespace skylight

namespace skylight {
namespace {

// The vertical transmittance of the whole atmosphere at nm, with and without the given aerosols:
// their ratio is exp(-tau_aerosol(nm)) whatever the other components do.
double aerosol_transmittance_ratio(const NishitaParameters& hazy, double nm) {
  NishitaParameters clean = hazy;
  clean.turbidity.reset();
  clean.aerosol_optical_depth = 0.0;
  clean.angstrom_exponent.reset();
  double t[2];
  int k = 0;
  for (const NishitaParameters* p : {&hazy, static_cast<const NishitaParameters*>(&clean)}) {
    const NishitaSetup s = p->setup();
    const atmosphere::Atmosphere a(s.atmosphere);
    const double solar[] = {1.0}, nms[] = {nm};
    const atmosphere::Spectral spec = atmosphere::make_spectral(s.atmosphere, nms, solar);
    double out[1];
    const double r0 = s.atmosphere.ground_radius_m;
    a.transmittance({0.0, 0.0, r0 + 1e-3}, {0.0, 0.0, 1.0}, s.atmosphere.top_radius_m - r0 - 2e-3,
                    spec, out);
    t[k++] = out[0];
  }
  return t[0] / t[1];
}

// --aerosol-optical-depth is the vertical optical depth of the aerosols at 550 nm, scaled by the
// Angstrom law elsewhere (the optical-length tables integrate the profile: 1e-4 relative).
TEST(NishitaAerosols, TheOpticalDepthIsTheColumnsAndFollowsAngstromsLaw) {
  constexpr double kTableTolerance = 1e-4;
  NishitaParameters p;
  p.aerosol_optical_depth = 0.3;
  p.angstrom_exponent = 1.2;
  EXPECT_NEAR(-std::log(aerosol_transmittance_ratio(p, 550.0)), 0.3, 0.3 * kTableTolerance);
  const double tau440 = 0.3 * std::pow(550.0 / 440.0, 1.2);
  EXPECT_NEAR(-std::log(aerosol_transmittance_ratio(p, 440.0)), tau440, tau440 * kTableTolerance);
  p.aerosol_albedo = 0.7;
  const atmosphere::Component mie = p.setup().atmosphere.components[1];
  EXPECT_DOUBLE_EQ(mie.scattering_per_m / mie.extinction_per_m, 0.7);
  EXPECT_EQ(mie.angstrom_exponent, 1.2);
}

// --turbidity is Preetham's aerosol: tau_550 = (0.04608 T - 0.04586) 0.55^-1.3, alpha = 1.3
// (Preetham et al. 1999, appendix A.3).
TEST(NishitaAerosols, TurbidityIsPreethamsAngstromLaw) {
  NishitaParameters p;
  p.turbidity = 3.0;
  const double tau550 = (0.04608 * 3.0 - 0.04586) * std::pow(0.55, -1.3);
  EXPECT_NEAR(-std::log(aerosol_transmittance_ratio(p, 550.0)), tau550, tau550 * 1e-4);
  EXPECT_EQ(p.setup().atmosphere.components[1].angstrom_exponent, 1.3);
  p.aerosol_optical_depth = 0.1;
  EXPECT_NE(testing_support::error_message([&] {
              (void)p.setup();
            }).find("turbidity and aerosol-optical-depth exclude each other"),
            std::string::npos);
}

// Without aerosol flags the Mie layer is Earth's default, bit for bit.
TEST(NishitaAerosols, WithoutThemTheMieLayerIsEarthsDefault) {
  const atmosphere::Component mie = NishitaParameters{}.setup().atmosphere.components[1];
  const atmosphere::Component earth = atmosphere::earth_mie();
  EXPECT_EQ(mie.scattering_per_m, earth.scattering_per_m);
  EXPECT_EQ(mie.extinction_per_m, earth.extinction_per_m);
  EXPECT_EQ(mie.angstrom_exponent, earth.angstrom_exponent);
  // More aerosols brighten the sky near the sun and darken the light of the sun's own direction.
  NishitaParameters clean, hazy;
  clean.sun = hazy.sun = {deg_to_rad(40.0), kPi};
  hazy.turbidity = 4.0;
  const NishitaModel a(clean), b(hazy);
  const Vec3 near_sun = direction_from_angles(deg_to_rad(45.0), kPi);
  EXPECT_GT(b.tristimulus(near_sun).Y, 1.5 * a.tristimulus(near_sun).Y);
}

}  // namespace
}  // namespace skylight
