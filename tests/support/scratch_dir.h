// Test helper: a scratch directory per test (removed afterwards) and whole-file reading, of any
// file or of one of the source tree.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace skylight::testing_support {

namespace fs = std::filesystem;

// A fresh directory named after the running test and the process, removed on destruction.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::path(::testing::TempDir()) / fmt::format("skylight_test_{}_{}_{}", ::getpid(),
                                                         info->test_suite_name(), info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  fs::path operator/(const std::string& name) const { return path_ / name; }
  const fs::path& path() const { return path_; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

inline std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A file of the source tree that a test holds the code to, by its path from the root
// ("docs/MODELS.md"); empty when it cannot be read.
inline std::string source_file(const std::string& relative) {
  return slurp(fs::path(SKYLIGHT_SOURCE_DIR) / relative);
}

}  // namespace skylight::testing_support
