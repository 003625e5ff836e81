// End-to-end tests of `skylight operations`: the command line's flags come from the library's
// operation schemas.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "skylight/operations/operations.h"
#include "support/cli_run.h"

namespace skylight {
namespace {

namespace fs = std::filesystem;

using Cli = testing_support::CliTest;

// Every parameter of every operation is a flag of its subcommand, shown by its --help.
TEST_F(Cli, EveryOperationParameterIsAFlagOfItsCommand) {
  for (const auto& op : operations::registry()) {
    const testing_support::CliResult r = run(op.name + " --help");
    ASSERT_EQ(r.status, 0) << op.name << ": " << r.err;
    for (const auto& p : op.parameters)
      EXPECT_NE(r.out.find(p.flag()), std::string::npos)
          << "skylight " << op.name << " --help lacks " << p.flag();
  }
}

// The JSON lists the operations that are not sky models, with units, ranges and defaults.
TEST_F(Cli, OperationsJsonListsTheNonModelOperations) {
  const testing_support::CliResult r = run("operations --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), operations::registry().size());
  bool haze_turbidity = false;
  for (const auto& op : j) {
    EXPECT_TRUE(op.contains("description") && op.contains("result")) << op["name"];
    for (const auto& p : op["parameters"]) {
      EXPECT_TRUE(p.contains("unit") && p.contains("default")) << op["name"] << " " << p["name"];
      if (op["name"] == "haze add" && p["name"] == "turbidity") {
        haze_turbidity = true;
        EXPECT_EQ(p["min"], 1.0);  // the haze model's range, declared once in haze/
        EXPECT_EQ(p["max"], 64.0);
      }
    }
  }
  EXPECT_TRUE(haze_turbidity);
  EXPECT_EQ(j[0]["name"], "render");
}

TEST_F(Cli, OperationsMarkdownAndJsonExcludeEachOther) {
  const testing_support::CliResult r = run("operations --json --markdown");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("exclude each other"), std::string::npos) << r.err;
}

// Issue 45 item 2: every operation checks its whole request before any model is built or trained.
// Each command gets a deliberately expensive configuration (the largest images, the most
// iterations, bruneton's tables) with one usage error: exit 2, one line naming it, nothing
// written, and almost no work done, measured as the CPU time of the child processes (the shell
// and skylight; a count of work, not wall time, so the machine's load does not matter).
// kUsageErrorCpuSeconds: the "well under a second"; a request refused before work costs
// the process's start-up and the schemas, 5-30 ms here (100x under the bound).
constexpr double kUsageErrorCpuSeconds = 1.0;

double children_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

TEST_F(Cli, EveryCommandRefusesAUsageErrorBeforeAnyWork) {
  const std::string d = dir_.string();
  // Inputs that exist (their contents are never read: prepare checks a request without work).
  for (const char* name : {"sky.exr", "depth.pfm", "w.json", "table.json", "w.epw", "c.csv"})
    std::ofstream(dir_ / name) << "x";
  struct Case {
    std::string op, args, message;
  };
  const std::vector<Case> cases = {
      {"render",
       "--model bruneton --scattering-orders 10 --width 8192 --height 4096 -o D/a.png --preview "
       "D/a.png",
       "name the same file"},
      {"eval", "--model bruneton --quantity spectral --input D/missing.csv", "no such file"},
      {"estimate",
       "--image D/sky.exr --bootstrap 10000 --ransac-iterations 100000 --samples 1000000 "
       "--sun-zenith 30",
       "--sun-zenith needs --sun-azimuth"},
      {"measured", "--model hosek --kider D/missing -o D/m.csv", "--kider"},
      {"measured", "--model preetham --utc-offset EDT -o D/m.csv", "is not a UTC offset"},
      {"measured", "--model hosek -o D/m.txt", "write .csv"},
      {"sun", "--time 2026-06-21T12:00:00Z --lat 91 --lon 11", "--lat = 91 is outside"},
      {"daylight", "--epw D/c.csv -o D/c.csv", "an output never overwrites an input"},
      {"irradiance", "--model bruneton --scattering-orders 10 --epw D/w.epw --tilt 200 -o D/s.csv",
       "--tilt = 200 is outside"},
      {"irradiance", "--model hosek --horizon D/missing.csv", "no such file"},
      {"bench", "--width 32768 --height 32768 --repeats 1000 --models preetham,nope", "nope"},
      {"report", "-o D/report --measurements D/missing.csv", "no such file"},
      {"sh fit", "--model bruneton --bands 30 --grid 1000,1000 --parameter nope -o D/t.json",
       "is not a number parameter of model 'bruneton'"},
      {"sh eval", "--table D/missing.json --sun-zenith 30", "no such file"},
      {"sh export", "--monomial -o D/t.h", "--monomial needs --c-header"},
      {"sh render", "--width 32768 -o D/s.exr --sphere D/s.exr", "name the same file"},
      {"sh error", "--points 1000,1000 --table D/missing.json", "no such file"},
      {"haze coefficients", "--turbidity 3 --wavelength 5000", "--wavelength"},
      {"haze attenuation",
       "--turbidity 3 --distance 1000 --camera canon-eos-5d --camera-csv D/c.csv",
       "exclude each other"},
      {"haze cameras", "--turbidity 3", "--turbidity is not a parameter of haze cameras"},
      {"haze add",
       "--image D/sky.exr --depth D/depth.pfm --turbidity 3 --sky-model hosek --airlight 1,1,1 "
       "-o D/h.exr",
       "exclude each other"},
      {"haze retarget",
       "--image D/sky.exr --depth D/depth.pfm --turbidity 3 --sky-model hosek -o D/h.exr",
       "--target-turbidity"},
      {"haze remove",
       "--image D/sky.exr --depth D/depth.pfm --turbidity 3 --sky-model hosek -o D/sky.exr",
       "an output never overwrites an input"},
      {"haze composite",
       "--background D/sky.exr --object D/sky.exr --object-depth D/depth.pfm --object-alpha "
       "D/missing.png --turbidity 3 --sky-model hosek -o D/h.exr",
       "no such file"},
      {"haze sky-mask", "--sky D/sky.exr -o D/m.jpg", "write .png"},
      {"nn train", "--iterations 100000 -o D/x.json --log D/x.json", "name the same file"},
      {"nn validate", "--weights D/missing.json --samples 100000000", "no such file"},
      {"nn export", "--weights D/w.json --glsl D/w.json", "an output never overwrites an input"},
      {"nn animate",
       "--weights D/w.json --frames 100000 --width 4096 --height 2048 --turbidity 3 "
       "--observer-altitude 1000 -o D/a.exr",
       "exclude each other"},
      {"nn study", "--iterations 100000000 --repeats 1000 --source nope", "nope"},
      {"nn planet", "--weights D/w.json --subdivisions 9 --width 32768 --height 32768 -o D/p.txt",
       "write"},
      {"view", "-o D/page --kider D/missing", "no such folder"},
  };
  std::set<std::string> covered;
  for (const Case& c : cases) {
    std::string args = c.args;
    for (std::size_t at = args.find("D/"); at != std::string::npos; at = args.find("D/", at))
      args.replace(at, 1, d), at += d.size();
    const double before = children_cpu_seconds();
    const testing_support::CliResult r = run(c.op + " " + args);
    const double cpu = children_cpu_seconds() - before;
    SCOPED_TRACE(c.op + " " + c.args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err.rfind("skylight: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_LT(cpu, kUsageErrorCpuSeconds);
    std::printf("%-18s %.3f s CPU: %s", c.op.c_str(), cpu, r.err.c_str());
    // Nothing written: the scratch folder holds the inputs alone.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 6);
    covered.insert(c.op);
  }
  for (const auto& op : operations::registry()) EXPECT_TRUE(covered.count(op.name)) << op.name;
}

}  // namespace
}  // namespace skylight
