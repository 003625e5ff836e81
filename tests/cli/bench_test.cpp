// End-to-end tests of `skylight bench`: real processes, real files.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/io/image.h"
#include "support/cli_run.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;
using testing_support::parse_csv_numbers;

TEST_F(Cli, BenchRunsAndPrintsRatios) {
  const testing_support::CliResult r =
      run("bench --width 64 --height 32 --repeats 1 --models preetham,cie,perez");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("SIMD x"), std::string::npos);
  EXPECT_NE(r.out.find("preetham"), std::string::npos);
}

}  // namespace
}  // namespace skylight
