// The command line under bad input, faults and extreme parameters: a table of cases (arguments,
// standard input, expected exit status, the start of the message), each checked to leave no output
// and no temporary file behind; then the cases that need their own set-up (full or closed stdout,
// existing outputs that must survive a failure, legal long names, directories as inputs).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "skylight/io/file.h"
#include "support/cli_run.h"
#include "support/scratch_dir.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

using Cli = testing_support::CliTest;
using testing_support::CliResult;

// stderr of any failure is one line of at most this many bytes, whatever the input's size
// (excerpts are bounded: core/numbers.h).
constexpr std::size_t kMaxErrorBytes = 600;

struct Case {
  std::string args;   // after `skylight`; OUT is replaced by an output path in the scratch dir
  std::string input;  // standard input
  int status;
  std::string message;  // the start of stderr's first line
  // An input file: IN in args and message stands for it (written to a folder beside the outputs;
  // in the message as messages show paths, io::shown_path).
  std::string file_name = {};
  std::string file_content = {};
};

// The EXR the fuzz target image_exr found (a float attribute of size 0, then 1.6 GB asked for).
std::string planted_exr() {
  return testing_support::source_file("tests/fuzz/corpus/image_exr/regression_float_size_0.exr");
}

// A valid EXR whose channel list claims one byte more than it holds.
std::string long_channel_list_exr() {
  std::string bytes =
      testing_support::source_file("tests/fuzz/corpus/image_exr/y_half_none_3x2.exr");
  const std::size_t size_at = bytes.find(std::string("chlist\0", 7));
  if (size_at != std::string::npos) ++bytes[size_at + 7];
  return bytes;
}

const std::string kDirs = "zenith_deg,azimuth_deg\n0,0\n45,180\n";

// The 8 header lines of an EPW at 48 N, 11 E, UTC+1, and one record (month,day,hour; direct
// normal and diffuse horizontal radiation as written).
std::string epw_header() {
  return "LOCATION,X,,,,0,48,11,1,500\nDESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\nGROUND "
         "TEMPERATURES,0\nHOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\nCOMMENTS 1,\nCOMMENTS 2,\nDATA "
         "PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";
}
std::string epw_record(const std::string& date_hour, const std::string& dni,
                       const std::string& dhi) {
  return "2019," + date_hour + ",60,x,10,5,60,95000,9999,9999,9999,500," + dni + "," + dhi +
         ",999999,999999,999999,9999,0,0,0,0,0,0,9,x,999,.999,999,99,999,999,99\n";
}

