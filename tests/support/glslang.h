// Test helper: runs glslangValidator (glslang-tools, found by CMake: SKYLIGHT_GLSLANG_VALIDATOR)
// on GLSL files. Where it is missing the calling test FAILS saying so (scripts/setup.sh installs
// it).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace skylight::testing_support {

struct GlslangResult {
  int status = -1;
  std::string output;
};

// glslangValidator `args` (paths quoted by the caller), stdout + stderr captured through a file
// beside `log`.
inline GlslangResult run_glslang(const std::string& args, const std::filesystem::path& log) {
  const std::string tool = SKYLIGHT_GLSLANG_VALIDATOR;
  if (tool.empty()) {
    ADD_FAILURE() << "glslangValidator was not found when configuring (install glslang-tools, "
                     "scripts/setup.sh, and re-run cmake)";
    return {};
  }
  const std::string cmd = "'" + tool + "' " + args + " > '" + log.string() + "' 2>&1";
  const int raw = std::system(cmd.c_str());
  GlslangResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  return r;
}

}  // namespace skylight::testing_support
