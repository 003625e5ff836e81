#include "skylight/models/preetham.h"

#include <gtest/gtest.h>

#include <random>

#include "skylight/core/error.h"

namespace skylight {
namespace {

// Closed forms evaluated in double: only round-off separates the library from the hand value.
constexpr double kClosedFormRelTol = 1e-12;

PreethamParameters preetham_params(double T, double sun_zenith_deg,
                                   double sun_azimuth_deg = 180.0) {
  PreethamParameters p;
  p.turbidity = T;
  p.sun = {deg_to_rad(sun_zenith_deg), deg_to_rad(sun_azimuth_deg)};
  return p;
}

TEST(Preetham, ZenithLuminanceClosedForm) {
  // Yz = (4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192 [kcd/m^2], chi = (4/9 - T/120)(pi - 2 ts).
  // T = 3, ts = 45 deg: chi = (0.444444 - 0.025) pi/2 = 0.658866 rad, tan chi = 0.775290;
  //   Yz = 7.1649 * 0.775290 - 0.6465 + 2.4192 = 7.320358 kcd/m^2.
  struct Case {
    double T, ts_deg, Yz;
  };
  const Case cases[] = {
      {3.0, 45.0, 7320.358316713677},
      {2.0, 30.0, 5886.743249307964},  // chi = 0.4278 * 2.0944 = 0.89594, tan = 1.24496
      {6.0, 60.0, 9585.269809711832},
      {10.0, 80.0, 4760.601043974065},
      {1.0, 0.0, -2346.260863662609},  // chi = 1.37008; (4.0453-4.9710) tan chi < 0: NEGATIVE
      {12.0, 90.0, -166.8},            // chi = 0: Yz = -0.2155*12 + 2.4192 = -0.1668 kcd: NEGATIVE
  };
  for (const auto& c : cases) {
    EXPECT_NEAR(preetham_zenith_luminance(c.T, deg_to_rad(c.ts_deg)), c.Yz,
                std::abs(c.Yz) * kClosedFormRelTol)
        << "T " << c.T << " ts " << c.ts_deg;
  }
}

TEST(Preetham, NegativeZenithRegionIsFlaggedAndReturnsZero) {
  // Zotti et al. 2007 Fig. 1: very clear air (T ~ 1) with a high sun gives Yz < 0.
  const PreethamModel m(preetham_params(1.0, 0.0));
  EXPECT_LT(m.zenith_luminance(), 0.0);
  const Domain d = m.domain();
  EXPECT_EQ(d.worst(), Validity::unphysical);
  bool flagged = false;
  for (const auto& i : d.issues) flagged |= i.parameter == "zenith_luminance";
  EXPECT_TRUE(flagged);
  // Documented value: 0, never NaN.
  const Xyz c = m.tristimulus(direction_from_angles(0.3, 1.0));
  EXPECT_EQ(c.Y, 0.0);
  EXPECT_EQ(c.X, 0.0);
  // Also at T = 12 at sunset (Zotti: fails for T >~ 10 near theta_s = 90 deg).
  const PreethamModel sunset(preetham_params(12.0, 90.0));
  EXPECT_EQ(sunset.domain().worst(), Validity::unphysical);
  EXPECT_EQ(sunset.tristimulus(direction_from_angles(1.0, 0.5)).Y, 0.0);
  // Inside the fitted range, nothing to report.
  EXPECT_TRUE(PreethamModel(preetham_params(3.0, 45.0)).domain().valid());
  EXPECT_EQ(PreethamModel(preetham_params(8.0, 45.0)).domain().worst(), Validity::extrapolated);
  EXPECT_EQ(PreethamModel(preetham_params(1.5, 45.0)).domain().worst(), Validity::unphysical);
}

TEST(Preetham, ZenithValuesAreReproduced) {
  // Y(zenith) = Yz exactly (the Perez ratio is F(0, ts)/F(0, ts) = 1), chromaticity = (x_z, y_z).
  for (double T : {2.0, 3.0, 4.5, 6.0}) {
    for (double ts : {0.0, 30.0, 60.0, 85.0}) {
      const PreethamModel m(preetham_params(T, ts));
      const Xyz c = m.tristimulus({0, 0, 1});
      EXPECT_NEAR(c.Y, m.zenith_luminance(), m.zenith_luminance() * kClosedFormRelTol);
      const Chromaticity xy = chromaticity(c);
      const Chromaticity z = preetham_zenith_chromaticity(T, deg_to_rad(ts));
      EXPECT_NEAR(xy.x, z.x, 1e-12);
      EXPECT_NEAR(xy.y, z.y, 1e-12);
    }
  }
  // x_z at T = 3, ts = 0: row sums of the T^0 / T^1 / T^2 rows' last column:
  // 0.25886 + 3 * 0.00394 + 9 * 0 = 0.27068.
  EXPECT_NEAR(preetham_zenith_chromaticity(3.0, 0.0).x, 0.27068, 1e-12);
  EXPECT_NEAR(preetham_zenith_chromaticity(3.0, 0.0).y, 0.26688 + 3 * 0.00516, 1e-12);
}

TEST(Preetham, PerezCoefficientsLinearInT) {
  // Preetham A.2: A_Y = 0.1787 T - 1.4630 etc.
  const PreethamPerez c = preetham_perez_coefficients(2.0);
  EXPECT_NEAR(c.Y.A, 0.1787 * 2 - 1.4630, 1e-15);
  EXPECT_NEAR(c.Y.E, -0.0670 * 2 + 0.3703, 1e-15);
  EXPECT_NEAR(c.x.D, -0.0641 * 2 - 0.8989, 1e-15);
  EXPECT_NEAR(c.y.C, -0.0079 * 2 + 0.2102, 1e-15);
}

TEST(Preetham, SymmetricAboutSolarMeridianAndBrighterTowardsSun) {
  const PreethamModel m(preetham_params(3.0, 50.0, 120.0));
  for (double dphi : {10.0, 45.0, 90.0, 170.0}) {
    for (double t : {10.0, 45.0, 80.0}) {
      const Xyz a = m.tristimulus(direction_from_angles(deg_to_rad(t), deg_to_rad(120.0 + dphi)));
      const Xyz b = m.tristimulus(direction_from_angles(deg_to_rad(t), deg_to_rad(120.0 - dphi)));
      EXPECT_NEAR(a.Y, b.Y, a.Y * 1e-12) << t << " " << dphi;
      EXPECT_NEAR(a.X, b.X, a.X * 1e-12);
    }
  }
  // Along the sun's almucantar luminance falls with distance from the sun.
  double prev = 1e300;
  for (double dphi = 5.0; dphi <= 180.0; dphi += 5.0) {
    const double Y =
        m.tristimulus(direction_from_angles(deg_to_rad(50.0), deg_to_rad(120.0 + dphi))).Y;
    EXPECT_LT(Y, prev) << dphi;
    prev = Y;
  }
}

TEST(Preetham, DefinedBelowHorizonAndForSunBelowHorizon) {
  const PreethamModel m(preetham_params(3.0, 45.0));
  EXPECT_EQ(m.tristimulus({0, 0.6, -0.8}).Y, 0.0);
  const PreethamModel night(preetham_params(3.0, 100.0));
  EXPECT_EQ(night.domain().worst(), Validity::undefined);
  EXPECT_EQ(night.tristimulus({0, 0, 1}).Y, 0.0);
  EXPECT_EQ(*night.spectral_radiance({0, 0, 1}, 550.0), 0.0);
  EXPECT_EQ(night.sun_tristimulus(night.sun().direction()).Y, 0.0);
  // The horizon itself is finite for every turbidity in the accepted range.
  for (double T : {1.0, 1.1, 2.0, 10.0, 30.0, 64.0}) {
    const PreethamModel h(preetham_params(T, 60.0));
    for (double az = 0; az < 360; az += 30) {
      const Xyz c = h.tristimulus(direction_from_angles(kPi / 2, deg_to_rad(az)));
      EXPECT_TRUE(std::isfinite(c.X) && std::isfinite(c.Y) && std::isfinite(c.Z)) << T;
      EXPECT_GE(c.Y, 0.0);
    }
  }
  EXPECT_THROW(PreethamModel(preetham_params(0.5, 45.0)), InvalidArgument);
}

TEST(Preetham, SpectralRadianceIntegratesToLuminance) {
  // L(lambda) is the daylight spectrum scaled so that 683 int L y-bar = Y; integrating it back on
  // a 1 nm grid reproduces Y and xy (linear interpolation of the 5 nm basis: < 1e-3 relative).
  constexpr double kSpectralRoundTripTol = 1e-3;
  const PreethamModel m(preetham_params(3.0, 40.0));
  const Vec3 v = direction_from_angles(deg_to_rad(60.0), deg_to_rad(30.0));
  std::vector<double> nm, L;
  for (int l = 360; l <= 830; ++l) {
    nm.push_back(l);
    L.push_back(*m.spectral_radiance(v, l));
  }
  const Xyz from_spectrum = spectral_radiance_to_xyz(nm, L);
  const Xyz direct = m.tristimulus(v);
  EXPECT_NEAR(from_spectrum.Y, direct.Y, direct.Y * kSpectralRoundTripTol);
  EXPECT_NEAR(chromaticity(from_spectrum).x, chromaticity(direct).x, kSpectralRoundTripTol);
  EXPECT_NEAR(chromaticity(from_spectrum).y, chromaticity(direct).y, kSpectralRoundTripTol);
  EXPECT_FALSE(m.spectral_radiance(v, 250.0).has_value());
  // A blue sky: more radiance at 450 nm than at 650 nm.
  EXPECT_GT(*m.spectral_radiance(v, 450.0), *m.spectral_radiance(v, 650.0));
}

TEST(Preetham, SunTransmittanceClosedForms) {
  // Zenith sun: m = 1 / (1 + 0.15 * 93.885^-1.253) = 1 / (1 + 0.0006761) (Kasten 1966).
  EXPECT_NEAR(relative_optical_mass(0.0), 1.0 / (1.0 + 0.15 * std::pow(93.885, -1.253)), 1e-15);
  // Rayleigh at 500 nm, zenith: exp(-0.008735 * 0.5^-4.08 * m).
  const double m0 = relative_optical_mass(0.0);
  const SolarTransmittance t = preetham_solar_transmittance(0.0, 2.0, 500.0);
  EXPECT_NEAR(t.rayleigh, std::exp(-0.008735 * std::pow(0.5, -4.08) * m0), 1e-15);
  // Aerosol, T = 2: beta = 0.04608*2 - 0.04586 = 0.0463, alpha = 1.3.
  EXPECT_NEAR(t.aerosol, std::exp(-0.0463 * std::pow(0.5, -1.3) * m0), 1e-15);
  // Ozone at 500 nm: k_o = 0.03 cm^-1, l = 0.35 cm.
  EXPECT_NEAR(t.ozone, std::exp(-0.03 * 0.35 * m0), 1e-15);
  EXPECT_EQ(t.mixed_gas, 1.0);  // no O2 band at 500 nm
  // The 760 nm O2 band: k_g = 3.0.
  const double kg = 3.0;
  EXPECT_NEAR(preetham_solar_transmittance(0.0, 2.0, 760.0).mixed_gas,
              std::exp(-1.41 * kg * m0 / std::pow(1 + 118.93 * kg * m0, 0.45)), 1e-15);
  // Lower sun, longer path: less light; higher turbidity: less light.
  EXPECT_LT(preetham_solar_transmittance(deg_to_rad(80), 2.0, 500.0).total(), t.total());
  EXPECT_LT(preetham_solar_transmittance(0.0, 6.0, 500.0).total(), t.total());
}

TEST(Preetham, SunDiscRadiance) {
  const PreethamModel m(preetham_params(3.0, 30.0));
  const Vec3 s = m.sun().direction();
  // Inside the disc: extraterrestrial table value x transmittance; 550 nm table value 25503.8.
  const double expected =
      25503.8 * preetham_solar_transmittance(deg_to_rad(30.0), 3.0, 550.0).total();
  EXPECT_NEAR(*m.sun_spectral_radiance(s, 550.0), expected, expected * 1e-12);
  const Vec3 off = direction_from_angles(deg_to_rad(30.0) + 2 * kPreethamSunAngularRadius, kPi);
  EXPECT_EQ(*m.sun_spectral_radiance(off, 550.0), 0.0);
  EXPECT_EQ(m.sun_tristimulus(off).Y, 0.0);
  // The disc is ~1e9 cd/m^2 at 30 deg (the sun's luminance at noon is 1.6e9 cd/m^2 above the air).
  EXPECT_GT(m.sun_tristimulus(s).Y, 5e8);
  EXPECT_LT(m.sun_tristimulus(s).Y, 2e9);
}

}  // namespace
}  // namespace skylight