std::vector<Case> cases() {
  const std::string e = "skylight: error: ";
  const std::string huge_line = "zenith_deg,azimuth_deg\n" + std::string(1 << 20, '7') + ",0\n";
  return {
      // Numbers: NaN, infinities, huge, empty, malformed, hex, just outside the range.
      {"eval --model preetham --turbidity nan", kDirs, 2, e + "--turbidity: 'nan' is not a number"},
      {"eval --model preetham --turbidity inf", kDirs, 2, e + "--turbidity: 'inf' is not a number"},
      {"eval --model preetham --turbidity -1e308", kDirs, 2, e + "--turbidity = -1e+308"},
      {"eval --model preetham --turbidity 1e", kDirs, 2, e + "--turbidity: '1e' is not a number"},
      {"sh fit --model cie --range 5,2 -o OUT.json", "", 2,
       e + "--range: a fit in the sun zenith only has no second parameter (model 'cie'"},
      {"eval --model cie --zenith-luminance 1e-400", kDirs, 2,
       e + "--zenith-luminance: '1e-400' underflows to 0"},
      {"eval --model preetham --turbidity 1e400", kDirs, 2, e + "--turbidity: '1e400' overflows"},
      {"--threads 0x10 eval --model cie", kDirs, 2, e + "--threads: '0x10' is not an integer"},
      {"eval --model cie --threads 4096", kDirs, 2, e + "--threads = 4096 is outside [1, 1024]"},
      {"eval --model preetham --turbidity 0x3", kDirs, 2, e + "--turbidity: '0x3'"},
      {"eval --model preetham --turbidity ''", kDirs, 2, e + "--turbidity: '' is not a number"},
      {"eval --model preetham --turbidity 64.0001", kDirs, 2, e + "--turbidity = 64.0001"},
      {"eval --model hosek --turbidity 10.5", kDirs, 2,
       e + "--turbidity = 10.5 is outside [1, 10]"},
      {"eval --model cie --sun-zenith 180.1", kDirs, 2, e},
      {"eval --model cie --cie-type 2.5", kDirs, 2, e + "--cie-type: '2.5' is not an integer"},
      {"eval --model perez --perez 1,2,3,4,5, --zenith-luminance 1", kDirs, 2,
       e + "--perez: element 6 of '1,2,3,4,5,' is empty"},
      {"eval --model preetham --quantity spectral --wavelengths 550,,650", kDirs, 2,
       e + "--wavelengths: element 2 of '550,,650' is empty"},
      // Perez coefficients that overflow the output are refused, not rendered as Inf/NaN.
      {"render --model perez --perez 50,50,50,50,50 --zenith-luminance 1e9 --width 8 --height 4 "
       "-o OUT.exr",
       "", 2, e + "--perez 50,50,50,50,50 with --zenith-luminance 1000000000 overflows"},
      {"render --model perez --perez 5.5,1.083,47.27,31.17,42.89 --zenith-luminance 5000 "
       "--sun-zenith 30 --width 8 --height 4 -o OUT.exr",
       "", 2, e + "--perez 5.5,1.083,47.27,31.17,42.89"},
      // CSV input: bad numbers, bad header, huge and control-character lines quoted briefly.
      {"eval --model cie", "zenith_deg,azimuth_deg\n0x10,0\n", 2,
       e + "<stdin> line 2: zenith_deg '0x10' is not a number"},
      {"eval --model cie", "zenith,azimuth\n", 2, e + "<stdin> line 1: header must be"},
      {"eval --model cie", "", 2, e + "<stdin>: empty input"},
      {"eval --model cie", huge_line, 2, e + "<stdin> line 2: zenith_deg '7777"},
      {"eval --model cie", std::string("zenith_deg,azimuth_deg\n1\x1b[31m,0\n"), 2,
       e + "<stdin> line 2: zenith_deg '1\\x1b[31m'"},
      // Projections and sizes.
      {"render --model cie --projection fisheye --lens stereographic --fov 360 -o OUT.exr", "", 2,
       e + "fov = 360 deg is outside (0, 360) for the stereographic lens"},
      {"render --model cie --width 32769 -o OUT.exr", "", 2, e},
      {"render --model cie --width 32768 --height 32768 -o OUT.exr", "", 1,
       e + "rendering a 32768x32768 image needs about"},
      // Files: a missing input and an output's format are usage errors found before any work.
      {"eval --model cie --input /nonexistent/dirs.csv", "", 2,
       e + "--input '/nonexistent/dirs.csv': no such file"},
      {"render --model cie --width 8 --height 4 -o OUT.txt", "", 2,
       e + "-o 'OUT.txt': write .exr, .hdr, .pfm or .png"},
      {"report --quick --measurements /nonexistent/scan.csv -o OUT", "", 2,
       e + "--measurements '/nonexistent/scan.csv': no such file"},
      // EXR headers that OpenEXR and our walk would read differently (issue 28 item 10).
      {"estimate --image IN", "", 1,
       e + "cannot read 'IN': not a valid OpenEXR file: attribute 'pixelAspectRatio' of type "
           "float has 0 bytes, not 4",
       "sky.exr", planted_exr()},
      {"estimate --image IN", "", 1,
       e + "cannot read 'IN': not a valid OpenEXR file: channel list 'channels' does not fill its",
       "y.exr", long_channel_list_exr()},
      // EPW weather files (issue 32): a bad field, a truncated header, and a record the sky
      // cannot use; nothing written.
      {"daylight --epw IN -o OUT.csv", "", 2,
       e + "IN line 9: field 15 (direct normal radiation) 'x' is not a number", "w.epw",
       epw_header() + epw_record("6,21,13", "x", "100")},
      {"daylight --epw IN -o OUT.csv", "", 2,
       e + "IN line 3: header line 3 must start with 'TYPICAL/EXTREME PERIODS', got 'DATA PERIODS'",
       "h.epw", "LOCATION,X,,,,0,48,11,1,500\nDESIGN CONDITIONS,0\nDATA PERIODS,1\n"},
      {"daylight --epw IN -o OUT.npy", "", 2,
       e + "IN line 9: the sun is up (65.32 deg) and the diffuse horizontal radiation is missing",
       "m.epw", epw_header() + epw_record("6,21,13", "500", "9999")},
      {"daylight --dni 1500 --dhi 100 --sun-zenith 30 --day-of-year 1", "", 2,
       e + "--dni = 1500 W/m^2 exceeds the extraterrestrial irradiance 1414.9 W/m^2 of day 1"},
      // A file name with a newline stays on the message's one line.
      {"haze attenuation --turbidity 3 --distance 5000 --camera-csv IN", "", 2,
       e + "IN line 1: the header must be 'nm,r,g,b'", "cam\nera.csv", "nm,r,g\n380,1,1\n"},
  };
}

