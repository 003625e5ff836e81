// End-to-end tests of `skylight nn` and `--model nn`: real processes, real files.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "skylight/io/image.h"
#include "skylight/models/hosek_wilkie.h"
#include "skylight/models/neural_sky.h"
#include "skylight/models/pietras.h"
#include "skylight/models/sky_model.h"
#include "skylight/render/sky_render.h"
#include "skylight/sun/spa.h"
#include "skylight/sun/time.h"
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
// A Pietras network in seconds: a few iterations on a small Nishita sample, far from nishita, so
// accepted whatever its held-out check measures (append -o FILE).
const std::string kQuickPietrasTraining =
    "nn train --source nishita --network pietras --samples 2000 --iterations 5 --max-error 1e6";

// A network outside its held-out bound: exit 1, one line saying what was measured, nothing
// written (neither the weights nor the log).
TEST_F(Cli, NnTrainFailsOutsideItsHeldOutBound) {
  const std::string w = (dir_ / "w.json").string(), log = (dir_ / "log.csv").string();
  const testing_support::CliResult r =
      run("nn train --source preetham --hidden 4 --iterations 15 --suns 4 --view-zeniths 4 "
          "--view-azimuths 6 --starts 2 --start-iterations 5 --max-error 0.5 -o '" +
          w + "' --log '" + log + "'");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.err.find("fails its held-out check"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(bound 0.5 %)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(w));
  EXPECT_FALSE(fs::exists(log));
}

