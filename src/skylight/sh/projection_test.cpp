#include "skylight/sh/projection.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/math.h"
#include "skylight/models/preetham.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/rotation.h"

namespace skylight::sh {
namespace {

// A band-limited function is integrated exactly by the product rule: round-off only.
// Closed forms of a few terms: double round-off only.
constexpr double kRoundOff = 1e-15;
constexpr double kExact = 1e-12;
// The refinement's stopping tolerance (relative to c_00); the sin terms vanish by the symmetry of
// the azimuth grid about phi = 0, so 10x this is a loose bound.
constexpr double kConvergedTolerance = 1e-6;

TEST(ShProjection, GaussLegendreIntegratesPolynomialsExactly) {
  std::vector<double> x, w;
  gauss_legendre(5, 0.0, 1.0, x, w);
  double s0 = 0.0, s9 = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    s0 += w[i];
    s9 += w[i] * std::pow(x[i], 9);
  }
  EXPECT_NEAR(s0, 1.0, kRoundOff);
  EXPECT_NEAR(s9, 0.1, kRoundOff);  // degree 2n - 1 = 9 is exact
}

TEST(ShProjection, AKnownShFunctionReproducesItsCoefficients) {
  constexpr int kBands = 6;
  Coefficients known{kBands, std::vector<Triple>(coefficient_count(kBands))};
  for (int i = 0; i < coefficient_count(kBands); ++i) {
    known.c[static_cast<std::size_t>(i)] = {std::sin(1.0 + i), 0.5 * std::cos(3.0 * i),
                                            1.0 / (i + 1)};
  }
  ProjectionOptions o;
  o.region = Region::full_sphere;
  o.min_nodes = 8;
  const auto p = project([&](Vec3 d) { return reconstruct(known, d); }, kBands, o);
  ASSERT_TRUE(p.converged);
  for (std::size_t i = 0; i < known.c.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(p.coefficients.c[i][ch], known.c[i][ch], kExact);
  }
}

// P_l(0): 0 for odd l, (-1)^k (2k)! / (4^k (k!)^2) for l = 2k.
double legendre_at_zero(int l) {
  if (l % 2 == 1) return 0.0;
  double p = 1.0;
  for (int k = 1; 2 * k <= l; ++k) p *= -(2.0 * k - 1.0) / (2.0 * k);
  return p;
}

TEST(ShProjection, AConstantSkyGivesTheClosedForm) {
  // c_l0 = 2 pi L K_l0 integral_0^1 P_l(mu) d mu, with integral_0^1 P_l = (P_{l-1}(0) -
  // P_{l+1}(0)) / (2l + 1) (l >= 1) and 1 (l = 0); c_lm = 0 for m != 0.
  constexpr int kBands = 8;
  constexpr double kL = 2.5;
  ProjectionOptions o;
  o.tolerance = 1e-12;
  const auto p = project([](Vec3) { return Triple{kL, 2 * kL, 3 * kL}; }, kBands, o);
  ASSERT_TRUE(p.converged);
  for (int l = 0; l < kBands; ++l) {
    const double integral =
        l == 0 ? 1.0 : (legendre_at_zero(l - 1) - legendre_at_zero(l + 1)) / (2.0 * l + 1.0);
    for (int m = -l; m <= l; ++m) {
      const double expect = m == 0 ? 2.0 * kPi * kL * normalisation(l, 0) * integral : 0.0;
      const auto& c = p.coefficients.c[static_cast<std::size_t>(index(l, m))];
      EXPECT_NEAR(c[0], expect, kExact) << "l=" << l << " m=" << m;
      EXPECT_NEAR(c[2], 3 * expect, 3 * kExact) << "l=" << l << " m=" << m;
    }
  }
}

// A sky of constant XYZ radiance (kL, 2 kL, 3 kL) and, optionally, a uniform solar disc of
// radiance sun_l (all channels) and angular radius sun_r: closed forms for the ground.
class ConstantSky final : public SkyModel {
 public:
  ConstantSky(SunPosition sun, double l, double sun_l, double sun_r)
      : SkyModel(sun), l_(l), sun_l_(sun_l), sun_r_(sun_r) {}
  std::string_view name() const override { return "constant"; }
  ParameterValues parameter_values() const override { return {}; }
  Xyz tristimulus(Vec3 view) const override {
    return view.z >= 0.0 ? Xyz{l_, 2 * l_, 3 * l_} : Xyz{};
  }
  bool has_sun() const override { return sun_l_ > 0.0; }
  double sun_angular_radius() const override { return sun_r_; }
  Xyz sun_tristimulus(Vec3 view) const override {
    const bool in =
        dot(view, direction_from_angles(sun().zenith, sun().azimuth)) >= std::cos(sun_r_) - 1e-15;
    return in ? Xyz{sun_l_, sun_l_, sun_l_} : Xyz{};
  }
  Domain domain() const override { return {}; }

