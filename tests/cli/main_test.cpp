// End-to-end tests of the command line as a whole (exit statuses, global options): real processes,
// real files.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/io/image.h"
#include "skylight/models/sky_model.h"
#include "support/cli_run.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;

// Every help page, found by walking the "Subcommands:" lists from the top: the group pages (nn, sh,
// haze) and the leaves list the global --threads; a command's line in its parent's list fits in
// HelpFormatter::kHelpWidth columns; values read as a manual (INT, NUMBER, {a|b}; no CLI11
// "TEXT:1" or "INT:INT", no "[1]" unit, integers written whole).
TEST_F(Cli, EveryHelpPageReadsLikeAManual) {
  constexpr std::size_t kWidth = 100;  // HelpFormatter::kHelpWidth
  std::vector<std::string> pages = {""};
  std::size_t visited = 0;
  for (std::size_t i = 0; i < pages.size(); ++i, ++visited) {
    const std::string page = pages[i];  // a copy: pages grows below
    const testing_support::CliResult r = run(page + (page.empty() ? "" : " ") + "--help");
    ASSERT_EQ(r.status, 0) << page;
    std::istringstream lines(r.out);
    bool listing = false;
    for (std::string line; std::getline(lines, line);) {
      if (line == "Subcommands:") {
        listing = true;
        continue;
      }
      if (line.empty()) listing = false;
      if (listing) {
        EXPECT_LE(line.size(), kWidth) << page << ": " << line;
        pages.push_back(page + (page.empty() ? "" : " ") + line.substr(2, line.find(' ', 2) - 2));
      }
    }
    if (!page.empty()) {
      EXPECT_NE(r.out.find("Global option (before or after the subcommand):\n  --threads INT"),
                std::string::npos)
          << page << ":\n"
          << r.out;
    }
    for (const char* noise : {"TEXT:", "INT:", "NUMBER:", ":deg", "[1]", "2.14748e+09"})
      EXPECT_EQ(r.out.find(noise), std::string::npos) << page << ": '" << noise << "' in\n"
                                                      << r.out;
  }
  // The top page, 3 groups, every leaf.
  EXPECT_GE(visited, 30u);
  const testing_support::CliResult est = run("estimate --help");
  EXPECT_NE(est.out.find("--seed INT "), std::string::npos) << est.out;
  EXPECT_NE(est.out.find("0 .. 2147483647; default 1"), std::string::npos) << est.out;
  EXPECT_NE(est.out.find("2 .. 1000000;"), std::string::npos) << est.out;  // --samples
  EXPECT_NE(est.out.find("--model {preetham|cie|hosek|nishita|hillaire|bruneton|nn|sh}"),
            std::string::npos)
      << est.out;
  EXPECT_NE(run("render --help").out.find("--false-colour-range N,N "), std::string::npos);
}

// A value outside its range: the one line names the flag as typed ("--lat = 91", not CLI11's
// "--lat: = 91").
TEST_F(Cli, OutOfRangeValuesNameTheirFlag) {
  const testing_support::CliResult r = run("sun --time 2003-10-17T12:30:30-07:00 --lat 91 --lon 0");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "skylight: error: --lat = 91 is outside [-90, 90]\n");
  const testing_support::CliResult w = run("render --model preetham --width 0 -o x.exr");
  EXPECT_EQ(w.status, 2);
  EXPECT_EQ(w.err, "skylight: error: --width = 0 is outside [1, 32768]\n");
  const testing_support::CliResult z = run("sun --time 2003-10-17T12:30:30+25:00 --lat 0 --lon 0");
  EXPECT_EQ(z.status, 2);
  EXPECT_NE(z.err.find("UTC offset: +25:00 is beyond +-18:00"), std::string::npos) << z.err;
}

