#include "skylight/daylight/sky_patches.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "skylight/core/error.h"
#include "skylight/core/math.h"

namespace skylight::daylight {
namespace {

// Tregenza's patches per 12-degree row, horizon to the row below the cap.
constexpr std::array<int, 7> kTregenzaRow = {30, 30, 24, 24, 18, 12, 6};

double solid_angle_of_band(double lo_deg, double hi_deg) {
  return 2.0 * kPi * (std::sin(deg_to_rad(hi_deg)) - std::sin(deg_to_rad(lo_deg)));
}

}  // namespace

PatchSet::PatchSet(int mf) : mf_(mf) {
  if (mf < 1) throw InvalidArgument("the patch subdivision factor must be at least 1");
  alpha_deg_ = 90.0 / (7.0 * mf + 0.5);
  SkyPatch ground;
  ground.row = -1;
  ground.altitude_lo_deg = -90.0;
  ground.altitude_hi_deg = 0.0;
  ground.azimuth_lo_deg = 0.0;
  ground.azimuth_hi_deg = 360.0;
  ground.centre = {0.0, 0.0, -1.0};
  ground.solid_angle = 2.0 * kPi;
  patches_.push_back(ground);
  for (int r = 0; r < 7 * mf; ++r) {
    const int n = mf * kTregenzaRow[static_cast<std::size_t>(r / mf)];
    const double lo = r * alpha_deg_, hi = (r + 1) * alpha_deg_, step = 360.0 / n;
    row_start_.push_back(patches_.size());
    row_count_.push_back(n);
    for (int j = 0; j < n; ++j) {
      SkyPatch p;
      p.row = r;
      p.altitude_lo_deg = lo;
      p.altitude_hi_deg = hi;
      p.azimuth_lo_deg = (j - 0.5) * step;
      p.azimuth_hi_deg = (j + 0.5) * step;
      p.centre = direction_from_angles(deg_to_rad(90.0 - 0.5 * (lo + hi)), deg_to_rad(j * step));
      p.solid_angle = solid_angle_of_band(lo, hi) / n;
      patches_.push_back(p);
    }
  }
  SkyPatch cap;
  cap.row = 7 * mf;
  cap.altitude_lo_deg = 90.0 - 0.5 * alpha_deg_;
  cap.altitude_hi_deg = 90.0;
  cap.azimuth_lo_deg = 0.0;
  cap.azimuth_hi_deg = 360.0;
  cap.centre = {0.0, 0.0, 1.0};
  cap.solid_angle = solid_angle_of_band(cap.altitude_lo_deg, 90.0);
  row_start_.push_back(patches_.size());
  row_count_.push_back(1);
  patches_.push_back(cap);
}

std::optional<PatchSet> PatchSet::named(const std::string& name) {
  if (name == "tregenza") return PatchSet(1);
  if (name == "reinhart2") return PatchSet(2);
  if (name == "reinhart4") return PatchSet(4);
  return std::nullopt;
}

std::size_t PatchSet::find(Vec3 d) const {
  if (d.z < 0.0) return 0;
  const double altitude = rad_to_deg(std::asin(std::min(1.0, d.z / length(d))));
  if (altitude >= 90.0 - 0.5 * alpha_deg_) return patches_.size() - 1;
  const auto r =
      static_cast<std::size_t>(std::min(std::floor(altitude / alpha_deg_), 7.0 * mf_ - 1.0));
  const int n = row_count_[r];
  const double azimuth = rad_to_deg(angles_from_direction(d).azimuth);
  const double step = 360.0 / n;
  const int j = static_cast<int>(std::floor((azimuth + 0.5 * step) / step)) % n;
  return row_start_[r] + static_cast<std::size_t>(j);
}

}  // namespace skylight::daylight
