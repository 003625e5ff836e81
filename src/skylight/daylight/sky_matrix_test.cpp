#include "skylight/daylight/sky_matrix.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "skylight/core/error.h"
#include "skylight/core/math.h"
#include "skylight/core/numbers.h"
#include "support/error_message.h"

namespace skylight::daylight {
namespace {

// Sums over a few thousand patches in double: round-off only.
constexpr double kSumTol = 1e-9;

const io::EpwFile& sample_year() {
  static const io::EpwFile f =
      io::read_epw(std::string(SKYLIGHT_TEST_DATA_DIR) + "/weather/synthetic_munich.epw");
  return f;
}

SkyMatrix matrix(const std::string& patches, int sun_patches,
                 PerezCompat compat = PerezCompat::papers) {
  MatrixSettings s;
  s.patches = patches;
  s.sun_patches = sun_patches;
  s.compat = compat;
  return sky_matrix(sample_year(), s, "synthetic_munich.epw");
}

TEST(SkyMatrix, PatchesReproduceEachHoursDiffuseLightAndTheSunsDirectLight) {
  for (const char* patches : {"tregenza", "reinhart2"}) {
    const SkyMatrix sky = matrix(patches, 0);
    const SkyMatrix with_sun = matrix(patches, 4);
    ASSERT_EQ(sky.hours.size(), with_sun.hours.size());
    ASSERT_GT(sky.hours.size(), 4000u);  // about half of 8760 hours have the sun up
    const auto& ps = sky.patches.patches();
    for (std::size_t h = 0; h < sky.hours.size(); ++h) {
      const MatrixHour& hour = sky.hours[h];
      double e_lux = 0.0, e_w = 0.0, sun = 0.0;
      for (std::size_t i = 1; i < ps.size(); ++i) {
        e_lux += sky.value(h, i, true) * ps[i].solid_angle * ps[i].centre.z;
        e_w += sky.value(h, i, false) * ps[i].solid_angle * ps[i].centre.z;
        sun += (with_sun.value(h, i, false) - sky.value(h, i, false)) * ps[i].solid_angle;
      }
      if (hour.dhi_w_m2 > 0.0) {
        EXPECT_NEAR(e_lux / hour.diffuse_horizontal_lux, 1.0, kSumTol) << patches << " " << h;
        EXPECT_NEAR(e_w / hour.dhi_w_m2, 1.0, kSumTol);
      }
      // The sun's patches hold exactly the direct normal irradiance.
      EXPECT_NEAR(sun, hour.dni_w_m2, kSumTol * std::max(1.0, hour.dni_w_m2));
      // Ground: albedo 0.2 of the global horizontal light.
      const double cz = std::cos(deg_to_rad(hour.sun_zenith_deg));
      EXPECT_NEAR(sky.value(h, 0, false), 0.2 * (hour.dhi_w_m2 + hour.dni_w_m2 * cz) / kPi, 1e-9);
    }
  }
}

TEST(SkyMatrix, OneSunPatchIsThePatchThatHoldsTheSunEveryHour) {
  const SkyMatrix sky = matrix("tregenza", 0);
  const SkyMatrix one = matrix("tregenza", 1);
  const auto& ps = sky.patches.patches();
  std::size_t with_direct = 0;
  for (std::size_t h = 0; h < sky.hours.size(); ++h) {
    const MatrixHour& hour = sky.hours[h];
    if (hour.dni_w_m2 <= 0.0 || hour.dhi_w_m2 <= 0.0) continue;
    ++with_direct;
    const std::size_t holder = sky.patches.find(
        SunPosition{deg_to_rad(hour.sun_zenith_deg), deg_to_rad(hour.sun_azimuth_deg)}.direction());
    for (std::size_t i = 1; i < ps.size(); ++i) {
      const double added = one.value(h, i, false) - sky.value(h, i, false);
      if (i == holder)
        EXPECT_NEAR(added * ps[i].solid_angle, hour.dni_w_m2, 1e-9 * hour.dni_w_m2);
      else
        EXPECT_EQ(added, 0.0) << "hour " << h << " patch " << i;
    }
  }
  EXPECT_GT(with_direct, 2000u);
}

TEST(SkyMatrix, CsvAndNpyHoldTheSameRows) {
  MatrixSettings s;
  s.hours = "4000-4048";  // two days in June
  s.quantity = "luminance";
  const SkyMatrix m = sky_matrix(sample_year(), s, "w.epw");
  ASSERT_FALSE(m.hours.empty());
  const std::string csv = matrix_csv(m);
  const std::string npy = matrix_npy(m);
  const std::size_t cols = matrix_hour_columns().size() + m.patches.size();
  // NPY 1.0: magic, version, little-endian header length, a 64-byte aligned header.
  ASSERT_EQ(npy.compare(0, 8, std::string("\x93NUMPY\x01\x00", 8)), 0);
  const std::size_t header_len =
      static_cast<unsigned char>(npy[8]) + 256u * static_cast<unsigned char>(npy[9]);
  EXPECT_EQ((10 + header_len) % 64, 0u);
  const std::string header = npy.substr(10, header_len);
  EXPECT_NE(header.find(fmt::format("'shape': ({}, {})", m.hours.size(), cols)), std::string::npos)
      << header;
  EXPECT_EQ(npy.size(), 10 + header_len + 8 * m.hours.size() * cols);
  // Row 1 of the CSV against the first row of the .npy.
  const std::size_t row1 = csv.find('\n') + 1;
  const std::string line = csv.substr(row1, csv.find('\n', row1) - row1);
  std::size_t pos = 0;
  for (std::size_t c = 0; c < cols; ++c) {
    const std::size_t comma = std::min(line.find(',', pos), line.size());
    const double from_csv = *parse_number(line.substr(pos, comma - pos));
    double from_npy = 0.0;
    std::memcpy(&from_npy, npy.data() + 10 + header_len + 8 * c, 8);
    EXPECT_NEAR(from_csv, from_npy, 1e-6 * std::max(1.0, std::abs(from_npy))) << "column " << c;
    pos = comma + 1;
  }
  EXPECT_GE(m.hours.front().record, 4000u);
  EXPECT_LE(m.hours.back().record, 4048u);
}

TEST(SkyMatrix, BadRecordsAndRangesNameTheLine) {
  const std::string head =
      "LOCATION,X,,,,0,48,11,1,500\nDESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\nGROUND "
      "TEMPERATURES,0\nHOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\nCOMMENTS 1,\nCOMMENTS 2,\nDATA "
      "PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";
  auto rec = [](int month, int day, int hour, const char* dni, const char* dhi) {
    return fmt::format(
        "2019,{},{},{},60,x,10,5,60,95000,9999,9999,9999,500,{},{},999999,999999,999999,9999,"
        "0,0,0,0,0,0,9,x,999,.999,999,99,999,999,99\n",
        month, day, hour, dni, dhi);
  };
  auto error = [&](const std::string& text, const std::string& hours = {}) {
    MatrixSettings s;
    s.hours = hours;
    return testing_support::error_message(
        [&] { sky_matrix(io::parse_epw(text, "w.epw"), s, "w.epw"); });
  };
  EXPECT_EQ(error(head + rec(6, 21, 13, "9999", "100")),
            "w.epw line 9: the sun is up (65.32 deg) and the direct normal radiation is missing");
  EXPECT_EQ(error(head + rec(2, 29, 13, "100", "100")),
            "w.epw line 9: date.day = 29 is out of range [1, 28]");
  EXPECT_EQ(error(head + rec(6, 21, 13, "1500", "100")),
            "w.epw line 9: dni = 1500 W/m^2 exceeds the extraterrestrial irradiance 1322.5 W/m^2 "
            "of day 172");
  EXPECT_EQ(error(head + rec(6, 21, 13, "100", "100"), "2-1"),
            "hours '2-1' must be FIRST-LAST with 1 <= FIRST <= LAST");
  EXPECT_EQ(error(head + rec(6, 21, 13, "100", "100"), "1-2"),
            "hours '1-2' goes beyond the file's 1 records");
  // The sun below the horizon: no row, no error.
  MatrixSettings s;
  const SkyMatrix night =
      sky_matrix(io::parse_epw(head + rec(6, 21, 1, "9999", "9999"), "w.epw"), s, "w.epw");
  EXPECT_TRUE(night.hours.empty());
  EXPECT_EQ(night.skipped_sun_down, 1u);
}

}  // namespace
}  // namespace skylight::daylight

