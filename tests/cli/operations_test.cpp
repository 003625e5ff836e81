// End-to-end tests of `skylight operations`: the command line's flags come from the library's
// operation schemas.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "skylight/operations/operations.h"
#include "support/cli_run.h"

namespace skylight {
namespace {

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

}  // namespace
}  // namespace skylight
