#include "skylight/models/sh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "skylight/core/error.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/projection.h"
#include "skylight/sh/rotation.h"
#include "support/sh_tables.h"

namespace skylight {
namespace {

// Double sums of ~50 terms of size ~1e3 in two orders: round-off only.
constexpr double kSumRelTol = 1e-11;
// The embedded (17, 12) Preetham table against a converged projection: docs/SH.md measures a worst
// E_mean of ~2e-5 of L_min over the range; 1e-4 of c_00 per coefficient leaves a factor ~3.
constexpr double kEmbeddedTableRelTol = 1e-4;

std::unique_ptr<ShSkyModel> make(const std::shared_ptr<const sh::PolynomialTable>& t, double zenith,
                                 double azimuth, double turbidity, int bands, bool filter) {
  ShParameters p;
  p.sun = {zenith, azimuth};
  p.bands = bands;
  p.no_ringing_filter = !filter;
  p.turbidity = turbidity;
  return std::make_unique<ShSkyModel>(p, t);
}

TEST(ShModel, EqualsDirectEvaluationOfTheTablesShEverywhere) {
  const auto t =
      std::make_shared<const sh::PolynomialTable>(testing_support::synthetic_sh_table(5, 4, 3));
  for (bool filter : {false, true}) {
    const auto m = make(t, 0.7, 2.1, 3.7, 5, filter);
    const sh::Coefficients c = sh::evaluate_table(*t, 0.7, 3.7, 2.1, 5, filter);
    bool negative = false;
    for (int it = 0; it <= 12; ++it) {
      for (int ip = 0; ip < 8; ++ip) {
        const double theta = it * kPi / 12, phi = ip * kPi / 4 + 0.1;
        // Direct: sum c_lm Y_lm with the explicit reference basis, below the horizon too.
        double y = 0.0;
        for (int l = 0; l < 5; ++l)
          for (int mm = -l; mm <= l; ++mm)
            y += c.c[static_cast<std::size_t>(sh::index(l, mm))][1] *
                 sh::basis_reference(l, mm, theta, phi);
        const Xyz v = m->tristimulus(direction_from_angles(theta, phi));
        EXPECT_NEAR(v.Y, y, kSumRelTol * 1e3 * 25) << theta << " " << phi;
        negative = negative || v.Y < 0.0;
      }
    }
    EXPECT_TRUE(negative) << "the synthetic table's reconstruction is returned unclamped";
  }
}

TEST(ShModel, SunAzimuthRotatesTheSkyExactly) {
  // Habel 2008 eq. 4: the sky of a sun at azimuth phi0 is the sky of a sun at azimuth 0 turned by
  // phi0 about the zenith, at every direction.
  const auto t =
      std::make_shared<const sh::PolynomialTable>(testing_support::synthetic_sh_table(6, 3, 2));
  const auto m0 = make(t, 1.0, 0.0, 4.0, 6, true);
  for (double phi0 : {0.3, 1.9, 4.0}) {
    const auto m = make(t, 1.0, phi0, 4.0, 6, true);
    for (double theta : {0.0, 0.5, 1.4, 2.0, 3.0}) {
      for (double phi : {0.0, 1.0, 2.5, 5.0}) {
        const Xyz a = m0->tristimulus(direction_from_angles(theta, phi));
        const Xyz b = m->tristimulus(direction_from_angles(theta, phi + phi0));
        EXPECT_NEAR(a.X, b.X, kSumRelTol * 1e3 * 36);
        EXPECT_NEAR(a.Z, b.Z, kSumRelTol * 1e3 * 36);
      }
    }
  }
}

TEST(ShModel, RingingFilterBandsAndRangesAreParameters) {
  const auto t =
      std::make_shared<const sh::PolynomialTable>(testing_support::synthetic_sh_table(4, 2, 2));
  const auto on = make(t, 0.5, 0.0, 3.0, 4, true), off = make(t, 0.5, 0.0, 3.0, 4, false);
  for (int l = 0; l < 4; ++l) {
    const auto i = static_cast<std::size_t>(sh::index(l, 0));
    EXPECT_NEAR(on->coefficients().c[i][0], off->coefficients().c[i][0] * sh::ringing_factor(l, 4),
                kSumRelTol * 1e3);
  }
  EXPECT_EQ(make(t, 0.5, 0.0, 3.0, 2, true)->coefficients().bands, 2);
  EXPECT_THROW(make(t, 0.5, 0.0, 3.0, 5, true), InvalidArgument);  // more than the table's 4
  EXPECT_THROW(make(t, 0.5, 0.0, 7.0, 4, true), InvalidArgument);  // T outside [2.5, 6]
  EXPECT_THROW(make(t, 1.7, 0.0, 3.0, 4, true), InvalidArgument);  // sun below the horizon
  // The linear sRGB channels of an XYZ table are the sRGB matrix of its XYZ.
  const Vec3 d = direction_from_angles(0.4, 1.0);
  const Rgb expected = xyz_to_linear_srgb(on->tristimulus(d));
  EXPECT_NEAR(on->rgb(d).g, expected.g, kSumRelTol * 1e4);
}

TEST(ShModel, EmbeddedDefaultTableReproducesPreetham) {
  SkyParameters sp;
  sp.sun = {45.0 * kDegree, 1.0};
  sp.values.set("turbidity", 3.0).set("no-ringing-filter", true);
  const auto m = make_sky_model("sh", sp);
  const auto& sh_model = dynamic_cast<const ShSkyModel&>(*m);
  EXPECT_EQ(sh_model.coefficients().bands, 7);
  SkyParameters pp;
  pp.sun = sp.sun;
  pp.values.set("turbidity", 3.0);
  const auto preetham = make_sky_model("preetham", pp);
  const sh::Projection ref = fit::project_model(*preetham, sh::Channels::xyz, 7);
  const double c00 = ref.coefficients.c[0][1];
  for (std::size_t i = 0; i < ref.coefficients.c.size(); ++i)
    for (std::size_t ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(sh_model.coefficients().c[i][ch], ref.coefficients.c[i][ch],
                  kEmbeddedTableRelTol * c00)
          << i << " " << ch;
  // What the model read, fed back, builds the same sky (turbidity and bands resolved).
  EXPECT_EQ(m->parameter_values().number("bands"), 7.0);
}

// The report judges the embedded table against the model it was fitted to over its fitted range
// (ReportPolicy beside the registry entry): both must be the table's own.
TEST(ShSky, ReportPolicyMatchesTheEmbeddedTable) {
  const auto model = make_sky_model(ShSkyModel::kName, {});
  const sh::PolynomialTable& table = dynamic_cast<const ShSkyModel&>(*model).table();
  const ReportPolicy& policy = find_model(ShSkyModel::kName)->report;
  EXPECT_EQ(policy.source, table.model);
  EXPECT_EQ(policy.axis, table.parameter);
  ASSERT_TRUE(policy.axis_range.has_value());
  EXPECT_EQ((*policy.axis_range)[0], table.tau_min);
  EXPECT_EQ((*policy.axis_range)[1], table.tau_max);
  EXPECT_EQ(policy.truncation_range[1], table.bands);
}

}  // namespace
}  // namespace skylight
