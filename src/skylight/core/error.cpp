#include "skylight/core/error.h"

#include <fmt/format.h>

namespace skylight {

void check_failed(const char* expr, const char* file, int line, const std::string& msg) {
  throw std::logic_error(
      fmt::format("internal check failed: {} ({}:{}): {}", expr, file, line, msg));
}

}  // namespace skylight
