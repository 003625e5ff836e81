#include "skylight/core/icosphere.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skylight/core/error.h"

namespace skylight {
namespace {

// Unit length of every vertex: double rounding of normalize().
constexpr double kUnitTolerance = 1e-14;

TEST(Icosphere, CountsFollowTheSubdivisionLevel) {
  for (int n = 0; n <= 4; ++n) {
    const Icosphere s = icosphere(n);
    const std::size_t f = std::size_t{1} << (2 * n);  // 4^n
    EXPECT_EQ(s.vertices.size(), 10 * f + 2) << n;
    EXPECT_EQ(s.indices.size(), 3 * 20 * f) << n;
    for (const Vec3& v : s.vertices) EXPECT_NEAR(length(v), 1.0, kUnitTolerance);
  }
}

TEST(Icosphere, TrianglesFaceOutwardAndCoverTheSphere) {
  const Icosphere s = icosphere(3);
  // Counter-clockwise from outside: the normal (b - a) x (c - a) points away from the centre.
  // The flat triangles' areas sum to just under 4 pi (a polyhedron inscribed in the sphere).
  double area = 0.0;
  for (std::size_t k = 0; k < s.indices.size(); k += 3) {
    const Vec3 a = s.vertices[s.indices[k]], b = s.vertices[s.indices[k + 1]],
               c = s.vertices[s.indices[k + 2]];
    const Vec3 n = cross(b - a, c - a);
    EXPECT_GT(dot(n, a + b + c), 0.0);
    area += 0.5 * length(n);
  }
  EXPECT_LT(area, 4.0 * kPi);
  EXPECT_GT(area, 0.99 * 4.0 * kPi);  // level 3: the inscribed area is 99.4 % of the sphere's
}

TEST(Icosphere, RejectsLevelsOutOfRange) {
  EXPECT_THROW(icosphere(-1), InvalidArgument);
  EXPECT_THROW(icosphere(kMaxIcosphereSubdivisions + 1), InvalidArgument);
}

}  // namespace
}  // namespace skylight
