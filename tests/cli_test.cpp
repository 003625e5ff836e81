// End-to-end tests of the `skylight` command line: real processes, real files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "skylight/core/colorimetry.h"
#include "skylight/core/frame.h"
#include "skylight/io/image.h"

namespace fs = std::filesystem;

namespace skylight {
namespace {

// The render path is the float SIMD batch; eval is the double scalar path: they agree to the
// batch tolerance (2e-5 relative, see batch_test.cpp) plus float storage (6e-8).
constexpr double kRenderVsEvalRelTol = 3e-5;
// hosek: its batch bound (1e-5, hosek_wilkie_test.cpp) plus the XYZ -> sRGB matrix and float
// storage; a channel that nearly cancels in the matrix gets relatively more.
constexpr double kHosekRenderVsEvalRelTol = 1e-4;

struct Result {
  int status = -1;
  std::string out, err;
};

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("skylight_cli_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `skylight ARGS` with `input` on stdin.
  Result run(const std::string& args, const std::string& input = "") {
    const fs::path in = dir_ / "stdin.txt", out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    std::ofstream(in) << input;
    const std::string cmd = std::string("'") + SKYLIGHT_CLI_PATH + "' " + args + " < '" +
                            in.string() + "' > '" + out.string() + "' 2> '" + err.string() + "'";
    const int raw = std::system(cmd.c_str());
    Result r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream f(p);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }
  fs::path dir_;
};

std::vector<std::vector<double>> parse_csv_numbers(const std::string& text, std::string* header) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, *header);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream ls(line);
    std::string f;
    while (std::getline(ls, f, ',')) row.push_back(std::stod(f));
    rows.push_back(row);
  }
  return rows;
}

