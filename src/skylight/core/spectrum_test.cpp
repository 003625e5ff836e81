#include "skylight/core/spectrum.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/data.h"
#include "skylight/core/error.h"

namespace skylight {
namespace {

// Linear interpolation of exactly representable samples: only the rounding of one division.
constexpr double kInterpolationRelTol = 1e-15;

TEST(Spectrum, InterpolatesLinearlyAndReturnsOutsideBeyondTheTable) {
  const Spectrum s({400, 500, 700}, {1, 3, 7}, "test");
  EXPECT_EQ(s(400), 1.0);
  EXPECT_EQ(s(500), 3.0);
  EXPECT_EQ(s(700), 7.0);
  EXPECT_NEAR(s(450), 2.0, kInterpolationRelTol * 2.0);
  EXPECT_NEAR(s(600), 5.0, kInterpolationRelTol * 5.0);
  EXPECT_EQ(s(399.999), 0.0);
  EXPECT_EQ(s(701, -1.0), -1.0);
  EXPECT_FALSE(s.at(300).has_value());
  EXPECT_FALSE(s.at(std::nan("")).has_value());
  EXPECT_EQ(s(std::nan("")), 0.0);
  EXPECT_EQ(s.at(650), s(650));
  EXPECT_EQ(s.min_nm(), 400.0);
  EXPECT_EQ(s.max_nm(), 700.0);
  EXPECT_EQ(Spectrum()(500), 0.0);
  EXPECT_EQ(Spectrum({550}, {2}, "one")(550), 2.0);
}

TEST(Spectrum, UniformGridAgreesWithTheGeneralLookup) {
  std::vector<double> v;
  for (int i = 0; i < 41; ++i) v.push_back(std::sin(0.3 * i));
  const Spectrum u = Spectrum::uniform(380, 10, v, "u");
  const Spectrum g(u.wavelengths(), v, "g");
  for (double nm = 375; nm <= 790; nm += 0.37)
    EXPECT_NEAR(u(nm), g(nm), 1e-12) << nm;  // same formula, index found differently
  EXPECT_EQ(u(780), v.back());
}

TEST(Spectrum, ScaledMultipliesEveryValue) {
  const Spectrum s({400, 500}, {1, 3}, "s");
  const Spectrum t = s.scaled(2.5);
  EXPECT_EQ(t(400), 2.5);
  EXPECT_EQ(t(450), 2.5 * s(450));
}

TEST(Spectrum, RejectsBadSamples) {
  EXPECT_THROW(Spectrum({}, {}, "e"), InvalidArgument);
  EXPECT_THROW(Spectrum({400, 500}, {1}, "n"), InvalidArgument);
  EXPECT_THROW(Spectrum({500, 400}, {1, 2}, "d"), InvalidArgument);
  EXPECT_THROW(Spectrum({400, 400}, {1, 2}, "d"), InvalidArgument);
  EXPECT_THROW(Spectrum({0, 400}, {1, 2}, "z"), InvalidArgument);
  EXPECT_THROW(Spectrum({400, 500}, {1, std::nan("")}, "v"), InvalidArgument);
  EXPECT_THROW(Spectrum::uniform(400, 0, {1, 2}, "s"), InvalidArgument);
}

TEST(Spectrum, FromTableNamesTheBadRow) {
  const data::CsvTable t("nm,v\n400,1\n500,2\n450,3\n", "t.csv", true, 2);
  try {
    Spectrum::from_table(t, 0, 1, "t.csv");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(), "t.csv line 4: wavelength 450 nm does not ascend");
  }
}

}  // namespace
}  // namespace skylight
