// Fast path vs reference: every model's SIMD single-precision batch against its scalar double path.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/models/perez.h"
#include "skylight/models/sky_model.h"
#include "support/batch_check.h"

namespace skylight {
namespace {

// The batch path evaluates in float: each of exp/asin is within 2 ulp (Highway's bound), the
// exponent arguments reach |B/cos theta| ~ 50 near the horizon, where a relative input error of
// 6e-8 grows to 3e-6 in exp; 2e-5 of the value leaves margin for the ~15 chained operations.
constexpr double kPerezBatchRelativeTolerance = 2e-5;
// Values this far below the largest in a sky are compared absolutely (float denormal/underflow).
constexpr double kPerezBatchAbsoluteFloor = 1e-6;

std::vector<Vec3> random_directions(int n, unsigned seed, bool include_special) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<Vec3> d;
  for (int i = 0; i < n; ++i) d.push_back(normalize({g(rng), g(rng), g(rng)}));
  if (include_special) {
    d.push_back({0, 0, 1});
    d.push_back({1, 0, 0});  // horizon
    d.push_back({0, -1, 0});
  }
  return d;
}

void expect_batch_matches_scalar(const SkyModel& m, const std::vector<Vec3>& dirs) {
  testing_support::expect_batch_matches_scalar(m, dirs, kPerezBatchRelativeTolerance,
                                               kPerezBatchAbsoluteFloor);
}

// Registry model `model` with its parameter `name` = `value` and the sun at (zenith, azimuth)
// [deg]: batch against scalar over `dirs`.
void expect_batch_matches_scalar(const std::string& model, const std::string& name, double value,
                                 double sun_zenith_deg, double sun_azimuth_deg,
                                 const std::vector<Vec3>& dirs) {
  SkyParameters p;
  p.values.set(name, value);
  p.sun = {deg_to_rad(sun_zenith_deg), deg_to_rad(sun_azimuth_deg)};
  const auto m = make_sky_model(model, p);
  SCOPED_TRACE(testing::Message() << name << " " << value << " zs " << sun_zenith_deg);
  expect_batch_matches_scalar(*m, dirs);
}

TEST(Batch, PreethamMatchesScalar) {
  const auto dirs = random_directions(5000, 1, true);
  for (double T : {1.7, 2.0, 3.0, 6.0, 10.0})
    for (double zs : {0.0, 30.0, 60.0, 85.0})
      expect_batch_matches_scalar("preetham", "turbidity", T, zs, 130.0, dirs);
}

TEST(Batch, CieMatchesScalarForAllTypes) {
  const auto dirs = random_directions(3000, 2, true);
  for (int type = 1; type <= 16; ++type)
    for (double zs : {10.0, 50.0, 80.0})
      expect_batch_matches_scalar("cie", "cie-type", type, zs, 250.0, dirs);
}

TEST(Batch, PerezMatchesScalarAndSunNeighbourhood) {
  // Directions within a few degrees of the sun: where acos(v.s) in float would lose accuracy.
  std::vector<Vec3> dirs;
  const double zs = deg_to_rad(35.0), as = deg_to_rad(160.0);
  for (double dt = -3.0; dt <= 3.0; dt += 0.05)
    for (double dp = -3.0; dp <= 3.0; dp += 0.5)
      dirs.push_back(direction_from_angles(zs + deg_to_rad(dt), as + deg_to_rad(dp)));
  SkyParameters p;
  p.sun = {zs, as};
  p.values.set("perez", std::vector<double>{-1.0, -0.32, 10.0, -3.0, 0.45});
  p.values.set("zenith-luminance", 5000.0);
  const auto m = make_sky_model("perez", p);
  expect_batch_matches_scalar(*m, dirs);
  expect_batch_matches_scalar(*m, random_directions(2000, 3, true));
}

TEST(Batch, OddSizesAndEmpty) {
  SkyParameters p;
  const auto m = make_sky_model("preetham", p);
  for (int n : {0, 1, 3, 7, 15, 17, 33})
    expect_batch_matches_scalar(*m, random_directions(n, 4, false));
}

TEST(Perez, MatchesPreethamLuminanceWithItsCoefficients) {
  // The perez model with Preetham's Y coefficients and Yz reproduces Preetham's luminance.
  SkyParameters p;
  p.values.set("turbidity", 3.0);
  p.sun = {deg_to_rad(40.0), deg_to_rad(100.0)};
  const auto pre = make_sky_model("preetham", p);
  p.values.erase("turbidity");
  const double T = 3.0;
  p.values.set("perez",
               std::vector<double>{0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251,
                                   0.1206 * T - 2.5771, -0.0670 * T + 0.3703});
  p.values.set("zenith-luminance", pre->tristimulus({0, 0, 1}).Y);
  const auto per = make_sky_model("perez", p);
  for (const Vec3& v : random_directions(200, 5, false)) {
    const double a = pre->tristimulus(v).Y, b = per->tristimulus(v).Y;
    EXPECT_NEAR(a, b, 1e-9 * std::max(a, 1.0));
  }
}

}  // namespace
}  // namespace skylight