TEST_F(Cli, RenderedExrPixelMatchesEval) {
  const std::string model = "--model preetham --turbidity 3.5 --sun-zenith 50 --sun-azimuth 120";
  const fs::path exr = dir_ / "sky.exr";
  const Result r = run("render " + model + " --width 64 --height 32 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF img = io::read_image(exr);
  ASSERT_EQ(img.width, 64);
  ASSERT_EQ(img.height, 32);
  ASSERT_EQ(img.channels, 3);
  // Pixel (col 20, row 9) of a 64x32 equirect: theta = 180 * 9.5/32, phi = 360 * 20.5/64.
  const double zen = 180.0 * 9.5 / 32.0, az = 360.0 * 20.5 / 64.0;
  const Result e =
      run("eval " + model + " --quantity rgb",
          "zenith_deg,azimuth_deg\n" + std::to_string(zen) + "," + std::to_string(az) + "\n");
  ASSERT_EQ(e.status, 0) << e.err;
  std::string header;
  const auto rows = parse_csv_numbers(e.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,r,g,b");
  ASSERT_EQ(rows.size(), 1u);
  const float* px = img.pixel(20, 9);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(px[c], rows[0][2 + c], std::abs(rows[0][2 + c]) * kRenderVsEvalRelTol)
        << "channel " << c;
  // Lower half (below the horizon) is 0 for the analytic skies.
  EXPECT_EQ(img.pixel(20, 25)[1], 0.0f);
  // Every parameter and the version are recorded.
  const auto md = io::read_exr_metadata(exr);
  auto find = [&](const std::string& k) {
    for (const auto& [key, value] : md)
      if (key == k) return value;
    return std::string("<missing>");
  };
  EXPECT_EQ(find("skylight:model"), "preetham");
  EXPECT_EQ(find("skylight:turbidity"), "3.5");
  EXPECT_EQ(find("skylight:sun_zenith_deg"), "50");
  EXPECT_NE(find("skylight:version"), "<missing>");
}

TEST_F(Cli, RenderAllFormatsAndProjections) {
  for (const char* ext : {"exr", "hdr", "pfm", "png"}) {
    const fs::path p = dir_ / (std::string("a.") + ext);
    const Result r =
        run("render --model cie --cie-type 7 --width 24 --height 12 -o '" + p.string() + "'");
    EXPECT_EQ(r.status, 0) << ext << ": " << r.err;
    EXPECT_GT(fs::file_size(p), 0u) << ext;
  }
  const fs::path fc = dir_ / "fc.png", fe = dir_ / "fe.exr";
  Result r =
      run("render --model preetham --projection fisheye --lens equisolid --fov 180 --width 40 "
          "--height 40 -o '" +
          fe.string() + "' --false-colour '" + fc.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF img = io::read_image(fe);
  EXPECT_EQ(img.pixel(0, 0)[1], 0.0f) << "corner outside the image circle";
  EXPECT_GT(img.pixel(20, 20)[1], 0.0f) << "zenith";
  EXPECT_TRUE(fs::exists(fc));
  r = run("render --model cie --projection cubemap --width 60 --height 10 -o '" +
          (dir_ / "c.exr").string() + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  r = run("render --model cie --projection hemisphere --width 20 --height 10 -o '" +
          (dir_ / "h.pfm").string() + "'");
  EXPECT_EQ(r.status, 0) << r.err;
  // The sun disc adds a pixel far brighter than the sky.
  r = run("render --model preetham --sun-zenith 45 --include-sun --width 2048 --height 1024 -o '" +
          (dir_ / "s.pfm").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF sun = io::read_image(dir_ / "s.pfm");
  float peak = 0;
  for (int x = 0; x < sun.width; ++x)
    for (int y = 0; y < sun.height; ++y) peak = std::max(peak, sun.pixel(x, y)[1]);
  EXPECT_GT(peak, 1e8f);
}

TEST_F(Cli, EvalQuantities) {
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n60,90\n";
  Result r = run("eval --model cie --cie-type 16 --zenith-luminance 3000 --quantity luminance", in);
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  auto rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,luminance");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0][2], 3000.0);
  EXPECT_NEAR(rows[1][2], 2000.0, 1e-9);  // (1 + 2 cos 60) / 3 = 2/3
  r = run("eval --model preetham --quantity xyz", in);
  ASSERT_EQ(r.status, 0) << r.err;
  rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,x,y,z");
  r = run("eval --model preetham --quantity spectral --wavelengths 450,550,650", in);
  ASSERT_EQ(r.status, 0) << r.err;
  rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,L450,L550,L650");
  EXPECT_GT(rows[0][2], rows[0][4]) << "blue sky";
  // Round-trip precision: the printed numbers re-parse to the same double.
  r =
      run("eval --model perez --perez -1,-0.32,10,-3,0.45 --zenith-luminance 1234.5 --quantity "
          "luminance",
          in);
  ASSERT_EQ(r.status, 0) << r.err;
  rows = parse_csv_numbers(r.out, &header);
  EXPECT_DOUBLE_EQ(rows[0][2], 1234.5);
  // --input file works like stdin.
  std::ofstream(dir_ / "in.csv") << in;
  r = run("eval --model cie --input '" + (dir_ / "in.csv").string() + "' --quantity luminance");
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(Cli, EvalNishitaUnitIrradianceAndObserverAltitude) {
  // zenith, horizon (north), 30 deg below the horizon (south).
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n90,0\n120,180\n";
  Result r =
      run("eval --model nishita --sun-elevation 30 --solar-irradiance 1 --quantity "
          "spectral --wavelengths 440,550,680",
          in);
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  auto rows = parse_csv_numbers(r.out, &header);
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,L440,L550,L680");
  ASSERT_EQ(rows.size(), 3u);
  // Per unit irradiance [sr^-1]: a clear zenith scatters ~1 % sr^-1 at 440 nm, bluer than red.
  EXPECT_GT(rows[0][2], 0.005);
  EXPECT_LT(rows[0][2], 0.03);
  EXPECT_GT(rows[0][2], 3 * rows[0][4]) << "blue zenith";
  EXPECT_EQ(rows[2][2], 0.0) << "observer on the ground looking down: no air in between";
  // From 400 km: the horizontal ray passes above the atmosphere (0), the zenith sees nothing, the
  // planet below is bright.
  r =
      run("eval --model nishita --sun-elevation 30 --solar-irradiance 1 --observer-altitude 4e5 "
          "--quantity spectral --wavelengths 440,550,680",
          in);
  ASSERT_EQ(r.status, 0) << r.err;
  rows = parse_csv_numbers(r.out, &header);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0][3], 0.0);
  EXPECT_EQ(rows[1][3], 0.0);
  EXPECT_GT(rows[2][2], 0.01);
}

TEST_F(Cli, EvalNishitaOzoneAbsorbsInTheChappuisBand) {
  // Sun at 2 deg: the zenith's light crosses the ozone layer obliquely. Ozone only absorbs, most
  // near 600 nm (cross-section 5.2e-25 m^2 vs 6.6e-27 at 440 nm).
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n";
  const std::string q =
      "eval --model nishita --sun-elevation 2 --solar-irradiance 1 --quantity "
      "spectral --wavelengths 440,600";
  const Result a = run(q, in), b = run(q + " --ozone 300", in);
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(b.status, 0) << b.err;
  std::string header;
  const auto ra = parse_csv_numbers(a.out, &header), rb = parse_csv_numbers(b.out, &header);
  ASSERT_EQ(ra.size(), 1u);
  ASSERT_EQ(rb.size(), 1u);
  const double loss440 = rb[0][2] / ra[0][2], loss600 = rb[0][3] / ra[0][3];
  EXPECT_LT(loss440, 1.0);
  EXPECT_LT(loss600, loss440);
  EXPECT_GT(loss440, 0.95);  // 440 nm: ozone optical depth ~0.001 per column crossed
  EXPECT_EQ(run("eval --model nishita --ozone -1", in).status, 2);
}

TEST_F(Cli, RenderNishitaFromOrbitWithCamera) {
  const fs::path exr = dir_ / "orbit.exr";
  const Result r =
      run("render --model nishita --observer-altitude 1e6 --sun-elevation 20 --projection camera "
          "--look-elevation -30 --fov 70 --width 32 --height 16 -o '" +
          exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF img = io::read_image(exr);
  ASSERT_EQ(img.width, 32);
  EXPECT_EQ(img.pixel(16, 0)[1], 0.0f) << "top centre: space above the limb";
  EXPECT_GT(img.pixel(16, 15)[1], 0.0f) << "bottom centre: the lit atmosphere over the planet";
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
      {"eval --model preetham --sun-zenith 10 --sun-elevation 10", ok_in, "excludes"},
      {"eval --model nope", ok_in, "unknown model 'nope'"},
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
      {"render --model cie", "", "--output"},
      {"eval --model nishita --observer-altitude -5", ok_in, "--observer-altitude"},
      {"eval --model nishita --observer-altitude 2e7", ok_in, "--observer-altitude"},
      {"eval --model nishita --solar-irradiance 0", ok_in, "--solar-irradiance"},
      {"eval --model nishita --mie-g 1", ok_in, "--mie-g"},
      {"eval --model nishita --ground-radius 1e6 --top-radius 9e5", ok_in, "--top-radius"},
  };
  for (const auto& c : cases) {
    const Result r = run(c.args, c.input);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.must_contain), std::string::npos) << c.args << "\nstderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
    EXPECT_TRUE(r.out.empty() || r.out.find("zenith_deg") == std::string::npos)
        << "no partial output: " << r.out;
  }
}

TEST_F(Cli, RuntimeFailuresExitOne) {
  Result r = run("eval --model cie --input '" + (dir_ / "missing.csv").string() + "'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("missing.csv"), std::string::npos);
  r = run("render --model cie --width 8 --height 4 -o '" + (dir_ / "no/such/dir/x.exr").string() +
          "'");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "no"));
}

TEST_F(Cli, HosekEvalAllQuantitiesAndRender) {
  const std::string model =
      "--model hosek --turbidity 4.5 --albedo 0.2 --sun-zenith 50 --sun-azimuth 120";
  // Zenith, the sun centre, and a direction far from the sun.
  const std::string in = "zenith_deg,azimuth_deg\n0,0\n50,120\n60,300\n";
  std::string header;
  auto eval = [&](const std::string& args) {
    const Result r = run("eval " + model + " " + args, in);
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
    return parse_csv_numbers(r.out, &header);
  };
  const auto sky = eval("--quantity luminance");
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,luminance");
  const auto both = eval("--quantity luminance --include-sun");
  const auto sun = eval("--quantity luminance --sun-only");
  ASSERT_EQ(sky.size(), 3u);
  ASSERT_EQ(both.size(), 3u);
  ASSERT_EQ(sun.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_GT(sky[i][2], 0.0);
    EXPECT_NEAR(both[i][2], sky[i][2] + sun[i][2], 1e-9 * both[i][2]);
  }
  EXPECT_EQ(sun[0][2], 0.0);
  EXPECT_EQ(sun[2][2], 0.0);
  EXPECT_GT(sun[1][2], 1e4 * sky[1][2]) << "the solar disc";
  const auto xyz = eval("--quantity xyz");
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,x,y,z");
  EXPECT_DOUBLE_EQ(xyz[0][3], sky[0][2]);
  const auto rgb = eval("--quantity rgb");
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,r,g,b");
  EXPECT_GT(rgb[0][4], rgb[0][2]) << "blue zenith (native RGB)";
  eval("--quantity rgb --include-sun");
  eval("--quantity xyz --sun-only");
  const auto L = eval("--quantity spectral --wavelengths 320,450,550,720");
  EXPECT_EQ(header, "zenith_deg,azimuth_deg,L320,L450,L550,L720");
  const auto Ls = eval("--quantity spectral --wavelengths 320,450,550,720 --sun-only");
  const auto Lb = eval("--quantity spectral --wavelengths 320,450,550,720 --include-sun");
  for (int c = 2; c < 6; ++c) {
    EXPECT_GT(L[0][c], 0.0);
    EXPECT_NEAR(Lb[1][c], L[1][c] + Ls[1][c], 1e-9 * Lb[1][c]);
    EXPECT_EQ(Ls[0][c], 0.0);
  }
  // Outside the spectral range 320-720 nm, or outside turbidity 1-10: a clear error.
  Result r = run("eval " + model + " --quantity spectral --wavelengths 800", in);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("800"), std::string::npos) << r.err;
  r = run("eval --model hosek --turbidity 12", in);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("turbidity"), std::string::npos) << r.err;

  // render: the float batch path; pixel = linear sRGB of the XYZ dataset.
  const fs::path exr = dir_ / "hosek.exr";
  r = run("render " + model + " --width 64 --height 32 -o '" + exr.string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF img = io::read_image(exr);
  const double zen = 180.0 * 9.5 / 32.0, az = 360.0 * 20.5 / 64.0;
  r = run("eval " + model + " --quantity xyz",
          "zenith_deg,azimuth_deg\n" + std::to_string(zen) + "," + std::to_string(az) + "\n");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto px_xyz = parse_csv_numbers(r.out, &header);
  const Rgb want = xyz_to_linear_srgb({px_xyz[0][2], px_xyz[0][3], px_xyz[0][4]});
  const float* px = img.pixel(20, 9);
  EXPECT_NEAR(px[0], want.r, std::abs(want.r) * kHosekRenderVsEvalRelTol);
  EXPECT_NEAR(px[1], want.g, std::abs(want.g) * kHosekRenderVsEvalRelTol);
  EXPECT_NEAR(px[2], want.b, std::abs(want.b) * kHosekRenderVsEvalRelTol);
  r = run("render " + model + " --include-sun --width 256 --height 128 -o '" +
          (dir_ / "hs.pfm").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("render " + model + " --sun-only --width 256 --height 128 -o '" +
          (dir_ / "so.pfm").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  const io::ImageF so = io::read_image(dir_ / "so.pfm");
  float peak = 0;
  for (int x = 0; x < so.width; ++x)
    for (int y = 0; y < so.height; ++y) peak = std::max(peak, so.pixel(x, y)[1]);
  EXPECT_GT(peak, 0.0f);
  EXPECT_EQ(so.pixel(0, 0)[1], 0.0f);
}

TEST_F(Cli, ModelsJsonAndHelp) {
  Result r = run("models --json");
  ASSERT_EQ(r.status, 0);
  const auto j = nlohmann::json::parse(r.out);
  std::vector<std::string> names;
  for (const auto& m : j) names.push_back(m["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"perez", "preetham", "cie", "hosek", "nishita"}));
  for (const auto& m : j) {
    for (const auto& p : m["parameters"]) {
      EXPECT_TRUE(p.contains("unit") && p.contains("min") && p.contains("max") &&
                  p.contains("default"));
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

TEST_F(Cli, BenchRunsAndPrintsRatios) {
  const Result r = run("bench --width 64 --height 32 --repeats 1 --models preetham,cie,perez");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("SIMD x"), std::string::npos);
  EXPECT_NE(r.out.find("preetham"), std::string::npos);
}

}  // namespace
}  // namespace skylight
