#include "skylight/core/colorimetry.h"

#include <gtest/gtest.h>

#include <vector>

namespace skylight {
namespace {

// The CIE metadata lists the column sums of the 1 nm table to ~15 digits; summing 471 doubles
// reproduces them to ~1e-12 relative.
constexpr double kColumnSumTol = 1e-9;
// IEC 61966-2-1 publishes its matrix to 4 decimals, computed from rounded intermediates; the
// matrix derived exactly from the primaries and the (0.3127, 0.3290) white differs by <= 3.7e-4.
constexpr double kPublishedMatrixTol = 4e-4;
// Daylight at 6504 K integrated on a 1 nm grid from the 5 nm basis: CIE tabulates D65 at
// (0.31272, 0.32903); linear interpolation of S0..S2 moves xy by < 5e-4.
constexpr double kDaylightChromaTol = 5e-4;

TEST(Colorimetry, CmfColumnSumsMatchCieMetadata) {
  // CIE_xyz_1931_2deg.csv_metadata.json "sumOfColumns": [280245, 106.865469489595,
  // 106.8569171011719, 106.892251278636].
  double sx = 0, sy = 0, sz = 0;
  for (int nm = 360; nm <= 830; ++nm) {
    const Cmf c = cie1931_cmf(nm);
    sx += c.x;
    sy += c.y;
    sz += c.z;
  }
  EXPECT_NEAR(sx, 106.865469489595, kColumnSumTol);
  EXPECT_NEAR(sy, 106.8569171011719, kColumnSumTol);
  EXPECT_NEAR(sz, 106.892251278636, kColumnSumTol);
  // Sample row from the same metadata: 479 nm -> 0.1042979, 0.1334528, 0.8566193.
  EXPECT_DOUBLE_EQ(cie1931_cmf(479).x, 0.104297900000);
  EXPECT_DOUBLE_EQ(cie1931_cmf(479).y, 0.1334528000000);
  EXPECT_EQ(cie1931_cmf(300).y, 0.0) << "zero outside 360-830 nm (CIE extrapolation rule)";
  EXPECT_NEAR(cie1931_cmf(555.5).y, 0.5 * (cie1931_cmf(555).y + cie1931_cmf(556).y), 1e-15);
}

TEST(Colorimetry, SrgbMatrixMatchesIec61966) {
  // IEC 61966-2-1 XYZ -> linear sRGB, as published.
  const double published[3][3] = {
      {3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  const Matrix3& m = xyz_to_srgb_matrix();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(m[r][c], published[r][c], kPublishedMatrixTol) << r << "," << c;
  // Luminance row of the inverse: Y = 0.2126 R + 0.7152 G + 0.0722 B.
  EXPECT_NEAR(srgb_to_xyz_matrix()[1][0], 0.2126, kPublishedMatrixTol);
  EXPECT_NEAR(srgb_to_xyz_matrix()[1][1], 0.7152, kPublishedMatrixTol);
  EXPECT_NEAR(srgb_to_xyz_matrix()[1][2], 0.0722, kPublishedMatrixTol);
}

TEST(Colorimetry, SrgbRoundTripAndWhite) {
  const Xyz w = xyY_to_xyz(kD65WhiteSrgb, 100.0);
  const Rgb rgb = xyz_to_linear_srgb(w);
  // D65 white maps to equal RGB (matrix built from the white point): double round-off only.
  EXPECT_NEAR(rgb.r, 100.0, 1e-10);
  EXPECT_NEAR(rgb.g, 100.0, 1e-10);
  EXPECT_NEAR(rgb.b, 100.0, 1e-10);
  const Xyz c{12.5, 30.0, 7.25};
  const Xyz back = linear_srgb_to_xyz(xyz_to_linear_srgb(c));
  EXPECT_NEAR(back.X, c.X, 1e-12);
  EXPECT_NEAR(back.Y, c.Y, 1e-12);
  EXPECT_NEAR(back.Z, c.Z, 1e-12);
}

TEST(Colorimetry, XyYRoundTrip) {
  const Xyz c = xyY_to_xyz({0.25, 0.28}, 5000.0);
  const Chromaticity xy = chromaticity(c);
  EXPECT_NEAR(xy.x, 0.25, 1e-15);
  EXPECT_NEAR(xy.y, 0.28, 1e-15);
  EXPECT_EQ(c.Y, 5000.0);
  const Chromaticity black = chromaticity({});
  EXPECT_EQ(black.x, kD65WhiteSrgb.x) << "black has a defined chromaticity, not NaN";
}

TEST(Colorimetry, DaylightAt6504KIsD65) {
  // CIE 015: D65 has nominal CCT 6504 K and chromaticity (0.31272, 0.32903).
  const Chromaticity locus = daylight_chromaticity(6504.0);
  // The locus formula (CIE 015 eq. 4.7-4.9) vs D65's tabulated xy, which comes from the SPD built
  // with M1, M2 rounded to 3 decimals: they differ by 9e-5 in y.
  constexpr double kLocusVsTableTol = 1e-4;
  EXPECT_NEAR(locus.x, 0.31272, kLocusVsTableTol);
  EXPECT_NEAR(locus.y, 0.32903, kLocusVsTableTol);
  const DaylightSpectrum d65(locus);
  // CIE 015:2018 rounds M1, M2 of D65 to -0.295 and -0.689.
  EXPECT_NEAR(d65.m1(), -0.295, 1e-3);
  EXPECT_NEAR(d65.m2(), -0.689, 1e-3);
  const Chromaticity xy = chromaticity(d65.integral_xyz());
  EXPECT_NEAR(xy.x, 0.31272, kDaylightChromaTol);
  EXPECT_NEAR(xy.y, 0.32903, kDaylightChromaTol);
  // S(560 nm) = 100 by the basis' normalisation (S0 = 100, S1 = S2 = 0 there).
  EXPECT_NEAR(d65(560.0), 100.0, 1e-12);
}

// CIE S 026:2018: s_mel peaks at 1 at 490 nm (its table), and D65's melanopic efficacy of
// luminous radiation, (integral E s_mel) / (683 integral E V), is 1.3262 mW/lm. D65 here is the
// daylight basis with CIE 015's rounded M1 = -0.295, M2 = -0.689 at 5 nm, linearly interpolated
// to 1 nm (the official D65 table is the same SPD); V = y-bar of 1931.
TEST(Colorimetry, MelanopicActionSpectrumAndD65Efficacy) {
  EXPECT_EQ(melanopic_sensitivity(490.0), 1.0);
  EXPECT_EQ(melanopic_sensitivity(480.0), 9.65605E-01);
  EXPECT_EQ(melanopic_sensitivity(555.0), 1.62056E-01);
  EXPECT_EQ(melanopic_sensitivity(379.0), 0.0);
  EXPECT_EQ(melanopic_sensitivity(781.0), 0.0);
  double mel = 0.0, lum = 0.0;
  for (int nm = 380; nm <= 780; ++nm) {
    const auto b = daylight_basis(nm);
    const double e = b.s0 - 0.295 * b.s1 - 0.689 * b.s2;
    mel += e * melanopic_sensitivity(nm);
    lum += kMaxLuminousEfficacy * e * cie1931_cmf(nm).y;
  }
  // The standard gives 4 digits; the basis' 5 nm rows interpolated to 1 nm differ from the
  // 1 nm D65 table by up to ~0.1 %, which moves the ratio by ~1e-4 of itself.
  EXPECT_NEAR(mel / lum / kMelanopicEfficacyD65, 1.0, 5e-4);
}

TEST(Colorimetry, McCamyCct) {
  // McCamy 1992 on D65 xy gives 6504 K within a few kelvin; illuminant A (0.44757, 0.40745) 2856 K.
  EXPECT_NEAR(cct_mccamy({0.31272, 0.32903}), 6504.0, 5.0);
  EXPECT_NEAR(cct_mccamy({0.44757, 0.40745}), 2856.0, 5.0);
}

TEST(Colorimetry, SpectrumIntegrationEqualEnergy) {
  // An equal-energy spectrum of 1 W m^-2 sr^-1 nm^-1 over 360-830 nm: Y = 683 * sum(y-bar)
  // (trapezoid = sum minus half the end values, which are ~4e-6).
  std::vector<double> nm, v;
  for (int l = 360; l <= 830; ++l) {
    nm.push_back(l);
    v.push_back(1.0);
  }
  const Xyz c = spectral_radiance_to_xyz(nm, v);
  EXPECT_NEAR(c.Y, 683.0 * 106.8569171011719, 683.0 * 1e-5);
  const Chromaticity xy = chromaticity(c);
  EXPECT_NEAR(xy.x, 1.0 / 3.0, 2e-4);  // illuminant E is (1/3, 1/3) by construction of the CMFs
  EXPECT_NEAR(xy.y, 1.0 / 3.0, 2e-4);
}

}  // namespace
}  // namespace skylight
