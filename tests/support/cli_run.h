// Test helper: runs the real `skylight` executable (SKYLIGHT_CLI_PATH) in a scratch directory per
// test, with given standard input, and captures its exit status, stdout and stderr.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "skylight/models/sky_model.h"

namespace skylight::testing_support {

// " --NAME VALUE" for each of the model's example values (ModelInfo::example: what its required
// parameters need for a typical sky).
inline std::string example_flags(const ModelInfo& m) {
  std::string flags;
  for (const auto& [name, value] : m.example.all())
    flags += " --" + name + " " + m.find_parameter(name)->format(value);
  return flags;
}

// The value of the labelled line `label` of a record's text form (operations::text_of: the label,
// two or more spaces, the value with its unit): "zenith      50.111622 deg" -> "50.111622 deg";
// "" when there is no such line.
inline std::string text_field(const std::string& out, const std::string& label) {
  std::size_t at = 0;
  while (at < out.size()) {
    const std::size_t nl = std::min(out.find('\n', at), out.size());
    const std::string line = out.substr(at, nl - at);
    if (line.rfind(label + "  ", 0) == 0) {
      const std::size_t v = line.find_first_not_of(' ', label.size());
      return v == std::string::npos ? std::string() : line.substr(v);
    }
    at = nl + 1;
  }
  return {};
}

struct CliResult {
  int status = -1;
  std::string out, err;
};

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("skylight_cli_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" +
            info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Runs `skylight ARGS` (a shell word list) with `input` on stdin.
  CliResult run(const std::string& args, const std::string& input = "") {
    const auto in = dir_ / "stdin.txt", out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    std::ofstream(in, std::ios::binary) << input;
    const std::string cmd = std::string("'") + SKYLIGHT_CLI_PATH + "' " + args + " < '" +
                            in.string() + "' > '" + out.string() + "' 2> '" + err.string() + "'";
    const int raw = std::system(cmd.c_str());
    CliResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    std::filesystem::remove(in);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
  }
  static std::string slurp(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }
  std::filesystem::path dir_;
};

// A `--gpu` run of a build without the GPU module: exit status 1 and the reason.
inline void expect_built_without_gpu(const CliResult& r) {
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("built without the GPU module"), std::string::npos) << r.err;
}

// `eval` input for the direction at the centre of pixel (col, row) of a width x height equirect
// render: theta = 180 (row + 0.5) / height, phi = 360 (col + 0.5) / width [deg].
inline std::string equirect_pixel_input(int col, int row, int width, int height) {
  const double zen = 180.0 * (row + 0.5) / height, az = 360.0 * (col + 0.5) / width;
  return "zenith_deg,azimuth_deg\n" + std::to_string(zen) + "," + std::to_string(az) + "\n";
}

// CSV text -> header and rows of numbers.
inline std::vector<std::vector<double>> parse_csv_numbers(const std::string& text,
                                                          std::string* header) {
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

}  // namespace skylight::testing_support