// No output and no temporary: the scratch directory holds nothing else after a failure.
void expect_nothing_written(const fs::path& dir, const std::string& what) {
  for (const auto& entry : fs::directory_iterator(dir)) ADD_FAILURE() << what << " left " << entry;
}

TEST_F(Cli, BadInputMatrix) {
  int held = 0;
  const auto all = cases();
  for (const auto& c : all) {
    std::string args = c.args;
    const std::string out = fmt::format("'{}'", (dir_ / "out").string());
    for (std::size_t at; (at = args.find("OUT")) != std::string::npos;) args.replace(at, 3, out);
    std::string message = c.message;
    // OUT in a message: the output's path as messages show it (no quotes of the shell).
    for (std::size_t at; (at = message.find("OUT")) != std::string::npos;)
      message.replace(at, 3, (dir_ / "out").string());
    const fs::path inputs = dir_.parent_path() / (dir_.filename().string() + "-inputs");
    if (!c.file_name.empty()) {
      fs::create_directories(inputs);
      const fs::path in = inputs / c.file_name;
      std::ofstream(in, std::ios::binary) << c.file_content;
      args.replace(args.find("IN"), 2, "'" + in.string() + "'");
      message.replace(message.find("IN"), 2, io::shown_path(in));
    }
    const CliResult r = run(args, c.input);
    if (!c.file_name.empty()) fs::remove_all(inputs);
    const bool ok = r.status == c.status && r.err.rfind(message, 0) == 0 &&
                    r.err.size() <= kMaxErrorBytes &&
                    r.err.find('\n') == r.err.size() - 1;  // one line
    EXPECT_TRUE(ok) << "skylight " << c.args << "\n  status " << r.status << " (want " << c.status
                    << ")\n  stderr: " << r.err.substr(0, 300);
    expect_nothing_written(dir_, c.args);
    held += ok;
  }
  std::printf("bad-input matrix: %d of %zu cases held\n", held, all.size());
}

