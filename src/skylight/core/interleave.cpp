#include "skylight/core/interleave.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "skylight/core/error.h"

namespace skylight {

namespace {

// Out of line: the loops that check stay tight.
[[noreturn, gnu::noinline, gnu::cold]] void bad_direction(std::size_t i, Vec3 d) {
  throw InvalidArgument(
      fmt::format("direction {} = ({}, {}, {}) is not a finite non-zero vector", i, d.x, d.y, d.z));
}

}  // namespace

Vec3 row_direction(const double* rows, std::size_t i) {
  const Vec3 d{rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]};
  const double l2 = dot(d, d);
  if (!(l2 > 0.0) || !(l2 < std::numeric_limits<double>::infinity())) [[unlikely]]
    bad_direction(i, d);
  return (1.0 / std::sqrt(l2)) * d;
}

}  // namespace skylight
