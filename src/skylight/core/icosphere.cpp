#include "skylight/core/icosphere.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "skylight/core/error.h"

namespace skylight {

Icosphere icosphere(int subdivisions) {
  if (subdivisions < 0 || subdivisions > kMaxIcosphereSubdivisions)
    throw InvalidArgument(fmt::format("icosphere: subdivision level {} is not in [0, {}]",
                                      subdivisions, kMaxIcosphereSubdivisions));
  // The icosahedron's 12 vertices (0, +-1, +-phi) and cyclic permutations.
  const double t = 0.5 * (1.0 + std::sqrt(5.0));
  Icosphere s;
  for (const Vec3 v : {Vec3{-1, t, 0}, Vec3{1, t, 0}, Vec3{-1, -t, 0}, Vec3{1, -t, 0},
                       Vec3{0, -1, t}, Vec3{0, 1, t}, Vec3{0, -1, -t}, Vec3{0, 1, -t},
                       Vec3{t, 0, -1}, Vec3{t, 0, 1}, Vec3{-t, 0, -1}, Vec3{-t, 0, 1}})
    s.vertices.push_back(normalize(v));
  s.indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < subdivisions; ++level) {
    std::unordered_map<std::uint64_t, unsigned> midpoint;
    auto mid = [&](unsigned a, unsigned b) {
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      const auto i = static_cast<unsigned>(s.vertices.size());
      s.vertices.push_back(normalize(s.vertices[a] + s.vertices[b]));
      midpoint.emplace(key, i);
      return i;
    };
    std::vector<unsigned> next;
    next.reserve(4 * s.indices.size());
    for (std::size_t k = 0; k < s.indices.size(); k += 3) {
      const unsigned a = s.indices[k], b = s.indices[k + 1], c = s.indices[k + 2];
      const unsigned ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      for (const unsigned i : {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca}) next.push_back(i);
    }
    s.indices = std::move(next);
  }
  return s;
}

}  // namespace skylight
