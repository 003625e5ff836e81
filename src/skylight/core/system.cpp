#include "skylight/core/system.h"

#include <fmt/format.h>
#include <time.h>

#include <fstream>
#include <sstream>
#include <string>

#include "skylight/core/error.h"

namespace skylight {

std::optional<std::size_t> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  std::size_t value = 0;
  while (in >> key >> value) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return value * 1024;  // the file states kB
  }
  return std::nullopt;
}

void require_memory(std::size_t bytes, std::string_view what) {
  const auto available = available_memory_bytes();
  if (!available || bytes <= *available) return;
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  throw IoError(fmt::format("{} needs about {:.1f} GiB of memory; {:.1f} GiB is available", what,
                            static_cast<double>(bytes) / kGiB,
                            static_cast<double>(*available) / kGiB));
}

namespace {
double clock_s(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
}  // namespace

double thread_cpu_s() {
  return clock_s(CLOCK_THREAD_CPUTIME_ID);
}

double process_cpu_s() {
  return clock_s(CLOCK_PROCESS_CPUTIME_ID);
}

}  // namespace skylight
