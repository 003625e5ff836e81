// Shared by the libFuzzer targets (docs/TESTING.md): what counts as a finding besides a crash or a
// sanitizer report. Each target calls a parser of user files; skylight::InvalidArgument and
// skylight::IoError are normal outcomes, and their message must be one bounded, printable line
// (core/numbers.h, excerpt()). Any other exception escapes the target and aborts (a finding).
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include "skylight/core/error.h"

namespace skylight::fuzz {

// A message names the file and quotes bounded excerpts (64 characters each, a few per message) of
// the input: anything much longer echoes unbounded input.
inline constexpr std::size_t kMaxMessageChars = 1024;

[[noreturn]] inline void finding(std::string_view what, std::string_view detail = {}) {
  std::fprintf(stderr, "FINDING: %.*s %.*s\n", static_cast<int>(what.size()), what.data(),
               static_cast<int>(std::min<std::size_t>(detail.size(), 4096)), detail.data());
  std::abort();
}

inline void require(bool ok, std::string_view what) {
  if (!ok) finding(what);
}

inline void require_finite(double v, std::string_view what) {
  if (!std::isfinite(v)) finding(what, "non-finite value accepted");
}

inline void check_message(const std::exception& e) {
  const std::string_view m = e.what();
  if (m.empty()) finding("empty error message");
  if (m.size() > kMaxMessageChars) finding("unbounded error message", m.substr(0, 200));
  for (const char c : m) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) finding("control character in error message", m);
  }
}

// Runs `body`; the project's own errors are normal outcomes (their message checked), everything
// else propagates and aborts the run.
template <class F>
void expect_parsed_or_refused(F&& body) {
  try {
    body();
  } catch (const InvalidArgument& e) {
    check_message(e);
  } catch (const IoError& e) {
    check_message(e);
  }
}

// The input as a file for readers that take a path: one file per process in /dev/shm when
// present (no disk traffic), else in the temporary directory; removed at exit.
class ScratchFile {
 public:
  explicit ScratchFile(std::string_view extension) {
    const std::filesystem::path dir = std::filesystem::is_directory("/dev/shm")
                                          ? "/dev/shm"
                                          : std::filesystem::temp_directory_path();
    path_ = dir / ("skylight-fuzz-" + std::to_string(::getpid()) + std::string(extension));
  }
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (f == nullptr) finding("cannot create the scratch file", path_.string());
    const bool ok = (size == 0 || std::fwrite(data, 1, size, f) == size);
    if (std::fclose(f) != 0 || !ok) finding("cannot write the scratch file", path_.string());
    return path_;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace skylight::fuzz
