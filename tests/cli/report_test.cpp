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
  EXPECT_EQ(r.out, (out / "index.html").string() + "\n");
  // Not a terminal: at most one progress line per step (none in the first second), then the
  // summary.
  std::size_t lines = 0;
  for (std::size_t at = r.err.find("skylight report: ["); at != std::string::npos;
       at = r.err.find("skylight report: [", at + 1))
    ++lines;
  EXPECT_LE(lines, 17u) << r.err;
  EXPECT_NE(r.err.find("files to"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_regular_file(out / "index.html"));
  const auto j = nlohmann::json::parse(slurp(out / "report.json"));
  EXPECT_EQ(j["measurements"]["samples"], 5);
  EXPECT_FALSE(j["measurements"]["synthetic"].get<bool>());
  EXPECT_DOUBLE_EQ(j["measurements"]["sun_elevation_deg"].get<double>(), 40.0);
}

TEST_F(ReportCli, BadScanIsAUsageErrorNamingLineAndColumn) {
  const fs::path scan = dir_ / "bad.csv";
  std::ofstream(scan) << "# sun_azimuth_deg = 180\n# sun_elevation_deg = 30\n"
                         "azimuth_deg,elevation_deg,luminance_cd_m2\n0,6,100\n0,nan,3\n";
  const Result r = run("report --quick -o '" + (dir_ / "r").string() + "' --measurements '" +
                       scan.string() + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("bad.csv line 5 column 2: 'nan' is not a finite number"), std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
}

TEST_F(ReportCli, UsageAndIoErrors) {
  Result r = run("report");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("-o/--output DIR is required"), std::string::npos) << r.err;
  r = run("report -o '" + dir_.string() + "' --bogus");
  EXPECT_EQ(r.status, 2);
  r = run("report -o '" + dir_.string() + "' --sun-azimuth 10");
  EXPECT_EQ(r.status, 2);
  r = run("report -o '" + dir_.string() + "' --sun-elevation 95 --sun-azimuth 0");
  EXPECT_EQ(r.status, 2);
  r = run("report -o '" + dir_.string() + "' --measurements '" + (dir_ / "missing.csv").string() +
          "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("cannot read"), std::string::npos) << r.err;
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