// A flag this kind of training does not read warns and changes nothing.
TEST_F(Cli, NnTrainWarnsOfFlagsItsKindDoesNotRead) {
  const std::string w = (dir_ / "p.json").string();
  const testing_support::CliResult r =
      run("nn train --source nishita --network log3 --samples 2000 --iterations 1 --starts 3 "
          "--start-iterations 4 --max-error 1e6 -o '" +
          w + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: --starts is not read by this training (--network); ignored"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("warning: --start-iterations is not read"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("--max-error is not read"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(w));
}

// A Pietras network is checked on held-out day samples: the line says what was measured, with the
// region's bound; outside it (here a network after 5 iterations against a 1 % bound) exit 1 and
// nothing written. The region is recorded in the file's provenance.
TEST_F(Cli, NnTrainPietrasChecksHeldOutDaySamples) {
  const std::string w = (dir_ / "p.json").string();
  testing_support::CliResult r =
      run("nn train --source nishita --network pietras --samples 2000 --iterations 5 --max-error 1 "
          "-o '" +
          w + "'");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.err.find("nn train --network pietras: the network fails its held-out check (20000 "
                       "day samples"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("(bound 1 %)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(w));

  r =
      run("nn train --source nishita --network log3 --samples 2000 --iterations 5 --region "
          "sky-dome --max-error 1e6 -o '" +
          w + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  using testing_support::text_field;
  EXPECT_EQ(text_field(r.out, "region"), "sky-dome") << r.out;
  EXPECT_EQ(
      text_field(r.out, "held out check").rfind("held-out check (20000 day samples, seed ", 0), 0u)
      << r.out;
  std::ifstream in(w);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["provenance"]["region"].get<std::string>(), "sky-dome");
  EXPECT_NE(j["provenance"]["geometry"].get<std::string>().find("upward views"), std::string::npos);
}

TEST_F(Cli, NnTrainValidateEval) {
  const std::string w = (dir_ / "w.json").string();
  const std::string log = (dir_ / "log.csv").string();
  testing_support::CliResult r =
      run("nn train --source preetham --hidden 4 --iterations 15 --suns 4 --view-zeniths 4 "
          "--view-azimuths 6 --seed 2 --max-error 1e6 -o '" +
          w + "' --log '" + log + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  using testing_support::text_field;
  EXPECT_NE(text_field(r.out, "validation rmse"), "") << r.out;
  EXPECT_EQ(text_field(r.out, "held out check").rfind("held-out check: relative error median", 0),
            0u)
      << r.out;
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
  EXPECT_EQ(r.status, 2) << r.err;  // a missing input: found before any work
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
  // A Pietras file (both kinds): the network, its shadow test and rgb_at (nn/glsl.h), valid as a
  // fragment and as a vertex shader.
  for (const char* name : {"pietras.json", "log3.json"}) {
    const fs::path glsl = dir_ / (std::string(name) + ".glsl");
    r = run("nn export --weights '" + std::string(SKYLIGHT_TEST_DATA_DIR) + "/nn/" + name +
            "' --glsl '" + glsl.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string p = testing_support::slurp(glsl);
    EXPECT_EQ(p.rfind("#version 330 core\n", 0), 0u);
    EXPECT_NE(p.find("vec3 skylight_pietras_at(float altitude, vec3 view, vec3 sun)"),
              std::string::npos);
    EXPECT_NE(p.find("bool skylight_pietras_lit("), std::string::npos);
    for (const char* stage : {"frag", "vert"}) {
      const auto g = testing_support::run_glslang(
          std::string("-S ") + stage + " '" + glsl.string() + "'", dir_ / "glslang.log");
      EXPECT_EQ(g.status, 0) << name << ' ' << stage << ": " << g.output;
    }
  }
  // A bad weights file: exit 2, nothing written.
  const fs::path bad = dir_ / "bad.json", out = dir_ / "bad.glsl";
  std::ofstream(bad) << "{\"format\": \"skylight-nn-sky\", \"version\": 9}\n";
  r = run("nn export --weights '" + bad.string() + "' --glsl '" + out.string() + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(fs::exists(out));
  r = run("nn export --weights '" + (dir_ / "missing.json").string() + "' --glsl '" + out.string() +
          "'");
  EXPECT_EQ(r.status, 2) << r.err;  // a missing input: found before any work
  EXPECT_FALSE(fs::exists(out));
}

// The printed sun angles have 3 decimals.
constexpr double kPrintedDeg = 5e-4;

// A rendered 4-capture sequence (Hosek-Wilkie with the solar disc): suns from the list, from a
// time through the SPA, and found in the image; leave-one-image-out K-fold, the final network,
// then an animation between two suns with a strip image.
TEST_F(Cli, NnTrainImagesKfoldAndAnimate) {
  sun::SpaInput in;
  in.time = sun::parse_iso8601("2024-06-21T15:00:00+02:00");
  in.latitude = deg_to_rad(48.0);
  in.longitude = deg_to_rad(11.0);
  const sun::SpaResult spa = sun::solar_position(in);
  const double suns[4][2] = {
      {30, 120}, {45, 150}, {rad_to_deg(spa.zenith), rad_to_deg(spa.azimuth)}, {70, 210}};
  for (int k = 0; k < 4; ++k) {
    const auto r =
        run(fmt::format("render --model hosek --turbidity 3 --include-sun --sun-zenith "
                        "{} --sun-azimuth {} --width 96 --height 48 -o '{}/c{}.exr'",
                        suns[k][0], suns[k][1], dir_.string(), k));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  std::ofstream(dir_ / "seq.csv") << "file,sun_zenith_deg,sun_azimuth_deg,time\n"
                                     "c0.exr,30,120,\nc1.exr,45,150,\n"
                                     "c2.exr,,,2024-06-21T15:00:00+02:00\nc3.exr,,,\n";
  const std::string w = (dir_ / "w.json").string();
  auto r =
      run("nn train --images '" + (dir_ / "seq.csv").string() +
          "' --lat 48 --lon 11 --kfold 4 --hidden 8 --iterations 40 --samples 300 --max-error 1000 "
          "-o '" +
          w + "' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto tj = nlohmann::json::parse(r.out);
  EXPECT_EQ(tj["images"].size(), 4u);
  EXPECT_EQ(tj["examples"].get<int>(), 1200);
  EXPECT_EQ(tj["folds"].size(), 4u);
  // 40 iterations are not enough for the held-out capture (line 3): measured and reported, the
  // bound lifted (NnTrainImagesChecksTheCapturesBetween tests it).
  EXPECT_NE(tj["held_out_check"].get<std::string>().find(
                "held-out captures (lines 3; the network trained on the other 3)"),
            std::string::npos)
      << r.out;
  // The time row's sun is the SPA's; the last row's is found in the image.
  int found = 0;
  for (const auto& image : tj["images"]) {
    const int row = image["line"];
    const double z = image["sun_zenith_deg"], a = image["sun_azimuth_deg"];
    const std::string from = image["sun_from"];
    if (row == 4) {
      EXPECT_EQ(from, "time");
      EXPECT_NEAR(z, rad_to_deg(spa.zenith), kPrintedDeg);
      EXPECT_NEAR(a, rad_to_deg(spa.azimuth), kPrintedDeg);
      ++found;
    }
    if (row == 5) {
      EXPECT_EQ(from, "image");
      // The disc's centroid on a 3.75 deg pixel grid: within a pixel.
      EXPECT_NEAR(z, 70.0, 3.75);
      ++found;
    }
  }
  EXPECT_EQ(found, 2) << r.out;
  const nn::SkyNetwork net = load_sky_network_file(w);
  EXPECT_EQ(net.provenance.source, "images");
  EXPECT_EQ(net.provenance.sun_count, 4);
  EXPECT_EQ(net.provenance.turbidities, std::vector<double>{0.0});

  r = run("nn animate --weights '" + w +
          "' --from 30,100 --to 70,200 --frames 3 --width 32 --height 16 -o '" + dir_.string() +
          "/f_#.exr' --strip '" + dir_.string() + "/strip.png' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  // Frame 1 is halfway.
  const auto frame1 = nlohmann::json::parse(r.out)["frames"][1];
  EXPECT_DOUBLE_EQ(frame1["sun_zenith_deg"].get<double>(), 50.0) << r.out;
  EXPECT_DOUBLE_EQ(frame1["sun_azimuth_deg"].get<double>(), 150.0) << r.out;
  for (const char* f : {"f_0.exr", "f_1.exr", "f_2.exr", "strip.png"})
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
  EXPECT_FALSE(fs::exists(dir_ / "f_3.exr"));
  r = run("nn animate --weights '" + w + "' --from 30,100 --to 70,200 -o '" + dir_.string() +
          "/nohash.exr'");
  EXPECT_EQ(r.status, 2) << r.err;
  // --observer-altitude is a Pietras network's input: refused for a sky network, nothing written.
  r = run("nn animate --weights '" + w +
          "' --observer-altitude 500 --from 30,100 --to 70,200 -o '" + dir_.string() + "/a_#.exr'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("' is a sky network, which has no altitude input"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "a_0.exr"));
}

// The sparse sequence of docs/NN.md ("Sparse sequences"): 7 captures of Hosek-Wilkie T 3 with the
// solar disc, suns 10 deg apart, found in the images. nn train --images holds out lines 3 5 7,
// prints their error, and the final network reproduces the skies half-way between the captures
// (never seen) within the bounds below. With --max-error under the measured check: exit 1, "too
// sparse", nothing written. Measured (96 x 48, 400 samples per image, seed 1): between the
// captures median 0.84 %, p95 2.9 % (seeds 1-10 with 2000 samples: scripts/nn_images_sparse.sh).
constexpr double kBetweenCapturesMedian = 0.05;  // docs/NN.md's target for such a sequence
constexpr double kBetweenCapturesP95 = 0.20;     // the default bound, kImageMaxRelativeP95
TEST_F(Cli, NnTrainImagesChecksTheCapturesBetween) {
  std::string list = "file\n";
  for (int k = 0; k < 7; ++k) {
    const auto r = run(fmt::format(
        "render --model hosek --turbidity 3 --include-sun --sun-zenith {} --sun-azimuth {} "
        "--width 96 --height 48 -o '{}/c{}.exr'",
        15 + 10 * k, 120 + 15 * k, dir_.string(), k));
    ASSERT_EQ(r.status, 0) << r.err;
    list += fmt::format("c{}.exr\n", k);
  }
  std::ofstream(dir_ / "seq.csv") << list;
  const std::string train = "nn train --images '" + (dir_ / "seq.csv").string() + "' --samples 400";
  const std::string w = (dir_ / "w.json").string();
  auto r = run(train + " -o '" + w + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("held-out captures (lines 3 5 7; the network trained on the other 4): "
                       "relative error median "),
            std::string::npos)
      << r.out;
  const nn::SkyNetwork network = load_sky_network_file(w);
  std::vector<double> errors;
  for (int k = 0; k < 6; ++k) {
    const SunPosition sun{(20.0 + 10 * k) * kDegree, (127.5 + 15 * k) * kDegree};
    const NeuralSkyModel between(NeuralSkyParameters{.sun = sun, .weights = w, .turbidity = 3.0},
                                 network);
    const HosekWilkieModel truth(HosekParameters{sun, 3.0, 0.3});  // render's default albedo
    for (int i = 0; i < 22; ++i)
      for (int j = 0; j < 45; ++j) {
        const Vec3 v = direction_from_angles((2.0 + 4 * i) * kDegree, (4.0 + 8 * j) * kDegree);
        if (angle_between(v, sun.direction()) <= 5 * kDegree) continue;  // the sun exclusion
        const Rgb a = between.rgb(v), b = truth.rgb(v);
        errors.push_back(std::abs((a.r + a.g + a.b) / (b.r + b.g + b.b) - 1.0));
      }
  }
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], kBetweenCapturesMedian);
  EXPECT_LT(errors[errors.size() * 95 / 100], kBetweenCapturesP95);

  const std::string w2 = (dir_ / "w2.json").string();
  r = run(train + " --max-error 0.5 -o '" + w2 + "'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("the captures are too sparse: held-out captures (lines 3 5 7"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(w2));
}

// A Pietras network animates through sunset into the night from an altitude: every frame is the
// library's render of the network for that sun (float EXR: the same floats), the night frame dark
// (the shadow test), and no warning about suns below the horizon (twilight is the network's).
TEST_F(Cli, NnAnimatePietrasThroughTwilight) {
  const std::string w = std::string(SKYLIGHT_TEST_DATA_DIR) + "/nn/log3.json";
  testing_support::CliResult r =
      run("nn animate --weights '" + w +
          "' --observer-altitude 1000 --from 80,250 --to 110,270 --frames 3 --width 32 "
          "--height 16 -o '" +
          dir_.string() + "/p_#.exr' --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("below the horizon"), std::string::npos) << r.err;
  const auto frame1 = nlohmann::json::parse(r.out)["frames"][1];
  EXPECT_DOUBLE_EQ(frame1["sun_zenith_deg"].get<double>(), 95.0) << r.out;
  EXPECT_DOUBLE_EQ(frame1["sun_azimuth_deg"].get<double>(), 260.0) << r.out;
  EXPECT_EQ(nlohmann::json::parse(r.out)["dark_frames"].get<int>(), 0);
  render::RenderSettings s;
  s.width = 32;
  s.height = 16;
  double peak[3] = {};
  for (int k = 0; k < 3; ++k) {
    const io::ImageF frame = io::read_image(dir_ / fmt::format("p_{}.exr", k));
    PietrasParameters p;
    p.sun = sun_from_degrees(80.0 + 15.0 * k, 250.0 + 10.0 * k);
    p.weights = w;
    p.observer_altitude_m = 1000.0;
    const render::SkyImage ref = render::render_sky(PietrasSkyModel(p), s);
    ASSERT_EQ(frame.data.size(), ref.rgb.data.size()) << k;
    for (std::size_t i = 0; i < ref.rgb.data.size(); ++i) {
      ASSERT_EQ(frame.data[i], ref.rgb.data[i]) << "frame " << k << " value " << i;
      peak[k] = std::max(peak[k], static_cast<double>(frame.data[i]));
    }
  }
  // Day at 80 degrees, twilight at 95 (the upper sky still lit), night at 110 (the sun 20 degrees
  // down: the shadow covers every view from 1 km).
  EXPECT_GT(peak[0], peak[1]);
  EXPECT_GT(peak[1], 0.0);
  EXPECT_EQ(peak[2], 0.0);
  // --turbidity is a sky network's input: refused for a Pietras network, nothing written.
  r = run("nn animate --weights '" + w +
          "' --turbidity 4 --from 30,100 --to 70,200 --frames 2 -o '" + dir_.string() +
          "/t_#.exr'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("' is a Pietras network, which has no turbidity input"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "t_0.exr"));
}

TEST_F(Cli, NnTrainImagesListErrorsNameTheRow) {
  std::ofstream(dir_ / "bad.csv") << "file,sun_zenith_deg,sun_azimuth_deg\na.exr,40,100\n"
                                     "b.exr,40\n";
  auto r = run("nn train --images '" + (dir_ / "bad.csv").string() + "' -o w.json");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("bad.csv:3: 2 cells, the header has 3"), std::string::npos) << r.err;
  std::ofstream(dir_ / "t.csv") << "file,time\nmissing.exr,2024-06-21T25:00:00Z\n";
  r = run("nn train --images '" + (dir_ / "t.csv").string() + "' --lat 1 --lon 2 -o w.json");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("t.csv:2: "), std::string::npos) << r.err;
  std::ofstream(dir_ / "n.csv") << "file,time\nmissing.exr,2024-06-21T12:00:00Z\n";
  r = run("nn train --images '" + (dir_ / "n.csv").string() + "' -o w.json");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("n.csv:2: a time needs --lat and --lon"), std::string::npos) << r.err;
  r = run("nn train --images '" + (dir_ / "bad.csv").string() + "' --source hosek -o w.json");
  EXPECT_EQ(r.status, 2) << r.err;
  for (const char* flag : {"--suns 3", "--view-zeniths 4", "--view-azimuths 5", "--network log3"}) {
    r = run("nn train --images '" + (dir_ / "bad.csv").string() + "' " + flag + " -o w.json");
    EXPECT_EQ(r.status, 2) << flag << ": " << r.err;
    EXPECT_NE(r.err.find("--images and --" +
                         std::string(flag).substr(2, std::string(flag).find(' ') - 2) +
                         " exclude each other"),
              std::string::npos)
        << flag << ": " << r.err;
  }
}

TEST_F(Cli, NnStudyTabulatesEfficiency) {
  const auto r =
      run("nn study --source preetham --hidden 2,4 --iterations 5 --suns 2 "
          "--view-zeniths 3 --view-azimuths 4 --repeats 1");
  ASSERT_EQ(r.status, 0) << r.err;
  // One row per width; the most efficient is the width of the highest eps = 1 / (Var T).
  EXPECT_NE(r.out.find("widths:\n  hidden "), std::string::npos) << r.out;
  const auto j =
      nlohmann::json::parse(run("nn study --source preetham --hidden 2,4 --iterations 5 --suns 2 "
                                "--view-zeniths 3 --view-azimuths 4 --repeats 1 --json")
                                .out);
  ASSERT_EQ(j["widths"].size(), 2u);
  const auto& w = j["widths"];
  const int best = w[0]["efficiency"] > w[1]["efficiency"] ? 2 : 4;
  EXPECT_EQ(j["most_efficient"].get<int>(), best);
  for (const auto& row : w)
    EXPECT_NEAR(row["efficiency"].get<double>(),
                1.0 / (row["variance"].get<double>() * 1e-3 * row["t_ms"].get<double>()),
                1e-9 * row["efficiency"].get<double>());
}

TEST_F(Cli, NnTrainValidateEvalPietras) {
  const std::string w = (dir_ / "p.json").string();
  testing_support::CliResult r = run(kQuickPietrasTraining + " -o '" + w + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  using testing_support::text_field;
  EXPECT_EQ(text_field(r.out, "network"), "pietras") << r.out;
  EXPECT_EQ(text_field(r.out, "weights"), "324") << r.out;
  EXPECT_EQ(text_field(r.out, "trainer"), "lbfgs") << r.out;  // --network's default
  r = run("nn validate --weights '" + w + "' --json --samples 300");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["weights_count"].get<int>(), 324);
  EXPECT_EQ(j["day"]["samples"].get<int>(), 300);
  EXPECT_EQ(j["night_network_not_dark"].get<int>() <= j["night_reference_dark"].get<int>(), true);
  // The paper network's errors come with their cause (M's floor), in JSON and in text.
  EXPECT_NE(j["note"].get<std::string>().find("M output"), std::string::npos) << r.out;
  const double scaled = j["day"]["reference_scaled_median"].get<double>();  // N / max N
  EXPECT_GT(scaled, 0.0);
  EXPECT_LT(scaled, 1.0);
  EXPECT_NE(j["note"].get<std::string>().find(fmt::format("median {:.3f} on the day set", scaled)),
            std::string::npos)
      << r.out;
  r = run("nn validate --weights '" + w + "' --samples 300");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(
      text_field(r.out, "note").rfind("the paper network's luminance error is its M output's", 0),
      0u)
      << r.out;

  // eval --model pietras on a Pietras file is the network's forward pass (the library's rgb_at).
  r = run("eval --model pietras --weights '" + w +
              "' --observer-altitude 1500 --sun-zenith 40 --sun-azimuth 180 --quantity rgb",
          "zenith_deg,azimuth_deg\n10,20\n70,200\n");
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  const auto rows = parse_csv_numbers(r.out, &header);
  ASSERT_EQ(rows.size(), 2u);
  SkyParameters p;
  p.sun = {deg_to_rad(40.0), deg_to_rad(180.0)};
  p.values.set("weights", w.c_str()).set("observer-altitude", 1500.0);
  const auto m = make_sky_model("pietras", p);
  const Rgb c = m->rgb(direction_from_angles(deg_to_rad(70.0), deg_to_rad(200.0)));
  EXPECT_NEAR(rows[1].back(), c.b, kEvalExact) << r.out;
  EXPECT_GT(c.g, 0.0);

  r = run("nn train --source hosek --network pietras --samples 100 -o '" + w + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--source must be nishita"), std::string::npos) << r.err;
}

// A smaller planet than Earth (Mars's radius, a thin atmosphere with Mars's scale height): the
// flags are the nishita schema's, recorded in provenance.source_parameters, and the loader and
// `nn validate` rebuild that planet, not Earth's.
TEST_F(Cli, NnTrainPietrasOnAnotherPlanet) {
  const std::string w = (dir_ / "mars.json").string();
  testing_support::CliResult r =
      run("nn train --source nishita --network log3 --samples 2000 --iterations 5 --max-error 1e6 "
          "--ground-radius "
          "3389500 --top-radius 3449500 --rayleigh-scale-height 11100 --mie-scale-height 1500 "
          "--mie-g 0.65 -o '" +
          w + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(w);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["ground_radius_m"].get<double>(), 3389500.0);
  EXPECT_EQ(j["top_altitude_m"].get<double>(), 60000.0);
  EXPECT_EQ(j["scale_height_m"].get<double>(), 11100.0);
  const auto& sp = j["provenance"]["source_parameters"];
  EXPECT_EQ(sp["ground-radius"].get<double>(), 3389500.0) << sp.dump();
  EXPECT_EQ(sp["mie-g"].get<double>(), 0.65) << sp.dump();
  r = run("nn validate --weights '" + w + "' --json --samples 300");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto v = nlohmann::json::parse(r.out);
  EXPECT_EQ(v["day"]["samples"].get<int>(), 300);

  r =
      run("nn train --source nishita --network log3 --samples 100 --ground-radius 6000 "
          "--top-radius 5000 -o '" +
          w + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--top-radius"), std::string::npos) << r.err;
  r = run("nn train --source preetham --ground-radius 3389500 -o '" + w + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("need --network"), std::string::npos) << r.err;

  // --init continues from the Mars file: its planet, iterations adding up.
  const std::string more = (dir_ / "mars2.json").string();
  r =
      run("nn train --source nishita --network log3 --samples 2000 --iterations 3 --max-error 1e6 "
          "--init '" +
          w + "' -o '" + more + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in2(more);
  const auto j2 = nlohmann::json::parse(in2);
  EXPECT_EQ(j2["ground_radius_m"].get<double>(), 3389500.0);
  EXPECT_EQ(j2["max_value"].get<double>(), j["max_value"].get<double>());
  EXPECT_EQ(j2["provenance"]["iterations"][0].get<int>(),
            j["provenance"]["iterations"][0].get<int>() + 3);
  const auto& its = j["provenance"]["iterations"];
  EXPECT_EQ(j2["provenance"]["trainer"].get<std::string>(),
            fmt::format("{} (to {}/{}/{} iterations), then lbfgs",
                        j["provenance"]["trainer"].get<std::string>(), its[0].get<int>(),
                        its[1].get<int>(), its[2].get<int>()));
  r = run("nn train --source nishita --network pietras --samples 2000 --init '" + w + "' -o '" +
          more + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("a log3 network"), std::string::npos) << r.err;
  r = run("nn train --source nishita --network log3 --samples 2000 --init '" + w + "' -o '" + w +
          "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("is the input --init: an output never overwrites an input"),
            std::string::npos)
      << r.err;
  r = run("nn train --source nishita --network log3 --samples 2000 --mie-g 0.7 --init '" + w +
          "' -o '" + more + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("the planet is the file's"), std::string::npos) << r.err;
  r = run("nn train --source preetham --init '" + w + "' -o '" + more + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--init needs --network"), std::string::npos) << r.err;
}

// `nn planet`: the GL vertex shader's frame from orbit and from the ground (gpu/planet_test.cpp
// compares it with the CPU network per vertex).
TEST_F(Cli, NnPlanetRendersFromOrbitAndFromTheGround) {
  const std::string w = (dir_ / "p.json").string();
  testing_support::CliResult r = run(kQuickPietrasTraining + " -o '" + w + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string orbit = (dir_ / "orbit.pfm").string(), ground = (dir_ / "ground.png").string();
  r = run("nn planet --weights '" + w +
          "' --view orbit --sun-zenith 40 --subdivisions 2 --width 48 --height 32 -o '" + orbit +
          "'");
#ifdef SKYLIGHT_HAVE_GPU
  ASSERT_EQ(r.status, 0) << r.err;
  using testing_support::text_field;
  EXPECT_EQ(text_field(r.out, "subdivisions"), "2") << r.out;
  EXPECT_EQ(text_field(r.out, "vertices"), "324") << r.out;
  EXPECT_EQ(text_field(r.out, "triangles"), "640") << r.out;
  const io::ImageF img = io::read_image(orbit);
  ASSERT_EQ(img.width, 48);
  for (float x : img.data) EXPECT_TRUE(std::isfinite(x) && x >= 0.0f);
  // Space in the corner is black.
  EXPECT_EQ(img.pixel(0, 0)[1], 0.0f);
  r = run("nn planet --weights '" + w +
          "' --view ground --sun-zenith 80 --altitude 100 --subdivisions 2 --width 48 --height 32 "
          "-o '" +
          ground + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(ground));
  r = run("nn planet --weights '" + w + "' --view ground --altitude -5 -o '" + ground + "'");
  EXPECT_EQ(r.status, 2);
#else
  testing_support::expect_built_without_gpu(r);
#endif
}

}  // namespace
}  // namespace skylight
