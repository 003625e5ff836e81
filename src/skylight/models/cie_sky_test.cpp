#include "skylight/models/cie_sky.h"

#include <gtest/gtest.h>

#include "skylight/core/error.h"

namespace skylight {
namespace {

// Hand-computed closed forms vs double evaluation: round-off only.
constexpr double kHandValueTol = 1e-12;
// The gradation uses cos Z clamped at kPerezMinCosTheta; with b <= -0.15 the horizon term is
// a e^{b/0.01} <= 4 e^{-15} ~ 1.2e-6 instead of exactly 0.
constexpr double kHorizonClampTol = 2e-6;

CieParameters cie_params(int type, double sun_zenith_deg, double sun_azimuth_deg = 180.0) {
  CieParameters p;
  p.type = type;
  p.sun = {deg_to_rad(sun_zenith_deg), deg_to_rad(sun_azimuth_deg)};
  return p;
}

TEST(CieSky, PublishedTypeParameters) {
  // CIE S 011:2003 Table: type 12 (standard clear sky) a=-1, b=-0.32, c=10, d=-3, e=0.45.
  const CieSkyType& t = cie_sky_type(12);
  EXPECT_EQ(t.a, -1.0);
  EXPECT_EQ(t.b, -0.32);
  EXPECT_EQ(t.c, 10.0);
  EXPECT_EQ(t.d, -3.0);
  EXPECT_EQ(t.e, 0.45);
  EXPECT_EQ(cie_sky_type(1).a, 4.0);    // standard overcast: a = 4, b = -0.7
  EXPECT_EQ(cie_sky_type(15).c, 24.0);  // white-blue turbid: c = 24, d = -2.8, e = 0.15
  EXPECT_THROW(cie_sky_type(0), InvalidArgument);
  EXPECT_THROW(cie_sky_type(16), InvalidArgument);
}

TEST(CieSky, GradationAndIndicatrixByHand) {
  const CieSkyType& t12 = cie_sky_type(12);
  // phi(60 deg) = 1 - exp(-0.32 / 0.5) = 1 - 0.527292424 = 0.472707576.
  EXPECT_NEAR(cie_gradation(t12, deg_to_rad(60.0)), 0.47270757595695145, kHandValueTol);
  // phi(0) = 1 - exp(-0.32) = 0.273850963.
  EXPECT_NEAR(cie_gradation(t12, 0.0), 0.27385096292630906, kHandValueTol);
  // phi(horizon) = 1.
  EXPECT_NEAR(cie_gradation(t12, kPi / 2), 1.0, kHorizonClampTol);
  // f(30 deg) = 1 + 10 (e^{-pi/2} - e^{-3 pi/2}) + 0.45 cos^2 30
  //           = 1 + 10 (0.2078796 - 0.0089833) + 0.45 * 0.75 = 3.3264629.
  EXPECT_NEAR(cie_indicatrix(t12, kPi / 6), 3.326462853296325, kHandValueTol);
  // f(90 deg) = 1 exactly (the exp terms cancel, cos = 0).
  EXPECT_NEAR(cie_indicatrix(t12, kPi / 2), 1.0, kHandValueTol);
  // Type 1 (overcast): phi(60) = 1 + 4 e^{-1.4} = 1.98638786; f = 1 (c = e = 0).
  EXPECT_NEAR(cie_gradation(cie_sky_type(1), deg_to_rad(60.0)), 1.9863878557664258, kHandValueTol);
  EXPECT_NEAR(cie_indicatrix(cie_sky_type(1), 1.0), 1.0, kHandValueTol);
  // Relative luminance, type 12, Z = 60, chi = 30, Zs = 45:
  // 0.472708 * 3.326463 / (0.273851 * 2.082969) = 2.7566275.
  EXPECT_NEAR(cie_relative_luminance(12, deg_to_rad(60), deg_to_rad(30), deg_to_rad(45)),
              2.7566275440292927, kHandValueTol);
}

TEST(CieSky, ZenithEqualsLzForEveryType) {
  for (int type = 1; type <= 16; ++type) {
    for (double zs : {0.0, 20.0, 45.0, 70.0, 89.0}) {
      CieParameters p = cie_params(type, zs, 33.0);
      p.zenith_luminance = 4321.0;
      const CieSkyModel m(p);
      EXPECT_NEAR(m.tristimulus({0, 0, 1}).Y, 4321.0, 4321.0 * kHandValueTol) << type << " " << zs;
    }
  }
}

TEST(CieSky, TraditionalOvercastFormula) {
  CieParameters p = cie_params(16, 40.0);
  p.zenith_luminance = 3000.0;
  const CieSkyModel m(p);
  for (double Z : {0.0, 30.0, 60.0, 89.0, 90.0}) {
    const double expected = 3000.0 * (1.0 + 2.0 * std::cos(deg_to_rad(Z))) / 3.0;
    EXPECT_NEAR(m.tristimulus(direction_from_angles(deg_to_rad(Z), 1.0)).Y, expected,
                expected * kHandValueTol);
  }
  // Horizon: one third of the zenith (Moon & Spencer 1942).
  EXPECT_NEAR(m.tristimulus(direction_from_angles(kPi / 2, 0.0)).Y, 1000.0, 1e-9);
}

TEST(CieSky, SymmetricAboutSolarMeridian) {
  for (int type : {2, 7, 12, 15}) {
    const CieSkyModel m(cie_params(type, 50.0, 200.0));
    for (double t : {5.0, 40.0, 85.0})
      for (double dphi : {15.0, 90.0, 160.0}) {
        const double a =
            m.tristimulus(direction_from_angles(deg_to_rad(t), deg_to_rad(200 + dphi))).Y;
        const double b =
            m.tristimulus(direction_from_angles(deg_to_rad(t), deg_to_rad(200 - dphi))).Y;
        EXPECT_NEAR(a, b, a * 1e-12) << type;
      }
  }
}

TEST(CieSky, KittlerDarulaTypicalZenithLuminance) {
  const double gs = deg_to_rad(30.0);
  // Type 12 (sunny formula): 3.3 sin30 + 0.7 * 3.5 * sin30^4.43 / cos30^0.74 + 0.04 * 2.5
  //   = 1.65 + 2.45 * 0.046404 / 0.898960 + 0.1 = 1.876424 kcd/m^2.
  EXPECT_NEAR(kittler_darula_zenith_luminance(12, gs), 1876.4242937286251, 1e-9);
  // Type 1 (overcast formula, C = 1, D = 0, E = 0): 0.1 * 54.63 * sin30 = 2.7315 kcd/m^2.
  EXPECT_NEAR(kittler_darula_zenith_luminance(1, gs), 2731.5, 1e-9);
  // Type 2: 0.18 (12.35 sin30^3.68 / cos30^0.59 + 50.47 sin30) = 4.731102 kcd/m^2.
  EXPECT_NEAR(kittler_darula_zenith_luminance(2, gs), 4731.101745872912, 1e-9);
  // Type 16: 9/(7 pi) * 0.1 * 133.8 klx * sin30 = 2.738 kcd/m^2.
  EXPECT_NEAR(kittler_darula_zenith_luminance(16, gs), 1000 * 9.0 / (7 * kPi) * 13.38 * 0.5, 1e-9);
  // Used by the model when no zenith luminance is given.
  const CieSkyModel m(cie_params(12, 60.0));
  EXPECT_NEAR(m.zenith_luminance(), 1876.4242937286251, 1e-9);
  EXPECT_TRUE(m.domain().valid());
  EXPECT_EQ(CieSkyModel(cie_params(12, 85.0)).domain().worst(), Validity::extrapolated);
}

TEST(CieSky, KittlerDarulaBand) {
  // The published A of types 7-15 is A1 Tv + A2 at the typical Tv (Kittler & Darula's table,
  // data/cie_standard_sky/kittler_darula_zenith_luminance.csv), to the table's two decimals.
  constexpr double kTableRounding = 0.005;
  for (int type = 7; type <= 15; ++type) {
    const KittlerDarulaParameters& k = kittler_darula_parameters(type);
    EXPECT_NEAR(k.A1 * k.Tv + k.A2, k.A, kTableRounding) << "type " << type;
  }
  for (int type = 1; type <= kCieTypeCount; ++type)
    for (double e : {10.0, 30.0, 60.0, 80.0}) {
      const ZenithLuminanceBand b = kittler_darula_zenith_luminance_band(type, deg_to_rad(e));
      EXPECT_DOUBLE_EQ(b.typical, kittler_darula_zenith_luminance(type, deg_to_rad(e)));
      EXPECT_LE(b.low, b.typical) << "type " << type;
      EXPECT_GE(b.high, b.typical) << "type " << type;
      EXPECT_GT(b.low, 0.0);
    }
  // Overcast types scale with Dv/Ev: type 1 (typical 0.10, the smallest) is its own low end.
  const ZenithLuminanceBand o = kittler_darula_zenith_luminance_band(1, deg_to_rad(40.0));
  EXPECT_DOUBLE_EQ(o.low, o.typical);
  EXPECT_NEAR(o.high / o.typical, 0.42 / 0.10, 1e-12);
}

TEST(CieSky, SunBelowHorizonAndGroundAreZero) {
  const CieSkyModel night(cie_params(12, 95.0));
  EXPECT_EQ(night.domain().worst(), Validity::undefined);
  EXPECT_EQ(night.tristimulus({0, 0, 1}).Y, 0.0);
  const CieSkyModel day(cie_params(12, 40.0));
  EXPECT_EQ(day.tristimulus({0.6, 0.0, -0.8}).Y, 0.0);
  // Luminance only: neutral D65 colour.
  const Rgb rgb = day.rgb({0, 0, 1});
  EXPECT_NEAR(rgb.r, rgb.g, rgb.g * 1e-9);
  EXPECT_NEAR(rgb.b, rgb.g, rgb.g * 1e-9);
  EXPECT_THROW(CieSkyModel(cie_params(17, 40.0)), InvalidArgument);
}

}  // namespace
}  // namespace skylight
