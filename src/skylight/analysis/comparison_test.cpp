#include "skylight/analysis/comparison.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "skylight/core/error.h"
#include "skylight/models/cie_sky.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/preetham.h"

namespace skylight::analysis {
namespace {

// Bisection stops at a bracket of 1e-10 in T; |dYz/dT| < 2e5 cd/m^2 per unit T over [1, 64], so
// |Yz| at a root is below 2e-5 cd/m^2; 1e-4 leaves room for round-off in the closed form.
constexpr double kYzAtRootTol = 1e-4;  // [cd/m^2]
// A root must sit between points of opposite sign this close on either side.
constexpr double kRootBracket = 1e-8;
// Closed-form root at theta_s = 90 deg: round-off of the bisection only.
constexpr double kClosedFormRootTol = 1e-9;
// A distribution compared with itself: exactly 0 (same numbers); allow last-bit noise of log10.
constexpr double kSelfRmsTol = 1e-12;
// Zotti et al. 2007, section 6: CIE type 12 is best approximated by Preetham with T ~ 2.3-2.5.
constexpr double kZottiBestTurbidityLow = 2.3, kZottiBestTurbidityHigh = 2.5;
// Zotti give no method or resolution for that range (and read it off their figures); ours is an
// RMS over a sampled hemisphere, so allow 0.1-0.2 in T on either side.
constexpr double kZottiBandMargin = 0.2;

// The whole-sky boundary: bisection to 1e-12 against a Lambert-W closed form solved by Newton to
// round-off; both are limited by double round-off in 1 + A e^B (|d/dT| ~ 0.5), so 1e-10.
constexpr double kWholeSkyBoundaryTol = 1e-10;
// docs/REPORT.md quotes the boundary to three decimals (T = 1.643).
constexpr double kThreeDecimals = 5e-4;
// region_ratio against the same model evaluations done here: identical arithmetic up to the
// order of the batch path's double evaluation.
constexpr double kRegionRatioTol = 1e-12;
// preetham_cie_ratio_band's typical ratio against absolute_luminance_ratio: the same logs summed
// in a different order (per sun position, then over them).
constexpr double kRatioBandTol = 1e-9;

// Preetham 1999 A.2, the Y row of the Perez coefficients: A = 0.1787 T - 1.4630,
// B = -0.3554 T + 0.4275.
constexpr double kPaperA1 = 0.1787, kPaperA0 = -1.4630, kPaperB1 = -0.3554, kPaperB0 = 0.4275;

// Principal branch of Lambert's W (w e^w = x, x > 0) by Newton's method.
double lambert_w0(double x) {
  double w = std::log1p(x);
  for (int i = 0; i < 100; ++i) {
    const double f = w * std::exp(w) - x, step = f / (std::exp(w) * (w + 1.0));
    w -= step;
    if (std::abs(step) < 1e-16 * (1.0 + std::abs(w))) break;
  }
  return w;
}

TEST(PreethamNegativeSky, BoundaryIsTheRootOfOnePlusAExpB) {
  // 1 + (a1 T + a0) e^(b1 T + b0) = 0. With u = a1 T + a0, k = b1 / a1, m = b0 - b1 a0 / a1:
  // u e^(k u) = -e^(-m), so k u = W(-k e^(-m)) (k < 0: the argument is positive, one real root).
  const double k = kPaperB1 / kPaperA1, m = kPaperB0 - kPaperB1 * kPaperA0 / kPaperA1;
  const double u = lambert_w0(-k * std::exp(-m)) / k;
  const double t_closed = (u - kPaperA0) / kPaperA1;
  const NegativeSkyRange r = preetham_negative_sky_range();
  EXPECT_NEAR(r.t_high, t_closed, kWholeSkyBoundaryTol);
  EXPECT_NEAR(r.t_high, 1.643, kThreeDecimals);
  EXPECT_NEAR(r.t_low, -kPaperB0 / kPaperB1, kWholeSkyBoundaryTol);
  // Between the two the zenith term is negative, outside positive (or B > 0 below t_low).
  for (double T : {r.t_low + 0.01, 0.5 * (r.t_low + r.t_high), r.t_high - 0.01}) {
    const auto c = preetham_perez_coefficients(T).Y;
    EXPECT_LT(1.0 + c.A * std::exp(c.B), 0.0) << "T = " << T;
    EXPECT_LT(c.B, 0.0);
  }
  const auto c = preetham_perez_coefficients(r.t_high + 0.01).Y;
  EXPECT_GT(1.0 + c.A * std::exp(c.B), 0.0);
}

// Closed forms on planted samples: a uniform 10 % excess; half the sky 10 % and half 30 % too
// bright (the median is where half the solid angle lies); a negative value counts as 1000x dark.
TEST(SourceError, MedianP95AndRmsOfPlantedErrors) {
  const HemisphereGrid grid = hemisphere_grid(4, 8);
  const std::size_t n = grid.solid_angle.size();
  RelativeSamples source, uniform, split, negative;
  source.absolute = {std::vector<double>(n, 100.0)};
  uniform.absolute = {std::vector<double>(n, 110.0)};
  split.absolute = {std::vector<double>(n, 110.0)};
  negative.absolute = {std::vector<double>(n, 100.0)};
  // The two lower rings (equal in number of cells, more solid angle than the upper two).
  for (std::size_t i = 0; i < n; ++i)
    if (grid.directions[i].z < std::cos(kPi / 4)) split.absolute[0][i] = 130.0;
  negative.absolute[0][0] = -5.0;
  const SourceError u = source_error({&uniform}, {&source}, grid);
  EXPECT_NEAR(u.median, 0.1, 1e-12);
  EXPECT_NEAR(u.p95, 0.1, 1e-12);
  EXPECT_NEAR(u.rms_log10, std::log10(1.1), 1e-12);
  EXPECT_EQ(u.directions, n);
  // The lower half holds cos(0) - cos(pi/4) = 0.71 of the hemisphere's solid angle: both
  // quantiles fall in it.
  const SourceError h = source_error({&split}, {&source}, grid);
  EXPECT_NEAR(h.median, 0.3, 1e-12);
  EXPECT_NEAR(h.p95, 0.3, 1e-12);
  const SourceError g = source_error({&negative}, {&source}, grid);
  EXPECT_NEAR(g.median, 0.0, 1e-12);
  const double w0 = grid.solid_angle[0], total = 2.0 * kPi;
  EXPECT_NEAR(g.rms_log10, std::sqrt(w0 / total * 9.0), 1e-9);  // log10(1e-3)^2 = 9
  // Pooled sets: the mean of squares over both.
  const SourceError both = source_error({&uniform, &negative}, {&source, &source}, grid);
  EXPECT_NEAR(both.rms_log10,
              std::sqrt((total * std::pow(std::log10(1.1), 2) + w0 * 9.0) / (2.0 * total)), 1e-9);
  EXPECT_EQ(both.directions, 2 * n);
}

// The uniform CIE sky (type 5) has no dip: darkest, horizon and zenith are one value; CIE 12 has
// one (darker than its zenith somewhere opposite the sun, horizon brighter than the darkest).
TEST(AntisolarDip, UniformSkyHasNoneAndTheClearSkyHasOne) {
  const HemisphereGrid grid = hemisphere_grid(18, 72);
  const AntisolarDip u =
      antisolar_dip(comparison_spec(CieSkyModel::kName, 5), 70 * kDegree, grid, 5 * kDegree);
  EXPECT_NEAR(u.depth(), 1.0, 1e-12);
  EXPECT_NEAR(u.contrast(), 1.0, 1e-12);
  const AntisolarDip c =
      antisolar_dip(comparison_spec(CieSkyModel::kName, 12), 70 * kDegree, grid, 5 * kDegree);
  EXPECT_LT(c.depth(), 1.0);
  EXPECT_GT(c.contrast(), 1.0);
  EXPECT_GT(c.darkest_elevation, 0.0);
}

// A sky against itself reads 1 in every reading; against the same sky of another level (CIE 12
// with twice its zenith luminance) 2 in every reading.
TEST(LuminanceReadings, EveryReadingOfAScaledSkyIsTheScale) {
  const HemisphereGrid grid = hemisphere_grid(12, 48);
  ComparisonSettings s;
  s.sun_zeniths = {30 * kDegree, 60 * kDegree};
  const ModelSpec a = comparison_spec(CieSkyModel::kName, 12);
  const LuminanceReadings same = luminance_readings(a, a, s, grid);
  for (const LuminanceRatio* r : {&same.geometric_mean, &same.peak, &same.zenith, &same.diffuse}) {
    EXPECT_NEAR(r->min, 1.0, 1e-12);
    EXPECT_NEAR(r->max, 1.0, 1e-12);
  }
  for (double sz : s.sun_zeniths) {
    ModelSpec b = a;
    const double lz = make_model(a, sz, s.sun_azimuth)->tristimulus({0, 0, 1}).Y;
    b.params.values.set("zenith-luminance", 2.0 * lz);
    ComparisonSettings one = s;
    one.sun_zeniths = {sz};
    const LuminanceReadings twice = luminance_readings(b, a, one, grid);
    for (const LuminanceRatio* r :
         {&twice.geometric_mean, &twice.peak, &twice.zenith, &twice.diffuse})
      EXPECT_NEAR(r->mean, 2.0, 1e-9);
  }
}

// A sky against itself differs by nothing; a grey sky (CIE, D65 white) against the same sky at
// twice its zenith luminance by nothing in colour and log10(2) in level; a coloured sky against
// a grey one by a positive distance.
TEST(ColourDifference, IsZeroForTheSameSkyAndTheLevelForAScaledOne) {
  const HemisphereGrid grid = hemisphere_grid(8, 32);
  ComparisonSettings s;
  s.sun_zeniths = {40 * kDegree};
  const ModelSpec cie = comparison_spec(CieSkyModel::kName, 12);
  const ColourDifference same = colour_difference(cie, cie, s, grid);
  EXPECT_NEAR(same.mean_duv, 0.0, 1e-15);
  EXPECT_NEAR(same.rms_log10, 0.0, 1e-15);
  ModelSpec twice = cie;
  twice.params.values.set(
      "zenith-luminance",
      2.0 * make_model(cie, s.sun_zeniths[0], s.sun_azimuth)->tristimulus({0, 0, 1}).Y);
  const ColourDifference level = colour_difference(twice, cie, s, grid);
  EXPECT_NEAR(level.mean_duv, 0.0, 1e-12);
  EXPECT_NEAR(level.rms_log10, std::log10(2.0), 1e-12);
  const ColourDifference coloured =
      colour_difference(comparison_spec(PreethamModel::kName, 3), cie, s, grid);
  EXPECT_GT(coloured.mean_duv, 0.001);
  EXPECT_GE(coloured.p95_duv, coloured.mean_duv);
}

TEST(RegionRatio, AntisolarHalfMatchesADirectRecomputation) {
  const HemisphereGrid grid = hemisphere_grid(6, 24);
  const double ts = deg_to_rad(70.0), T = 2.4;
  const RegionRatio r =
      region_ratio(comparison_spec(PreethamModel::kName, T),
                   comparison_spec(CieSkyModel::kName, 12), ts, grid, in_antisolar_half);
  const auto pr = make_model(comparison_spec(PreethamModel::kName, T), ts, kPi);
  const auto ci = make_model(comparison_spec(CieSkyModel::kName, 12), ts, kPi);
  const double pz = pr->tristimulus({0, 0, 1}).Y, cz = ci->tristimulus({0, 0, 1}).Y;
  double amin = 1e300, amax = 0.0, rmin = 1e300, rmax = 0.0;
  int n = 0;
  for (const Vec3& d : grid.directions) {
    // Sun at azimuth pi: the antisolar half is where the view's horizontal part points away.
    const Vec3 sun = direction_from_angles(ts, kPi);
    if (d.x * sun.x + d.y * sun.y > 0.0) continue;
    const double q = pr->tristimulus(d).Y / ci->tristimulus(d).Y;
    amin = std::min(amin, q);
    amax = std::max(amax, q);
    rmin = std::min(rmin, q * cz / pz);
    rmax = std::max(rmax, q * cz / pz);
    ++n;
  }
  EXPECT_EQ(r.directions, n);
  EXPECT_EQ(n, 6 * 24 / 2);  // sector centres never lie on the 90 deg boundary
  EXPECT_NEAR(r.absolute_min, amin, kRegionRatioTol * amin);
  EXPECT_NEAR(r.absolute_max, amax, kRegionRatioTol * amax);
  EXPECT_NEAR(r.relative_min, rmin, kRegionRatioTol * rmin);
  EXPECT_NEAR(r.relative_max, rmax, kRegionRatioTol * rmax);
}

TEST(RatioBand, TypicalMatchesTheLuminanceRatioAndTheBandBracketsIt) {
  ComparisonSettings s;
  s.sun_zeniths = {deg_to_rad(30.0), deg_to_rad(60.0)};
  s.n_theta = 8;
  s.n_phi = 32;
  const HemisphereGrid grid = hemisphere_grid(s.n_theta, s.n_phi);
  for (const auto& [T, type] : {std::pair{2.9, 10}, std::pair{10.0, 6}}) {
    const RatioBand b = preetham_cie_ratio_band(T, type, s);
    const LuminanceRatio r = absolute_luminance_ratio(
        relative_samples(comparison_spec(PreethamModel::kName, T), s, grid),
        relative_samples(comparison_spec(CieSkyModel::kName, type), s, grid), grid);
    EXPECT_NEAR(b.typical, r.mean, kRatioBandTol * r.mean);
    EXPECT_LE(b.against_cie_high, b.typical);
    EXPECT_GE(b.against_cie_low, b.typical);
  }
}

TEST(PreethamZenithRoots, BoundaryPointsAreRootsOfTheClosedForm) {
  std::vector<double> zeniths;
  for (int d = 0; d <= 90; d += 5) zeniths.push_back(deg_to_rad(d));
  const auto roots = preetham_zenith_roots(zeniths, 1.0, 64.0);
  ASSERT_GE(roots.size(), zeniths.size());  // the high-turbidity branch at every sun zenith
  for (const auto& r : roots) {
    SCOPED_TRACE(testing::Message()
                 << "theta_s = " << rad_to_deg(r.sun_zenith) << " deg, T = " << r.turbidity);
    EXPECT_LT(std::abs(preetham_zenith_luminance(r.turbidity, r.sun_zenith)), kYzAtRootTol);
    const double below = preetham_zenith_luminance(r.turbidity - kRootBracket, r.sun_zenith);
    const double above = preetham_zenith_luminance(r.turbidity + kRootBracket, r.sun_zenith);
    EXPECT_EQ(above < 0.0, r.negative_above);
    EXPECT_EQ(below < 0.0, !r.negative_above);
  }
}

TEST(PreethamZenithRoots, BranchesMatchTheClosedForm) {
  // theta_s = 90 deg: chi = 0, so Yz = 1000 (-0.2155 T + 2.4192) = 0 at T = 2.4192 / 0.2155.
  const auto horizon = preetham_zenith_roots({kPi / 2}, 1.0, 64.0);
  ASSERT_EQ(horizon.size(), 1u);
  EXPECT_NEAR(horizon[0].turbidity, 2.4192 / 0.2155, kClosedFormRootTol);
  EXPECT_TRUE(horizon[0].negative_above);
  // Sun at the zenith: negative below T ~ 1.12 (Zotti Fig. 1) and above T ~ 51.7.
  const auto top = preetham_zenith_roots({0.0}, 1.0, 64.0);
  ASSERT_EQ(top.size(), 2u);
  EXPECT_FALSE(top[0].negative_above);
  EXPECT_GT(top[0].turbidity, 1.1);
  EXPECT_LT(top[0].turbidity, 1.13);
  EXPECT_TRUE(top[1].negative_above);
  EXPECT_GT(top[1].turbidity, 51.0);
  // Above theta_s ~ 12.9 deg the low branch has left [1, 64]: only the high branch remains.
  EXPECT_EQ(preetham_zenith_roots({deg_to_rad(20.0)}, 1.0, 64.0).size(), 1u);
  EXPECT_THROW(preetham_zenith_roots({deg_to_rad(95.0)}, 1.0, 64.0), InvalidArgument);
}

ComparisonSettings small_settings() {
  ComparisonSettings s;
  s.sun_zeniths = {deg_to_rad(30.0), deg_to_rad(60.0)};
  s.n_theta = 12;
  s.n_phi = 48;
  return s;
}

TEST(Comparison, EachCieTypeBestMatchesItself) {
  const auto s = small_settings();
  for (int type = 1; type <= kCieTypeCount; ++type) {
    SCOPED_TRACE(testing::Message() << "CIE type " << type);
    ModelSpec spec{"cie", {}, "target"};
    spec.params.values.set("cie-type", type);
    const CieTypeMatch m = rank_cie_types(spec, s);
    EXPECT_EQ(m.best_type, type);
    EXPECT_NEAR(m.best_rms, 0.0, kSelfRmsTol);
    EXPECT_GT(m.second_rms, 0.0);
    // Same model, same zenith luminance: the luminance ratio is exactly 1.
    EXPECT_NEAR(m.ratio_best.mean, 1.0, kSelfRmsTol);
  }
}

TEST(Comparison, RmsIsSymmetricAndScaleFree) {
  const auto s = small_settings();
  const auto g = hemisphere_grid(s.n_theta, s.n_phi);
  const ModelSpec a = comparison_spec(CieSkyModel::kName, 12),
                  b = comparison_spec(CieSkyModel::kName, 13);
  ModelSpec b10 = comparison_spec(CieSkyModel::kName, 13);
  b10.params.values.set("zenith-luminance",
                        10.0 * kittler_darula_zenith_luminance(13, deg_to_rad(60.0)));
  const auto sa = relative_samples(a, s, g), sb = relative_samples(b, s, g);
  const double ab = relative_log_rms(sa, sb, g);
  EXPECT_GT(ab, 0.0);
  EXPECT_DOUBLE_EQ(ab, relative_log_rms(sb, sa, g));
  // Relative (zenith-normalised) distributions ignore the absolute level.
  EXPECT_NEAR(relative_log_rms(sa, relative_samples(b10, s, g), g), ab, kSelfRmsTol);
  // Directions within the exclusion around the sun are left out (NaN).
  const Vec3 sun = direction_from_angles(s.sun_zeniths[0], s.sun_azimuth);
  int excluded = 0;
  for (std::size_t i = 0; i < g.directions.size(); ++i)
    if (angle_between(g.directions[i], sun) < s.sun_exclusion) {
      ++excluded;
      EXPECT_TRUE(std::isnan(sa.relative[0][i]));
    }
  EXPECT_GT(excluded, 0);
}

TEST(Comparison, PreethamTurbidityForCie12IsNearZottis) {
  // Zotti et al. 2007: "The CIE Clear Sky (Type 12) is best approximated with T ~ 2.3...2.5".
  // A coarser grid than the report's (same sun positions): the minimum must lie in a band around
  // Zotti's values; the report states the full-resolution number.
  ComparisonSettings s;
  for (double z : {20, 30, 40, 50, 60, 70}) s.sun_zeniths.push_back(deg_to_rad(z));
  s.n_theta = 18;
  s.n_phi = 72;
  const TurbidityFit fit = best_preetham_turbidity_for_cie(12, 1.7, 10.0, 0.1, s);
  EXPECT_GT(fit.turbidity, kZottiBestTurbidityLow - kZottiBandMargin) << fit.turbidity;
  EXPECT_LT(fit.turbidity, kZottiBestTurbidityHigh + kZottiBandMargin) << fit.turbidity;
  // The golden-section refinement never ends above the grid's best point.
  for (double r : fit.curve_rms) EXPECT_LE(fit.rms, r + 1e-15);
  EXPECT_EQ(fit.curve_t.front(), 1.7);
  EXPECT_EQ(fit.curve_t.back(), 10.0);
}

TEST(Comparison, AntisolarHorizonRatioIsTheModelsRatio) {
  const auto rows = antisolar_horizon_ratios(2.4, {deg_to_rad(80.0)}, {deg_to_rad(3.0)});
  ASSERT_EQ(rows.size(), 1u);
  SkyParameters p;
  p.sun = {deg_to_rad(80.0), kPi};
  p.values.set("turbidity", 2.4);
  const auto pr = make_sky_model("preetham", p);
  p.values = ParameterValues().set("cie-type", 12);
  const auto cie = make_sky_model("cie", p);
  const Vec3 v = direction_from_angles(deg_to_rad(87.0), 0.0);  // north, 3 deg up
  EXPECT_DOUBLE_EQ(rows[0].preetham, pr->tristimulus(v).Y);
  EXPECT_DOUBLE_EQ(rows[0].cie, cie->tristimulus(v).Y);
  EXPECT_DOUBLE_EQ(rows[0].ratio, rows[0].preetham / rows[0].cie);
  // Zotti: the antisolar horizon at low sun is too bright in Preetham's model.
  EXPECT_GT(rows[0].ratio, 1.0);
}

TEST(ValidityGrid, GridReportsTheModelsDomain) {
  const ModelSpec spec = comparison_spec(PreethamModel::kName, 3.0);  // the rows set the turbidity
  const auto g =
      validity_grid(spec, {deg_to_rad(45.0), deg_to_rad(100.0)}, {3.0, 8.0, 20.0}, "turbidity");
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[0][0], Validity::valid);
  EXPECT_EQ(g[1][0], Validity::extrapolated);
  EXPECT_EQ(g[2][0], Validity::unphysical);
  EXPECT_EQ(g[0][1], Validity::undefined);  // sun below the horizon
  // Parameters the model rejects are drawn as undefined.
  const ModelSpec hosek = comparison_spec(HosekWilkieModel::kName, 5.0);
  const auto h = validity_grid(hosek, {deg_to_rad(45.0)}, {5.0, 20.0}, "turbidity");
  EXPECT_EQ(h[0][0], Validity::valid);
  EXPECT_EQ(h[1][0], Validity::undefined);
}
}  // namespace
}  // namespace skylight::analysis
