// A sky's light on a plane by quadrature (the `sky` method of `skylight irradiance`,
// docs/IRRADIANCE.md): the sky's radiance or luminance L integrated over the plane's field of view,
//   E = Integral over the open sky of L(w) max(0, n.w) dw,
// on a fixed grid over the upper hemisphere, and split into the parts Perez's transposition
// separates: circumsolar (within kCircumsolarHalfAngle of the sun), the horizon band (below
// kHorizonBandHeight, not circumsolar) and the rest.
//
// The grid: rings of elevation, `band_rings` over the horizon band [0, 6.5 deg] and `upper_rings`
// over [6.5, 90 deg], times `sectors` of azimuth, so that the band's edge is a ring edge. Each
// cell's weight is the exact integral of max(0, n.w) over its open part (closed form where the cell
// lies wholly in front of the plane and above the skyline; a K x K midpoint subdivision where the
// plane's horizon, the skyline or the circumsolar circle crosses it); L is taken at the cell's
// centre. The default grid (7 + 90 rings of ~0.93 deg, 360 sectors: 34 920 cells) is ~240 times
// finer than Tregenza's 145 patches; its error is measured in daylight/plane_sky_test.cpp.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "skylight/core/frame.h"
#include "skylight/io/horizon.h"
#include "skylight/models/sky_model.h"

namespace skylight::daylight {

// The plane that receives the light.
struct Plane {
  double tilt = 0.0;     // beta [rad], [0, pi]: 0 = facing up, pi/2 = vertical
  double azimuth = kPi;  // [rad] from north towards east, the way the normal faces

  // The unit normal (ENU): (sin beta sin a, sin beta cos a, cos beta).
  Vec3 normal() const;
};

// The parts of the sky that Perez's transposition separates (Perez et al. 1990; the circumsolar
// disc of 25 deg and the horizon band of 6.5 deg of the framework it simplifies).
inline constexpr double kCircumsolarHalfAngle = 25.0 * kDegree;
inline constexpr double kHorizonBandHeight = 6.5 * kDegree;

struct SkyGridSpec {
  int band_rings = 7, upper_rings = 90, sectors = 360;
  // Subdivision of a cell that the plane's horizon or the skyline crosses (K x K midpoints).
  int subdivision = 16;
};
// The circumsolar circle's share of a cell it crosses: a fixed kShareSubdivision^2 midpoints per
// cell, precomputed (a sun per hour would otherwise cost a subdivision per crossed cell).
inline constexpr int kShareSubdivision = 4;
inline constexpr std::size_t kShareSamples = kShareSubdivision * kShareSubdivision;

class SkyGrid {
 public:
  explicit SkyGrid(const SkyGridSpec& spec = {});
  std::size_t size() const { return centre_.size(); }
  const SkyGridSpec& spec() const { return spec_; }
  // Cell i = ring * sectors + sector; ring 0 touches the zenith, the last ring the horizon.
  int rings() const { return spec_.band_rings + spec_.upper_rings; }
  Vec3 centre(std::size_t i) const { return centre_[i]; }
  // The centres as the models' batch input (single precision).
  const std::vector<float>& x() const { return x_; }
  const std::vector<float>& y() const { return y_; }
  const std::vector<float>& z() const { return z_; }
  // Zenith-angle edges [rad] of ring r: theta_edges()[r] < theta_edges()[r + 1].
  const std::vector<double>& theta_edges() const { return theta_edges_; }
  bool in_band(std::size_t i) const;
  // The largest angle from cell i's centre to its corners [rad].
  double radius(std::size_t i) const { return radius_[i]; }
  // The cell lies wholly within the circumsolar circle of a sun s when dot(centre, s) >= this,
  // wholly outside when dot(centre, s) <= circumsolar_outside(i).
  double circumsolar_inside(std::size_t i) const { return cos_inside_[i]; }
  double circumsolar_outside(std::size_t i) const { return cos_outside_[i]; }
  // The exact integral of cos(theta) over cell i [sr] (sums to pi).
  double horizontal_weight(std::size_t i) const { return horizontal_[i]; }
  // Cell i's share samples: direction j (j < kShareSamples) and its solid angle [sr].
  Vec3 share_direction(std::size_t i, std::size_t j) const;
  double share_solid_angle(std::size_t i, std::size_t j) const;

 private:
  SkyGridSpec spec_;
  std::vector<double> theta_edges_;
  std::vector<Vec3> centre_;
  std::vector<float> x_, y_, z_;
  std::vector<double> radius_, horizontal_, cos_inside_, cos_outside_;
  std::vector<float> share_x_, share_y_, share_z_;
  std::vector<double> share_omega_;  // per ring and sample row
};
// The default grid, built once.
const SkyGrid& default_sky_grid();

// The weights of one plane and horizon on a grid: per cell, the integral of max(0, n.w) over its
// open part [sr]; the same for the horizontal plane (through the same horizon).
struct PlaneWeights {
  const SkyGrid* grid = nullptr;
  Plane plane{};
  const io::HorizonProfile* horizon = nullptr;
  std::vector<double> plane_weight, horizontal_weight;
  // Per cell, its share samples' weights max(0, n.w) [open] dw (the circumsolar split).
  std::vector<float> share_weight;
  // The plane's weights over the horizon band with a flat horizon (band_open's denominator).
  double band_flat = 0.0;
};
// The horizon is referenced (it must outlive the weights).
PlaneWeights plane_weights(const SkyGrid& grid, const Plane& plane,
                           const io::HorizonProfile& horizon);

// What a horizon leaves of an isotropic sky and of the horizon band:
//   sky_view = (1/pi) Integral over the open sky of max(0, n.w) dw ((1 + cos beta)/2 when flat),
//   horizontal_view = the same for the horizontal plane (1 when flat),
//   band_open = the band's weights with the horizon over those without (1 when flat, or when the
//     plane sees none of the band).
// With a flat horizon the closed forms are returned, not the quadrature.
struct HorizonViews {
  double sky_view = 1.0, horizontal_view = 1.0, band_open = 1.0;
};
HorizonViews horizon_views(const PlaneWeights& w);

// One sky's light on the plane, by part, in L's unit times sr; and on the horizontal plane,
// through the horizon (`horizontal_open`) and without it (`horizontal_flat`).
struct SkyParts {
  double total = 0.0, circumsolar = 0.0, horizon = 0.0, rest = 0.0;
  double horizontal_open = 0.0, horizontal_flat = 0.0;
};
// L: the sky's value at each cell centre (grid order). `sun`: the sun's direction (the
// circumsolar circle's centre).
SkyParts integrate_sky(const PlaneWeights& w, const std::vector<float>& L, Vec3 sun);

// A model's luminance Y [cd/m^2] at every cell centre (the batch path, on all threads).
std::vector<float> sky_luminance_on_grid(const SkyModel& model, const SkyGrid& grid);

// The solar disc's radiance integrated over the plane's view: Integral over the disc of
// radiance(w) max(0, n.w) [open] dw, on a polar grid of rings x sectors over the disc; 0 for a
// model without a sun. `normal`: the plane's (the horizontal plane: (0, 0, 1); the sun's own
// direction for the direct normal value). sun_on_plane integrates the disc's luminance [lx].
double sun_disc_on_plane(const SkyModel& model, Vec3 normal, const io::HorizonProfile& horizon,
                         const std::function<double(Vec3)>& radiance, int rings = 8,
                         int sectors = 16);
double sun_on_plane(const SkyModel& model, Vec3 normal, const io::HorizonProfile& horizon);

}  // namespace skylight::daylight
