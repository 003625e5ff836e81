// Small numeric helpers used wherever a formula approaches the edge of its domain
// (docs/ARCHITECTURE.md, "Errors"): never let a NaN out of a library function.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace skylight {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDegree = kPi / 180.0;  // one degree in radians

constexpr double deg_to_rad(double deg) {
  return deg * kDegree;
}
constexpr double rad_to_deg(double rad) {
  return rad / kDegree;
}

// sqrt that treats tiny negative round-off as 0.
inline double safe_sqrt(double x) {
  return std::sqrt(std::max(x, 0.0));
}

// A cosine forced into [-1, 1] before acos/asin.
inline double clamp_cosine(double mu) {
  return std::clamp(mu, -1.0, 1.0);
}

inline double safe_acos(double mu) {
  return std::acos(clamp_cosine(mu));
}

}  // namespace skylight