 private:
  double l_, sun_l_, sun_r_;
};

// integral_a^b P_l(mu) d mu for [0, 1] and [-1, 0] from the closed form of the test above.
double legendre_integral_upper(int l) {
  return l == 0 ? 1.0 : (legendre_at_zero(l - 1) - legendre_at_zero(l + 1)) / (2.0 * l + 1.0);
}
double legendre_integral_lower(int l) {
  return (l % 2 == 0 ? 1.0 : -1.0) * legendre_integral_upper(l);  // P_l(-mu) = (-1)^l P_l(mu)
}

TEST(ShProjection, AGroundOfAlbedoRhoUnderAConstantSkyIsRhoTimesTheSky) {
  // E = pi L for a constant sky, so L_ground = rho E / pi = rho L: c_l0 = 2 pi K_l0 L
  // (integral_0^1 P_l + rho integral_-1^0 P_l). With a uniform disc of radiance L_s, radius r at
  // zenith angle theta_s: E_sun = L_s pi sin^2 r cos theta_s (the projected solid angle of a cap).
  constexpr int kBands = 6;
  constexpr double kL = 2.0, kRho = 0.3, kSunL = 1e4, kSunR = 0.05, kSunZenith = 0.7;
  // The disc quadrature (Gauss in cos alpha on [cos r, 1], uniform azimuths about the centre)
  // integrates the uniform disc's cos theta exactly: round-off only.
  constexpr double kSunIrradianceTolerance = 1e-12;
  ProjectionOptions o;
  o.tolerance = 1e-12;
  o.ground_albedo = kRho;
  const ConstantSky no_sun({kSunZenith, 0.4}, kL, 0.0, 0.0);
  const auto p = project_model(no_sun, Channels::xyz, kBands, o);
  ASSERT_TRUE(p.converged);
  for (int l = 0; l < kBands; ++l) {
    const double expect = 2.0 * kPi * kL * normalisation(l, 0) *
                          (legendre_integral_upper(l) + kRho * legendre_integral_lower(l));
    EXPECT_NEAR(p.coefficients.c[static_cast<std::size_t>(index(l, 0))][0], expect, kExact) << l;
    EXPECT_NEAR(p.coefficients.c[static_cast<std::size_t>(index(l, 0))][2], 3 * expect, 3 * kExact)
        << l;
  }
  // Albedo 0: the black lower hemisphere.
  o.ground_albedo = 0.0;
  const auto black = project_model(no_sun, Channels::xyz, kBands, o);
  o.ground_albedo.reset();
  const auto none = project_model(no_sun, Channels::xyz, kBands, o);
  for (std::size_t i = 0; i < none.coefficients.c.size(); ++i)
    EXPECT_EQ(black.coefficients.c[i], none.coefficients.c[i]);
  // The sun's irradiance.
  const ConstantSky with_sun({kSunZenith, 0.4}, kL, kSunL, kSunR);
  const double e_sun = kSunL * kPi * std::sin(kSunR) * std::sin(kSunR) * std::cos(kSunZenith);
  const Triple e = sun_horizontal_irradiance(with_sun, Channels::xyz);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(e[ch], e_sun, kSunIrradianceTolerance * e_sun);
  o.ground_albedo = kRho;
  const auto lit = project_model(with_sun, Channels::xyz, kBands, o);
  // Ground radiance rho (pi L + E_sun) / pi: c_00 gains rho E_sun / pi * 2 pi K_00 * 1.
  const double extra = kRho * e_sun / kPi * 2.0 * kPi * normalisation(0, 0);
  EXPECT_NEAR(lit.coefficients.c[0][1] - p.coefficients.c[0][1], extra, kExact * extra);
}

TEST(ShProjection, PreethamConvergesAndIsSymmetricAboutTheSolarMeridian) {
  // With the sun at azimuth 0 the sky is even in phi: every sin (m < 0) coefficient vanishes.
  const PreethamModel model(PreethamParameters{{deg_to_rad(60.0), 0.0}, 3.0});
  ProjectionOptions o;
  o.tolerance = kConvergedTolerance;
  const auto p = project_model(model, Channels::xyz, 8, o);
  ASSERT_TRUE(p.converged) << "last change " << p.last_change;
  RecordProperty("nodes", p.nodes);
  for (int l = 1; l < 8; ++l) {
    for (int m = -l; m < 0; ++m) {
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(p.coefficients.c[static_cast<std::size_t>(index(l, m))][ch], 0.0,
                    10 * kConvergedTolerance * std::abs(p.coefficients.c[0][ch]));
      }
    }
  }
}

}  // namespace
}  // namespace skylight::sh
