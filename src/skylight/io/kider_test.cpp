#include "skylight/io/kider.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "skylight/core/colorimetry.h"
#include "skylight/core/data.h"
#include "skylight/core/math.h"
#include "support/error_message.h"
#include "support/scratch_dir.h"

namespace skylight::io {
namespace {

namespace fs = std::filesystem;
using testing_support::error_message;
using testing_support::ScratchDir;

// The integral of the CIE 1931 y-bar over 380-780 nm by the trapezoidal rule on the table's own
// 1 nm rows, summed here from the table (not through core/colorimetry).
double ybar_integral_380_780() {
  const auto t = data::load_table("cie_colorimetry/CIE_xyz_1931_2deg.csv", false, 4);
  double sum = 0.0;
  for (std::size_t r = 0; r + 1 < t.rows(); ++r) {
    const double a = t.number(r, 0), b = t.number(r + 1, 0);
    if (a >= 380.0 && b <= 780.0) sum += 0.5 * (t.number(r, 2) + t.number(r + 1, 2)) * (b - a);
  }
  return sum;
}

std::string spectrum_text(const std::vector<double>& nm, const std::vector<double>& v) {
  std::string s = "Wavelength\tsample.asd.rad\n";
  for (std::size_t i = 0; i < nm.size(); ++i) s += fmt::format("{}\t {:.17g} \n", nm[i], v[i]);
  return s;
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// A capture of the shipped subset written out in the original layout under `root`
// (<date>/RADIANCE/<capture>/..., <date>/IRRADIANCE/...), with a raw instrument file beside it.
fs::path write_capture(const fs::path& root, const KiderCapture& c) {
  const std::string date = c.name.substr(0, 10);
  const fs::path dir = root / date / "RADIANCE" / c.name;
  for (const KiderSample& s : c.samples) {
    const std::string name = fmt::format("{}_-_{}____{}___{}.asd.rad.txt", c.name, s.index,
                                         s.file_azimuth_deg, s.elevation_deg);
    write(dir / name, spectrum_text(c.wavelengths_nm, s.radiance));
  }
  write(dir / fmt::format("{}_-_0____0.0___12.1151.asd.txt", c.name), "raw instrument counts\n");
  std::string pyr;
  for (const auto& r : c.pyranometer)
    pyr += fmt::format("{} {}\n", r.global_horizontal_w_m2, r.time);
  std::string file = c.local_time;
  for (char& ch : file)
    if (ch == '-' || ch == 'T' || ch == ':') ch = '.';
  write(root / date / "IRRADIANCE" / (file + ".txt"), pyr);
  return dir;
}

TEST(KiderFileName, ReadsIndexAzimuthAndElevationAndSkipsOtherFiles) {
  const auto f = parse_kider_file_name("2013-05-27___09.30.00_-_10____112.5___12.1151.asd.rad.txt");
  ASSERT_TRUE(f);
  EXPECT_EQ(f->index, 10);
  EXPECT_EQ(f->file_azimuth_deg, 112.5);
  EXPECT_EQ(f->elevation_deg, 12.1151);
  EXPECT_FALSE(parse_kider_file_name("2013-05-27___09.30.00_-_10____112.5___12.1151.asd.txt"));
  EXPECT_FALSE(parse_kider_file_name("README.md"));
  EXPECT_NE(error_message([] {
              parse_kider_file_name("x_-_81____0.0___12.1.asd.rad.txt");
            }).find("sample index '81' is not an integer in 0..80"),
            std::string::npos);
  EXPECT_NE(error_message([] {
              parse_kider_file_name("x_-_3____400___12.1.asd.rad.txt");
            }).find("azimuth '400' is not a number in [0, 360)"),
            std::string::npos);
}

// The luminance of a spectrum equals 683 * integral L y-bar over 380-780 nm, summed independently
// from the CIE table: a constant spectrum on the data's own 1 nm grid (the same trapezoids, so the
// bound is rounding).
TEST(KiderLuminance, IsTheYBarIntegralOver380To780) {
  constexpr double kRoundingBound = 1e-12;
  std::vector<double> nm, flat;
  for (int w = 350; w <= 2500; ++w) {
    nm.push_back(w);
    flat.push_back(0.01);
  }
  const double expected = kMaxLuminousEfficacy * 0.01 * ybar_integral_380_780();
  EXPECT_NEAR(luminance_380_780(nm, flat) / expected, 1.0, kRoundingBound);
  // Published: integral of y-bar over 360-830 nm at 1 nm is 106.857 (CIE 015); 380-780 holds all
  // but about 0.01 % of it.
  EXPECT_NEAR(ybar_integral_380_780(), 106.857, 0.02);
}

TEST(KiderRadiance, BadFilesSayFileAndLine) {
  EXPECT_EQ(error_message([] { parse_kider_radiance("", "a.txt"); }),
            "a.txt: no header line (Wavelength<TAB>name)");
  EXPECT_EQ(error_message([] { parse_kider_radiance("W\n350\t1\n351\tx\n", "a.txt"); }),
            "a.txt line 3: radiance 'x' is not a number");
  EXPECT_EQ(error_message([] { parse_kider_radiance("W\n351\t1\n350\t1\n", "a.txt"); }),
            "a.txt line 3: wavelength 350 nm does not follow 351 nm in ascending order");
  EXPECT_EQ(error_message([] { parse_kider_radiance("W\n350\t1\t2\n", "a.txt"); }),
            "a.txt line 2: expected 2 fields (nm and radiance), found 3");
  EXPECT_EQ(error_message([] { parse_pyranometer("12 t\n-1 t\n", "p.txt"); }),
            "p.txt line 2: irradiance -1 W/m^2 is negative");
  // Negative radiance at the noisy ends of the range is data, not an error.
  EXPECT_EQ(parse_kider_radiance("W\n350\t-0.001\n351\t0.5\n", "a.txt").radiance[0], -0.001);
}

// The shipped subset: 15 captures of 81 samples, the scan's rings, sample 0 replaced by its ring
// neighbours, pyranometer readings for every capture but 13:30 (data/measured/kider2014/).
TEST(KiderSubset, HoldsFifteenCapturesOfEightyOneSamples) {
  const auto captures = shipped_kider_subset();
  ASSERT_EQ(captures.size(), 15u);
  EXPECT_EQ(captures.front().name, "2013-05-27___09.30.00");
  EXPECT_EQ(captures.front().local_time, "2013-05-27T09:30:00");
  EXPECT_EQ(captures.back().name, "2013-05-27___13.30.00");
  for (const KiderCapture& c : captures) {
    ASSERT_EQ(c.samples.size(), 81u) << c.name;
    ASSERT_EQ(c.wavelengths_nm.size(), 131u);
    EXPECT_EQ(c.wavelengths_nm.front(), 350.0);
    EXPECT_EQ(c.wavelengths_nm.back(), 1000.0);
    const KiderSample& zero = c.samples[0];
    EXPECT_TRUE(zero.replaced);
    EXPECT_DOUBLE_EQ(zero.luminance, 0.5 * (c.samples[1].luminance + c.samples[31].luminance));
    EXPECT_EQ(c.samples[80].elevation_deg, 90.0);
    EXPECT_NEAR(c.samples[80].zenith, 0.0, 1e-15);
    // File azimuth 90 (counter-clockwise from north) is west: 270 in skylight's convention.
    for (const KiderSample& s : c.samples)
      if (s.file_azimuth_deg == 90.0) {
        EXPECT_NEAR(rad_to_deg(s.azimuth), 270.0, 1e-12);
      }
    if (c.name == "2013-05-27___13.30.00") {
      EXPECT_FALSE(c.global_horizontal_w_m2());
    } else {
      ASSERT_EQ(c.pyranometer.size(), 81u) << c.name;
      EXPECT_GT(*c.global_horizontal_w_m2(), 600.0);
      EXPECT_LT(*c.global_horizontal_w_m2(), 1100.0);
    }
  }
}

// The stored luminance is the original 1 nm spectrum's (computed by derive.py with NumPy); the
// library's integral of the 5 nm subset agrees with it to the step's discretisation error.
TEST(KiderSubset, StoredLuminanceAgreesWithTheFiveNanometreSpectrum) {
  // Measured over the 1 215 samples: the 5 nm trapezoid differs from the 1 nm one by at most
  // 0.2 % (the instrument's spectra are smooth at 5 nm).
  constexpr double kFiveNanometreBound = 0.004;
  double worst = 0.0;
  for (const KiderCapture& c : shipped_kider_subset())
    for (const KiderSample& s : c.samples) {
      const double five = luminance_380_780(c.wavelengths_nm, s.radiance);
      worst = std::max(worst, std::abs(five / s.luminance - 1.0));
    }
  EXPECT_LT(worst, kFiveNanometreBound);
  EXPECT_GT(worst, 0.0);
}

// A capture written in the original layout reads back as the subset's: the same samples and
// spectra, the raw file ignored, the pyranometer found by the capture's time; from the capture
// folder, its RADIANCE folder, its date folder and the root alike.
TEST(KiderReader, ReadsTheOriginalLayoutFromAnyOfItsFolders) {
  ScratchDir dir;
  const auto subset = shipped_kider_subset();
  const KiderCapture& original = subset[3];
  const fs::path capture_dir = write_capture(dir.path(), original);
  for (const fs::path& p : {capture_dir, capture_dir.parent_path(),
                            capture_dir.parent_path().parent_path(), dir.path()}) {
    const auto read = read_kider(p);
    ASSERT_EQ(read.size(), 1u) << p;
    const KiderCapture& c = read[0];
    EXPECT_EQ(c.name, original.name);
    EXPECT_EQ(c.wavelengths_nm, original.wavelengths_nm);
    ASSERT_EQ(c.samples.size(), 81u);
    for (int i = 0; i < 81; ++i) {
      EXPECT_EQ(c.samples[i].radiance, original.samples[i].radiance) << i;
      EXPECT_EQ(c.samples[i].azimuth, original.samples[i].azimuth);
    }
    EXPECT_TRUE(c.samples[0].replaced);
    ASSERT_EQ(c.pyranometer.size(), original.pyranometer.size());
    EXPECT_EQ(*c.global_horizontal_w_m2(), *original.global_horizontal_w_m2());
  }
  EXPECT_EQ(read_kider(fs::path(SKYLIGHT_SOURCE_DIR) / "data" / "measured" / "kider2014").size(),
            15u);
}

TEST(KiderReader, BadCapturesAreNamed) {
  ScratchDir dir;
  const auto subset = shipped_kider_subset();
  const fs::path capture_dir = write_capture(dir.path(), subset[0]);
  const std::string shown = capture_dir.string();
  const fs::path one = capture_dir / "2013-05-27___09.30.00_-_7____78.75___12.1151.asd.rad.txt";
  fs::remove(one);
  EXPECT_EQ(error_message([&] { read_kider(dir.path()); }),
            fmt::format("{}: sample 7 of the 81 is missing", shown));
  write(one, "Wavelength\tx\n350\t1\n351\t1\n");
  EXPECT_NE(error_message([&] {
              read_kider(dir.path());
            }).find("its wavelengths (2 values, 350-351 nm) differ from the capture's"),
            std::string::npos);
  fs::remove(one);
  write(capture_dir / "2013-05-27___09.30.00_-_8____78.75___12.1151.asd.rad.txt",
        spectrum_text(subset[0].wavelengths_nm, subset[0].samples[8].radiance));
  write(capture_dir / "copy_-_8____90.0___12.1151.asd.rad.txt",
        spectrum_text(subset[0].wavelengths_nm, subset[0].samples[8].radiance));
  EXPECT_NE(error_message([&] { read_kider(dir.path()); }).find(": sample 8 given twice"),
            std::string::npos);
  ScratchDir empty;
  EXPECT_NE(error_message([&] { read_kider(empty.path()); }).find("no Kider capture in it"),
            std::string::npos);
  EXPECT_NE(error_message<IoError>([&] { read_kider(empty / "none"); }).find("no such folder"),
            std::string::npos);
}

TEST(KiderReader, ACaptureFolderNamesItsTime) {
  ScratchDir dir;
  write(dir / "scan" / "x_-_0____0.0___12.1151.asd.rad.txt", "W\n350\t1\n351\t1\n");
  EXPECT_NE(error_message([&] {
              read_kider(dir.path());
            }).find("a capture folder's name must be its local date and time"),
            std::string::npos);
}

TEST(KiderSubset, BadRowsSayFileAndLine) {
  const std::string header =
      "# c\ncapture,index,file_azimuth_deg,elevation_deg,luminance_cd_m2,350,355\n";
  EXPECT_EQ(error_message([&] {
              parse_kider_subset(header + "2013-05-27___09.30.00,0,0.0,12.1,-5,1,2\n", "", "d");
            }),
            "d/radiance.csv line 3: luminance_cd_m2 must be > 0");
  EXPECT_EQ(error_message([&] {
              parse_kider_subset(header + "2013-05-27___09.30.00,0,0.0,12.1,5,1\n", "", "d");
            }),
            "d/radiance.csv line 3: expected 7 fields, found 6");
  EXPECT_EQ(error_message([&] {
              parse_kider_subset(header + "2013-05-27___09.30.00,0,0.0,12.1,5,1,2\n", "", "d");
            }),
            "d/radiance.csv capture 2013-05-27___09.30.00: sample 1 of the 81 is missing");
}

}  // namespace
}  // namespace skylight::io