// A mistyped flag, subcommand, model or camera: exit 2, one line naming it and the nearest known
// name (core/text.h: within a third of its length), nothing for a word that is no typo.
TEST_F(Cli, TyposAreNamedWithTheNearestName) {
  struct Case {
    std::string args, line;
  };
  const Case cases[] = {
      // An operation's unknown names are the library's to refuse (operations::prepare): the same
      // message every front end gives, spelled as it spells names.
      {"render --turbidty 3",
       "skylight: error: --turbidty is not a parameter of render; did you mean '--turbidity'?"},
      {"render --model preetham --sun-azimuth -30 --frobnicate -o x.exr",
       "skylight: error: --frobnicate is not a parameter of render or of model 'preetham'"},
      {"--threads 2 rendr",
       "skylight: error: unknown subcommand 'rendr'; did you mean 'render'? (subcommands: models, "
       "operations, render, eval, estimate, measured, sun, daylight, irradiance, bench, report, "
       "sh, "
       "haze, nn, view)"},
      {"frobnicate",
       "skylight: error: unknown subcommand 'frobnicate' (subcommands: models, "
       "operations, render, eval, estimate, measured, sun, daylight, irradiance, bench, report, "
       "sh, "
       "haze, nn, view)"},
      {"nn trian --samples 10",
       "skylight: error: unknown subcommand 'trian' for 'nn'; did you mean 'train'? (subcommands: "
       "train, validate, export, animate, study, planet)"},
      {"sh eval --sun-zenit 30",
       "skylight: error: --sun-zenit is not a parameter of sh eval; did you mean "
       "'--sun-zenith'?"},
      {"eval --model preethm",
       "skylight: error: --model = 'preethm' is not one of "
       "perez|preetham|cie|hosek|nishita|hillaire|bruneton|nn|pietras|sh; did you mean "
       "'preetham'?"},
      {"nn train --source hosk -o x.json",
       "skylight: error: --source: unknown model 'hosk'; did you mean 'hosek'? (known: perez, "
       "preetham, cie, hosek, nishita, hillaire, bruneton, nn, pietras, sh)"},
      {"bench --models preetham,hosk",
       "skylight: error: --models: unknown model 'hosk'; did you mean 'hosek'? (known: perez, "
       "preetham, cie, hosek, nishita, hillaire, bruneton, nn, pietras, sh)"},
      {"sh fit --model preethm -o x.json",
       "skylight: error: --model = 'preethm' is not one of "
       "perez|preetham|cie|hosek|nishita|hillaire|bruneton|nn|pietras; did you mean 'preetham'?"},
      {"render --model cie --projection fisheey -o x.exr",
       "skylight: error: --projection = 'fisheey' is not one of "
       "equirect|hemisphere|fisheye|cubemap|camera; did you mean 'fisheye'?"},
      {"haze attenuation --camera canon-eos-5 --turbidity 3 --distance 1000",
       "skylight: error: unknown camera 'canon-eos-5'; did you mean 'canon-eos-5d'? (`skylight "
       "haze cameras` lists the 40; or --camera-csv)"},
  };
  for (const auto& c : cases) {
    const testing_support::CliResult r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err, c.line + "\n") << c.args;
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
}

TEST_F(Cli, BadInputExitsTwoWithMessage) {
  struct Case {
    std::string args, input, must_contain;
  };
  const std::string ok_in = "zenith_deg,azimuth_deg\n10,10\n";
  const Case cases[] = {
      {"eval --model preetham --turbidity 0.5", ok_in, "--turbidity"},
      {"eval --model preetham --turbidity nan", ok_in, "nan"},
      {"eval --model preetham --sun-zenith 200", ok_in, "--sun-zenith"},
      {"eval --model preetham --sun-zenith 10 --sun-elevation 10", ok_in,
       "--sun-zenith and --sun-elevation exclude each other"},
      {"eval --model nope", ok_in, "--model = 'nope' is not one of"},
      {"eval --model cie --cie-type 17", ok_in, "--cie-type"},
      {"eval --model perez --zenith-luminance 10", ok_in, "--perez"},
      {"eval --model preetham", "zenith,azimuth\n1,2\n", "header"},
      {"eval --model preetham", "zenith_deg,azimuth_deg\n10,abc\n", "line 2: azimuth_deg 'abc'"},
      {"eval --model preetham", "zenith_deg,azimuth_deg\n181,0\n", "line 2: zenith_deg = 181"},
      {"eval --model preetham", "zenith_deg,azimuth_deg\n1,2,3\n", "line 2"},
      {"eval --model cie --quantity spectral --wavelengths 500", ok_in, "no spectral output"},
      {"eval --model preetham --quantity spectral", ok_in, "--wavelengths"},
      {"eval --model cie --include-sun", ok_in, "has no sun"},
      {"render --model cie --width 0 -o x.exr", "", "--width"},
      {"render --model cie --width 10 --height 10 -o x.jpg", "", "x.jpg"},
      {"render --model cie --projection cubemap --width 10 --height 10 -o x.exr", "", "cubemap"},
      {"render --model cie --projection fisheye --lens orthographic --fov 200 -o x.exr", "", "fov"},
      {"render --model cie", "", "-o is required"},
      {"eval --model nishita --observer-altitude -5", ok_in, "--observer-altitude"},
      {"eval --model nishita --observer-altitude 2e7", ok_in, "--observer-altitude"},
      {"eval --model nishita --solar-irradiance 0", ok_in, "--solar-irradiance"},
      {"eval --model nishita --mie-g 1", ok_in, "--mie-g"},
      {"eval --model nishita --ground-radius 1e6 --top-radius 9e5", ok_in, "--top-radius"},
  };
  for (const auto& c : cases) {
    const testing_support::CliResult r = run(c.args, c.input);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.must_contain), std::string::npos) << c.args << "\nstderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_TRUE(r.out.empty() || r.out.find("zenith_deg") == std::string::npos)
        << "no partial output: " << r.out;
  }
}

