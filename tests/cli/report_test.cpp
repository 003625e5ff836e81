// End-to-end tests of `skylight report`: real processes, real files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/cli_run.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using ReportCli = testing_support::CliTest;
using Result = testing_support::CliResult;

TEST_F(ReportCli, QuickReportWithAScanFile) {
  const fs::path scan = dir_ / "scan.csv";
  std::ofstream(scan) << "azimuth_deg,elevation_deg,luminance_cd_m2\n"
                         "0,6,4000\n90,30,5000\n180,45,20000\n270,60,7000\n0,90,6000\n";
  const fs::path out = dir_ / "report";
  const Result r = run("report --quick --threads 1 -o '" + out.string() + "' --measurements '" +
                       scan.string() + "' --sun-azimuth 170 --sun-elevation 40");
  ASSERT_EQ(r.status, 0) << r.err;
  // The record: the page, and how many files (the labels in one column).
  EXPECT_EQ(r.out.rfind("index  " + (out / "index.html").string() + "\nfiles  ", 0), 0u) << r.out;
  // Not a terminal: at most one progress line per step (none in the first second), then the
  // summary.
  std::size_t lines = 0;
  for (std::size_t at = r.err.find("/20] "); at != std::string::npos;
       at = r.err.find("/20] ", at + 1))
    ++lines;
  EXPECT_LE(lines, 19u) << r.err;  // 20 steps, the first (reading a file) within the first second
  EXPECT_NE(r.err.find("files to"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_regular_file(out / "index.html"));
  const auto j = nlohmann::json::parse(slurp(out / "report.json"));
  EXPECT_EQ(j["measurements"]["samples"], 5);
  EXPECT_FALSE(j["measurements"]["synthetic"].get<bool>());
  EXPECT_DOUBLE_EQ(j["measurements"]["sun_elevation_deg"].get<double>(), 40.0);
}

// A weather file of the user's, with measured diffuse illuminance: section 9 compares with it.
TEST_F(ReportCli, QuickReportWithAWeatherFile) {
  const fs::path epw = dir_ / "station.epw";
  std::ofstream f(epw);
  f << "LOCATION,X,,,,0,48,11,1,500\nDESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\nGROUND "
       "TEMPERATURES,0\nHOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\nCOMMENTS 1,\nCOMMENTS 2,\nDATA "
       "PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";
  // June 21, 13:00 (sun up), measured diffuse illuminance 20000 lx.
  f << "2019,6,21,13,60,x,20,10,60,95000,9999,9999,9999,700,500,150,80000,50000,20000,9999,0,0,0,"
       "0,0,0,9,x,999,.999,999,99,999,999,99\n";
  f.close();
  const fs::path out = dir_ / "report";
  const Result r =
      run("report --quick --threads 1 -o '" + out.string() + "' --epw '" + epw.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out / "report.json"));
  const auto& w = j["daylight_from_weather"];
  EXPECT_FALSE(w["synthetic"].get<bool>());
  EXPECT_EQ(w["records"].get<int>(), 1);
  ASSERT_FALSE(w["sky_vs_measured"].is_null());
  EXPECT_EQ(w["sky_vs_measured"]["hours"].get<int>(), 1);
  // The hour's sky gives the efficacy model's illuminance (150 W/m^2 x about 120 lm/W), not the
  // file's 20000 lx: |sky / measured - 1| is what the section reports.
  const double rel = w["sky_vs_measured"]["median"].get<double>();
  EXPECT_GT(rel, 0.0);
  EXPECT_LT(rel, 0.5);
  // A bad weather file is a one-line error naming its line, and nothing is written.
  std::ofstream(epw) << "LOCATION,X\n";
  const Result bad =
      run("report --quick -o '" + (dir_ / "r2").string() + "' --epw '" + epw.string() + "'");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("line 1: LOCATION needs 10 fields"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "r2"));
}

TEST_F(ReportCli, BadScanIsAUsageErrorNamingLineAndColumn) {
  const fs::path scan = dir_ / "bad.csv";
  std::ofstream(scan) << "# sun_azimuth_deg = 180\n# sun_elevation_deg = 30\n"
                         "azimuth_deg,elevation_deg,luminance_cd_m2\n0,6,100\n0,nan,3\n";
  const Result r = run("report --quick -o '" + (dir_ / "r").string() + "' --measurements '" +
                       scan.string() + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bad.csv line 5 column 2: 'nan' is not a number"), std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
}

// A large scan: the statistics use every sample, the scatter plot draws every k-th (a million rows
// made a page of 430 MB and a peak of 2.2 GB; now 2.4 MB and 290 MB, docs/REPORT.md).
TEST_F(ReportCli, ALargeScanDrawsABoundedScatterPlot) {
  const fs::path scan = dir_ / "large.csv";
  {
    std::ofstream f(scan);
    f << "# sun_azimuth_deg = 165\n# sun_elevation_deg = 35\n"
         "azimuth_deg,elevation_deg,luminance_cd_m2\n";
    for (int i = 0; i < 20001; ++i) f << (i * 7919) % 360 << "," << 1 + (i * 31) % 89 << ",4000\n";
  }
  const fs::path out = dir_ / "r";
  const Result r =
      run("report --quick -o '" + out.string() + "' --measurements '" + scan.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(out / "report.json"));
  EXPECT_EQ(j["measurements"]["samples"].get<int>(), 20001);
  EXPECT_NE(slurp(out / "index.html").find("Every 5th sample's (of 20001; the table uses all)"),
            std::string::npos);
  // At most 5000 markers per model's series (every 5th of 20001: 4001), whatever the scan's size.
  const std::string svg = slurp(out / "measurements.svg");
  std::size_t markers = 0;
  for (std::size_t at = svg.find("<circle"); at != std::string::npos;
       at = svg.find("<circle", at + 1))
    ++markers;
  // The plot's series: the best CIE type, CIE 12, Preetham, Hosek-Wilkie and Nishita; each draws
  // 4001 samples and a legend marker.
  constexpr std::size_t kSeries = 5;
  EXPECT_LE(markers, kSeries * (4001 + 1)) << "markers " << markers;
  EXPECT_GT(markers, 4001u);
}

TEST_F(ReportCli, UsageAndIoErrors) {
  Result r = run("report");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "skylight: error: report needs -o DIR (or --write-synthetic-measurements FILE)\n");
  r = run("report -o '" + dir_.string() + "' --bogus");
  EXPECT_EQ(r.status, 2);
  r = run("report -o '" + dir_.string() + "' --sun-azimuth 10");
  EXPECT_EQ(r.status, 2);
  r = run("report -o '" + dir_.string() + "' --sun-elevation 95 --sun-azimuth 0");
  EXPECT_EQ(r.status, 2);
  r = run("report -o '" + dir_.string() + "' --measurements '" + (dir_ / "missing.csv").string() +
          "'");
  // A missing input is a usage error found before any work.
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("missing.csv': no such file"), std::string::npos) << r.err;
  std::ofstream(dir_ / "a_file") << "x";
  r = run("report --quick -o '" + (dir_ / "a_file").string() + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("cannot create directory"), std::string::npos) << r.err;
}

TEST_F(ReportCli, WritesTheShippedSyntheticScan) {
  const fs::path f = dir_ / "synthetic.csv";
  const Result r = run("report --write-synthetic-measurements '" + f.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(slurp(f), slurp(std::string(SKYLIGHT_TEST_DATA_DIR) +
                            "/measurements/synthetic_tregenza_cie7.csv"));
  EXPECT_EQ(run("report --write-synthetic-measurements '" + f.string() + "' --quick").status, 2);
}

}  // namespace
}  // namespace skylight
