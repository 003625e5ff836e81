#include "skylight/io/horizon.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "support/error_message.h"

namespace skylight::io {
namespace {

// Linear interpolation of degrees given to 1e-12: round-off only.
constexpr double kInterpolationTol = 1e-12;

double elevation_deg(const HorizonProfile& h, double azimuth_deg) {
  return rad_to_deg(h.elevation(deg_to_rad(azimuth_deg)));
}

TEST(Horizon, CsvIsInterpolatedLinearlyAndPeriodically) {
  const HorizonProfile h =
      parse_horizon("azimuth_deg,elevation_deg\n90,10\n270,30\n0,20\n", "h.csv");
  EXPECT_EQ(h.format(), "csv");
  EXPECT_NEAR(elevation_deg(h, 45.0), 15.0, kInterpolationTol);
  EXPECT_NEAR(elevation_deg(h, 180.0), 20.0, kInterpolationTol);
  // Between 270 and 360 (= 0): 30 -> 20.
  EXPECT_NEAR(elevation_deg(h, 315.0), 25.0, kInterpolationTol);
  EXPECT_NEAR(elevation_deg(h, -45.0), 25.0, kInterpolationTol);
  EXPECT_NEAR(elevation_deg(h, 405.0), 15.0, kInterpolationTol);
  // open(): above the skyline only.
  EXPECT_TRUE(h.open(direction_from_angles(deg_to_rad(90.0 - 16.0), deg_to_rad(45.0))));
  EXPECT_FALSE(h.open(direction_from_angles(deg_to_rad(90.0 - 14.0), deg_to_rad(45.0))));
  // Without a header, and 0 and 360 given with the same elevation.
  const HorizonProfile g = parse_horizon("0,5\n180,15\n360,5\n", "g.csv");
  EXPECT_EQ(g.points().size(), 2u);
  EXPECT_NEAR(elevation_deg(g, 270.0), 10.0, kInterpolationTol);
}

// PVGIS counts A from south towards west: A = -90 is east (skylight 90), A = 0 south (180).
TEST(Horizon, PvgisCsvAndJsonTurnTheirAzimuthToSkylights) {
  const std::string csv =
      "Latitude (decimal degrees):\t45.812\nLongitude (decimal degrees):\t8.628\n\n"
      "A\tH_hor\tA_sun(w)\tH_sun(w)\tA_sun(s)\tH_sun(s)\n"
      "-180.0\t4.0\t-120.0\t0.0\t-60.0\t0.0\n-90.0\t8.0\t-100\t10\t-50\t30\n"
      "0.0\t2.0\t0\t20\t0\t60\n90.0\t6.0\t100\t10\t50\t30\n180.0\t4.0\t120\t0\t60\t0\n"
      "\nA: Azimuth (0 = S, 90 = W, -90 = E) (degree).\n";
  const HorizonProfile c = parse_horizon(csv, "pvgis.csv");
  EXPECT_EQ(c.format(), "pvgis");
  EXPECT_NEAR(elevation_deg(c, 90.0), 8.0, kInterpolationTol);   // east
  EXPECT_NEAR(elevation_deg(c, 180.0), 2.0, kInterpolationTol);  // south
  EXPECT_NEAR(elevation_deg(c, 270.0), 6.0, kInterpolationTol);  // west
  EXPECT_NEAR(elevation_deg(c, 0.0), 4.0, kInterpolationTol);    // north
  const std::string json =
      R"({"inputs": {}, "outputs": {"horizon_profile": [{"A": -90.0, "H_hor": 8.0},
      {"A": 0.0, "H_hor": 2.0}, {"A": 90.0, "H_hor": 6.0}, {"A": 180.0, "H_hor": 4.0}]}})";
  const HorizonProfile j = parse_horizon(json, "pvgis.json");
  EXPECT_EQ(j.format(), "pvgis");
  for (double az : {0.0, 45.0, 90.0, 135.0, 180.0, 300.0})
    EXPECT_NEAR(elevation_deg(j, az), elevation_deg(c, az), kInterpolationTol) << az;
}

TEST(Horizon, BadFilesSayWhereAndWhat) {
  EXPECT_EQ(testing_support::error_message([] { parse_horizon("0,5\n90,95\n", "h.csv"); }),
            "h.csv line 2: elevation 95 deg is outside [0, 90] (the sky models end at the "
            "geometric horizon)");
  EXPECT_EQ(testing_support::error_message([] { parse_horizon("0,5\n90,x\n", "h.csv"); }),
            "h.csv line 2: elevation_deg: 'x' is not a number");
  EXPECT_EQ(testing_support::error_message([] { parse_horizon("0,5\n400,5\n", "h.csv"); }),
            "h.csv line 2: azimuth_deg 400 is outside [0, 360]");
  EXPECT_EQ(testing_support::error_message([] { parse_horizon("0,5,1\n", "h.csv"); }),
            "h.csv line 1: expected 2 fields (azimuth_deg,elevation_deg), found 3");
  EXPECT_EQ(testing_support::error_message([] { parse_horizon("10,5\n10,6\n", "h.csv"); }),
            "h.csv: azimuth 10 deg is given twice with different elevations (5 and 6, line 1 "
            "and line 2)");
  EXPECT_EQ(testing_support::error_message([] { parse_horizon("\n\n", "h.csv"); }),
            "h.csv: no points (expected lines azimuth_deg,elevation_deg)");
  EXPECT_EQ(testing_support::error_message([] { parse_horizon("A\tH_hor\n\nx\n", "p.csv"); }),
            "p.csv: PVGIS's table (A, H_hor) has no rows");
  EXPECT_EQ(testing_support::error_message(
                [] { parse_horizon(R"({"outputs": {"horizon_profile": [{"A": 0}]}})", "p.json"); }),
            "p.json: field 'outputs.horizon_profile[0].H_hor' is missing");
}

}  // namespace
}  // namespace skylight::io