namespace skylight::daylight {
namespace {

// --channels radiance,luminance: each channel's patches side by side, the same numbers as the
// matrices of one quantity each; melanopic is refused (the Perez sky has no spectrum).
TEST(SkyMatrix, ChannelsPutEachQuantitysPatchesSideBySide) {
  MatrixSettings s;
  s.hours = "4000-4024";
  s.channels = "radiance,luminance";
  const std::string both = matrix_csv(sky_matrix(sample_year(), s, "y.epw"));
  s.channels.clear();
  const std::string rad = matrix_csv(sky_matrix(sample_year(), s, "y.epw"));
  s.quantity = "luminance";
  const std::string lum = matrix_csv(sky_matrix(sample_year(), s, "y.epw"));
  // Row by row: the hour's columns and radiance's patches, then luminance's patches.
  const auto lines = [](const std::string& t) {
    std::vector<std::string> out;
    std::size_t a = 0;
    while (a < t.size()) {
      const std::size_t b = t.find('\n', a);
      out.push_back(t.substr(a, b - a));
      a = b + 1;
    }
    return out;
  };
  const auto lb = lines(both), lr = lines(rad), ll = lines(lum);
  ASSERT_EQ(lb.size(), lr.size());
  const std::size_t hour_fields = matrix_hour_columns().size();
  for (std::size_t k = 1; k < lb.size(); ++k) {
    std::size_t cut = 0;
    for (std::size_t f = 0; f < hour_fields; ++f) cut = ll[k].find(',', cut) + 1;
    EXPECT_EQ(lb[k], lr[k] + "," + ll[k].substr(cut)) << k;
  }
  EXPECT_EQ(lb[0].find("radiance_p0"), lr[0].find("p0"));
  s.channels = "radiance,melanopic";
  EXPECT_THROW(matrix_channels(s), InvalidArgument);
}

}  // namespace
}  // namespace skylight::daylight
