// End-to-end tests of `skylight sh fit|eval|export|render|error` and of the `sh` model in `eval`.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "skylight/core/math.h"
#include "support/cli_run.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;
using testing_support::parse_csv_numbers;

// A reduced fit the suite can afford: 3 bands, degrees (2, 1) on a 3 x 2 grid, projections to
// 1e-3 (docs/SH.md has the full-size study).
const std::string kSmallFit =
    "sh fit --model preetham --bands 3 --degrees 2,1 --grid 3,2 --tolerance 1e-3";
// Both sides print shortest round-trip doubles of the same sums, in different orders.
constexpr double kSameSumRelTol = 1e-12;

// The Y coefficient of (l, m) in an `sh eval --json` record.
double y_of(const nlohmann::json& record, int l, int m) {
  for (const auto& c : record["coefficients"])
    if (c["l"] == l && c["m"] == m) return c["values"][1].get<double>();
  ADD_FAILURE() << "no coefficient (" << l << ", " << m << ")";
  return 0.0;
}

TEST_F(Cli, ShFitEvalAndTheShModelAgree) {
  const std::string table = (dir_ / "t.json").string();
  const auto fit = run(kSmallFit + " -o " + table);
  ASSERT_EQ(fit.status, 0) << fit.err;
  const std::string sky = " --sun-zenith 30 --sun-azimuth 90 --turbidity 3";
  const auto eval = run("sh eval --table " + table + sky + " --json");
  ASSERT_EQ(eval.status, 0) << eval.err;
  const auto je = nlohmann::json::parse(eval.out);
  EXPECT_EQ(je["channel_names"], (nlohmann::json{"X", "Y", "Z"}));
  ASSERT_EQ(je["coefficients"].size(), 9u);
  // At the zenith only the zonal Y_l0 = sqrt((2l + 1) / (4 pi)) are non-zero.
  double zenith_y = 0.0;
  for (const auto& c : je["coefficients"])
    if (c["m"] == 0)
      zenith_y += c["values"][1].get<double>() * std::sqrt((2 * c["l"].get<int>() + 1) / (4 * kPi));
  std::string header;
  const auto model = run("eval --model sh --table " + table + sky + " --quantity xyz",
                         "zenith_deg,azimuth_deg\n0,0\n150,20\n");
  ASSERT_EQ(model.status, 0) << model.err;
  const auto values = parse_csv_numbers(model.out, &header);
  ASSERT_EQ(values.size(), 2u);
  EXPECT_NEAR(values[0][3], zenith_y, kSameSumRelTol * std::abs(zenith_y)) << header;
  EXPECT_NE(values[1][3], 0.0) << "below the horizon: the unclamped reconstruction";
  // Fewer bands: the first of the same coefficients; --no-ringing-filter changes the zonal ones
  // only.
  const auto two =
      nlohmann::json::parse(run("sh eval --table " + table + sky + " --json --bands 2").out);
  ASSERT_EQ(two["coefficients"].size(), 4u);
  EXPECT_TRUE(two["ringing_filter"].get<bool>());
  const auto off = nlohmann::json::parse(
      run("sh eval --table " + table + sky + " --no-ringing-filter --json").out);
  EXPECT_FALSE(off["ringing_filter"].get<bool>());
  EXPECT_EQ(y_of(off, 0, 0), y_of(je, 0, 0));  // l = 0: sinc(0) = 1
  EXPECT_NE(y_of(off, 1, 0), y_of(je, 1, 0));
  EXPECT_EQ(y_of(off, 1, -1), y_of(je, 1, -1));
  // The text form: a table of the coefficients, one row each.
  const auto text = run("sh eval --table " + table + sky);
  ASSERT_EQ(text.status, 0) << text.err;
  const auto table_at = text.out.find("coefficients:\n");
  ASSERT_NE(table_at, std::string::npos) << text.out;
  EXPECT_NE(text.out.find("values", table_at), std::string::npos) << text.out;
}

