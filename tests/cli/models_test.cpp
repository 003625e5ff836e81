// End-to-end tests of `skylight models`: real processes, real files.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/io/image.h"
#include "support/cli_run.h"
#include "support/exr_metadata.h"

namespace skylight {
namespace {

using Cli = testing_support::CliTest;

TEST_F(Cli, ModelsJsonAndHelp) {
  testing_support::CliResult r = run("models --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  std::vector<std::string> names;
  for (const auto& m : j) names.push_back(m["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"perez", "preetham", "cie", "hosek", "nishita",
                                             "hillaire", "bruneton", "nn", "pietras", "sh"}));
  for (const auto& m : j) {
    for (const auto& p : m["parameters"]) {
      // Text and flag parameters (nn's weights file, sh's --table and --no-ringing-filter) have no
      // numeric range.
      const bool numeric = p["kind"] != "text" && p["kind"] != "flag";
      EXPECT_TRUE(p.contains("unit") && p.contains("default") &&
                  (!numeric || (p.contains("min") && p.contains("max"))))
          << m["name"] << " " << p["name"];
    }
  }
  r = run("render --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--turbidity"), std::string::npos);
  EXPECT_NE(r.out.find("default 3"), std::string::npos);
  r = run("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("skylight "), std::string::npos);
  r = run("");
  EXPECT_EQ(r.status, 2);
}

TEST_F(Cli, ModelsJsonHasTypedDefaultsFromTheSchema) {
  const auto r = run("models --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  bool seen_hosek = false;
  for (const auto& m : j) {
    for (const auto& p : m["parameters"]) {
      ASSERT_TRUE(p.contains("required"));
      if (p["required"].get<bool>()) {
        EXPECT_EQ(p["default"], "required");
      } else if (p["default"].is_null()) {
        EXPECT_TRUE(p["when_absent"].is_string());
      } else {
        // A flag's default is a boolean (sh's --no-ringing-filter: false); a choice's is one of
        // its choices (perez's --compat: papers).
        const bool choice =
            p.contains("choices") && p["default"].is_string() &&
            std::find(p["choices"].begin(), p["choices"].end(), p["default"]) != p["choices"].end();
        EXPECT_TRUE(p["default"].is_number() || p["default"].is_array() ||
                    (p["kind"] == "flag" && p["default"].is_boolean()) || choice)
            << p.dump();
      }
    }
    if (m["name"] == "hosek") {
      seen_hosek = true;
      for (const auto& p : m["parameters"])
        if (p["name"] == "turbidity") {
          EXPECT_EQ(p["max"], 10.0);
          EXPECT_EQ(p["default"], 3.0);
        }
    }
  }
  EXPECT_TRUE(seen_hosek);
}

TEST_F(Cli, ModelsMarkdownIsTheDocsTables) {
  const auto r = run("models --markdown");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("<!-- parameters preetham -->"), std::string::npos);
  EXPECT_NE(r.out.find("| `--turbidity` | 1 | 1 .. 64 | 3 |"), std::string::npos) << r.out;
  EXPECT_EQ(run("models --json --markdown").status, 2);
}

TEST_F(Cli, MetadataRecordsOnlyWhatTheModelReads) {
  const auto out = dir_ / "p.exr";
  ASSERT_EQ(
      run("render --model preetham --turbidity 4 --width 8 --height 4 -o '" + out.string() + "'")
          .status,
      0);
  using testing_support::kMissingMetadata;
  using testing_support::metadata_value;
  const auto md = io::read_exr_metadata(out);
  EXPECT_NE(metadata_value(md, "skylight:turbidity"), kMissingMetadata);
  EXPECT_EQ(metadata_value(md, "skylight:cie_type"), kMissingMetadata);
  EXPECT_EQ(metadata_value(md, "skylight:albedo"), kMissingMetadata);
  const auto n = dir_ / "n.exr";
  ASSERT_EQ(
      run("render --model nishita --ozone 300 --width 8 --height 4 -o '" + n.string() + "'").status,
      0);
  const auto nmd = io::read_exr_metadata(n);
  EXPECT_EQ(metadata_value(nmd, "skylight:ozone_DU"), "300");
  EXPECT_EQ(metadata_value(nmd, "skylight:top_radius_m"), "6420000");
}

}  // namespace
}  // namespace skylight
