// An icosphere: the regular icosahedron with every triangle split into four `subdivisions` times,
// the new vertices pushed out to the unit sphere (docs/PIETRAS.md, the planet meshes of
// gpu/planet.h). 10 * 4^n + 2 vertices and 20 * 4^n triangles at level n; shared vertices are
// stored once; triangles are counter-clockwise seen from outside.
#pragma once

#include <vector>

#include "skylight/core/frame.h"

namespace skylight {

struct Icosphere {
  std::vector<Vec3> vertices;     // unit vectors
  std::vector<unsigned> indices;  // 3 per triangle
};

// Levels 0..kMaxIcosphereSubdivisions (InvalidArgument otherwise).
inline constexpr int kMaxIcosphereSubdivisions = 9;
Icosphere icosphere(int subdivisions);

}  // namespace skylight