TEST_F(Cli, ShFitOtherModelsFromTheirSchema) {
  // hosek: turbidity varies over its schema range 1..10, the albedo is held fixed.
  const std::string h = (dir_ / "h.json").string();
  const auto hosek = run(
      "sh fit --model hosek --bands 2 --degrees 1,1 --grid 2,2 --tolerance 1e-2 --set albedo=0.5 "
      "-o " +
      h);
  ASSERT_EQ(hosek.status, 0) << hosek.err;
  const auto hj = nlohmann::json::parse(Cli::slurp(h));
  EXPECT_EQ(hj["parameter"], "turbidity");
  EXPECT_EQ(hj["tau_max"].get<double>(), 10.0);
  EXPECT_EQ(hj["fixed"]["albedo"].get<double>(), 0.5);
  // Hosek's own structure by default (docs/SH.md, "Hosek fits"): one piece per integer
  // turbidity interval, in elevation^(1/3); --theta-axis theta on request.
  EXPECT_EQ(hj["theta_axis"], "elevation_cbrt");
  EXPECT_EQ(hj["tau_pieces"].get<int>(), 9);
  const auto cbrt =
      run("sh fit --model hosek --bands 2 --degrees 1,1 --grid 2,2 --tolerance 1e-2 --range 2,4 "
          "--theta-axis theta -o " +
          h);
  ASSERT_EQ(cbrt.status, 0) << cbrt.err;
  const auto cj = nlohmann::json::parse(Cli::slurp(h));
  EXPECT_EQ(cj["theta_axis"], "theta");
  EXPECT_EQ(cj["tau_pieces"].get<int>(), 2);
  EXPECT_EQ(run("sh eval --table " + h + " --sun-zenith 40 --turbidity 3.5").status, 0);
  // A ground of albedo 0.2 is recorded in the table; out-of-range albedos and pieces refused.
  const std::string g = (dir_ / "g.json").string();
  const auto ground = run(kSmallFit + " --ground-albedo 0.2 -o " + g);
  ASSERT_EQ(ground.status, 0) << ground.err;
  EXPECT_EQ(nlohmann::json::parse(Cli::slurp(g))["ground_albedo"].get<double>(), 0.2);
  EXPECT_EQ(run(kSmallFit + " --ground-albedo 1.5 -o " + g).status, 2);
  EXPECT_EQ(run(kSmallFit + " --tau-pieces 0 -o " + g).status, 2);
  // cie: the sun zenith only (no turbidity), a type held fixed.
  const std::string c = (dir_ / "c.json").string();
  const auto cie =
      run("sh fit --model cie --bands 2 --degrees 2,0 --grid 3,1 --tolerance 1e-2 --set cie-type=7 "
          "-o " +
          c);
  ASSERT_EQ(cie.status, 0) << cie.err;
  EXPECT_EQ(run("sh eval --table " + c + " --sun-zenith 40").status, 0);
  EXPECT_EQ(run("sh eval --table " + c + " --sun-zenith 40 --turbidity 3").status, 2);
  EXPECT_EQ(run("sh fit --model cie --degrees 2,1 -o " + c).status, 2);
  EXPECT_EQ(run("sh fit --model cie --tau-pieces 2 -o " + c).status, 2);
  EXPECT_EQ(run("sh fit --model preetham --set nope=1 -o " + c).status, 2);
  EXPECT_EQ(run("sh fit --model nope -o " + c).status, 2);
}

TEST_F(Cli, ShExportRenderAndErrors) {
  const std::string table = (dir_ / "t.json").string();
  ASSERT_EQ(run(kSmallFit + " -o " + table).status, 0);
  const std::string header = (dir_ / "t.h").string();
  const auto exp =
      run("sh export --table " + table + " --c-header --monomial --name sky -o " + header);
  ASSERT_EQ(exp.status, 0) << exp.err;
  const std::string h = Cli::slurp(header);
  EXPECT_NE(h.find("static const float sky_chebyshev[108]"), std::string::npos);  // 6*3*6
  EXPECT_NE(h.find("static const double sky_monomial[108]"), std::string::npos);
  EXPECT_EQ(run("sh export --table " + table + " --monomial -o " + header).status, 2);
  // The env map and the sphere.
  const std::string env = (dir_ / "env.pfm").string(), sphere = (dir_ / "s.png").string();
  const auto ren =
      run("sh render --table " + table + " --sun-zenith 40 --turbidity 4 --width 64 -o " + env +
          " --sphere " + sphere + " --sphere-size 32");
  ASSERT_EQ(ren.status, 0) << ren.err;
  EXPECT_TRUE(fs::exists(env));
  EXPECT_TRUE(fs::exists(sphere));
  // The error table: one row per band count and channel.
  const auto err = run("sh error --table " + table + " --points 2,2 --json");
  ASSERT_EQ(err.status, 0) << err.err;
  const auto rows = nlohmann::json::parse(err.out)["rows"];
  EXPECT_EQ(rows.size(), 9u);
  for (const auto& r : rows) {
    EXPECT_GE(r["e_max_worst_percent"].get<double>(), r["e_mean_worst_percent"].get<double>());
  }
  // The default adds the ranges' ends to the midpoints: a superset, so no worst is lower, and
  // the worst lies inside the ranges.
  const auto mid = run("sh error --table " + table + " --points 2,2 --midpoints-only --json");
  ASSERT_EQ(mid.status, 0) << mid.err;
  const auto mid_rows = nlohmann::json::parse(mid.out)["rows"];
  ASSERT_EQ(mid_rows.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_GE(rows[i]["e_mean_worst_percent"].get<double>(),
              mid_rows[i]["e_mean_worst_percent"].get<double>());
    const double z = rows[i]["worst_sun_zenith_deg"];
    EXPECT_GE(z, 0.0);
    EXPECT_LE(z, 90.0);
  }
  // Bad inputs: a missing table is a usage error before any work, a malformed one names the
  // field.
  const auto missing = run("sh eval --table " + (dir_ / "none.json").string());
  EXPECT_EQ(missing.status, 2) << missing.err;
  std::ofstream(dir_ / "bad.json") << "{\"format\": \"skylight-sh-polynomial-table\"}";
  const auto bad = run("sh eval --table " + (dir_ / "bad.json").string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("'version'"), std::string::npos) << bad.err;
  EXPECT_EQ(run("sh eval --table " + table + " --sun-zenith 30 --turbidity 9").status, 2);
  EXPECT_EQ(run("sh eval --table " + table + " --bands 4").status, 2);
}

}  // namespace
}  // namespace skylight
