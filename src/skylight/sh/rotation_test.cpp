#include "skylight/sh/rotation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "skylight/core/math.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/models/preetham.h"
#include "skylight/sh/basis.h"

namespace skylight::sh {
namespace {

// Rotation and reconstruction are exact: round-off only.
constexpr double kRotationExact = 1e-12;
// Two projections converged to a change below 1e-6 of c_00 are each within ~1.5e-7 of the limit
// (the change shrinks ~8x per doubling, docs/SH.md): they agree to 1e-6 with a factor 3 margin.
constexpr double kProjectionTolerance = 1e-6;
constexpr double kRotationVsReprojection = 1e-6;

Coefficients some_coefficients(int bands) {
  Coefficients c{bands, std::vector<Triple>(coefficient_count(bands))};
  for (int i = 0; i < coefficient_count(bands); ++i) {
    c.c[static_cast<std::size_t>(i)] = {std::cos(0.3 * i), std::sin(2.0 + i), 0.1 * i};
  }
  return c;
}

// R = Rz(a) Rx(b) Rz(c) in the project's frame.
RotationMatrix euler_zxz(double a, double b, double c) {
  const auto rz = [](double t) {
    return RotationMatrix{
        {{std::cos(t), -std::sin(t), 0.0}, {std::sin(t), std::cos(t), 0.0}, {0.0, 0.0, 1.0}}};
  };
  const RotationMatrix rx{
      {{1.0, 0.0, 0.0}, {0.0, std::cos(b), -std::sin(b)}, {0.0, std::sin(b), std::cos(b)}}};
  const auto mul = [](const RotationMatrix& p, const RotationMatrix& q) {
    RotationMatrix o{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) o[i][j] += p[i][k] * q[k][j];
    return o;
  };
  return mul(mul(rz(a), rx), rz(c));
}

Vec3 apply(const RotationMatrix& r, Vec3 d) {
  return {r[0][0] * d.x + r[0][1] * d.y + r[0][2] * d.z,
          r[1][0] * d.x + r[1][1] * d.y + r[1][2] * d.z,
          r[2][0] * d.x + r[2][1] * d.y + r[2][2] * d.z};
}
Vec3 apply_transpose(const RotationMatrix& r, Vec3 d) {
  return {r[0][0] * d.x + r[1][0] * d.y + r[2][0] * d.z,
          r[0][1] * d.x + r[1][1] * d.y + r[2][1] * d.z,
          r[0][2] * d.x + r[1][2] * d.y + r[2][2] * d.z};
}

// The recurrence's round-off grows with the band; 8 bands of O(1) coefficients stay within 1e-11.
constexpr double kGeneralRotation = 1e-11;

TEST(ShRotation, GeneralRotationMatchesTheRotatedSignalAndItsReprojection) {
  const auto c = some_coefficients(8);
  const RotationMatrix r = euler_zxz(0.7, 1.1, -2.3);
  const auto rotated = rotate(c, r);
  // Pointwise: g(R d) = f(d).
  for (double theta : {0.0, 0.6, 1.7, 3.0}) {
    for (double phi : {0.0, 2.0, 5.0}) {
      const Vec3 d = direction_from_angles(theta, phi);
      const Triple a = reconstruct(c, d);
      const Triple b = reconstruct(rotated, apply(r, d));
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(a[ch], b[ch], kGeneralRotation);
    }
  }
  // Re-projection of the rotated function d -> f(R^T d) over the sphere (band-limited: exact).
  ProjectionOptions o;
  o.region = Region::full_sphere;
  o.min_nodes = 16;  // exact for degree 2 (8 - 1) = 14 in mu and phi
  o.max_nodes = 32;  // the blue channel's c_00 is 0: relative convergence is not measurable
  const auto p = project([&](Vec3 d) { return reconstruct(c, apply_transpose(r, d)); }, 8, o);
  for (std::size_t i = 0; i < c.c.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(rotated.c[i][ch], p.coefficients.c[i][ch], kGeneralRotation) << i;
  }
  // A turn about the zenith by -alpha in the (x east, y north) plane moves azimuth 0 (north)
  // to alpha (towards east): eq. 4.
  constexpr double kAlpha = 0.9;
  const auto z = rotate(c, euler_zxz(-kAlpha, 0.0, 0.0));
  const auto eq4 = rotate_about_zenith(c, kAlpha);
  for (std::size_t i = 0; i < c.c.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(z.c[i][ch], eq4.c[i][ch], kGeneralRotation) << i;
  }
}

TEST(ShRotation, RotatesTheReconstructedSignalAboutTheZenith) {
  // f_rot(theta, phi + alpha) = f(theta, phi).
  const auto c = some_coefficients(8);
  constexpr double kAlpha = 1.234;
  const auto r = rotate_about_zenith(c, kAlpha);
  for (double theta : {0.2, 1.0, 2.0}) {
    for (double phi : {0.0, 1.5, 4.0}) {
      const Triple a = reconstruct(c, direction_from_angles(theta, phi));
      const Triple b = reconstruct(r, direction_from_angles(theta, phi + kAlpha));
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(a[ch], b[ch], kRotationExact);
    }
  }
  // Zonal coefficients are unchanged; a full turn is the identity.
  const auto full = rotate_about_zenith(c, 2.0 * kPi);
  for (std::size_t i = 0; i < c.c.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(full.c[i][ch], c.c[i][ch], kRotationExact);
  }
  EXPECT_EQ(r.c[static_cast<std::size_t>(index(5, 0))], c.c[static_cast<std::size_t>(index(5, 0))]);
}

TEST(ShRotation, EquationFourMatchesReprojectionOfTheRotatedSky) {
  // Habel 2008 eq. 4: the sky of a sun at azimuth phi is that of the sun at azimuth 0, rotated.
  constexpr int kBands = 8;
  constexpr double kSunZenith = 1.1, kSunAzimuth = 2.2;
  ProjectionOptions o;
  o.tolerance = kProjectionTolerance;
  const PreethamModel at0(PreethamParameters{{kSunZenith, 0.0}, 4.0});
  const PreethamModel atphi(PreethamParameters{{kSunZenith, kSunAzimuth}, 4.0});
  const auto p0 = fit::project_model(at0, Channels::linear_srgb, kBands, o);
  const auto pphi = fit::project_model(atphi, Channels::linear_srgb, kBands, o);
  ASSERT_TRUE(p0.converged && pphi.converged);
  const auto rotated = rotate_about_zenith(p0.coefficients, kSunAzimuth);
  double worst = 0.0;
  for (std::size_t i = 0; i < rotated.c.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      const double rel = std::abs(rotated.c[i][ch] - pphi.coefficients.c[i][ch]) /
                         std::abs(pphi.coefficients.c[0][ch]);
      worst = std::max(worst, rel);
      EXPECT_LT(rel, kRotationVsReprojection) << "i=" << i << " ch=" << ch;
    }
  }
  RecordProperty("worst_relative_difference", std::to_string(worst));
}

TEST(ShRingingFilter, ScalesOnlyZonalCoefficientsBySinc) {
  const auto c = some_coefficients(7);
  const auto f = ringing_filter(c);
  EXPECT_DOUBLE_EQ(ringing_factor(0, 7), 1.0);
  for (int l = 0; l < 7; ++l) {
    const double x = kPi * l / 7.0;
    const double s = l == 0 ? 1.0 : std::sin(x) / x;
    for (int m = -l; m <= l; ++m) {
      const auto i = static_cast<std::size_t>(index(l, m));
      EXPECT_NEAR(f.c[i][1], m == 0 ? s * c.c[i][1] : c.c[i][1], kRotationExact);
    }
  }
}

TEST(ShRingingFilter, EnergyBelowHorizonClosedFormForAConstant) {
  // Only c_00: f = c_00 Y_00 = c_00 / (2 sqrt(pi)); energy over 2 pi sr = c_00^2 / 2.
  Coefficients c{3, std::vector<Triple>(9)};
  c.c[0] = {2.0, 1.0, 0.5};
  const auto e = energy_below(c);
  EXPECT_NEAR(e[0], 2.0, kRotationExact);
  EXPECT_NEAR(e[2], 0.125, kRotationExact);
}

// Away from the horizon (theta >= 120 deg) the filter must cut the ringing energy at least 3x
// (measured 7.7x at 7 bands and 7.3x at 8 for this sky; Habel 2008 Fig. 4: "strongly reduced").
// Over the whole lower hemisphere it does not: the box filter widens the horizon step, and the
// energy just below the horizon grows (measured factor 0.86 and 0.73, docs/SH.md).
constexpr double kMinRingingReduction = 3.0;
constexpr double kRingingFrom = 120.0 * kDegree;

TEST(ShRingingFilter, ReducesTheRingingEnergyFarBelowTheHorizonOfPreetham) {
  const PreethamModel model(PreethamParameters{{deg_to_rad(30.0), 0.0}, 3.0});
  for (int bands : {7, 8}) {
    const auto p = fit::project_model(model, Channels::xyz, bands);
    const auto raw = energy_below(p.coefficients, kRingingFrom);
    const auto filtered = energy_below(ringing_filter(p.coefficients), kRingingFrom);
    const double factor = raw[1] / filtered[1];
    RecordProperty("factor_" + std::to_string(bands), std::to_string(factor));
    EXPECT_GT(factor, kMinRingingReduction) << "bands=" << bands;
  }
}

}  // namespace
}  // namespace skylight::sh