TEST_F(Cli, RuntimeFailuresExitOne) {
  // A missing input is a usage error, found before any work (operations::prepare); a directory
  // that does not exist for an output is an I/O error, found then too.
  testing_support::CliResult r =
      run("eval --model cie --input '" + (dir_ / "missing.csv").string() + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("missing.csv': no such file"), std::string::npos);
  r = run("render --model cie --width 8 --height 4 -o '" + (dir_ / "no/such/dir/x.exr").string() +
          "'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "no"));
}

TEST_F(Cli, FlagsUseTheStrictNumberParser) {
  const std::string csv = "zenith_deg,azimuth_deg\n0,0\n";
  for (const char* bad :
       {"--turbidity 0x3", "--turbidity 3e", "--sun-zenith 1e400", "--turbidity ''",
        "--perez 1,2,3,4,5, --zenith-luminance 1", "--perez 1,,2,3,4,5 --zenith-luminance 1"}) {
    const std::string model =
        std::string(bad).find("perez") != std::string::npos ? "perez" : "preetham";
    const auto r = run("eval --model " + model + " " + bad, csv);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
    EXPECT_EQ(r.err.rfind("skylight: error: ", 0), 0u) << r.err;
  }
  // Subnormal values in range are numbers.
  const auto r = run("eval --model cie --zenith-luminance 1e-9 --sun-azimuth 1e-310", csv);
  EXPECT_EQ(r.status, 0) << r.err;
}

// README ("a model flag the chosen model does not read is ignored with a warning"), for every
// registered model: a flag another model declares, given with a value valid for that model, is
// named in a warning and the command succeeds.
TEST_F(Cli, EveryModelWarnsOfAModelFlagItDoesNotRead) {
  const std::string csv = "zenith_deg,azimuth_deg\n30,90\n";
  for (const ModelInfo& m : model_registry()) {
    std::string args = "eval --model " + m.name + testing_support::example_flags(m);
    // The first parameter of another model that this one does not declare.
    const ParameterSpec* foreign = nullptr;
    for (const ModelInfo& other : model_registry())
      for (const ParameterSpec& spec : other.parameters)
        if (!foreign && spec.kind != ParameterKind::flag && !m.find_parameter(spec.name) &&
            std::holds_alternative<ParameterValue>(spec.default_value))
          foreign = &spec;
    ASSERT_NE(foreign, nullptr) << m.name;
    args += fmt::format(" {} {}", foreign->flag(),
                        foreign->format(std::get<ParameterValue>(foreign->default_value)));
    const auto r = run(args, csv);
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
    EXPECT_NE(r.err.find("skylight: warning: " + foreign->flag() +
                         " is not a parameter of model '" + m.name + "'; ignored\n"),
              std::string::npos)
        << args << ": " << r.err;
  }
}

// A command's outputs are one transaction (io::OutputTransaction): an output that cannot be
// written leaves the others unwritten; two outputs naming one file, or an output naming an input,
// are a usage error and nothing is written.
TEST_F(Cli, OutputsCommitTogetherAndNeverCollide) {
  const std::string train =
      "nn train --source preetham --iterations 3 --starts 1 --start-iterations 1 --max-error 1e6 ";
  fs::create_directory(dir_ / "logdir");
  auto r = run(train + "-o '" + (dir_ / "w.json").string() + "' --log '" +
               (dir_ / "logdir").string() + "'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("logdir': is a directory"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "w.json")) << "the weights were written without their log";
  EXPECT_EQ(r.err.find("wrote"), std::string::npos) << "claims a file it did not write: " << r.err;
  const std::string x = (dir_ / "x").string();
  r = run(train + "-o '" + x + "' --log '" + x + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err,
            "skylight: error: -o and --log name the same file '" + x + "'; give each its own\n");
  EXPECT_FALSE(fs::exists(x));
  const std::string png = (dir_ / "p.png").string();
  r = run("render --model cie --width 8 --height 4 -o '" + png + "' --false-colour '" + png + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(fs::exists(png));
  // haze add -o over its own --image: refused by the transaction, the image untouched.
  const std::string image = (dir_ / "i.exr").string();
  ASSERT_EQ(run("render --model cie --width 8 --height 4 -o '" + image + "'").status, 0);
  const std::string image_bytes = testing_support::CliTest::slurp(image);
  r = run("haze add --image '" + image + "' --depth '" + image +
          "' --turbidity 3 --camera canon-eos-5d --airlight 1,1,1 -o '" + image + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(
      r.err.find("-o '" + image + "' is the input --image: an output never overwrites an input"),
      std::string::npos)
      << r.err;
  EXPECT_EQ(testing_support::CliTest::slurp(image), image_bytes);
  // nn train --init W -o W: the weights it continues from are an input.
  const std::string w = (dir_ / "p.json").string();
  r =
      run("nn train --source nishita --network pietras --samples 200 --iterations 1 --max-error "
          "1e6 -o '" +
          w + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  // "wrote" comes after the commit (Result::notices), on stderr, last.
  EXPECT_TRUE(r.err.ends_with("skylight: wrote " + w + "\n")) << r.err;
  const std::string before = testing_support::CliTest::slurp(w);
  r =
      run("nn train --source nishita --network pietras --samples 200 --iterations 1 --max-error "
          "1e6 --init '" +
          w + "' -o '" + w + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("-o '" + w + "' is the input --init"), std::string::npos) << r.err;
  EXPECT_EQ(testing_support::CliTest::slurp(w), before);
}

// kill -9 in the middle of a command leaves at most its temporaries, which the next command that
// writes there removes: a rerun succeeds and nothing of the killed run is left.
TEST_F(Cli, ARerunAfterKillNineLeavesNothingBehind) {
  const fs::path report = dir_ / "report", log = dir_ / "train.csv", w = dir_ / "w.json";
  const auto killed_after = [](const std::string& args, const char* seconds) {
    const std::string cmd = std::string("timeout -s KILL ") + seconds + " '" + SKYLIGHT_CLI_PATH +
                            "' " + args + " > /dev/null 2>&1";
    const int raw = std::system(cmd.c_str());
    EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 128 + 9) << cmd << ": " << raw;
  };
  killed_after("report -o '" + report.string() + "'", "2");
  killed_after("nn train --source preetham --iterations 100000 --max-error 1e6 -o '" + w.string() +
                   "' --log '" + log.string() + "'",
               "1.5");
  EXPECT_FALSE(fs::exists(w));
  auto r = run("report --quick -o '" + report.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r =
      run("nn train --source preetham --iterations 3 --starts 1 --start-iterations 1 --max-error "
          "1e6 -o '" +
          w.string() + "' --log '" + log.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const fs::path& d : {report, dir_})
    for (const auto& e : fs::directory_iterator(d))
      EXPECT_NE(e.path().filename().string().rfind(".skylight-", 0), 0u)
          << "left behind: " << e.path();
  EXPECT_TRUE(fs::exists(report / "index.html"));
  EXPECT_TRUE(fs::exists(w));
}

TEST_F(Cli, AFlagTheModelDoesNotReadIsAWarning) {
  const auto r = run("eval --model cie --turbidity 5", "zenith_deg,azimuth_deg\n0,0\n");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("skylight: warning: --turbidity is not a parameter of model 'cie'"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace skylight