TEST_F(Cli, WriteErrorsOnStandardOutputFail) {
  const auto in = dir_ / "dirs.csv";
  std::ofstream(in) << kDirs;
  for (const std::string& cmd : std::vector<std::string>{
           "models", "models --json", "eval --model cie --input '" + in.string() + "'",
           "bench --width 8 --height 4 --repeats 1 --models cie", "eval --help", "--version"}) {
    for (const char* redirect : {"> /dev/full", ">&-"}) {
      const std::string line = std::string("'") + SKYLIGHT_CLI_PATH + "' " + cmd + " " + redirect +
                               " 2> '" + (dir_ / "err.txt").string() + "'";
      const int raw = std::system(line.c_str());
      EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 1) << cmd << " " << redirect;
      EXPECT_EQ(
          slurp(dir_ / "err.txt").rfind("skylight: error: cannot write to standard output", 0), 0u)
          << cmd << " " << redirect << ": " << slurp(dir_ / "err.txt");
    }
  }
}

TEST_F(Cli, AFailedCommandLeavesExistingOutputsUntouched) {
  const auto out = dir_ / "k.exr";
  ASSERT_EQ(run("render --model cie --width 8 --height 4 -o '" + out.string() + "'").status, 0);
  const std::string before = slurp(out);
  const auto r = run("render --model preetham --width 8 --height 4 -o '" + out.string() +
                     "' --preview /nonexistent/p.png");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(slurp(out), before);
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename(), "k.exr") << "left behind: " << e.path();
  // A report that fails leaves no directory behind: before any work (a missing input) and during
  // it (a scan that does not parse, read after the directory was made).
  const auto rep = dir_ / "report";
  EXPECT_EQ(run("report --quick --measurements /nonexistent.csv -o '" + rep.string() + "'").status,
            2);
  EXPECT_FALSE(fs::exists(rep));
  const auto scan = dir_.parent_path() / (dir_.filename().string() + "-scan.csv");
  std::ofstream(scan) << "azimuth_deg,elevation_deg,luminance_cd_m2\n0,6,x\n";
  EXPECT_EQ(
      run("report --quick --measurements '" + scan.string() + "' -o '" + rep.string() + "'").status,
      2);
  fs::remove(scan);
  EXPECT_FALSE(fs::exists(rep));
}

TEST_F(Cli, LegalLongFileNamesAndDirectoriesAsInputs) {
  const std::string name = std::string(251, 'a') + ".exr";  // 255 bytes: the longest legal name
  ASSERT_EQ(
      run("render --model cie --width 8 --height 4 -o '" + (dir_ / name).string() + "'").status, 0);
  EXPECT_TRUE(fs::exists(dir_ / name));
  fs::remove(dir_ / name);
  const auto sub = dir_ / "d";
  fs::create_directories(sub);
  auto r = run("eval --model cie --input '" + sub.string() + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "skylight: error: --input '" + sub.string() + "': is a directory\n");
  const std::string line = std::string("'") + SKYLIGHT_CLI_PATH + "' eval --model cie < '" +
                           sub.string() + "' 2> '" + (dir_ / "err.txt").string() + "'";
  const int raw = std::system(line.c_str());
  EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 1);
  EXPECT_EQ(slurp(dir_ / "err.txt"),
            "skylight: error: cannot read standard input: Is a directory\n");
  r = run("report --quick --measurements '" + sub.string() + "' -o '" + (dir_ / "r").string() +
          "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("is a directory"), std::string::npos) << r.err;
}

TEST_F(Cli, SolarDiscBelowTheHorizonIsDark) {
  const std::string below = "zenith_deg,azimuth_deg\n90.01,180\n";
  for (const std::string model :
       {"hosek --sun-zenith 89.99 --sun-only", "preetham --sun-zenith 90 --include-sun"}) {
    const auto r = run("eval --model " + model + " --quantity luminance", below);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "zenith_deg,azimuth_deg,luminance\n90.01,180,0\n") << model;
  }
}

TEST_F(Cli, ReportAcceptsTheSunAtTheHorizon) {
  const auto r =
      run("report --quick --sun-elevation 0 --sun-azimuth 180 -o '" + (dir_ / "r").string() + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "r" / "index.html"));
}

}  // namespace
}  // namespace skylight
