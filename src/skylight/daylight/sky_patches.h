// Sky patches for annual daylight matrices: Tregenza's 145 patches and Reinhart's subdivisions
// (as Radiance's tregenza.cal, reinhart.cal and gendaymtx number them), plus the ground.
//
// Geometry for a subdivision factor MF (1: Tregenza; 2: Reinhart 577; 4: Reinhart 2305): rows of
// altitude alpha = 90 / (7 MF + 0.5) deg from the horizon up; row r (0 .. 7 MF - 1) holds
// MF * (30, 30, 24, 24, 18, 12, 6)[r / MF] patches, and a cap of half-angle alpha / 2 around the
// zenith is the last patch. Within a row, patch j is centred at azimuth j * 360 / n from north
// towards east (patch 1 faces north at the horizon). Patch 0 is the ground (the lower
// hemisphere). Sky patches: 144 MF^2 + 1.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "skylight/core/frame.h"

namespace skylight::daylight {

struct SkyPatch {
  int row = 0;                   // 0 = the horizon row; the zenith cap is row 7 MF; ground -1
  double altitude_lo_deg = 0.0;  // altitude bounds [deg]
  double altitude_hi_deg = 0.0;
  double azimuth_lo_deg = 0.0;  // azimuth bounds [deg], from north towards east; lo may be < 0
  double azimuth_hi_deg = 0.0;  // (the first patch of a row straddles north)
  Vec3 centre{};                // unit vector: the centre's altitude and azimuth
  double solid_angle = 0.0;     // [sr]
};

class PatchSet {
 public:
  // MF >= 1.
  explicit PatchSet(int mf);
  // "tregenza" (MF 1), "reinhart2" (MF 2), "reinhart4" (MF 4); nullopt for another name.
  static std::optional<PatchSet> named(const std::string& name);

  int mf() const { return mf_; }
  // Every patch, the ground first (index 0), then the sky patches in Radiance's order.
  const std::vector<SkyPatch>& patches() const { return patches_; }
  std::size_t size() const { return patches_.size(); }
  // The patch that holds a unit direction (0 for a direction below the horizon).
  std::size_t find(Vec3 direction) const;

 private:
  int mf_ = 1;
  double alpha_deg_ = 12.0;
  std::vector<SkyPatch> patches_;
  std::vector<std::size_t> row_start_;  // index of each row's first patch
  std::vector<int> row_count_;
};

}  // namespace skylight::daylight
