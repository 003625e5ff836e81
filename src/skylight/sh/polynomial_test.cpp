#include "skylight/sh/polynomial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "skylight/core/data.h"
#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/fit/sh_fit.h"
#include "skylight/models/preetham.h"
#include "skylight/models/sh.h"
#include "skylight/sh/basis.h"
#include "skylight/sh/rotation.h"
#include "support/sh_tables.h"

namespace skylight::sh {
namespace {

// The suite's reduced Preetham fit (tests/support/sh_tables.h).
const PolynomialTable& small_table() {
  return testing_support::small_sh_fit_table();
}

// The embedded default table (7 bands, degrees (17, 12)).
const PolynomialTable& default_table() {
  static const PolynomialTable t =
      table_from_json(std::string(data::embedded_file(kDefaultShTable)), kDefaultShTable);
  return t;
}

TEST(ShPolynomial, FilterAndRotationApplyAfterEvaluation) {
  const auto& t = small_table();
  const auto base = evaluate_table(t, 0.5, 3.0, 0.0, 3, false);
  const auto rot = evaluate_table(t, 0.5, 3.0, 2.0, 3, true);
  const auto expect = ringing_filter(rotate_about_zenith(base, 2.0));
  for (std::size_t i = 0; i < expect.c.size(); ++i) {
    for (int ch = 0; ch < 3; ++ch) EXPECT_DOUBLE_EQ(rot.c[i][ch], expect.c[i][ch]);
  }
  // Fewer bands: the leading coefficients of the same evaluation.
  const auto two = evaluate_table(t, 0.5, 3.0, 0.0, 2, false);
  for (std::size_t i = 0; i < two.c.size(); ++i) EXPECT_EQ(two.c[i], base.c[i]);
  EXPECT_THROW(evaluate_table(t, 1.2, 3.0, 0.0, 3, false), InvalidArgument);  // > 60 deg
  EXPECT_THROW(evaluate_table(t, 0.5, 7.0, 0.0, 3, false), InvalidArgument);
  EXPECT_THROW(evaluate_table(t, 0.5, 3.0, 0.0, 4, false), InvalidArgument);
}

// Fast (float SIMD) vs reference (double) evaluation: float coefficients times a float product
// vector, summed in float over <= 234 terms whose sum is dominated by the first few; measured
// 2.8e-7 of |c_00| (the reduced and the default table), so 2e-6 leaves a factor 7.
constexpr double kPolynomialFastVsReference = 2e-6;

TEST(ShPolynomial, FastEvaluationMatchesTheDoubleReference) {
  double worst = 0.0;  // largest |fast - reference| / |c_00|
  for (const PolynomialTable* t : {&small_table(), &default_table()}) {
    for (double theta : {0.0, 0.4, 1.04}) {
      for (double tau : {2.5, 3.3, 5.9}) {
        for (bool filter : {false, true}) {
          const int bands = t->bands;
          const auto fast = evaluate_table(*t, theta, tau, 2.3, bands, filter);
          const auto ref = evaluate_table_reference(*t, theta, tau, 2.3, bands, filter);
          ASSERT_EQ(fast.c.size(), ref.c.size());
          for (int ch = 0; ch < 3; ++ch) {
            const double scale = std::abs(ref.c[0][ch]);
            for (std::size_t i = 0; i < ref.c.size(); ++i) {
              worst = std::max(worst, std::abs(fast.c[i][ch] - ref.c[i][ch]) / scale);
              EXPECT_NEAR(fast.c[i][ch], ref.c[i][ch], kPolynomialFastVsReference * scale)
                  << "bands " << bands << " i " << i << " ch " << ch;
            }
          }
        }
      }
    }
  }
  std::printf("fast vs reference: worst %.3g of |c_00|\n", worst);
}

TEST(ShPolynomial, JsonRoundTripIsExactAndLoadingNamesBadFields) {
  const auto& t = small_table();
  const auto back = table_from_json(table_to_json(t), "t.json");
  EXPECT_EQ(back.model, t.model);
  EXPECT_EQ(back.bands, t.bands);
  EXPECT_EQ(back.degree_theta, t.degree_theta);
  EXPECT_EQ(back.coefficients, t.coefficients);
  EXPECT_EQ(back.theta_max, t.theta_max);
  EXPECT_FALSE(back.ground_albedo.has_value());
  PolynomialTable grounded = t;
  grounded.ground_albedo = 0.25;
  EXPECT_EQ(table_from_json(table_to_json(grounded), "g.json").ground_albedo, 0.25);
  auto expect_error = [](const std::string& text, const std::string& needle) {
    try {
      table_from_json(text, "t.json");
      ADD_FAILURE() << "no error for " << text;
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  std::string j = table_to_json(t);
  expect_error("{", "not valid JSON");
  expect_error(std::string(j).replace(j.find("\"bands\": 3"), 10, "\"bands\": 99"), "'bands'");
  expect_error(std::string(j).replace(j.find("\"channels\": \"xyz\""), 17, "\"channels\": \"q\""),
               "'channels'");
  const std::string g = table_to_json(grounded);
  expect_error(
      std::string(g).replace(g.find("\"ground_albedo\": 0.25"), 21, "\"ground_albedo\": 1.5"),
      "'ground_albedo'");
  expect_error(std::string(j).replace(j.find("\"tau_pieces\": 1"), 15, "\"tau_pieces\": 0"),
               "'tau_pieces'");
}

// A fit in theta only with parameters held fixed (CIE type 7 at a fixed zenith luminance, 3 bands,
// degree 6 on 13 points, theta in [0, 60 deg]): `sh error` measures a worst E_mean of 3.6e-4 of
// Found by the fuzz target sh_table_json (docs/TESTING.md): coefficients are stored in float, so
// a finite double beyond FLT_MAX (~3.4e38) became +inf in an accepted table.
TEST(ShPolynomial, JsonLoadRefusesCoefficientsBeyondTheFloatRange) {
  auto table_with = [](const std::string& coefficients) {
    return R"({"format": "skylight-sh-polynomial-table", "version": 1, "model": "preetham",
      "parameter": "turbidity", "channels": "xyz", "bands": 1, "degree_theta": 0,
      "degree_tau": 0, "theta_min_rad": 0, "theta_max_rad": 1, "tau_min": 2, "tau_max": 6,
      "coefficients": [)" +
           coefficients + "]}";
  };
  const auto t = table_from_json(table_with("3e38, -3e38, 1"), "t.json");
  EXPECT_EQ(t.coefficients, (std::vector<float>{3e38f, -3e38f, 1.0f}));
  // A version-1 table (before theta_axis and tau_pieces) loads as theta axis, one piece.
  EXPECT_EQ(t.theta_axis, ThetaAxis::theta);
  EXPECT_EQ(t.tau_pieces, 1);
  // "1e400" overflows the JSON parser's double: it threw nlohmann's out_of_range, not ours.
  for (const std::string bad : {"1e39, 0, 0", "0, -1e39, 0", "1e400, 0, 0"}) {
    try {
      table_from_json(table_with(bad), "t.json");
      ADD_FAILURE() << "no error for " << bad;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("t.json: ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace skylight::sh
