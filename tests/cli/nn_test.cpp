// End-to-end tests of `skylight nn` and `--model nn`: real processes, real files.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "skylight/models/neural_sky.h"
#include "skylight/models/sky_model.h"
#include "support/cli_run.h"
#include "support/glslang.h"
#include "support/scratch_dir.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;
using testing_support::parse_csv_numbers;

// eval prints shortest round-trip doubles: the CLI's value is the library's exactly.
constexpr double kEvalExact = 0.0;

TEST_F(Cli, NnTrainValidateEval) {
  const std::string w = (dir_ / "w.json").string();
  const std::string log = (dir_ / "log.csv").string();
  testing_support::CliResult r =
      run("nn train --source preetham --hidden 4 --iterations 15 --suns 4 --view-zeniths 4 "
          "--view-azimuths 6 --seed 2 -o '" +
          w + "' --log '" + log + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("validation: RMSE"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(w));
  std::ifstream ls(log);
  std::string header;
  std::getline(ls, header);
  EXPECT_EQ(header, "restart,iteration,seconds,mse,validation_mse,step");
  const nn::SkyNetwork net = load_sky_network_file(w);
  EXPECT_EQ(net.net.layout().describe(), "6-4-3 satilmis/satilmis");
  EXPECT_EQ(net.provenance.seed, 2u);
  EXPECT_EQ(net.provenance.trainer, "lm");

  r = run("nn validate --weights '" + w + "' --json --suns 2 --view-zeniths 3 --view-azimuths 4");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["examples"].get<int>(), 4 * 2 * 12);
  EXPECT_GT(j["rmse"].get<double>(), 0.0);
  EXPECT_EQ(j["irradiance_per_sun"].size(), 8u);

  // eval --model nn equals the network's own forward pass.
  r = run("eval --model nn --weights '" + w +
              "' --turbidity 3 --sun-zenith 40 --sun-azimuth 120 --quantity rgb",
          "zenith_deg,azimuth_deg\n10,20\n70,200\n");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = parse_csv_numbers(r.out, &header);
  ASSERT_EQ(rows.size(), 2u);
  SkyParameters p;
  p.sun = {deg_to_rad(40.0), deg_to_rad(120.0)};
  p.values.set("turbidity", 3.0).set("weights", w.c_str());
  const auto m = make_sky_model("nn", p);
  const Rgb c = m->rgb(direction_from_angles(deg_to_rad(70.0), deg_to_rad(200.0)));
  EXPECT_NEAR(rows[1][2], c.r, kEvalExact);
  EXPECT_NEAR(rows[1][4], c.b, kEvalExact);

  r = run("render --model nn --weights '" + w + "' --width 32 --height 16 -o '" +
          (dir_ / "sky.exr").string() + "'");
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(Cli, NnBadWeightsAndFlags) {
  std::ofstream(dir_ / "bad.json") << "{\"format\": \"skylight-nn-sky\", \"version\": 7}";
  testing_support::CliResult r =
      run("eval --model nn --weights '" + (dir_ / "bad.json").string() + "'", "0,0\n");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("bad.json: field 'version'"), std::string::npos) << r.err;
  r = run("nn validate --weights '" + (dir_ / "none.json").string() + "'");
  EXPECT_EQ(r.status, 1) << r.err;
  r = run("nn train --trainer magic -o '" + (dir_ / "x.json").string() + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.json"));
  r = run("nn train --source nosuch -o '" + (dir_ / "x.json").string() + "'");
  EXPECT_EQ(r.status, 2) << r.err;
}

TEST_F(Cli, NnExportGlslIsValidAndAtomic) {
  // The embedded network (no --weights) and a weights file give the same GLSL.
  const fs::path embedded = dir_ / "embedded.glsl", from_file = dir_ / "file.glsl";
  const fs::path w = dir_ / "w.json";
  std::ofstream(w) << nn::to_json(embedded_sky_network());
  testing_support::CliResult r = run("nn export --glsl '" + embedded.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("nn export --weights '" + w.string() + "' --glsl '" + from_file.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string text = testing_support::slurp(embedded);
  EXPECT_EQ(text, testing_support::slurp(from_file));
  EXPECT_EQ(text.rfind("#version 330 core\n", 0), 0u);
  EXPECT_NE(text.find("vec3 skylight_sky(vec3 view, vec3 sun, float turbidity)"),
            std::string::npos);
  const auto v =
      testing_support::run_glslang("-S frag '" + embedded.string() + "'", dir_ / "glslang.log");
  EXPECT_EQ(v.status, 0) << v.output;
  // A bad weights file: exit 2, nothing written.
  const fs::path bad = dir_ / "bad.json", out = dir_ / "bad.glsl";
  std::ofstream(bad) << "{\"format\": \"skylight-nn-sky\", \"version\": 9}\n";
  r = run("nn export --weights '" + bad.string() + "' --glsl '" + out.string() + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(fs::exists(out));
  r = run("nn export --weights '" + (dir_ / "missing.json").string() + "' --glsl '" + out.string() +
          "'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, NnTrainValidateEvalPietras) {
  const std::string w = (dir_ / "p.json").string();
  testing_support::CliResult r = run(
      "nn train --source nishita --network pietras --samples 2000 --iterations 5 -o '" + w + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("pietras network (324 weights)"), std::string::npos) << r.out;
  r = run("nn validate --weights '" + w + "' --json --samples 300");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["weights_count"].get<int>(), 324);
  EXPECT_EQ(j["day"]["samples"].get<int>(), 300);
  EXPECT_EQ(j["night_network_not_dark"].get<int>() <= j["night_reference_dark"].get<int>(), true);

  // eval --model nn on a Pietras file is the network's forward pass (the library's rgb_at).
  r = run("eval --model nn --weights '" + w +
              "' --observer-altitude 1500 --sun-zenith 40 --sun-azimuth 180 --quantity rgb",
          "zenith_deg,azimuth_deg\n10,20\n70,200\n");
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  const auto rows = parse_csv_numbers(r.out, &header);
  ASSERT_EQ(rows.size(), 2u);
  SkyParameters p;
  p.sun = {deg_to_rad(40.0), deg_to_rad(180.0)};
  p.values.set("weights", w.c_str()).set("observer-altitude", 1500.0);
  const auto m = make_sky_model("nn", p);
  const Rgb c = m->rgb(direction_from_angles(deg_to_rad(70.0), deg_to_rad(200.0)));
  EXPECT_NEAR(rows[1].back(), c.b, kEvalExact) << r.out;
  EXPECT_GT(c.g, 0.0);

  r = run("nn train --source hosek --network pietras --samples 100 -o '" + w + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--source must be nishita"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace skylight
